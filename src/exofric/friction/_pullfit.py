"""Calibration from measured pulls: mu_wire, mu_wall, mu_wire_wall, mu_static (issue 39).

A pull logged with displacement is a force-displacement curve F(x) at one pressure. The forward
model is :func:`exofric.simulate.pullout` (first loading from rest; the squeeze is solved once
per pressure and reused, since the frictionless squeeze does not depend on the coefficients),
seen through a series compliance ``c`` of the rig (load cell, clamps, cable outside the tube):
the measured travel is x = delta + c F. :func:`fit_pullout` minimises the sum of squared force
residuals over every sample of every pull (N), with the coefficients in [0, 2].

What each signal identifies (docs/formulation.md section 12):

* **Plateau.** With the whole length sliding, F = L (mu_wire S_wire + mu_wire_wall N): linear
  in (mu_wire, mu_wire_wall) with the squeeze's S_wire(P), N(P). Over pressures S_wire / N
  moves little (1.00-1.07 on the paper's structures), so the plateau alone barely separates
  the two (the condition number of [S_wire, N] is reported as ``plateau_condition_number``).
  It never contains mu_wall with ``ends='fixed'``; with ``ends='free'`` and
  mu_wall S_wall < mu_wire S_wire the tube slides on the wall first and the plateau is
  L (mu_wall S_wall + mu_wire_wall N) instead.
* **Pre-slip curve.** The rigid-plastic wire-wall line contact carries mu_wire_wall N as soon
  as the wire moves (a jump over the cable's stretch, ~0.01 mm), while the tube's share rises
  over the section's slip displacement (~mu_wire S_wire / k0, 0.1-1 mm): the curve's shape
  separates mu_wire_wall from mu_wire where the plateau cannot. mu_wall enters only when the
  tube-wall arc slips before the tube-wire arc slides (mu_wall S_wall small): then the curve
  softens or, with fixed ends, keeps rising on the end fittings. Otherwise the curves do not
  depend on mu_wall at all, and it is reported *not identifiable*.
* **Peak.** mu_static > mu_wire gives a breakaway peak above the plateau.

Intervals: the Jacobian of the residuals at the optimum (central differences), a pull-clustered
CR2 covariance (Bell-McCaffrey degrees of freedom and a t quantile; the samples of one pull are
strongly correlated, so the pull is the independent unit), 95 % by default. A parameter whose
column of the Jacobian vanishes, which lies in a near-null direction of the column-scaled
Jacobian (condition number above :data:`~exofric.friction._interfaces.KAPPA_MAX`), or whose
interval half-width exceeds :data:`~exofric.friction._interfaces.CI_REL_MAX` of its estimate,
is *not identifiable*: NaN estimate and interval, an :class:`IdentifiabilityWarning`, and the
others' intervals are conditional on it (held at the value the fit left it). Nothing
identifiable is an :class:`~exofric.errors.InputError`.

Every pull is modelled as a first loading from a relaxed tube (the rest with the wire slack
between pulls is assumed to release the tube's axial shear). A pull that follows a full slide
without that relaxation starts softer (Masing); :func:`pulls_from_reduction` can keep only the
first pull of each plateau (``first_only=True``).

Units: mm, N, MPa; coefficients unitless.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import NDArray

from exofric import defaults
from exofric._display import DisplayMixin
from exofric._lsq import lsq_covariance, residual_variance, standard_errors
from exofric._validate import checked_init
from exofric.errors import (
    ConvergenceError,
    InputError,
    check_finite,
    check_range,
)
from exofric.friction._interfaces import CI_REL_MAX, KAPPA_MAX, IdentifiabilityWarning

if TYPE_CHECKING:
    import pandas as pd

    from exofric.friction._reduce import RigReduction
    from exofric.geometry import Structure
    from exofric.material import HyperelasticModel, MooneyRivlin

__all__ = ["PullFitSettings", "PulloutFit", "fit_pullout", "pulls_from_reduction"]

PARAMS = ("mu_wire", "mu_wall", "mu_wire_wall", "mu_static")
FitOr = float | Literal["fit"]
_START = {"mu_wire": 0.3, "mu_wall": 0.5, "mu_wire_wall": 0.1, "mu_static": 0.0}
#: Share of each pull's travel (its end) read as the plateau by the linear diagnostic.
PLATEAU_WINDOW = 0.25
_MU_MIN = 1e-3          # lower bound of mu_wire, mu_wall in the search (the solver needs > 0)


# ----------------------------------------------------------------------------------------------
# settings and result


@checked_init
@dataclass(frozen=True)
class PullFitSettings:
    """Numerical settings of :func:`fit_pullout` (the physics is in its arguments).

    Parameters
    ----------
    accuracy, mesh
        The squeeze's accuracy level or explicit mesh (see :func:`exofric.simulate.squeeze`).
    n_z : int
        Cable elements along the tube (count, >= 4).
    n_path : int
        Load steps of each first loading up to past the breakaway (count, >= 8).
    confidence : float
        Level of the intervals (unitless, 0.5-0.999).
    start : mapping, optional
        Start values of fitted coefficients (unitless); default from the plateaus
        (mu_wire, mu_wire_wall), mu_wall 0.5, mu_static = mu_wire.
    max_evaluations : int
        Most forward-model evaluations of the search (count, >= 5).
    diff_step_rel : float
        Step of the finite-difference Jacobian relative to max(|coefficient|, 0.1) (unitless,
        1e-5-0.1): large enough to average over the load steps (the model is piecewise
        smooth in the coefficients), small against the intervals.

    Examples
    --------
    >>> PullFitSettings(n_z=20).confidence
    0.95
    """

    accuracy: str | None = None
    mesh: Any = None
    n_z: int = defaults.PULLOUT_Z_ELEMENTS
    n_path: int = defaults.PULLOUT_PATH_STEPS
    confidence: float = 0.95
    start: Mapping[str, float] | None = None
    max_evaluations: int = 30
    diff_step_rel: float = 0.02

    def __post_init__(self) -> None:
        check_range("n_z", self.n_z, 4, 10000)
        check_range("n_path", self.n_path, 8, 10000)
        check_range("confidence", self.confidence, 0.5, 0.999)
        check_range("max_evaluations", self.max_evaluations, 5, 10000)
        check_range("diff_step_rel", self.diff_step_rel, 1e-5, 0.1)
        for k, v in dict(self.start or {}).items():
            if k not in PARAMS:
                raise InputError(f"start: unknown coefficient {k!r} (one of {', '.join(PARAMS)})",
                                 param="start")
            check_range(f"start {k}", v, 0.0, 2.0)


@checked_init
@dataclass(frozen=True)
class PulloutFit(DisplayMixin):
    """Friction coefficients fitted to measured pulls, with intervals (unitless; N, mm, MPa).

    Attributes
    ----------
    estimate : dict of str to float
        ``mu_wire``, ``mu_wall``, ``mu_wire_wall``, ``mu_static`` (unitless): fitted (NaN when
        not identifiable) or given.
    ci_low, ci_high, std_error : dict of str to float
        Interval at ``confidence`` and standard error of each fitted coefficient (unitless;
        NaN when not identifiable; absent for given ones).
    dof : dict of str to float
        Bell-McCaffrey degrees of freedom of each interval.
    std_error_iid : dict of str to float
        Classical standard error, sqrt of s^2 (J^T J)^-1 (unitless; independent samples), for
        comparison: the
        samples of a pull are correlated, so it is too small when the pulls scatter.
    fitted : tuple of str
        The coefficients that were fitted (the others were given).
    identifiable : dict of str to bool
        Per fitted coefficient.
    identifiability_reason : str
        Why a coefficient is not identifiable ('' when all are).
    held_at : dict of str to float
        Where the fit left every coefficient (the curves drawn use these).
    condition_number : float
        Condition number of the column-scaled Jacobian (unitless).
    correlation : ndarray
        Correlation of the identifiable fitted coefficients (order of ``fitted``).
    plateau : dict
        The linear part: plateau samples (the last quarter of the travel of the pulls whose
        fitted curve is flat there) regressed on L S_wire(P) and L N(P) by OLS (``mu_wire``,
        ``mu_wire_wall``, ``se_cr1`` pull-clustered CR1 standard errors, ``condition_number``
        of the column-scaled [S, N], ``pulls_used``, ``wire_pressure_integral_n`` and
        ``squeeze_force_n`` per pressure group in N).
    rmse_n : float
        Root-mean-square force residual (N).
    pressures_mpa : ndarray
        Pressure groups the model was evaluated at (MPa).
    pulls : tuple of dict
        Per pull: ``label``, ``pressure_mpa``, ``group``, ``displacement_mm``, ``force_n``
        (measured), ``model_n`` (fitted curve at the same displacements).
    ends : str
        Tube ends of the model.
    cable_ea_n, compliance_mm_per_n, length_mm : float
        Cable EA (N), rig series compliance (mm/N), tube length (mm).
    confidence : float
        Level of the intervals.
    n_evaluations : int
        Forward-model evaluations (each = one pull-out per pressure group).
    notes : tuple of str
        Statements from the model (e.g. travel beyond the held-squeeze assumption).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import PulloutNumerics, PulloutSetup, pullout
    >>> mat = MooneyRivlin.from_shore(62.5)
    >>> setup = PulloutSetup(BASE, mat, mu_wire=0.3, mu_wall=0.5, mu_wire_wall=0.15,
    ...                      accuracy="draft", numerics=PulloutNumerics(n_z=20, n_path=20))
    >>> r = pullout(setup, 0.6, displacement_mm=1.5, first_loading=True)
    >>> rng = np.random.default_rng(0)
    >>> pulls = [{"pressure_mpa": 0.6, "displacement_mm": r.displacement_mm,
    ...           "force_n": r.force_n * (1 + 0.02 * rng.standard_normal())} for _ in range(3)]
    >>> fit = fit_pullout(BASE, mat, pulls, mu_wall=0.5, mu_wire_wall=0.15,
    ...                   settings=PullFitSettings(accuracy="draft", n_z=20, n_path=20))
    >>> fit.fitted, round(fit.estimate["mu_wire"], 2)
    (('mu_wire',), 0.3)
    """

    estimate: dict[str, float]
    ci_low: dict[str, float]
    ci_high: dict[str, float]
    std_error: dict[str, float]
    dof: dict[str, float]
    std_error_iid: dict[str, float]
    fitted: tuple[str, ...]
    identifiable: dict[str, bool]
    identifiability_reason: str
    held_at: dict[str, float]
    condition_number: float
    correlation: NDArray[np.float64] = field(repr=False)
    plateau: dict[str, Any] = field(repr=False)
    rmse_n: float = 0.0
    pressures_mpa: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0), repr=False)
    pulls: tuple[dict[str, Any], ...] = field(default=(), repr=False)
    ends: str = "fixed"
    cable_ea_n: float = defaults.CABLE_EA_N
    compliance_mm_per_n: float = 0.0
    length_mm: float = 116.0
    confidence: float = 0.95
    n_evaluations: int = 0
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys; NaN as None; no per-sample arrays)."""
        def num(v: float) -> float | None:
            return None if not math.isfinite(v) else float(v)

        return {
            "estimate": {k: num(v) for k, v in self.estimate.items()},
            "ci_low": {k: num(v) for k, v in self.ci_low.items()},
            "ci_high": {k: num(v) for k, v in self.ci_high.items()},
            "std_error": {k: num(v) for k, v in self.std_error.items()},
            "dof": {k: num(v) for k, v in self.dof.items()},
            "std_error_iid": {k: num(v) for k, v in self.std_error_iid.items()},
            "fitted": list(self.fitted),
            "identifiable": dict(self.identifiable),
            "identifiability_reason": self.identifiability_reason,
            "held_at": dict(self.held_at),
            "condition_number": num(self.condition_number),
            "plateau": {k: (num(v) if isinstance(v, float) else
                            [num(u) if isinstance(u, float) else u for u in v]
                            if isinstance(v, list) else v)
                        for k, v in self.plateau.items()},
            "rmse_n": self.rmse_n,
            "pressures_mpa": self.pressures_mpa.tolist(),
            "n_pulls": len(self.pulls),
            "n_samples": int(sum(len(p["force_n"]) for p in self.pulls)),
            "ends": self.ends, "cable_ea_n": self.cable_ea_n,
            "compliance_mm_per_n": self.compliance_mm_per_n, "length_mm": self.length_mm,
            "confidence": self.confidence, "n_evaluations": self.n_evaluations,
            "notes": list(self.notes),
        }

    def to_frame(self) -> pd.DataFrame:
        """One row per coefficient: estimate, interval, standard error, dof, fitted/given."""
        import pandas as pd

        rows = []
        for k in PARAMS:
            fitted = k in self.fitted
            rows.append({"coefficient": k, "estimate": self.estimate[k],
                         "ci_low": self.ci_low.get(k, math.nan),
                         "ci_high": self.ci_high.get(k, math.nan),
                         "std_error": self.std_error.get(k, math.nan),
                         "dof": self.dof.get(k, math.nan),
                         "status": ("given" if not fitted else "fitted"
                                    if self.identifiable[k] else "not identifiable")})
        return pd.DataFrame(rows)

    def curves_frame(self) -> pd.DataFrame:
        """One row per sample: pull label, pressure (MPa), displacement (mm), measured and
        fitted force (N)."""
        import pandas as pd

        frames = [pd.DataFrame({"pull": p["label"], "pressure_mpa": p["pressure_mpa"],
                                "displacement_mm": p["displacement_mm"],
                                "force_n": p["force_n"], "model_n": p["model_n"]})
                  for p in self.pulls]
        return pd.concat(frames, ignore_index=True)

    def plot(self, fig: Any | None = None) -> Any:
        """Measured and fitted force-displacement curves per pressure, and the residuals
        (:func:`exofric.plots.plot_pullout_fit`).

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on.

        Returns
        -------
        matplotlib Figure
        """
        from exofric.plots import plot_pullout_fit

        return plot_pullout_fit(self, fig=fig)


# ----------------------------------------------------------------------------------------------
# input


@dataclass(frozen=True)
class _Pull:
    label: Any
    pressure: float
    x: NDArray[np.float64]
    f: NDArray[np.float64]


def _as_pulls(pulls: Any, length_mm: float) -> list[_Pull]:
    """Checked pulls from a long DataFrame (``pull`` column) or a sequence of mappings."""
    if hasattr(pulls, "columns"):
        for c in ("pressure_mpa", "displacement_mm", "force_n"):
            if c not in pulls.columns:
                raise InputError(f"pulls has no column {c!r} (needs pressure_mpa, "
                                 "displacement_mm, force_n and pull)", param="pulls")
        if "pull" not in pulls.columns:
            raise InputError("pulls needs a 'pull' column naming the pull of each sample "
                             "(the pull is the independent unit of the intervals)",
                             param="pulls")
        items = []
        for lab, g in pulls.groupby("pull", sort=False):
            pr = np.asarray(g["pressure_mpa"], dtype=float)
            items.append({"label": lab, "pressure_mpa": float(np.mean(pr)),
                          "displacement_mm": g["displacement_mm"].to_numpy(float),
                          "force_n": g["force_n"].to_numpy(float)})
    elif isinstance(pulls, Sequence) and not isinstance(pulls, str):
        items = list(pulls)
    else:
        raise InputError("pulls must be a DataFrame (columns pull, pressure_mpa, "
                         "displacement_mm, force_n) or a list of pulls", param="pulls")
    out = [_check_pull(k, item, length_mm) for k, item in enumerate(items)]
    if not out:
        raise InputError("pulls is empty", param="pulls")
    return out


def _check_pull(k: int, item: Any, length_mm: float) -> _Pull:
    get = item.get if isinstance(item, Mapping) else (lambda n, d=None: getattr(item, n, d))
    label = get("label", k + 1)
    where = f"pull {label}"
    p = get("pressure_mpa")
    if p is None:
        raise InputError(f"pressure_mpa missing in {where}", param="pressure_mpa")
    p = check_finite(f"pressure_mpa ({where})", p)
    if not 0.0 < p <= 2.0:
        raise InputError(f"pressure_mpa must be in (0, 2] MPa, got {p:g} ({where})",
                         param="pressure_mpa")
    try:
        x = np.asarray(get("displacement_mm"), dtype=float).ravel()
        f = np.asarray(get("force_n"), dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"displacement_mm and force_n must be numbers ({where})",
                         param="displacement_mm") from None
    if x.size != f.size or x.size < 5:
        raise InputError(f"displacement_mm and force_n must have the same length >= 5 "
                         f"({where}: {x.size}, {f.size})", param="displacement_mm")
    for name, a in (("displacement_mm", x), ("force_n", f)):
        if not np.all(np.isfinite(a)):
            raise InputError(f"{name} is not finite at sample "
                             f"{int(np.flatnonzero(~np.isfinite(a))[0]) + 1} ({where})",
                             param=name)
    span = float(x.max() - x.min())
    if span <= 0 or float(x[-1] - x[0]) <= 0:
        raise InputError(f"displacement_mm must increase along the pull (mm), it does not "
                         f"({where}: {x[0]:g} -> {x[-1]:g})", param="displacement_mm")
    back = float(np.max(np.maximum.accumulate(x) - x))
    if back > 0.01 * span:
        raise InputError(f"displacement_mm must increase along the pull: it goes back by "
                         f"{back:.3g} mm ({where}; more than 1 % of its travel)",
                         param="displacement_mm")
    if x.min() < -0.01 * span:
        raise InputError(f"displacement_mm must be >= 0 mm from the pull's start, got "
                         f"{x.min():g} ({where})", param="displacement_mm")
    if x.max() > length_mm:
        raise InputError(f"displacement_mm must be <= the tube length {length_mm:g} mm, got "
                         f"{x.max():g} ({where})", param="displacement_mm")
    fmax = float(np.max(np.abs(f)))
    if fmax <= 0 or f.min() < -0.05 * fmax:
        raise InputError(f"force_n must be >= 0 N (the friction magnitude; flip the sign of a "
                         f"backward pull), got {f.min():g} ({where})", param="force_n")
    return _Pull(label, p, x, f)


def _groups(pressures: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """Pressure groups (mean MPa, increasing) and the group of each pull: pressures within
    max(0.005 MPa, 2 %) of the previous one share a group (one squeeze, one model curve)."""
    order = np.argsort(pressures, kind="stable")
    srt = pressures[order]
    new = np.concatenate([[True], np.diff(srt) > np.maximum(0.005, 0.02 * srt[1:])])
    gid = np.empty(pressures.size, dtype=np.intp)
    gid[order] = np.cumsum(new) - 1
    means = np.array([pressures[gid == g].mean() for g in range(int(gid.max()) + 1)])
    return means, gid


# ----------------------------------------------------------------------------------------------
# reduced rig logs -> pulls


def pulls_from_reduction(reduction: RigReduction | Sequence[RigReduction], *,
                         first_only: bool = False) -> pd.DataFrame:
    """The force-displacement curve of each pull of reduced raw logs (mm, N, MPa).

    Uses :func:`~exofric.friction.reduce_log`'s segmentation (each used pull's start and end,
    direction, tare and direction bias): displacement from the pull's first sample, in the
    direction of the pull (mm); force tared and de-biased, as a friction magnitude
    d (F - tare - bias) (N).

    Parameters
    ----------
    reduction : RigReduction or sequence of RigReduction
        Reduced logs with a displacement column.
    first_only : bool
        Keep only the first used pull of each plateau (the one that starts from the tube's
        state after inflation; later pulls follow a full slide).

    Returns
    -------
    pandas.DataFrame
        One row per sample: ``pull`` (label ``<log>#<n>``), ``pressure_mpa``,
        ``displacement_mm``, ``force_n``, ``direction``, ``plateau``.

    Raises
    ------
    InputError
        A log without displacement.

    Examples
    --------
    >>> from exofric.friction import reduce_log, simulate_raw_log
    >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
    >>> df = pulls_from_reduction(red, first_only=True)
    >>> df["pull"].nunique(), round(float(df["displacement_mm"].max()), 1)
    (2, 10.0)
    """
    import pandas as pd

    reds: list[RigReduction] = ([reduction] if not isinstance(reduction, Sequence)
                                else list(reduction))
    frames = []
    for j, red in enumerate(reds):
        if red.displacement_mm is None:
            raise InputError(f"reduction {red.source or j + 1} has no displacement_mm: a "
                             "pull's force-displacement curve needs the wire displacement",
                             param="reduction")
        t, f, x = red.time_s, red.force_n, red.displacement_mm
        seen: set[int] = set()
        for row in red.pulls:
            if first_only and row["plateau"] in seen:
                continue
            seen.add(row["plateau"])
            a = int(np.searchsorted(t, row["t_start_s"]))
            b = int(np.searchsorted(t, row["t_end_s"], side="right"))
            d = 1.0 if row["direction"] == "forward" else -1.0
            frames.append(pd.DataFrame({
                "pull": f"{red.source or j + 1}#{row['pull']}",
                "pressure_mpa": float(row["pressure_mpa"]),
                "displacement_mm": d * (x[a:b] - x[a]),
                "force_n": d * (f[a:b] - row["tare_n"] - row["bias_n"]),
                "direction": row["direction"], "plateau": int(row["plateau"])}))
    if not frames:
        raise InputError("reduction has no used pull", param="reduction")
    return pd.concat(frames, ignore_index=True)


# ----------------------------------------------------------------------------------------------
# the model


@dataclass
class _Problem:
    """Everything one evaluation needs; ``names`` are the fitted coefficients (internal order
    of PARAMS; mu_static is searched as its excess over mu_wire)."""

    structure: Structure
    material: Any
    squeeze: Any
    pressures: NDArray[np.float64]
    travel: NDArray[np.float64]
    pulls: list[_Pull]
    gid: NDArray[np.intp]
    fixed: dict[str, float | None]
    names: tuple[str, ...]
    ends: str
    ea: float
    compliance: float
    settings: PullFitSettings
    x: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    y: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    sample_group: NDArray[np.intp] = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    sample_pull: NDArray[np.intp] = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    cache: dict[tuple[float, ...], NDArray[np.float64]] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    sections: list[Any] = field(default_factory=list)
    n_eval: int = 0

    def __post_init__(self) -> None:
        self.x = np.concatenate([p.x for p in self.pulls])
        self.y = np.concatenate([p.f for p in self.pulls])
        self.sample_pull = np.concatenate([np.full(p.x.size, k, dtype=np.intp)
                                           for k, p in enumerate(self.pulls)])
        self.sample_group = self.gid[self.sample_pull]

    def coefficients(self, z: NDArray[np.float64]) -> dict[str, float]:
        """All four coefficients from the search vector ``z``."""
        c: dict[str, Any] = dict(self.fixed)
        for name, v in zip(self.names, z, strict=True):
            c[name] = float(v)
        if "mu_static" in self.names:
            c["mu_static"] = min(c["mu_wire"] + c["mu_static"], 2.0)
        return c

    def predict(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        """Model force (N) at every sample for the search vector ``z``."""
        from exofric.simulate import PulloutNumerics, PulloutSetup, pullout

        key = tuple(float(v) for v in z)
        if key in self.cache:
            return self.cache[key]
        c = self.coefficients(z)
        pred = np.empty_like(self.y)
        s = self.settings
        secs = []
        self.notes = []
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            setup = PulloutSetup(self.structure, self.material, mu_wire=c["mu_wire"],
                                 mu_wall=c["mu_wall"], mu_wire_wall=c["mu_wire_wall"],
                                 mu_static=c["mu_static"], cable_ea_n=self.ea, ends=self.ends,
                                 accuracy=s.accuracy, mesh=s.mesh,
                                 numerics=PulloutNumerics(n_z=s.n_z, n_path=s.n_path))
            for g, p in enumerate(self.pressures):
                r = pullout(setup, float(p), displacement_mm=float(self.travel[g]),
                            squeeze_result=self.squeeze, squeeze_index=g, first_loading=True)
                xm = r.displacement_mm + self.compliance * r.force_n
                if np.any(np.diff(xm) <= 0):
                    self._note("the rig compliance makes the model's travel go back after the "
                               "breakaway peak (snap-back); the curve is read on its rising "
                               "envelope")
                    xm = np.maximum.accumulate(xm) + 1e-12 * np.arange(xm.size)
                m = self.sample_group == g
                pred[m] = np.interp(self.x[m], xm, r.force_n)
                secs.append(r.section)
                for n in r.notes:
                    self._note(f"P = {p:g} MPa: {n}")
        for w in caught:
            self._note(" ".join(str(w.message).split()))
        self.sections = secs
        self.n_eval += 1
        if len(self.cache) < 256:
            self.cache[key] = pred
        return pred

    def _note(self, text: str) -> None:
        if text not in self.notes:
            self.notes.append(text)

    def residuals(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        """Model minus measured force (N) at every sample."""
        return self.predict(z) - self.y

    def jacobian(self, z: NDArray[np.float64], lo: NDArray[np.float64],
                 hi: NDArray[np.float64]) -> NDArray[np.float64]:
        """d residuals / d z by central differences (N per unit), one-sided at a bound or
        where the model fails on one side (the shear lag's Newton can stall at one step)."""
        jac = np.empty((self.y.size, z.size))
        f0 = self.predict(z)
        for j in range(z.size):
            h = _step(self.settings, z[j])
            pts = []
            for side in (1.0, -1.0):
                zz = z.copy()
                zz[j] = min(max(z[j] + side * h, lo[j]), hi[j])
                if zz[j] == z[j]:
                    continue
                try:
                    pts.append((float(zz[j]), self.predict(zz)))
                except (ConvergenceError, InputError):
                    continue
            if not pts:
                raise ConvergenceError(f"fit_pullout: the pull-out model fails on both sides "
                                       f"of the optimum in {self.names[j]}")
            if len(pts) == 2:
                jac[:, j] = (pts[0][1] - pts[1][1]) / (pts[0][0] - pts[1][0])
            else:
                jac[:, j] = (pts[0][1] - f0) / (pts[0][0] - float(z[j]))
        return jac


# ----------------------------------------------------------------------------------------------
# the fit


def _step(settings: PullFitSettings, zj: float) -> float:
    """Finite-difference step of a coefficient: ``diff_step_rel`` x max(|z|, 0.1)."""
    return settings.diff_step_rel * max(abs(float(zj)), 0.1)


def _spec(name: str, value: Any) -> float | None | Literal["fit"]:
    if value is None and name == "mu_static":
        return None
    if isinstance(value, str):
        if value.strip().lower() == "fit":
            return "fit"
        try:
            value = float(value)
        except ValueError:
            raise InputError(f"{name} must be a number in [0, 2] or 'fit', got {value!r}",
                             param=name) from None
    from exofric.simulate import check_friction

    return check_friction(name, value)


def fit_pullout(
    structure: Structure,
    material: MooneyRivlin | HyperelasticModel,
    pulls: Any,
    *,
    ends: str = "fixed",
    cable_ea_n: float = defaults.CABLE_EA_N,
    compliance_mm_per_n: float = 0.0,
    mu_wall: FitOr = "fit",
    mu_wire_wall: FitOr = "fit",
    mu_static: FitOr | None = None,
    settings: PullFitSettings | None = None,
) -> PulloutFit:
    """Fit the pull-out friction coefficients to measured force-displacement curves.

    mu_wire is always fitted; mu_wall, mu_wire_wall and mu_static are fitted (``"fit"``) or
    given (a number; ``mu_static=None``: no static peak, mu_static = mu_wire). See the
    module docstring for what each signal identifies and how the intervals are made.

    Parameters
    ----------
    structure : Structure
        Hole, tube, wire and tube length (mm).
    material : MooneyRivlin or HyperelasticModel
        Tube material.
    pulls : DataFrame or sequence of mapping
        The measured pulls: a long table with columns ``pull`` (label), ``pressure_mpa``
        (MPa), ``displacement_mm`` (mm, from the pull's start, increasing), ``force_n`` (N,
        friction magnitude >= 0), e.g. :func:`pulls_from_reduction`; or one mapping per pull
        with ``pressure_mpa`` (scalar), ``displacement_mm`` and ``force_n`` (arrays) and an
        optional ``label``.
    ends : {'fixed', 'free'}
        The tube's end fittings (see :func:`exofric.simulate.section_pullout`).
    cable_ea_n : float
        Cable axial stiffness EA (N).
    compliance_mm_per_n : float
        Series compliance of the rig between the displacement sensor and the tube's pulled end
        (mm/N, >= 0): x = delta + c F. It competes with the tube's pre-slip stiffness and is
        not fitted: measure it (pull a rigid dummy) or give 0 when x is taken at the tube.
    mu_wall, mu_wire_wall : float or 'fit'
        Coulomb coefficients tube-wall and wire-wall (unitless, [0, 2]), or ``"fit"``.
    mu_static : float, 'fit' or None
        Static coefficient (unitless, >= mu_wire), ``"fit"``, or None (no static peak).
    settings : PullFitSettings, optional
        Mesh, steps, interval level, start values.

    Returns
    -------
    PulloutFit

    Raises
    ------
    InputError
        Bad pulls (negative force, displacement not increasing or beyond the tube, NaN),
        too few pulls for the pull-clustered interval (fitted coefficients + 2), mu_wire and
        mu_wire_wall both fitted from one pressure, nothing identifiable.
    ConvergenceError
        The forward model fails at the start values.

    Warns
    -----
    IdentifiabilityWarning
        A fitted coefficient the data do not determine (NaN estimate and interval).

    Examples
    --------
    See :class:`PulloutFit`.
    """
    from exofric.simulate import SqueezeSetup, check_pullout_friction

    s = settings or PullFitSettings()
    spec = {"mu_wall": _spec("mu_wall", mu_wall),
            "mu_wire_wall": _spec("mu_wire_wall", mu_wire_wall),
            "mu_static": _spec("mu_static", mu_static)}
    check_pullout_friction(0.0, 0.0, 0.0, ends)          # the one check of ``ends``
    ea = check_range("cable_ea_n", cable_ea_n, 1.0, 1e10, unit="N")
    top = spec["mu_static"]
    if isinstance(top, float) and top <= _MU_MIN:
        raise InputError(f"mu_static must be > {_MU_MIN:g} when given (mu_wire is fitted "
                         f"below it), got {top:g}", param="mu_static")
    comp = check_range("compliance_mm_per_n", compliance_mm_per_n, 0.0, 10.0, unit="mm/N")
    L = float(structure.length_mm)
    data = _as_pulls(pulls, L)
    names = tuple(n for n in PARAMS if n == "mu_wire" or spec.get(n) == "fit")
    pressures, gid = _groups(np.array([p.pressure for p in data]))
    if "mu_wire_wall" in names and pressures.size < 2:
        raise InputError(f"pressure_mpa: all pulls at one pressure ({pressures[0]:g} MPa) "
                         "cannot separate mu_wire from mu_wire_wall (both scale the plateau); "
                         "pull at 2 or more pressures, or give mu_wire_wall", param="pressure_mpa")
    if len(data) < len(names) + 2:
        raise InputError(f"pulls: {len(data)} pull(s) for {len(names)} fitted coefficients; the "
                         f"pull-clustered interval needs at least {len(names) + 2}",
                         param="pulls")
    fixed: dict[str, float | None] = {k: (None if v == "fit" else v) for k, v in spec.items()}
    travel = np.array([max(float(data[k].x.max()) for k in np.flatnonzero(gid == g))
                       for g in range(pressures.size)])
    squeeze = SqueezeSetup(structure, material, accuracy=s.accuracy, mesh=s.mesh,
                           keep_fields=True).solve(list(pressures))
    prob = _Problem(structure, material, squeeze, pressures, travel, data, gid, fixed, names,
                    ends, ea, comp, s)
    return _solve(prob)


def _bounds(prob: _Problem) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Search box: [0, 2] (mu_wire, mu_wall from 1e-3; the static excess to 1.5; mu_wire up to
    a given mu_static)."""
    names = prob.names
    top = prob.fixed.get("mu_static")
    lo = np.array([_MU_MIN if n in ("mu_wire", "mu_wall") else 0.0 for n in names])
    hi = np.array([1.5 if n == "mu_static" else
                   (float(top) if n == "mu_wire" and top is not None else 2.0) for n in names])
    return lo, hi


def _start(prob: _Problem) -> NDArray[np.float64]:
    """Start vector from the data (every fitted coefficient; ``settings.start`` overrides).

    The plateaus (last half of each pull's travel) against L (S_wire + N) give one combined
    coefficient c: mu_wire = mu_wire_wall = c when both are fitted (the plateau alone cannot
    split them), else mu_wire from the plateau with the given mu_wire_wall. The breakaway peak
    over the plateau gives mu_static / mu_wire. mu_wall: the best of 2, 0.6 and 0.25 x mu_wire
    (the tube-wall arc sticking, or slipping first: regimes a local search does not cross,
    since the curves do not depend on mu_wall while the arc sticks).
    """
    start = dict(_START)
    user = dict(prob.settings.start or {})
    lo, hi = _bounds(prob)
    z0 = np.clip(np.array([start[n] for n in prob.names]), lo, hi)
    prob.predict(z0)                  # S_wire, N per group from the sections (mu-independent)
    L = float(prob.structure.length_mm)
    s_w = np.array([sec.wire_pressure_integral_n_per_mm for sec in prob.sections]) * L
    n_w = np.array([sec.squeeze_force_n_per_mm for sec in prob.sections]) * L
    plat = np.array([float(np.mean(p.f[p.x >= 0.5 * p.x.max()])) for p in prob.pulls])
    peak = np.array([float(p.f.max()) for p in prob.pulls])
    g = prob.gid
    fixed_ww = prob.fixed.get("mu_wire_wall")
    if "mu_wire_wall" in prob.names:
        col = s_w[g] + n_w[g]
        c = float(col @ plat / (col @ col)) if col @ col > 0 else 0.3
        start["mu_wire"] = start["mu_wire_wall"] = c
    else:
        rest = plat - float(fixed_ww or 0.0) * n_w[g]
        col = s_w[g]
        start["mu_wire"] = float(col @ rest / (col @ col)) if col @ col > 0 else 0.3
    start["mu_wire"] = float(np.clip(start["mu_wire"], 0.02, 1.9))
    start["mu_wire_wall"] = float(np.clip(start["mu_wire_wall"], 0.0, 1.9))
    start["mu_wire"] = float(user.get("mu_wire", start["mu_wire"]))
    ratio = float(np.median(peak / np.maximum(plat, 1e-12)))
    start["mu_static"] = max(ratio - 1.0, 0.0) * start["mu_wire"]
    if "mu_static" in user:
        start["mu_static"] = max(float(user["mu_static"]) - start["mu_wire"], 0.0)
    for k in ("mu_wall", "mu_wire_wall"):
        if k in user:
            start[k] = float(user[k])
    if "mu_wall" in prob.names and "mu_wall" not in user:
        s_h = np.array([sec.wall_pressure_integral_n_per_mm for sec in prob.sections]) * L
        rest = plat - float(start["mu_wire_wall"]) * n_w[g]
        col = s_h[g]
        slip = float(col @ rest / (col @ col)) if col @ col > 0 else math.nan
        _best_wall_start(prob, start, "mu_wire" not in user, slip, lo, hi)
    return np.clip(np.array([start[n] for n in prob.names]), lo, hi)


def _best_wall_start(prob: _Problem, start: dict[str, float], vary_wire: bool,
                     wall_slip: float, lo: NDArray[np.float64],
                     hi: NDArray[np.float64]) -> None:
    """mu_wall (and mu_wire) start: the best of a small grid, in place.

    mu_wall at 2, 0.6 and 0.25 x mu_wire: the tube-wall arc sticking, or slipping first
    (regimes a local search does not cross). When the wall slips first, the plateau is the
    wall's (``wall_slip``: mu_wall from the plateaus against S_wall; the held ends add a rise,
    so 0.7 x it too) and says little about mu_wire, which the plateau then under-estimates:
    1.5 x the plateau's mu_wire is tried too (a weak wall with the wire at the plateau's value
    is a separate local minimum with a barrier between).
    """
    base_wire = start["mu_wire"]
    best, keep = math.inf, (base_wire, _START["mu_wall"])
    for fw in ((1.0, 1.5) if vary_wire else (1.0,)):
        start["mu_wire"] = float(np.clip(fw * base_wire, 0.02, 1.9))
        walls = [f * start["mu_wire"] for f in (2.0, 0.6, 0.25)]
        if math.isfinite(wall_slip) and wall_slip > 0:
            walls += [wall_slip, 0.7 * wall_slip]
        for w in walls:
            start["mu_wall"] = float(np.clip(w, _MU_MIN, 2.0))
            z = np.clip(np.array([start[n] for n in prob.names]), lo, hi)
            try:
                cost = float(np.sum(prob.residuals(z) ** 2))
            except (ConvergenceError, InputError):
                continue
            if cost < best:
                best, keep = cost, (start["mu_wire"], start["mu_wall"])
    start["mu_wire"], start["mu_wall"] = keep


def _solve(prob: _Problem) -> PulloutFit:
    from scipy.optimize import least_squares

    s = prob.settings
    lo, hi = _bounds(prob)
    try:
        z0 = _start(prob)
    except ConvergenceError as exc:
        raise ConvergenceError(f"fit_pullout: the pull-out model fails at the start values "
                               f"({exc}); give settings.start") from None
    scale = float(np.sqrt(np.mean(prob.y ** 2))) or 1.0

    def fun(z: NDArray[np.float64]) -> NDArray[np.float64]:
        try:
            return prob.residuals(z)
        except (ConvergenceError, InputError):   # the shear lag's Newton raises InputError
            # a trial step where the pull-out does not converge: a large residual makes the
            # trust region shrink back (the optimum itself must converge, checked below)
            return np.full(prob.y.size, 10.0 * scale)

    def fd_jac(z: NDArray[np.float64]) -> NDArray[np.float64]:
        # forward differences with the step of the final Jacobian (not scipy's x * diff_step:
        # the static cascade and the load-step grid make the model piecewise smooth, and a
        # step near 0 for a small coefficient would read the steps, not the slope)
        f0 = fun(z)
        out = np.empty((f0.size, z.size))
        for j in range(z.size):
            h = _step(s, z[j])
            zz = z.copy()
            zz[j] = z[j] + h if z[j] + h <= hi[j] else z[j] - h
            out[:, j] = (fun(zz) - f0) / (zz[j] - z[j])
        return out

    sol = least_squares(fun, z0, jac=fd_jac, bounds=(lo, hi), x_scale="jac",
                        max_nfev=s.max_evaluations, xtol=1e-4, ftol=1e-6, gtol=1e-8)
    z = np.asarray(sol.x, dtype=float)
    prob.cache.pop(tuple(float(v) for v in z), None)
    r = prob.residuals(z)        # raises ConvergenceError if the optimum itself fails
    notes, sections = list(prob.notes), prob.sections
    jac = prob.jacobian(z, lo, hi)
    prob.notes, prob.sections = notes, sections
    return _result(prob, z, r, jac, lo)


def _transform(names: tuple[str, ...]) -> NDArray[np.float64]:
    """d(reported coefficients) / d(search vector): mu_static = mu_wire + excess."""
    a = np.eye(len(names))
    if "mu_static" in names:
        a[names.index("mu_static"), names.index("mu_wire")] = 1.0
    return a


def _result(prob: _Problem, z: NDArray[np.float64], r: NDArray[np.float64],
            jac_z: NDArray[np.float64], lo: NDArray[np.float64]) -> PulloutFit:
    from scipy import stats

    names = prob.names
    coef = prob.coefficients(z)
    a = _transform(names)
    jac = jac_z @ np.linalg.inv(a)            # d r / d(reported coefficients)
    theta = np.array([coef[n] for n in names])
    ok, reason, kappa = _identifiable(jac, theta, r, prob, names)
    est = {n: float(coef[n]) if coef[n] is not None else float(coef["mu_wire"])
           for n in PARAMS}
    ci_lo: dict[str, float] = {}
    ci_hi: dict[str, float] = {}
    se_d: dict[str, float] = {}
    dof_d: dict[str, float] = {}
    iid_d: dict[str, float] = {}
    keep = [j for j, n in enumerate(names) if ok[n]]
    corr = np.full((len(names), len(names)), np.nan)
    if keep:
        cov, dofs = _cluster_cov(jac[:, keep], theta[keep], r, prob.sample_pull,
                                 len(prob.pulls))
        se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        se_iid = standard_errors(lsq_covariance(jac[:, keep],
                                                residual_variance(r, len(keep))))
        q = 1.0 - 0.5 * (1.0 - prob.settings.confidence)
        with np.errstate(divide="ignore", invalid="ignore"):
            c = cov / np.outer(se, se)
        corr[np.ix_(keep, keep)] = c
        for i, j in enumerate(keep):
            n = names[j]
            t = float(stats.t.ppf(q, max(dofs[i], 1.0)))
            se_d[n], dof_d[n], iid_d[n] = float(se[i]), float(dofs[i]), float(se_iid[i])
            ci_lo[n], ci_hi[n] = theta[j] - t * se[i], theta[j] + t * se[i]
    ok, reason = _wide(ok, reason, names, theta, ci_lo, ci_hi)
    _clip_to_bounds(prob, z, lo, coef, ci_lo, ci_hi)
    for n in names:
        if not ok[n]:
            est[n] = math.nan
            for d in (ci_lo, ci_hi, se_d, dof_d, iid_d):
                d[n] = math.nan
    if not any(ok.values()):
        raise InputError(f"pulls: no coefficient is identifiable from these pulls ({reason})",
                         param="pulls")
    if reason:
        warnings.warn(IdentifiabilityWarning(f"fit_pullout: {reason}"), stacklevel=3)
    pred = r + prob.y
    pulls = tuple({"label": p.label, "pressure_mpa": p.pressure, "group": int(prob.gid[k]),
                   "displacement_mm": p.x, "force_n": p.f,
                   "model_n": pred[prob.sample_pull == k]}
                  for k, p in enumerate(prob.pulls))
    held = {n: float(v) if v is not None else float(coef["mu_wire"]) for n, v in coef.items()}
    return PulloutFit(
        estimate={n: float(v) for n, v in est.items()}, ci_low=ci_lo, ci_high=ci_hi,
        std_error=se_d, dof=dof_d, std_error_iid=iid_d, fitted=names, identifiable=ok,
        identifiability_reason=reason, held_at=held, condition_number=kappa,
        correlation=corr, plateau=_plateau_fit(prob, pred),
        rmse_n=float(np.sqrt(np.mean(r ** 2))), pressures_mpa=prob.pressures, pulls=pulls,
        ends=prob.ends, cable_ea_n=prob.ea, compliance_mm_per_n=prob.compliance,
        length_mm=float(prob.structure.length_mm), confidence=prob.settings.confidence,
        n_evaluations=prob.n_eval, notes=tuple(prob.notes))


def _clip_to_bounds(prob: _Problem, z: NDArray[np.float64], lo: NDArray[np.float64],
                    coef: dict[str, Any], ci_lo: dict[str, float],
                    ci_hi: dict[str, float]) -> None:
    """Intervals cut to the admissible range ([0, 2]; mu_static >= mu_wire), and a note for a
    coefficient the search left on a bound (its interval is then one-sided at best)."""
    for j, n in enumerate(prob.names):
        floor = float(coef["mu_wire"]) if n == "mu_static" else 0.0
        if n in ci_lo and math.isfinite(ci_lo[n]):
            ci_lo[n], ci_hi[n] = max(ci_lo[n], floor), min(ci_hi[n], 2.0)
        if z[j] <= lo[j] + 1e-9:
            prob.notes.append(f"{n} is at its lower bound ({float(coef[n]):.3g})"
                              + (": the pulls show no breakaway peak above the plateau"
                                 if n == "mu_static" else ""))
        elif n != "mu_static" and z[j] >= 2.0 - 1e-9:
            prob.notes.append(f"{n} is at its upper bound 2")


def _identifiable(jac: NDArray[np.float64], theta: NDArray[np.float64],
                  r: NDArray[np.float64], prob: _Problem, names: tuple[str, ...]
                  ) -> tuple[dict[str, bool], str, float]:
    """Per-coefficient verdict from the Jacobian: a vanishing column (the curves do not depend
    on it), or a near-null direction of the column-scaled Jacobian (kappa > KAPPA_MAX)."""
    ok = {n: True for n in names}
    why: list[str] = []
    norms = np.linalg.norm(jac, axis=0)
    # a coefficient that moves no force by more than 1e-6 x the rms force per 10 % of itself
    # (or per 0.01 absolute) does not enter the curves
    scale = float(np.sqrt(np.mean(prob.y ** 2))) * math.sqrt(prob.y.size)
    step = np.maximum(0.1 * np.abs(theta), 0.01)
    dead = norms * step <= 1e-6 * scale
    for j in np.flatnonzero(dead):
        ok[names[j]] = False
        why.append(f"{names[j]} does not change the force-displacement curves (e.g. mu_wall "
                   "while the tube-wall arc sticks)")
    live = np.flatnonzero(~dead)
    kappa = math.inf if dead.any() else 1.0
    if live.size:
        js = jac[:, live] / norms[live]
        _, sv, vt = np.linalg.svd(js, full_matrices=False)
        k_live = float(sv[0] / sv[-1]) if sv[-1] > 0 else math.inf
        kappa = k_live if not dead.any() else math.inf
        if k_live > KAPPA_MAX:
            v = np.abs(vt[-1])
            bad = [names[live[i]] for i in np.flatnonzero(v > 0.2)]
            for n in bad:
                ok[n] = False
            why.append(f"{' and '.join(bad)} are confounded (condition number {k_live:.3g} > "
                       f"{KAPPA_MAX:g}: only a combination is determined)")
    return ok, "; ".join(why), kappa


def _wide(ok: dict[str, bool], reason: str, names: tuple[str, ...],
          theta: NDArray[np.float64], lo: dict[str, float], hi: dict[str, float]
          ) -> tuple[dict[str, bool], str]:
    """Flag identifiable coefficients whose interval is wider than CI_REL_MAX of the value."""
    why = [reason] if reason else []
    for j, n in enumerate(names):
        if ok[n] and n in lo:
            half = 0.5 * (hi[n] - lo[n])
            if not half <= CI_REL_MAX * max(abs(float(theta[j])), 1e-12):
                ok = {**ok, n: False}
                why.append(f"{n}'s interval half-width {half:.3g} exceeds "
                           f"{100 * CI_REL_MAX:g} % of its value {theta[j]:.3g}")
    return ok, "; ".join(why)


def _cluster_cov(jac: NDArray[np.float64], theta: NDArray[np.float64],
                 r: NDArray[np.float64], codes: NDArray[np.intp], n_clusters: int
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pull-clustered CR2 covariance and Bell-McCaffrey dof of the linearised fit.

    The Gauss-Newton linearisation at the optimum is the OLS of the pseudo-data
    J theta - r on the design J (the residual e = data - model = -r), so the CR2 of
    :mod:`exofric.friction._fit` applies unchanged (its working variance |J theta| is then the
    linearised force).
    """
    from exofric.friction import _fit as fitmod

    cov, dof = fitmod._cr2_bm(jac, jac @ theta - r, theta, codes, n_clusters)
    return np.asarray(cov), np.asarray(dof)


def _plateau_fit(prob: _Problem, pred: NDArray[np.float64]) -> dict[str, Any]:
    """OLS of the plateau samples on L S_wire and L N (the linear part; a diagnostic).

    Plateau samples: the last quarter of the travel of each pull whose *fitted* curve is flat
    there (changes by < 2 %: the whole length slides); a pull still rising is left out (its
    force is below the sliding force). With ``mu_wire_wall`` given, L mu_wire_wall N is
    subtracted and only mu_wire is fitted. Pull-clustered CR1 standard errors (statsmodels'
    ``cov_type='cluster'``).
    """
    from exofric.friction import _fit as fitmod

    L = float(prob.structure.length_mm)
    s_w = np.array([sec.wire_pressure_integral_n_per_mm for sec in prob.sections]) * L
    n_w = np.array([sec.squeeze_force_n_per_mm for sec in prob.sections]) * L
    fit_ww = "mu_wire_wall" in prob.names
    out: dict[str, Any] = {"window_fraction": PLATEAU_WINDOW, "pulls_used": [],
                           "wire_pressure_integral_n": s_w.tolist(),
                           "squeeze_force_n": n_w.tolist(), "mu_wire": math.nan,
                           "se_cr1": [math.nan] * (2 if fit_ww else 1),
                           "condition_number": math.nan}
    if fit_ww:
        out["mu_wire_wall"] = math.nan
    sel = np.zeros(prob.y.size, dtype=bool)
    for k, p in enumerate(prob.pulls):
        m = prob.sample_pull == k
        w = m & (prob.x >= (1.0 - PLATEAU_WINDOW) * float(p.x.max()))
        fm = pred[w]
        if fm.size >= 3 and float(fm.max() - fm.min()) < 0.02 * max(float(fm.max()), 1e-12):
            sel |= w
            out["pulls_used"].append(p.label)
    g = prob.sample_group[sel]
    y = prob.y[sel]
    x = np.column_stack([s_w[g], n_w[g]]) if fit_ww else s_w[g][:, None]
    if not fit_ww:
        y = y - float(prob.fixed["mu_wire_wall"] or 0.0) * n_w[g]
    if len(out["pulls_used"]) <= x.shape[1] or np.unique(g).size < x.shape[1]:
        out["note"] = ("too few pulls reach the whole-length sliding within their travel "
                       "for the plateau regression")
        return out
    beta = np.asarray(np.linalg.lstsq(x, y, rcond=None)[0], dtype=np.float64)
    codes = np.unique(prob.sample_pull[sel], return_inverse=True)[1]
    cov = fitmod._cluster_covariance(x, y, beta, codes, int(codes.max()) + 1, "cr1")
    sv = np.linalg.svd(x / np.linalg.norm(x, axis=0), compute_uv=False)
    out.update({"mu_wire": float(beta[0]),
                "se_cr1": np.sqrt(np.clip(np.diag(cov), 0.0, None)).tolist(),
                "condition_number": float(sv[0] / sv[-1]) if sv[-1] > 0 else math.inf})
    if fit_ww:
        out["mu_wire_wall"] = float(beta[1])
    return out
