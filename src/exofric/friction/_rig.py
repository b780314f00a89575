"""A virtual friction rig: synthetic friction tests like the paper's platform (Sec. 3.2, Fig 3).

The paper publishes no raw friction curves, so examples and tests use this rig; its output is
always labelled SYNTHETIC. Units: time s, pressure MPa, displacement mm, force N.

What it simulates, per pressure step (and per repeat):

1. *settle* (``settle_s``): the regulator moves the tube pressure to the set point (first-order
   lag ``pressure_tau_s``); the wire is slack, so the load cell reads only its own error
   (offset + drift + noise). The second half of this window is the tare reading.
2. *pull* (``pull_s``): the wire is pulled at ``pull_speed_mm_per_s``; the force rises over the
   wire/fixture compliance (``ramp_mm``) and then slides at the true friction
   gamma_true N(P) + drag, where N(P) is the squeeze curve (PCHIP) and ``drag_n`` a
   pressure-independent drag (the F0 of the affine model; taring does not remove it).

The load cell adds zero-mean Gaussian noise with standard deviation ``noise_pct`` % of the true
force plus ``noise_n`` N, a constant ``offset_n`` and a drift ``drift_n_per_s`` x t; the
pressure sensor adds ``pressure_noise_mpa``. The logger samples at ``sample_rate_hz``.

The reduction is what one would do with real logs: per step, friction = mean force over the
steady sliding window (after the ramp plus ``discard_pct`` % of the sliding time) minus the tare
reading (if ``tare``), pressure = mean measured pressure over the same window.

All randomness comes from one ``numpy.random.Generator`` seeded with ``seed``: same inputs,
same output.

Examples
--------
>>> import numpy as np
>>> p = np.linspace(0.2, 0.6, 9); n = 400.0 * p
>>> run = simulate_rig(p, n, 0.7, seed=1)
>>> round(run.pressure_mpa[0], 4), abs(run.friction_n[0] / (0.7 * 80.0) - 1) < 0.01
(0.2, True)
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import (
    InputError,
    check_finite,
    check_positive,
    check_range,
    check_seed,
    check_series,
)
from exofric.friction._fit import match_squeeze
from exofric.friction._law import FrictionLaw, curve_column, law_columns

__all__ = ["RigConfig", "RigRun", "simulate_law_rig", "simulate_rig"]


@checked_init
@dataclass(frozen=True)
class RigConfig:
    """Settings of the virtual rig (s, mm/s, Hz, mm, %, N, N/s, MPa).

    Parameters
    ----------
    pull_speed_mm_per_s : float
        Wire pull speed in mm/s (> 0). Default 2 mm/s.
    sample_rate_hz : float
        Logger sample rate in Hz (1-1e5). Default 100 Hz.
    settle_s : float
        Settling time per pressure step before the pull, in s (> 0); its second half is the
        tare window. Default 2 s.
    pull_s : float
        Pull duration per step in s (> 0); the wire must slide for at least 2 samples after
        the ramp. Default 5 s.
    ramp_mm : float
        Wire/fixture compliance in mm (0-1000): pull distance over which the force rises to
        the sliding friction. Default 1 mm.
    discard_pct : float
        Share of the sliding time discarded at its start before averaging, in % (0-90).
        Default 10 %.
    pressure_tau_s : float
        Regulator lag time constant in s (0-1000; 0 for an instant step). Default 0.3 s.
    noise_pct : float
        Load-cell noise standard deviation in % of the true force (0-100). Default 2 %.
    noise_n : float
        Additional absolute load-cell noise standard deviation in N (>= 0). Default 0 N.
    offset_n : float
        Constant load-cell offset in N (removed by taring). Default 0 N.
    drift_n_per_s : float
        Load-cell drift in N/s (partly removed by taring). Default 0 N/s.
    drag_n : float
        Pressure-independent drag in N (>= 0; the F0 of the affine model, not removed by
        taring). Default 0 N.
    pressure_noise_mpa : float
        Pressure sensor noise standard deviation in MPa (0-1). Default 0 MPa.
    tare : bool
        Subtract the tare reading (slack wire) from each step's friction. Default True.

    Raises
    ------
    InputError
        A setting outside its range; the message names it.

    Examples
    --------
    >>> RigConfig(noise_pct=2.0).sample_rate_hz
    100.0
    """

    pull_speed_mm_per_s: float = 2.0
    sample_rate_hz: float = 100.0
    settle_s: float = 2.0
    pull_s: float = 5.0
    ramp_mm: float = 1.0
    discard_pct: float = 10.0
    pressure_tau_s: float = 0.3
    noise_pct: float = 2.0
    noise_n: float = 0.0
    offset_n: float = 0.0
    drift_n_per_s: float = 0.0
    drag_n: float = 0.0
    pressure_noise_mpa: float = 0.0
    tare: bool = True

    def __post_init__(self) -> None:
        check_positive("pull_speed_mm_per_s", self.pull_speed_mm_per_s, "mm/s")
        check_range("sample_rate_hz", self.sample_rate_hz, 1.0, 1e5, unit="Hz")
        check_positive("settle_s", self.settle_s, "s")
        check_positive("pull_s", self.pull_s, "s")
        check_range("ramp_mm", self.ramp_mm, 0.0, 1e3, unit="mm")
        check_range("discard_pct", self.discard_pct, 0.0, 90.0, unit="%")
        check_range("pressure_tau_s", self.pressure_tau_s, 0.0, 1e3, unit="s")
        check_range("noise_pct", self.noise_pct, 0.0, 100.0, unit="%")
        check_range("noise_n", self.noise_n, 0.0, 1e6, unit="N")
        check_finite("offset_n", self.offset_n)
        check_finite("drift_n_per_s", self.drift_n_per_s)
        check_range("drag_n", self.drag_n, 0.0, 1e6, unit="N")
        check_range("pressure_noise_mpa", self.pressure_noise_mpa, 0.0, 1.0, unit="MPa")
        slide_s = self.pull_s - self.ramp_mm / self.pull_speed_mm_per_s
        n_win = slide_s * (1.0 - self.discard_pct / 100.0) * self.sample_rate_hz
        if n_win < 2:
            raise InputError(
                "pull_s is too short: the wire must slide (after ramp_mm at pull_speed_mm_per_s) "
                "for at least 2 logger samples"
            )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready settings (unit-suffixed keys)."""
        return dict(asdict(self))


@checked_init
@dataclass(frozen=True)
class RigRun(DisplayMixin):
    """A synthetic friction test: raw logs and one friction value per pressure step.

    Attributes
    ----------
    test : tuple of str
        Repeat label per reduced point (``"1"``, ``"2"``, ...).
    pressure_mpa, friction_n : tuple of float
        Reduced points (MPa, N), what a real analysis would write.
    true_friction_n : tuple of float
        gamma_true N(P) + drag at the set points (N), for checking.
    gamma_true : float
        The planted equivalent coefficient (unitless).
    seed : int
        Seed of the random generator used.
    config : RigConfig
        The rig settings used.
    time_s, raw_pressure_mpa, raw_force_n, displacement_mm : ndarray
        The logger record (s, MPa, N, mm); not compared or serialised.

    Examples
    --------
    >>> run = simulate_rig([0.2, 0.4, 0.6], [80.0, 160.0, 240.0], 0.5, seed=3, repeats=2)
    >>> run.test, [round(f, 9) for f in run.true_friction_n[:3]]     # gamma_true N(P), N
    (('1', '1', '1', '2', '2', '2'), [40.0, 80.0, 120.0])
    >>> run.to_csv_text().splitlines()[3]
    'test,pressure_mpa,friction_n'
    """

    test: tuple[str, ...]
    pressure_mpa: tuple[float, ...]
    friction_n: tuple[float, ...]
    true_friction_n: tuple[float, ...]
    gamma_true: float
    seed: int
    config: RigConfig
    time_s: NDArray[np.float64] = field(repr=False, compare=False)
    raw_pressure_mpa: NDArray[np.float64] = field(repr=False, compare=False)
    raw_force_n: NDArray[np.float64] = field(repr=False, compare=False)
    displacement_mm: NDArray[np.float64] = field(repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (reduced points, settings; no raw logs)."""
        return {
            "synthetic": True,
            "gamma_true": self.gamma_true,
            "seed": self.seed,
            "n_points": len(self.pressure_mpa),
            "n_samples": int(self.time_s.size),
            "duration_s": float(self.time_s[-1]) if self.time_s.size else 0.0,
            "test": list(self.test),
            "pressure_mpa": list(self.pressure_mpa),
            "friction_n": list(self.friction_n),
            "true_friction_n": list(self.true_friction_n),
            "config": self.config.to_dict(),
        }

    def to_csv_text(self) -> str:
        """The rig CSV (``pressure_mpa,friction_n`` [+ ``test``]) with a SYNTHETIC header."""
        c = self.config
        lines = [
            "# SYNTHETIC friction data from the exofric virtual rig (simulate_rig); NOT measured.",
            f"# gamma_true={self.gamma_true:g} seed={self.seed} noise_pct={c.noise_pct:g} "
            f"noise_n={c.noise_n:g} offset_n={c.offset_n:g} drift_n_per_s={c.drift_n_per_s:g} "
            f"drag_n={c.drag_n:g} pressure_noise_mpa={c.pressure_noise_mpa:g} tare={c.tare}",
            f"# logger {c.sample_rate_hz:g} Hz, pull {c.pull_speed_mm_per_s:g} mm/s for "
            f"{c.pull_s:g} s after {c.settle_s:g} s settling; units: MPa, N",
        ]
        multi = len(set(self.test)) > 1
        lines.append("test,pressure_mpa,friction_n" if multi else "pressure_mpa,friction_n")
        for t, p, f in zip(self.test, self.pressure_mpa, self.friction_n, strict=True):
            row = f"{p:.5f},{f:.4f}"
            lines.append(f"{t},{row}" if multi else row)
        return "\n".join(lines) + "\n"


def rig_set_points(
    squeeze_pressure_mpa: ArrayLike, squeeze_force_n: ArrayLike, pressures_mpa: ArrayLike | None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
           NDArray[np.float64]]:
    """The checked squeeze curve (MPa, N), the rig's set points (MPa) and N at them (N).

    Set points default to the curve's pressures with N > 0; they must be strictly increasing
    and inside the curve's range (InputError otherwise). Shared by both virtual rigs.
    """
    ps, ns = check_series("squeeze_pressure_mpa", squeeze_pressure_mpa, "squeeze_force_n",
                          squeeze_force_n, x_unit="MPa", y_unit="N")
    sp = ps[ns > 0.0] if pressures_mpa is None else np.asarray(pressures_mpa, float).ravel()
    if sp.size == 0:
        raise InputError("rig needs at least one pressure set point with squeeze force > 0")
    sp, _ = check_series("pressures_mpa", sp, x_unit="MPa", min_points=1,
                         where="rig set points")
    n_set, inside = match_squeeze(ps, ns, sp, edge_tol_mpa=0.0)
    if not np.all(inside):
        raise InputError(f"rig set point {sp[~inside][0]:g} MPa is outside the squeeze curve's "
                         f"range [{ps.min():g}, {ps.max():g}] MPa")
    return ps, ns, sp, n_set


def simulate_rig(
    squeeze_pressure_mpa: ArrayLike,
    squeeze_force_n: ArrayLike,
    gamma_true: float,
    pressures_mpa: ArrayLike | None = None,
    *,
    config: RigConfig | None = None,
    seed: int = 0,
    repeats: int = 1,
) -> RigRun:
    """Simulate friction tests on the virtual rig (see module docstring).

    Parameters
    ----------
    squeeze_pressure_mpa, squeeze_force_n : array_like
        The squeeze curve N(P) (MPa, N total), e.g. from ``exofric squeeze``.
    gamma_true : float
        The planted equivalent coefficient (unitless, > 0).
    pressures_mpa : array_like, optional
        Pressure set points (MPa, strictly increasing, inside the curve's range); default:
        the curve's pressures where N > 0.
    config : RigConfig, optional
        Rig, logger and sensor settings.
    seed : int
        Seed of the ``numpy.random.Generator`` (deterministic output).
    repeats : int
        Number of repeated tests (labelled ``"1"``, ``"2"``, ...; a ``test`` column is
        written when > 1).

    Returns
    -------
    RigRun

    Raises
    ------
    InputError
        Invalid curve, gamma_true <= 0, repeats outside 1-100, or set points outside the
        curve's pressure range.

    Examples
    --------
    >>> run = simulate_rig([0.2, 0.4, 0.6], [80.0, 160.0, 240.0], 0.7, seed=1,
    ...                    config=RigConfig(noise_pct=0.0, pressure_tau_s=0.0))  # ideal
    >>> [round(f, 6) for f in run.friction_n]
    [56.0, 112.0, 168.0]
    >>> run.time_s.size            # 3 steps x (2 s settling + 5 s pull) at 100 Hz
    2100
    """
    cfg = config or RigConfig()
    g = check_positive("gamma_true", gamma_true)
    seed = check_seed("seed", seed)
    if not isinstance(repeats, int) or not 1 <= repeats <= 100:
        raise InputError(f"repeats must be an integer in [1, 100], got {repeats!r}")
    ps, ns, sp, n_set = rig_set_points(squeeze_pressure_mpa, squeeze_force_n, pressures_mpa)
    rng = np.random.default_rng(seed)
    fs = cfg.sample_rate_hz
    n_settle = int(round(cfg.settle_s * fs))
    n_pull = int(round(cfg.pull_s * fs))
    m = n_settle + n_pull
    steps = np.tile(sp, repeats)
    k = steps.size
    # Sample grid: (k steps, m samples); global time runs on across steps and repeats.
    local = np.arange(m) / fs
    t = (np.arange(k)[:, None] * m + np.arange(m)[None, :]) / fs
    prev = np.concatenate([[0.0], steps[:-1]])
    prev[:: sp.size] = 0.0                    # every repeat starts from a vented tube
    lag = (1.0 - np.exp(-local / cfg.pressure_tau_s)) if cfg.pressure_tau_s > 0 else 1.0
    p_true = np.broadcast_to(prev[:, None] + (steps - prev)[:, None] * lag, (k, m))
    x = np.clip((local - cfg.settle_s) * cfg.pull_speed_mm_per_s, 0.0, None)[None, :]
    engage = np.clip(x / cfg.ramp_mm, 0.0, 1.0) if cfg.ramp_mm > 0 else (x > 0).astype(float)
    p_clip = np.clip(p_true, ps.min(), ps.max()).ravel()
    n_now, _ = match_squeeze(ps, ns, p_clip, edge_tol_mpa=0.0)
    f_slide = g * n_now.reshape(k, m) + cfg.drag_n
    f_true = engage * f_slide
    noise_sd = cfg.noise_pct / 100.0 * np.abs(f_true) + cfg.noise_n
    f_meas = (f_true + cfg.offset_n + cfg.drift_n_per_s * t
              + noise_sd * rng.standard_normal((k, m)))
    p_meas = p_true + cfg.pressure_noise_mpa * rng.standard_normal((k, m))
    # Reduction: steady sliding window and tare window (second half of settling).
    slide_start = cfg.settle_s + cfg.ramp_mm / cfg.pull_speed_mm_per_s
    slide_start += (cfg.pull_s - (slide_start - cfg.settle_s)) * cfg.discard_pct / 100.0
    win = local >= slide_start - 1e-12
    tare_win = (local >= 0.5 * cfg.settle_s) & (local < cfg.settle_s)
    friction = f_meas[:, win].mean(axis=1)
    if cfg.tare:
        friction = friction - f_meas[:, tare_win].mean(axis=1)
    pressure = p_meas[:, win].mean(axis=1)
    labels = np.repeat(np.arange(1, repeats + 1), sp.size).astype(str)
    return RigRun(
        test=tuple(labels.tolist()),
        pressure_mpa=tuple(np.round(pressure, 12).tolist()),
        friction_n=tuple(friction.tolist()),
        true_friction_n=tuple(np.tile(g * n_set + cfg.drag_n, repeats).tolist()),
        gamma_true=g,
        seed=int(seed),
        config=cfg,
        time_s=t.ravel(),
        raw_pressure_mpa=p_meas.ravel(),
        raw_force_n=f_meas.ravel(),
        displacement_mm=np.broadcast_to(x, (k, m)).ravel().copy(),
    )


def simulate_law_rig(
    law: FrictionLaw,
    curves: Any,
    pressures_mpa: ArrayLike | None = None,
    *,
    config: RigConfig | None = None,
    seed: int = 0,
    repeats: int = 1,
) -> RigRun:
    """The virtual rig (:func:`simulate_rig`) planting any friction law on FE curves.

    The planted friction curve is the law's F (N) at the curves' nodes (plus the rig's
    ``drag_n``), interpolated by PCHIP between them; noise, lag, taring and reduction are
    :func:`simulate_rig`'s. The run's ``gamma_true`` is 1: the curve already is the friction.

    Parameters
    ----------
    law : FrictionLaw
        The planted law (:class:`~exofric.friction.FrictionModel`,
        :class:`~exofric.friction.InterfaceFrictionModel` or any other).
    curves : object or mapping
        ``pressure_mpa`` (MPa, strictly increasing), ``squeeze_force_n`` (N) and the law's
        other inputs (N) at the nodes, e.g. a :class:`~exofric.friction.SqueezeCurve` or
        :class:`~exofric.friction.InterfaceCurves`.
    pressures_mpa : array_like, optional
        Set points (MPa, strictly increasing, inside the curves); default the nodes where the
        squeezing force is > 0.
    config : RigConfig, optional
        Rig, logger and sensor settings.
    seed : int
        RNG seed (deterministic output).
    repeats : int
        Repeated tests (1-100).

    Returns
    -------
    RigRun

    Raises
    ------
    InputError
        A curve the law needs is missing, or as :func:`simulate_rig`.

    Examples
    --------
    >>> from exofric.friction import FrictionModel, SqueezeCurve
    >>> run = simulate_law_rig(FrictionModel(0.7), SqueezeCurve([0.2, 0.4, 0.6],
    ...                        [80.0, 160.0, 240.0]), config=RigConfig(noise_pct=0.0,
    ...                        pressure_tau_s=0.0))
    >>> [round(f, 6) for f in run.friction_n]
    [56.0, 112.0, 168.0]
    """
    cols = law_columns(law, curves)
    if pressures_mpa is None:
        n = curve_column(curves, "squeeze_force_n", law.name, size=cols["pressure_mpa"].size)
        pressures_mpa = cols["pressure_mpa"][n > 0]
    return simulate_rig(cols["pressure_mpa"], law.friction_of(cols), 1.0, pressures_mpa,
                        config=config, seed=seed, repeats=repeats)
