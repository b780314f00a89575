"""The locked knee: stiffness K(P) (Nm/rad) and breakaway torque T_break(P) (Nm) (issue 39).

The wire pulled through the inflated tube (:func:`exofric.simulate.pullout`, first loading)
and carried over the knee arc (:func:`capstan_factor`): theta = delta / R (rad), T = capstan x
F R (Nm). The paper's "variable stiffness", as a number per pressure.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_pressures, check_range, warn_implausible
from exofric.friction._torque import capstan_factor

if TYPE_CHECKING:
    import pandas as pd

    from exofric.simulate import PulloutSetup

__all__ = ["JointStiffness", "joint_stiffness"]


@checked_init
@dataclass(frozen=True)
class JointStiffness(DisplayMixin):
    """The locked knee: stiffness K(P) (Nm/rad) and breakaway torque T_break(P) (Nm).

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    stiffness_nm_per_rad : ndarray
        Secant stiffness at half the breakaway torque (Nm/rad): the locked joint's
        stiffness before slip (the rigid-stick wire-wall contact makes the very first
        tangent infinite, so the secant is the meaningful number).
    breakaway_torque_nm, sliding_torque_nm : ndarray
        Torque at breakaway and with the whole wire sliding (Nm).
    breakaway_force_n : ndarray
        Cable force at breakaway (N).
    angle_rad, torque_nm : tuple of ndarray
        T(theta) of the first loading, per pressure (rad, Nm).
    radius_m, wrap_deg, mu_arc, capstan : float
        Lever arm (m), wrap (deg), arc coefficient (unitless), capstan factor (unitless).
    notes : tuple of str
        Statements per pressure (e.g. zero force below the contact onset).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import PulloutSetup
    >>> setup = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...                      mu_wire_wall=0.2, accuracy="draft")
    >>> j = joint_stiffness(setup, [0.3, 0.6], radius_m=0.1)
    >>> bool(j.breakaway_torque_nm[1] > j.breakaway_torque_nm[0] > 0)
    True
    """

    pressure_mpa: np.ndarray
    stiffness_nm_per_rad: np.ndarray
    breakaway_torque_nm: np.ndarray
    sliding_torque_nm: np.ndarray
    breakaway_force_n: np.ndarray
    angle_rad: tuple[np.ndarray, ...] = field(repr=False)
    torque_nm: tuple[np.ndarray, ...] = field(repr=False)
    radius_m: float = 0.1
    wrap_deg: float = 0.0
    mu_arc: float = 0.0
    capstan: float = 1.0
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return {
            "pressure_mpa": self.pressure_mpa.tolist(),
            "stiffness_nm_per_rad": self.stiffness_nm_per_rad.tolist(),
            "breakaway_torque_nm": self.breakaway_torque_nm.tolist(),
            "sliding_torque_nm": self.sliding_torque_nm.tolist(),
            "breakaway_force_n": self.breakaway_force_n.tolist(),
            "angle_rad": [a.tolist() for a in self.angle_rad],
            "torque_nm": [t.tolist() for t in self.torque_nm],
            "radius_m": self.radius_m, "wrap_deg": self.wrap_deg, "mu_arc": self.mu_arc,
            "capstan_factor": self.capstan, "notes": list(self.notes),
        }

    def to_frame(self) -> pd.DataFrame:
        """One row per pressure: K (Nm/rad), T_break, T_slide (Nm), F_break (N)."""
        import pandas as pd

        return pd.DataFrame({
            "pressure_mpa": self.pressure_mpa, "stiffness_nm_per_rad": self.stiffness_nm_per_rad,
            "breakaway_torque_nm": self.breakaway_torque_nm,
            "sliding_torque_nm": self.sliding_torque_nm,
            "breakaway_force_n": self.breakaway_force_n})

    def plot(self, ax: Any | None = None) -> Any:
        """K(P) (Nm/rad) and T_break(P) (Nm, right axis) against pressure (MPa).

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes
        """
        from exofric.plots import plot_joint_stiffness

        return plot_joint_stiffness(self, ax)


def joint_stiffness(
    setup: PulloutSetup,
    pressures_mpa: Any,
    *,
    radius_m: float,
    wrap_deg: float = 0.0,
    mu_arc: float = 0.0,
    displacement_mm: float = 3.0,
) -> JointStiffness:
    """The locked knee over pressures: K(P) (Nm/rad) and T_break(P) (Nm).

    One squeeze solve over all pressures, then per pressure the section law and the first
    loading of the shear lag; theta = delta / R (rad), T = capstan x F R (Nm,
    :func:`capstan_factor`, ``"locking"``).

    Parameters
    ----------
    setup : PulloutSetup
        The pull-out problem (:class:`exofric.simulate.PulloutSetup`: structure in mm,
        material, the three interfaces' coefficients and ``mu_static``, the cable's EA in N,
        the ends, the squeeze's accuracy, the numerics).
    pressures_mpa : array_like
        Strictly increasing pressures (MPa).
    radius_m : float
        Pulley radius / lever arm R (m, in (0, 1]; a warning above 0.3).
    wrap_deg, mu_arc : float
        Wrap of the wire on the knee arc (deg) and its coefficient (unitless).
    displacement_mm : float
        Pulled-end travel of each pull (mm), in (0, L], default 3: must pass the breakaway
        (a note says when it does not).

    Returns
    -------
    JointStiffness

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import PulloutSetup
    >>> setup = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...                      mu_wire_wall=0.2, accuracy="draft")
    >>> j = joint_stiffness(setup, [0.6], radius_m=0.1)
    >>> round(float(j.breakaway_torque_nm[0]), 1)   # L q_slide (N) x 0.1 m: no static peak
    12.5
    """
    from exofric.simulate import PulloutSetup, SqueezeSetup, pullout

    if not isinstance(setup, PulloutSetup):
        raise InputError(f"setup must be a PulloutSetup, got {type(setup).__name__}",
                         param="setup")
    p = check_pressures("pressures_mpa", pressures_mpa, max_mpa=2.0)
    # a lever arm at a knee: centimetres; over 1 m cannot be a wearable joint's, over 0.3 m is
    # implausible (K scales with R^2, so a unit slip of m for mm would be 1e6 off)
    r_m = check_range("radius_m", radius_m, 0.0, 1.0, lo_open=True, unit="m")
    if r_m > 0.3:
        warn_implausible(f"radius_m = {r_m:g} m: a knee's lever arm is a few centimetres")
    cap = capstan_factor(wrap_deg, mu_arc, "locking")
    L = setup.structure.length_mm
    travel = setup.travel_mm(displacement_mm)    # pullout's own check, before the squeeze
    res = SqueezeSetup(setup.structure, setup.material, accuracy=setup.accuracy,
                       mesh=setup.mesh, keep_fields=True).solve(list(p))
    K, Tb, Ts, Fb, angs, tqs = [], [], [], [], [], []
    notes: list[str] = []
    stiff_zones: list[tuple[float, str]] = []   # one note for all pressures (the last one's)
    for k in range(len(p)):
        r = pullout(setup, float(p[k]), displacement_mm=travel,
                    squeeze_result=res, squeeze_index=k, first_loading=True)
        stiff_zones += [(float(p[k]), n) for n in r.notes if n.startswith(_STIFF_ZONES)]
        notes += [f"P = {p[k]:g} MPa: {n}" for n in r.notes if not n.startswith(_STIFF_ZONES)]
        if r.section.initial_stiffness_n_per_mm2 > 0 and r.slip_length_mm[-1] < L:
            notes.append(f"P = {p[k]:g} MPa: the whole length does not slide within "
                         f"{travel:g} mm: T_break is the largest torque reached "
                         "(increase displacement_mm)")
        theta = r.displacement_mm / (1000.0 * r_m)
        torque = cap * r.force_n * r_m
        fb = r.static_force_n
        K.append(_secant(theta, torque, 0.5 * cap * fb * r_m))
        Tb.append(cap * fb * r_m)
        Ts.append(cap * r.sliding_force_n * r_m)
        Fb.append(fb)
        angs.append(theta)
        tqs.append(torque)
    if stiff_zones:
        notes.append(f"P = {', '.join(f'{q:g}' for q, _ in stiff_zones)} MPa: "
                     + stiff_zones[-1][1])
    return JointStiffness(p, np.array(K), np.array(Tb), np.array(Ts), np.array(Fb),
                          tuple(angs), tuple(tqs), r_m, float(wrap_deg), float(mu_arc), cap,
                          tuple(notes))


#: how exofric.simulate's pull notes that its held end zones are too stiff (the start of
#: ``exofric.simulate._pullout.held_stretch_note``; tests/test_pullout_held_zone.py checks it)
_STIFF_ZONES = "held end zones too stiff"


def _secant(theta: np.ndarray, torque: np.ndarray, level: float) -> float:
    """T / theta where the first loading reaches ``level`` (Nm/rad; NaN without torque)."""
    if level <= 0.0:
        return float("nan")
    i = int(np.argmax(torque >= level))
    if torque[i] < level or i == 0:
        return float("nan")
    th = np.interp(level, torque[i - 1:i + 1], theta[i - 1:i + 1])
    return float(level / th)
