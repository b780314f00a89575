"""A virtual friction rig that writes raw logs: time series with planted truths (paper Sec. 3.2).

:func:`simulate_rig` gives one reduced friction value per pressure step; this module gives what a
real rig's computer records: time (s), pressure (MPa), load-cell force (N) and wire displacement
(mm), sampled at ``sample_rate_hz``, so that :func:`exofric.friction.reduce_log` can be tested on
data whose answer is known. Everything is labelled SYNTHETIC.

The schedule (one *plateau* per pressure set point; ``sweep="up-down"`` goes back down through
every set point but the highest, a second *branch*):

1. the regulator moves the tube pressure to the set point (first-order lag ``pressure_tau_s``)
   while the wire rests for ``settle_s``;
2. ``replicates`` times: a pull of ``pull_mm`` at ``pull_speed_mm_per_s`` in each direction of
   ``directions`` (forward: force positive, displacement growing; backward: the reverse), each
   followed by a rest of ``rest_s`` with the wire slack.

The force of one pull, against its travel x (mm), with kinetic friction F_k and static
(breakaway) friction F_s = ``static_ratio`` F_k:

* x < ``ramp_mm``: the wire and fixture stretch, F rises linearly to F_s at x = ``ramp_mm``;
* then breakaway: F = F_k + (F_s - F_k) exp(-(x - ramp_mm) / ``breakaway_mm``), plus a zero-mean
  saw-tooth stick-slip (zero at the peak) of amplitude ``stick_slip_pct`` % of F_k and period
  ``stick_slip_mm``;
* after the pull the wire relaxes to zero force with a 0.05 s time constant.

Truth per pull: F_k = (gamma_true N(P_set) (1 + h) + ``drag_n``) (1 + e_plateau)(1 + e_pull), with
h = ``hysteresis_pct`` / 100 on the down branch (0 on the up branch), e_plateau ~ N(0,
``plateau_scatter_pct`` %) shared by the pulls of one plateau and e_pull ~ N(0,
``pull_scatter_pct`` %) per pull: between-pull scatter, which real rigs show and which is why
gamma's interval must treat the pulls of one plateau as a cluster.

The load cell reads direction x F + ``bias_n`` (gravity: same sign both ways, only while the wire
moves) + ``tare_offset_n`` + ``drift_n_per_s`` t + noise. The noise is Gaussian AR(1) with
correlation time ``noise_tau_s`` and standard deviation ``noise_n`` + ``noise_pct`` % of |F|. The
pressure sensor adds white noise ``pressure_noise_mpa``. One ``numpy.random.Generator`` seeded
with ``seed`` drives everything: same inputs, same log.

Examples
--------
>>> log = simulate_raw_log([0.2, 0.4, 0.6], [80.0, 160.0, 240.0], 0.7, seed=1)
>>> log.n_pulls, log.to_frame().columns.tolist()
(30, ['time_s', 'pressure_mpa', 'force_n', 'displacement_mm'])
>>> round(float(log.truth_frame()["kinetic_n"].iloc[0]) / (0.7 * 80.0), 1)   # scatter ~2 %
1.0
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_finite, check_positive, check_range, check_seed
from exofric.friction._rig import rig_set_points

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["RawRigConfig", "RawRigLog", "simulate_raw_log"]

_RELAX_S = 0.05          # wire relaxation time constant after a pull stops (s)


@checked_init
@dataclass(frozen=True)
class RawRigConfig:
    """Settings of the raw-log virtual rig (s, Hz, mm, mm/s, N, N/s, MPa, %).

    Parameters
    ----------
    sample_rate_hz : float
        Logger rate in Hz (10-1e5). Default 500 Hz.
    pull_speed_mm_per_s : float
        Wire speed during a pull in mm/s (> 0). Default 2 mm/s.
    pull_mm : float
        Travel of one pull in mm (> ramp_mm + 3 breakaway_mm). Default 10 mm.
    settle_s : float
        Rest after each pressure change, before the first pull, in s (> 0). Default 2 s.
    rest_s : float
        Rest after each pull in s (> 0; the tare windows). Default 1 s.
    replicates : int
        Pulls per direction and plateau (1-100). Default 5.
    directions : {"both", "forward"}
        Pull forward then backward (both) or forward only. Default both.
    sweep : {"up", "up-down"}
        Set points in increasing order, or up then back down (two branches). Default up.
    static_ratio : float
        Static (breakaway) over kinetic friction (1-10). Default 1.3.
    ramp_mm, breakaway_mm : float
        Travel over which the force rises to the breakaway peak, and decay length from the peak
        to kinetic friction, in mm (> 0). Defaults 0.5 mm and 0.3 mm.
    stick_slip_pct, stick_slip_mm : float
        Saw-tooth stick-slip amplitude in % of kinetic friction (0-50) and its period in mm
        (> 0). Defaults 1 % and 0.5 mm.
    noise_n, noise_pct : float
        Load-cell noise standard deviation: N (>= 0) plus % of |F| (0-100). Defaults 0.1 N, 0.3 % (a
        500 N load cell on a 24-bit logger).
    noise_tau_s : float
        Correlation time of the AR(1) load-cell noise in s (0 for white noise). Default 0.02 s.
    tare_offset_n : float
        Load-cell zero offset in N (removed by taring). Default 5 N.
    drift_n_per_s : float
        Load-cell drift in N/s (removed by taring before and after each pull). Default 0.01 N/s.
    bias_n : float
        Force of constant sign while the wire moves (gravity) in N; removed by pairing the two
        directions. Default 1.5 N.
    drag_n : float
        Pressure-independent drag in N (>= 0; follows the direction like friction: the F0 of
        the affine model). Default 0 N.
    hysteresis_pct : float
        Down-branch friction above the up branch's at the same set point, in % (-50-100).
        Default 0 %.
    pull_scatter_pct, plateau_scatter_pct : float
        Standard deviations of the per-pull and per-plateau friction scatter in % (0-50).
        Defaults 1.5 % and 1 %.
    pressure_tau_s : float
        Regulator time constant in s (0-1000; 0 for an instant step). Default 0.3 s.
    pressure_noise_mpa : float
        Pressure sensor noise standard deviation in MPa (0-1). Default 0.002 MPa.

    Raises
    ------
    InputError
        A setting outside its range; the message names it.

    Examples
    --------
    >>> RawRigConfig(replicates=3).pull_s
    5.0
    """

    sample_rate_hz: float = 500.0
    pull_speed_mm_per_s: float = 2.0
    pull_mm: float = 10.0
    settle_s: float = 2.0
    rest_s: float = 1.0
    replicates: int = 5
    directions: Literal["both", "forward"] = "both"
    sweep: Literal["up", "up-down"] = "up"
    static_ratio: float = 1.3
    ramp_mm: float = 0.5
    breakaway_mm: float = 0.3
    stick_slip_pct: float = 1.0
    stick_slip_mm: float = 0.5
    noise_n: float = 0.1
    noise_pct: float = 0.3
    noise_tau_s: float = 0.02
    tare_offset_n: float = 5.0
    drift_n_per_s: float = 0.01
    bias_n: float = 1.5
    drag_n: float = 0.0
    hysteresis_pct: float = 0.0
    pull_scatter_pct: float = 1.5
    plateau_scatter_pct: float = 1.0
    pressure_tau_s: float = 0.3
    pressure_noise_mpa: float = 0.002

    def __post_init__(self) -> None:
        check_range("sample_rate_hz", self.sample_rate_hz, 10.0, 1e5, unit="Hz")
        check_positive("pull_speed_mm_per_s", self.pull_speed_mm_per_s, "mm/s")
        check_positive("pull_mm", self.pull_mm, "mm")
        check_positive("settle_s", self.settle_s, "s")
        check_positive("rest_s", self.rest_s, "s")
        if not isinstance(self.replicates, int) or not 1 <= self.replicates <= 100:
            raise InputError(f"replicates must be an integer in [1, 100], got "
                             f"{self.replicates!r}")
        if self.directions not in ("both", "forward"):
            raise InputError(f"directions must be 'both' or 'forward', got {self.directions!r}")
        if self.sweep not in ("up", "up-down"):
            raise InputError(f"sweep must be 'up' or 'up-down', got {self.sweep!r}")
        check_range("static_ratio", self.static_ratio, 1.0, 10.0)
        check_positive("ramp_mm", self.ramp_mm, "mm")
        check_positive("breakaway_mm", self.breakaway_mm, "mm")
        check_range("stick_slip_pct", self.stick_slip_pct, 0.0, 50.0, unit="%")
        check_positive("stick_slip_mm", self.stick_slip_mm, "mm")
        check_range("noise_n", self.noise_n, 0.0, 1e6, unit="N")
        check_range("noise_pct", self.noise_pct, 0.0, 100.0, unit="%")
        check_range("noise_tau_s", self.noise_tau_s, 0.0, 100.0, unit="s")
        check_finite("tare_offset_n", self.tare_offset_n)
        check_finite("drift_n_per_s", self.drift_n_per_s)
        check_finite("bias_n", self.bias_n)
        check_range("drag_n", self.drag_n, 0.0, 1e6, unit="N")
        check_range("hysteresis_pct", self.hysteresis_pct, -50.0, 100.0, unit="%")
        check_range("pull_scatter_pct", self.pull_scatter_pct, 0.0, 50.0, unit="%")
        check_range("plateau_scatter_pct", self.plateau_scatter_pct, 0.0, 50.0, unit="%")
        check_range("pressure_tau_s", self.pressure_tau_s, 0.0, 1e3, unit="s")
        check_range("pressure_noise_mpa", self.pressure_noise_mpa, 0.0, 1.0, unit="MPa")
        if self.pull_mm <= self.ramp_mm + 3.0 * self.breakaway_mm:
            raise InputError(f"pull_mm must exceed ramp_mm + 3 breakaway_mm = "
                             f"{self.ramp_mm + 3 * self.breakaway_mm:g} mm (the wire must "
                             f"slide), got {self.pull_mm:g}")

    @property
    def pull_s(self) -> float:
        """Duration of one pull in s (pull_mm / pull_speed_mm_per_s)."""
        return self.pull_mm / self.pull_speed_mm_per_s

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready settings (unit-suffixed keys)."""
        return dict(asdict(self))


@checked_init
@dataclass(frozen=True)
class RawRigLog(DisplayMixin):
    """A synthetic raw rig log and the truths planted in it.

    Attributes
    ----------
    time_s, pressure_mpa, force_n, displacement_mm : ndarray
        The logger record (s, MPa, N, mm).
    gamma_true : float
        The planted equivalent coefficient (unitless) of the up branch.
    setpoints_mpa : tuple of float
        The plateaus' set points in schedule order (MPa).
    pulls : tuple of dict
        Per pull: ``pull``, ``plateau`` (1-based), ``setpoint_mpa``, ``branch``, ``direction``
        (``"forward"``/``"backward"``), ``t_start_s``, ``t_end_s``, ``kinetic_n`` and
        ``static_n`` (true friction magnitudes, N).
    config : RawRigConfig
    seed : int

    Examples
    --------
    >>> log = simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=2,
    ...                        config=RawRigConfig(replicates=1, directions="forward"))
    >>> [p["direction"] for p in log.pulls], log.setpoints_mpa
    (['forward', 'forward'], (0.2, 0.6))
    """

    time_s: NDArray[np.float64] = field(repr=False, compare=False)
    pressure_mpa: NDArray[np.float64] = field(repr=False, compare=False)
    force_n: NDArray[np.float64] = field(repr=False, compare=False)
    displacement_mm: NDArray[np.float64] = field(repr=False, compare=False)
    gamma_true: float
    setpoints_mpa: tuple[float, ...]
    pulls: tuple[dict[str, Any], ...]
    config: RawRigConfig
    seed: int

    @property
    def n_pulls(self) -> int:
        """Number of pulls in the log."""
        return len(self.pulls)

    def to_frame(self) -> pd.DataFrame:
        """The raw log: ``time_s``, ``pressure_mpa``, ``force_n``, ``displacement_mm``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> log = simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=2)
        >>> len(log.to_frame()) == log.time_s.size
        True
        """
        import pandas as pd

        return pd.DataFrame({"time_s": self.time_s, "pressure_mpa": self.pressure_mpa,
                             "force_n": self.force_n, "displacement_mm": self.displacement_mm})

    def truth_frame(self) -> pd.DataFrame:
        """The planted truth per pull (one row per pull; MPa, s, N).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> log = simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=2)
        >>> log.truth_frame().columns.tolist()[:3]
        ['pull', 'plateau', 'setpoint_mpa']
        """
        import pandas as pd

        return pd.DataFrame(list(self.pulls))

    def metadata(self) -> list[str]:
        """Provenance lines for the log file's header (SYNTHETIC, seed, planted truths)."""
        c = self.config
        return [
            "SYNTHETIC raw friction-rig log from the exofric virtual rig (simulate_raw_log); "
            "NOT measured.",
            f"gamma_true={self.gamma_true:g} seed={self.seed} static_ratio={c.static_ratio:g} "
            f"tare_offset_n={c.tare_offset_n:g} drift_n_per_s={c.drift_n_per_s:g} "
            f"bias_n={c.bias_n:g} drag_n={c.drag_n:g} hysteresis_pct={c.hysteresis_pct:g}",
            f"logger {c.sample_rate_hz:g} Hz; {c.replicates} pull(s) of {c.pull_mm:g} mm at "
            f"{c.pull_speed_mm_per_s:g} mm/s per direction ({c.directions}) and plateau; "
            f"sweep {c.sweep}; units: s, MPa, N, mm",
        ]

    def to_dict(self) -> dict[str, Any]:
        """The planted truths, JSON-ready (the sidecar of ``exofric rig --raw``)."""
        return {
            "synthetic": True,
            "gamma_true": self.gamma_true,
            "seed": self.seed,
            "n_samples": int(self.time_s.size),
            "duration_s": float(self.time_s[-1]),
            "setpoints_mpa": list(self.setpoints_mpa),
            "static_ratio": self.config.static_ratio,
            "tare_offset_n": self.config.tare_offset_n,
            "drift_n_per_s": self.config.drift_n_per_s,
            "bias_n": self.config.bias_n,
            "hysteresis_pct": self.config.hysteresis_pct,
            "pulls": [dict(p) for p in self.pulls],
            "config": self.config.to_dict(),
        }


def _ar1(rng: np.random.Generator, n: int, tau_s: float, fs: float) -> NDArray[np.float64]:
    """Unit-variance stationary AR(1) noise with correlation time tau_s (white if 0)."""
    from scipy.signal import lfilter

    e = rng.standard_normal(n)
    if tau_s <= 0:
        return e
    phi = float(np.exp(-1.0 / (tau_s * fs)))
    out = lfilter([np.sqrt(1.0 - phi * phi)], [1.0, -phi], e, zi=[phi * e[0]])[0]
    return np.asarray(out, dtype=float)


def simulate_raw_log(
    squeeze_pressure_mpa: ArrayLike,
    squeeze_force_n: ArrayLike,
    gamma_true: float,
    pressures_mpa: ArrayLike | None = None,
    *,
    config: RawRigConfig | None = None,
    seed: int = 0,
) -> RawRigLog:
    """Simulate a raw friction-rig log with planted truths (see module docstring).

    Parameters
    ----------
    squeeze_pressure_mpa, squeeze_force_n : array_like
        The squeeze curve N(P) (MPa, N total), e.g. from ``exofric squeeze``.
    gamma_true : float
        The planted equivalent coefficient (unitless, > 0).
    pressures_mpa : array_like, optional
        Set points (MPa, strictly increasing, inside the curve's range); default: the curve's
        pressures where N > 0.
    config : RawRigConfig, optional
        Schedule, friction, sensor and noise settings.
    seed : int
        Seed of the ``numpy.random.Generator`` (deterministic output).

    Returns
    -------
    RawRigLog

    Raises
    ------
    InputError
        Invalid curve, gamma_true <= 0, or set points outside the curve's range.

    Examples
    --------
    >>> log = simulate_raw_log([0.2, 0.4], [80.0, 160.0], 0.7, seed=0,
    ...                        config=RawRigConfig(replicates=2))
    >>> log.n_pulls, round(float(log.time_s[1]), 3)      # 2 plateaus x 2 x 2 directions; 500 Hz
    (8, 0.002)
    """
    cfg = config or RawRigConfig()
    g = check_positive("gamma_true", gamma_true)
    seed = check_seed("seed", seed)
    _, _, sp, n_set = rig_set_points(squeeze_pressure_mpa, squeeze_force_n, pressures_mpa)
    rng = np.random.default_rng(seed)
    fs = cfg.sample_rate_hz
    order = list(range(sp.size))
    if cfg.sweep == "up-down":
        order += list(range(sp.size - 2, -1, -1))
    branches = ["up"] * sp.size + ["down"] * (len(order) - sp.size)
    dirs = (1, -1) if cfg.directions == "both" else (1,)
    n_settle = int(round(cfg.settle_s * fs))
    n_pull = int(round(cfg.pull_s * fs))
    n_rest = int(round(cfg.rest_s * fs))
    # Build the schedule as sample-index segments; everything else is vectorised on them.
    setpoint = []                   # per sample: set point (MPa)
    pulls: list[dict[str, Any]] = []
    pull_rows = []                  # (first sample, direction, F_k, F_s)
    k = 0
    plateau_eff = rng.standard_normal(len(order)) * cfg.plateau_scatter_pct / 100.0
    n_per_plateau = cfg.replicates * len(dirs)
    pull_eff = rng.standard_normal((len(order), n_per_plateau)) * cfg.pull_scatter_pct / 100.0
    for j, (i, branch) in enumerate(zip(order, branches, strict=True)):
        setpoint.append(np.full(n_settle, sp[i]))
        k += n_settle
        h = cfg.hysteresis_pct / 100.0 if branch == "down" else 0.0
        base = (g * n_set[i] * (1.0 + h) + cfg.drag_n) * (1.0 + plateau_eff[j])
        for r in range(cfg.replicates):
            for m, d in enumerate(dirs):
                fk = base * (1.0 + pull_eff[j, r * len(dirs) + m])
                pull_rows.append((k, d, fk, cfg.static_ratio * fk))
                pulls.append({
                    "pull": len(pulls) + 1, "plateau": j + 1, "setpoint_mpa": float(sp[i]),
                    "branch": branch, "direction": "forward" if d > 0 else "backward",
                    "t_start_s": k / fs, "t_end_s": (k + n_pull) / fs,
                    "kinetic_n": float(fk), "static_n": float(cfg.static_ratio * fk),
                })
                setpoint.append(np.full(n_pull + n_rest, sp[i]))
                k += n_pull + n_rest
    n = k
    t = np.arange(n) / fs
    sp_t = np.concatenate(setpoint)
    if cfg.pressure_tau_s > 0:
        from scipy.signal import lfilter

        a = float(np.exp(-1.0 / (cfg.pressure_tau_s * fs)))
        p_true = np.asarray(lfilter([1.0 - a], [1.0, -a], sp_t, zi=[0.0])[0], dtype=float)
    else:
        p_true = sp_t
    # Force and displacement: per pull, a travel profile on its samples (vectorised per pull).
    f_true = np.zeros(n)
    moving = np.zeros(n)
    velocity = np.zeros(n)
    x_loc = np.arange(n_pull) / fs * cfg.pull_speed_mm_per_s
    after = np.arange(n_rest) / fs
    for k0, d, fk, fstat in pull_rows:
        slide = x_loc - cfg.ramp_mm
        u = slide / cfg.stick_slip_mm + 0.5          # phase: zero at the breakaway peak
        saw = 2.0 * (u - np.floor(u)) - 1.0
        prof = np.where(
            x_loc < cfg.ramp_mm, fstat * x_loc / cfg.ramp_mm,
            fk + (fstat - fk) * np.exp(-np.maximum(slide, 0.0) / cfg.breakaway_mm)
            + cfg.stick_slip_pct / 100.0 * fk * saw)
        f_true[k0:k0 + n_pull] = d * prof
        f_true[k0 + n_pull:k0 + n_pull + n_rest] = d * prof[-1] * np.exp(-after / _RELAX_S)
        moving[k0:k0 + n_pull] = 1.0
        velocity[k0:k0 + n_pull] = d * cfg.pull_speed_mm_per_s
    disp = np.concatenate([[0.0], np.cumsum(velocity[:-1]) / fs])
    noise_sd = cfg.noise_n + cfg.noise_pct / 100.0 * np.abs(f_true)
    force = (f_true + cfg.bias_n * moving + cfg.tare_offset_n + cfg.drift_n_per_s * t
             + noise_sd * _ar1(rng, n, cfg.noise_tau_s, fs))
    pressure = p_true + cfg.pressure_noise_mpa * rng.standard_normal(n)
    return RawRigLog(
        time_s=t, pressure_mpa=pressure, force_n=force, displacement_mm=disp,
        gamma_true=g, setpoints_mpa=tuple(float(sp[i]) for i in order),
        pulls=tuple(pulls), config=cfg, seed=int(seed),
    )
