"""Reduce a raw friction-rig log to pulls and a friction curve (paper Sec. 3.2, Fig 3).

A rig log is a time series (s) of tube pressure (MPa), load-cell force (N) and, optionally,
wire displacement (mm): the tube is inflated to a set point, then the wire is pulled at constant
speed, several times, maybe in both directions. :func:`reduce_log` finds, without being told:

* **pressure plateaus**: stretches of at least ``min_plateau_s`` where the smoothed pressure
  moves less than max(``plateau_tol_mpa``, ``plateau_tol_rel`` x level) over that time and
  whose linear drift over the whole stretch stays within twice that band (a slow steady ramp is
  no plateau: a log that only ramps is an error). Plateaus at one level are one *set point*; a
  plateau reached from above is on the *down* branch.
* **pulls**: from the displacement speed when there is a displacement column (faster than
  ``speed_fraction`` of the log's typical speed; the sign gives the direction), otherwise from
  the force (leaving its rest level by more than ``force_sigmas`` rest-noise standard
  deviations, median and MAD of the first ``tare_s`` window, or of the first quiet one when the
  log starts during a pull; the sign of the force gives the direction). A pull cut by the log's
  start is skipped (no breakaway, no rest before it).
* **tare**: the force at rest (wire slack) in windows of ``tare_s`` before and after each pull,
  ``tare_gap_s`` away from it, interpolated linearly in time: offset and drift are removed.

Per pull (signed tared force g(t) = F(t) - tare(t); d = +1 forward, -1 backward):

* ``kinetic_n``: the mean of g over the steady sliding window (after ``skip_mm`` of travel, or
  ``skip_s`` without displacement, and before the last ``end_trim_s``), made a friction
  magnitude: d (mean - bias);
* ``static_n``: the breakaway peak, d (peak - bias), with peak the extreme of the
  ``static_window_s`` moving average of g before the kinetic window;
* ``bias_n``: (F_fwd + F_back) / 2 of the mean signed forces of the forward and backward pulls
  (gravity, drag of constant sign): per plateau in the curve (NaN with one direction only), and
  pooled over those plateaus (weighted by 1 / (friction^2 (1/n_fwd + 1/n_back)): scatter grows
  with the force) for each pull's friction (0 when no plateau has both directions).
  So with as many pulls each way the mean of ``kinetic_n`` over a plateau is exactly
  (F_fwd - F_back) / 2;
* ``kinetic_se_n``: the standard error of the window mean, sd x sqrt(tau / n), where tau is the
  integrated autocorrelation time of the detrended force (the larger of Sokal's automatic-window
  estimate, c = 5, and the AR(1) value (1 + r1)/(1 - r1), which is steadier on short windows),
  combined with the error of the tare at the window's centre (the rest windows' variance with
  the same autocorrelation time: one sensor): samples of a plateau are
  autocorrelated, so sd / sqrt(n) (``kinetic_naive_se_n``, the window alone) is too small;
* ``stick_slip_n`` (half the 5-95 % range of the detrended window: stick-slip plus noise),
  ``slope_n_per_s`` (drift check), ``n_samples`` and ``n_eff``.

The curve has one point per set point and branch: mean pressure, friction (F_fwd - F_back) / 2
of the mean signed forces (the mean ``kinetic_n`` with one direction), the between-pull
standard deviation of ``kinetic_n``, mean ``static_n`` and the number of pulls; ``hysteresis`` pairs
the up and down branches at common set points. Nothing is dropped silently: every pull found but
not used is in ``skipped`` with its reason.

Examples
--------
>>> from exofric.friction import RawRigConfig, simulate_raw_log
>>> log = simulate_raw_log([0.2, 0.4, 0.6], [80.0, 160.0, 240.0], 0.7, seed=1)
>>> red = reduce_log(log.to_frame())
>>> len(red.pulls), [round(k, 1) for k in red.curve["kinetic_n"]]
(30, [56.3, 112.9, 167.8])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_range, warn_implausible

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "ReduceSettings", "RigReduction", "friction_curve", "integrated_autocorr_time", "pool_pulls",
    "reduce_log",
]

_MIN_WINDOW = 10        # fewest samples of a steady window or of a tare window


@checked_init
@dataclass(frozen=True)
class ReduceSettings:
    """How :func:`reduce_log` segments a raw log (MPa, s, mm; defaults in ``exofric.defaults``).

    Parameters
    ----------
    plateau_tol_mpa : float
        Absolute pressure band of a plateau in MPa (1e-6-10).
    plateau_tol_rel : float
        Relative band of a plateau (unitless, 0-0.5; x the pressure level).
    min_plateau_s : float
        Shortest plateau in s (1e-3-1e4).
    smooth_s : float
        Moving-median window for pressure and displacement in s (1e-4-100).
    skip_mm : float
        Travel in mm excluded at the start of each pull before the kinetic window (>= 0; used
        when the log has displacement).
    skip_s : float
        Time in s excluded at the start of each pull (>= 0; used without displacement).
    end_trim_s : float
        Time in s excluded at the end of each pull (>= 0).
    min_pull_s : float
        Shortest pull in s (1e-3-1e4).
    tare_s, tare_gap_s : float
        Length of the tare windows and their distance from a pull, in s (1e-3-1e3, 0-1e3).
    static_window_s : float
        Moving-average window of the breakaway peak in s (>= 0; 0 for the raw maximum).
    speed_fraction : float
        Pull threshold: share of the typical displacement speed (unitless, 0.01-0.99).
    force_sigmas : float
        Pull threshold without displacement, in rest-noise standard deviations (unitless,
        0.1-1e3).

    Raises
    ------
    InputError
        A setting outside its range; the message names it.

    Examples
    --------
    >>> ReduceSettings(skip_mm=3.0).skip_mm
    3.0
    """

    plateau_tol_mpa: float = D.REDUCE_PLATEAU_TOL_MPA
    plateau_tol_rel: float = D.REDUCE_PLATEAU_TOL_REL
    min_plateau_s: float = D.REDUCE_MIN_PLATEAU_S
    smooth_s: float = D.REDUCE_SMOOTH_S
    skip_mm: float = D.REDUCE_SKIP_MM
    skip_s: float = D.REDUCE_SKIP_S
    end_trim_s: float = D.REDUCE_END_TRIM_S
    min_pull_s: float = D.REDUCE_MIN_PULL_S
    tare_s: float = D.REDUCE_TARE_S
    tare_gap_s: float = D.REDUCE_TARE_GAP_S
    static_window_s: float = D.REDUCE_STATIC_WINDOW_S
    speed_fraction: float = D.REDUCE_SPEED_FRACTION
    force_sigmas: float = D.REDUCE_FORCE_SIGMAS

    def __post_init__(self) -> None:
        check_range("plateau_tol_mpa", self.plateau_tol_mpa, 1e-6, 10.0, unit="MPa")
        check_range("plateau_tol_rel", self.plateau_tol_rel, 0.0, 0.5)
        check_range("min_plateau_s", self.min_plateau_s, 1e-3, 1e4, unit="s")
        check_range("smooth_s", self.smooth_s, 1e-4, 100.0, unit="s")
        check_range("skip_mm", self.skip_mm, 0.0, 1e4, unit="mm")
        check_range("skip_s", self.skip_s, 0.0, 1e4, unit="s")
        check_range("end_trim_s", self.end_trim_s, 0.0, 1e4, unit="s")
        check_range("min_pull_s", self.min_pull_s, 1e-3, 1e4, unit="s")
        check_range("tare_s", self.tare_s, 1e-3, 1e3, unit="s")
        check_range("tare_gap_s", self.tare_gap_s, 0.0, 1e3, unit="s")
        check_range("static_window_s", self.static_window_s, 0.0, 10.0, unit="s")
        check_range("speed_fraction", self.speed_fraction, 0.01, 0.99)
        check_range("force_sigmas", self.force_sigmas, 0.1, 1e3)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready settings (unit-suffixed keys)."""
        return dict(asdict(self))


@checked_init
@dataclass(frozen=True)
class RigReduction(DisplayMixin):
    """Pulls, skipped pulls, plateaus, the friction curve and hysteresis of one raw log.

    Attributes
    ----------
    pulls : tuple of dict
        One row per used pull (keys as the columns of :meth:`to_frame`; MPa, N, s, mm).
    skipped : tuple of dict
        Pulls found but not used: ``pull``, ``t_start_s``, ``t_end_s``, ``reason``.
    plateaus : tuple of dict
        ``plateau``, ``setpoint``, ``branch``, ``pressure_mpa``, ``t_start_s``, ``t_end_s``,
        ``n_pulls``.
    curve : dict of lists
        Per set point and branch: ``pressure_mpa``, ``kinetic_n``, ``kinetic_sd_n``,
        ``static_n``, ``n_pulls``, ``branch``, ``bias_n``.
    hysteresis : tuple of dict
        Per set point on both branches: ``pressure_mpa``, ``kinetic_up_n``, ``kinetic_down_n``,
        ``hysteresis_n`` (down - up) and ``hysteresis_pct``.
    source : str
        Where the log came from (file name), for messages and plots.
    pull_detection : {"displacement", "force"}
        Which channel the pulls were found in.
    settings : ReduceSettings
    time_s, pressure_mpa, force_n, displacement_mm : ndarray
        The log's samples (s, MPa, N, mm; displacement None without that column), for plots.

    Examples
    --------
    >>> from exofric.friction import simulate_raw_log
    >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
    >>> red.to_frame()[["direction", "branch"]].iloc[0].tolist(), red.pull_detection
    (['forward', 'up'], 'displacement')
    """

    pulls: tuple[dict[str, Any], ...]
    skipped: tuple[dict[str, Any], ...]
    plateaus: tuple[dict[str, Any], ...]
    curve: dict[str, list[Any]]
    hysteresis: tuple[dict[str, Any], ...]
    source: str
    pull_detection: str
    settings: ReduceSettings
    time_s: NDArray[np.float64] = field(repr=False, compare=False)
    pressure_mpa: NDArray[np.float64] = field(repr=False, compare=False)
    force_n: NDArray[np.float64] = field(repr=False, compare=False)
    displacement_mm: NDArray[np.float64] | None = field(repr=False, compare=False)

    def to_frame(self) -> pd.DataFrame:
        """One row per used pull (the table ``exofric reduce --out`` writes).

        Columns: ``pressure_mpa``, ``static_n``, ``kinetic_n``, ``direction``, ``branch``,
        ``pull``, ``plateau``, ``setpoint``, ``t_start_s``, ``t_end_s``, ``t_static_s`` (the
        breakaway peak), ``t_kinetic_start_s``,
        ``t_kinetic_end_s``, ``pressure_se_mpa``, ``kinetic_se_n``, ``kinetic_naive_se_n``,
        ``force_kinetic_n`` (signed, tared), ``bias_n``, ``tare_n``, ``stick_slip_n``,
        ``slope_n_per_s``, ``n_samples``, ``n_eff``, ``travel_mm``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.friction import simulate_raw_log
        >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
        >>> red.to_frame().columns.tolist()[:5]
        ['pressure_mpa', 'static_n', 'kinetic_n', 'direction', 'branch']
        """
        import pandas as pd

        return pd.DataFrame(list(self.pulls), columns=list(_PULL_COLUMNS))

    def curve_frame(self) -> pd.DataFrame:
        """The friction curve, one row per set point and branch (MPa, N).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.friction import simulate_raw_log
        >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
        >>> red.curve_frame()["n_pulls"].tolist()
        [10, 10]
        """
        import pandas as pd

        return pd.DataFrame(self.curve)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``pulls``, ``curve``, ``skipped``, ``plateaus``, ``hysteresis``, ...

        Examples
        --------
        >>> from exofric.friction import simulate_raw_log
        >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
        >>> sorted(red.to_dict()["curve"])[:3]
        ['bias_n', 'branch', 'kinetic_n']
        """
        return {
            "source": self.source,
            "pull_detection": self.pull_detection,
            "n_pulls": len(self.pulls),
            "n_skipped": len(self.skipped),
            "pulls": [dict(p) for p in self.pulls],
            "curve": {k: list(v) for k, v in self.curve.items()},
            "skipped": [dict(s) for s in self.skipped],
            "plateaus": [dict(p) for p in self.plateaus],
            "hysteresis": [dict(h) for h in self.hysteresis],
            "settings": self.settings.to_dict(),
        }

    def plot(self, fig: Any | None = None) -> Any:
        """The log with plateaus, pulls and averaging windows shaded (see
        :func:`exofric.plots.plot_reduction`).

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on.

        Returns
        -------
        matplotlib Figure

        Examples
        --------
        >>> from exofric.friction import simulate_raw_log
        >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
        >>> len(red.plot().axes)
        3
        """
        from exofric.plots import plot_reduction

        return plot_reduction(self, fig=fig)


_PULL_COLUMNS = (
    "pressure_mpa", "static_n", "kinetic_n", "direction", "branch", "pull", "plateau",
    "setpoint", "t_start_s", "t_end_s", "t_static_s", "t_kinetic_start_s", "t_kinetic_end_s",
    "pressure_se_mpa", "kinetic_se_n", "kinetic_naive_se_n", "force_kinetic_n", "bias_n",
    "tare_n", "stick_slip_n", "slope_n_per_s", "n_samples", "n_eff", "travel_mm",
)


def integrated_autocorr_time(x: NDArray[np.float64], c: float = 5.0) -> float:
    """Integrated autocorrelation time of a series, in samples (Sokal's automatic window).

    tau = 1 + 2 sum_{k=1}^{M} rho_k with the smallest window M >= c tau (rho: sample
    autocorrelation by FFT). The variance of the mean of n samples is about var x tau / n, so
    n / tau is the effective sample size. tau >= 1/n; a white series gives ~1, an AR(1) series
    with coefficient phi gives (1 + phi) / (1 - phi).

    Parameters
    ----------
    x : ndarray
        The series (any unit), at least 3 samples; it is mean-centred here.
    c : float
        Window factor (Sokal: 4-10).

    Returns
    -------
    float
        tau in samples (>= 1 / n).

    Examples
    --------
    >>> import numpy as np
    >>> round(integrated_autocorr_time(np.random.default_rng(0).standard_normal(20000)), 1)
    1.0
    """
    y = np.asarray(x, dtype=float)
    n = y.size
    if n < 3:
        return 1.0
    y = y - y.mean()
    var = float(y @ y)
    if var == 0.0:
        return 1.0
    m = 1 << int(np.ceil(np.log2(2 * n)))
    spec = np.fft.rfft(y, m)
    acf = np.fft.irfft(spec * np.conj(spec), m)[:n] / var
    taus = 2.0 * np.cumsum(acf) - 1.0
    ok = np.arange(n) >= c * taus
    win = int(np.argmax(ok)) if np.any(ok) else n - 1
    return float(max(taus[win], 1.0 / n))


def _runs(mask: NDArray[np.bool_]) -> NDArray[np.int64]:
    """(start, stop) index pairs of the True runs of a boolean array."""
    d = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return np.column_stack([np.flatnonzero(d == 1), np.flatnonzero(d == -1)])


def _check_saturation(t: NDArray[np.float64], f: NDArray[np.float64], source: str) -> None:
    n_min = D.REDUCE_SATURATION_SAMPLES
    for extreme, word in ((f.max(), "maximum"), (f.min(), "minimum")):
        if extreme == 0.0:   # an exact zero is a simulated or zeroed signal, not a clipped one
            continue
        runs = _runs(f == extreme)
        long = runs[runs[:, 1] - runs[:, 0] >= n_min]
        if long.size:
            a, b = long[0]
            raise InputError(
                f"{source}force_n saturated at {extreme:g} N from {t[a]:.2f} s to "
                f"{t[b - 1]:.2f} s ({b - a} samples flat at the channel's {word}): clipped pulls "
                "cannot be reduced; use a load cell with a larger range")


def _tol(level: NDArray[np.float64] | float, s: ReduceSettings) -> NDArray[np.float64]:
    return np.maximum(s.plateau_tol_mpa, s.plateau_tol_rel * np.abs(level))


def _cluster_levels(levels: NDArray[np.float64], s: ReduceSettings) -> NDArray[np.int64]:
    """Set-point number (1 = lowest) per level: sorted levels closer than the band share one."""
    order = np.argsort(levels, kind="stable")
    srt = levels[order]
    new = np.concatenate([[True], np.diff(srt) > _tol(srt[1:], s)])
    out = np.empty(levels.size, dtype=np.int64)
    out[order] = np.cumsum(new)
    return out


def _plateaus(t: NDArray[np.float64], p_s: NDArray[np.float64], fs: float, s: ReduceSettings,
              source: str) -> list[dict[str, Any]]:
    n = p_s.size
    h = max(1, int(round(0.5 * s.min_plateau_s * fs)))
    idx = np.arange(n)
    change = np.abs(p_s[np.minimum(idx + h, n - 1)] - p_s[np.maximum(idx - h, 0)])
    steady = change < _tol(p_s, s)
    runs = [r for r in _runs(steady) if t[r[1] - 1] - t[r[0]] >= 0.5 * s.min_plateau_s]
    out: list[dict[str, Any]] = []
    ramps: list[tuple[int, int, float]] = []
    for a, b in runs:
        level = float(np.median(p_s[a:b]))
        # A slow steady ramp changes by less than the band over min_plateau_s everywhere, so
        # the local test calls all of it steady: a plateau must also hold its level over its
        # whole length (a linear drift over the run of more than the band's full width is a
        # ramp, not a set point; issue 31: a ramping log gave one plateau holding every pull).
        tc = t[a:b] - t[a:b].mean()
        slope = float(tc @ (p_s[a:b] - p_s[a:b].mean()) / (tc @ tc)) if b - a > 2 else 0.0
        if abs(slope) * (t[b - 1] - t[a]) > 2.0 * float(_tol(level, s)):
            ramps.append((int(a), int(b), slope))
            continue
        band = np.abs(p_s - level) > _tol(level, s)
        before = np.flatnonzero(band[:a])
        after = np.flatnonzero(band[b:])
        a2 = int(before[-1] + 1) if before.size else 0
        b2 = int(b + after[0]) if after.size else n
        if out and abs(out[-1]["level"] - level) <= float(_tol(level, s)) and a2 <= out[-1]["b"]:
            out[-1]["b"] = max(out[-1]["b"], b2)
            continue
        if out and a2 < out[-1]["b"]:
            a2 = out[-1]["b"]
        if t[b2 - 1] - t[a2] >= s.min_plateau_s:
            out.append({"a": a2, "b": b2, "level": level})
    if not out and ramps:
        a, b, slope = max(ramps, key=lambda r: r[1] - r[0])
        raise InputError(
            f"{source}pressure ramps steadily ({slope:+.3g} MPa/s, {p_s[a]:.4g} to "
            f"{p_s[b - 1]:.4g} MPa in {t[a]:.2f}-{t[b - 1]:.2f} s) and is never held: no plateau "
            f"of {s.min_plateau_s:g} s within +-max({s.plateau_tol_mpa:g} MPa, "
            f"{100 * s.plateau_tol_rel:g} %); friction needs the pressure held at set points")
    if not out:
        raise InputError(
            f"{source}pressure never steady in {t[0]:.2f}-{t[-1]:.2f} s: no stretch of "
            f"{s.min_plateau_s:g} s within +-max({s.plateau_tol_mpa:g} MPa, "
            f"{100 * s.plateau_tol_rel:g} %); check the regulator or widen plateau_tol_mpa")
    setpoint = _cluster_levels(np.array([pl["level"] for pl in out]), s)
    for j, pl in enumerate(out):
        pl["setpoint"] = int(setpoint[j])
        if j == 0:
            pl["branch"] = "up"
        else:
            prev = out[j - 1]
            pl["branch"] = ("up" if pl["level"] > prev["level"] else "down") \
                if pl["setpoint"] != prev["setpoint"] else prev["branch"]
    return out


def _pulls_from_displacement(x: NDArray[np.float64], fs: float, w: int, s: ReduceSettings,
                             t: NDArray[np.float64], source: str) -> list[tuple[int, int, int]]:
    from scipy.ndimage import median_filter, uniform_filter1d

    x_s = uniform_filter1d(median_filter(x, size=w, mode="nearest"), size=w, mode="nearest")
    v = np.gradient(x_s) * fs
    v_typ = float(np.percentile(np.abs(v), 95))
    span = float(np.ptp(x))
    if span == 0.0 or v_typ <= 1e-9 * max(span, 1.0) * fs:
        raise InputError(f"{source}no pull found in {t[0]:.2f}-{t[-1]:.2f} s: displacement_mm "
                         "never moves (log the wire displacement, or drop the column to find "
                         "pulls in the force)")
    moving = np.abs(v) > s.speed_fraction * v_typ
    out = []
    for sign in (1, -1):
        for a, b in _runs(moving & (np.sign(v) == sign)):
            out.append((int(a), int(b), sign))
    return sorted(out)


def _first(mask: Any, start: int, n: int, chunk: int) -> int:
    """First index >= start where ``mask(lo, hi)`` (a boolean array for [lo, hi)) is True, or
    -1: windows from ``chunk`` samples, doubling, so a search near ``start`` is cheap."""
    lo = start
    size = chunk
    while lo < n:
        hi = min(n, lo + size)
        m = mask(lo, hi)
        if m.size and np.any(m):
            return lo + int(np.argmax(m))
        lo = hi
        size *= 2
    return -1


def _pulls_from_force(f: NDArray[np.float64], fs: float, s: ReduceSettings,
                      t: NDArray[np.float64], source: str) -> list[tuple[int, int, int]]:
    n = f.size
    n0 = max(_MIN_WINDOW, int(round(s.tare_s * fs)))
    # Rest level and noise from a window of tare_s, by median and MAD: a pull's edge inside the
    # window must not inflate the threshold (that hid every pull of a plateau). The window is the
    # log's first one unless that is much noisier than the quietest ones (the log starts during
    # a pull, which slides with stick-slip): then the first quiet window, and the partial pull
    # before it is returned as starting at sample 0 (reduce_log skips it, with its reason).
    nb = max(1, n // n0)
    blocks = f[: nb * n0].reshape(nb, -1) if n >= n0 else f[None, :]
    med = np.median(blocks, axis=1)
    mad = 1.4826 * np.median(np.abs(blocks - med[:, None]), axis=1)
    quiet = mad <= 2.5 * max(float(np.percentile(mad, 5)), 1e-12)
    j0 = int(np.argmax(quiet))
    base = float(med[j0])
    floor = 1e-9 * max(1.0, float(np.abs(f).max()))
    thr = s.force_sigmas * max(float(mad[j0]), floor)
    q = max(2, int(round(s.tare_gap_s * fs)))     # quiet samples that end a pull
    out: list[tuple[int, int, int]] = []
    if j0 > 0:
        away = np.flatnonzero(np.abs(f[: j0 * n0] - base) > thr)
        if away.size:
            b0 = int(away[-1]) + 1
            out.append((0, b0, 1 if float(np.mean(f[:b0])) >= base else -1))
    k = (j0 + 1) * n0
    chunk = max(4 * q, int(10.0 * fs))        # search windows (doubling): O(n), not O(n pulls)
    while k < n:
        a = _first(lambda lo, hi, base=base: np.abs(f[lo:hi] - base) > thr, k, n, chunk)
        if a < 0:
            break

        def quiet_run(lo: int, hi: int, base: float = base) -> NDArray[np.bool_]:
            quiet = (np.abs(f[lo:min(hi + q - 1, n)] - base) <= thr).astype(float)
            run = np.convolve(quiet, np.ones(q), mode="valid") >= q - 0.5
            return np.asarray(run[: hi - lo], dtype=bool)

        found = _first(quiet_run, a, n, chunk)
        b = found if found >= 0 else n
        sign = 1 if float(np.mean(f[a:b])) >= base else -1
        # the pull ends where the force falls below half its median level, not where the
        # relaxing wire reaches the rest band (that tail is not sliding)
        level = float(np.median(sign * (f[a:b] - base)))
        high = np.flatnonzero(sign * (f[a:b] - base) >= 0.5 * level)
        b_end = a + int(high[-1]) + 1 if high.size else b
        out.append((a, b_end, sign))
        rest = f[b:b + q]
        if rest.size:
            base = float(np.median(rest))
        k = b + q
    if not out:
        raise InputError(f"{source}no pull found in {t[0]:.2f}-{t[-1]:.2f} s: the force never "
                         f"left its rest level {base:.3g} N by more than {thr:.3g} N "
                         f"({s.force_sigmas:g} x the rest noise in {t[j0 * n0]:.2f}-"
                         f"{t[min(n, (j0 + 1) * n0) - 1]:.2f} s)")
    return out


def _rest_mean(t: NDArray[np.float64], f: NDArray[np.float64]) -> tuple[float, float, float,
                                                                          int]:
    """Mid time (s), mean force (N), sample variance (N^2) and size of a rest (tare) window."""
    var = float(np.var(f, ddof=1)) if f.size > 1 else 0.0
    return float(t.mean()), float(f.mean()), var, int(f.size)


def _ar1_time(x: NDArray[np.float64]) -> float:
    """(1 + r1) / (1 - r1) from the lag-1 autocorrelation r1: the integrated autocorrelation time
    of AR(1) noise, stable on short windows where the windowed sum scatters (samples)."""
    y = x - x.mean()
    den = float(y @ y)
    if y.size < 3 or den == 0.0:
        return 1.0
    r1 = min(max(float(y[:-1] @ y[1:]) / den, 0.0), 0.99)
    return (1.0 + r1) / (1.0 - r1)


def _window_mean(y: NDArray[np.float64], t: NDArray[np.float64]) -> tuple[float, float, float,
                                                                           float, float, float]:
    """mean, se (autocorrelation-aware), naive se, slope (per s), stick-slip half range, n_eff."""
    n = y.size
    tc = t - t.mean()
    slope = float((tc @ (y - y.mean())) / (tc @ tc)) if n > 1 else 0.0
    resid = y - y.mean() - slope * tc
    sd = float(np.std(resid, ddof=1)) if n > 1 else 0.0
    tau = max(integrated_autocorr_time(resid), _ar1_time(resid))
    n_eff = float(min(n, max(1.0, n / tau)))
    lo, hi = np.percentile(resid, [5.0, 95.0])
    return (float(y.mean()), sd / np.sqrt(n_eff), sd / np.sqrt(n), slope,
            float(0.5 * (hi - lo)), n_eff)


@dataclass(frozen=True)
class _Log:
    """A checked raw log: time (s), pressure (MPa), force (N), displacement (mm) or None, and
    the sample rate ``fs`` (Hz, from the median time step)."""

    t: NDArray[np.float64]
    p: NDArray[np.float64]
    f: NDArray[np.float64]
    x: NDArray[np.float64] | None
    fs: float


def _checked_log(log: pd.DataFrame | Mapping[str, Any], s: ReduceSettings, pre: str) -> _Log:
    """The log's columns as float arrays, checked (InputError naming the column or time)."""
    cols = {}
    for name in ("time_s", "pressure_mpa", "force_n"):
        if name not in log:
            raise InputError(f"{pre}log has no column {name!r} (needs time_s, pressure_mpa, "
                             "force_n and optionally displacement_mm)")
        cols[name] = np.asarray(log[name], dtype=float).ravel()
    t, p, f = cols["time_s"], cols["pressure_mpa"], cols["force_n"]
    x = np.asarray(log["displacement_mm"], dtype=float).ravel() \
        if "displacement_mm" in log else None
    n = t.size
    if n < 3 * _MIN_WINDOW or any(a.size != n for a in (p, f)) or (x is not None
                                                                   and x.size != n):
        raise InputError(f"{pre}log needs >= {3 * _MIN_WINDOW} samples and equal-length "
                         f"columns, got {n}")
    for name, arr in (("time_s", t), ("pressure_mpa", p), ("force_n", f)) + (
            (("displacement_mm", x),) if x is not None else ()):
        if not np.all(np.isfinite(arr)):
            k = int(np.flatnonzero(~np.isfinite(arr))[0])
            raise InputError(f"{pre}{name} is not finite at row {k + 1} "
                             f"(t = {t[k]:.3f} s)" if name != "time_s" else
                             f"{pre}time_s is not finite at row {k + 1}")
    dt = np.diff(t)
    if np.any(dt <= 0):
        k = int(np.argmax(dt <= 0))
        raise InputError(f"{pre}time_s not increasing at {t[k]:.3f} s -> {t[k + 1]:.3f} s "
                         f"(row {k + 2})")
    fs = 1.0 / float(np.median(dt))
    if fs * s.tare_s < 4.0:  # e.g. milliseconds read as seconds
        raise InputError(f"{pre}time_s steps by {1.0 / fs:.4g} s (median; {fs:.4g} Hz): fewer "
                         f"than 4 samples per tare window of {s.tare_s:g} s; is the time in "
                         "ms? (name the column time_ms)")
    _check_saturation(t, f, pre)
    return _Log(t=t, p=p, f=f, x=x, fs=fs)


def _segment(lg: _Log, s: ReduceSettings, pre: str
             ) -> tuple[list[dict[str, Any]], list[tuple[int, int, int]], str]:
    """Pressure plateaus, pulls (start, stop, direction) and how the pulls were found."""
    from scipy.ndimage import median_filter

    w = max(3, int(round(s.smooth_s * lg.fs)) | 1)
    p_s = median_filter(lg.p, size=w, mode="nearest")
    plateaus = _plateaus(lg.t, p_s, lg.fs, s, pre)
    if lg.x is not None:
        found = _pulls_from_displacement(lg.x, lg.fs, w, s, lg.t, pre)
        detection = "displacement"
    else:
        found = _pulls_from_force(lg.f, lg.fs, s, lg.t, pre)
        detection = "force"
    if not found:
        raise InputError(f"{pre}no pull found in {lg.t[0]:.2f}-{lg.t[-1]:.2f} s")
    return plateaus, found, detection


@dataclass(frozen=True)
class _PullWindows:
    """Where each pull's windows may lie: the rest samples (indices, ``tare_gap_s`` away from
    every pull), the plateau number per sample (0: none), and the tare window's length, the
    fewest rest samples of a tare and the breakaway moving-average length (samples)."""

    rest_idx: NDArray[np.intp]
    plateau_of: NDArray[np.int_]
    n_tare: int
    min_tare: int
    n_static: int


def _pull_windows(lg: _Log, s: ReduceSettings, plateaus: list[dict[str, Any]],
                  found: list[tuple[int, int, int]]) -> _PullWindows:
    """Rest samples, plateau per sample and the window lengths (samples) of all pulls."""
    from scipy.ndimage import uniform_filter1d

    n, fs = lg.t.size, lg.fs
    in_pull = np.zeros(n, dtype=bool)
    for a, b, _ in found:
        in_pull[a:b] = True
    gap = int(round(s.tare_gap_s * fs))
    busy = uniform_filter1d(in_pull.astype(float), size=2 * gap + 1, mode="nearest") > 0 \
        if gap else in_pull
    rest = ~busy
    n_tare = max(_MIN_WINDOW, int(round(s.tare_s * fs)))
    # fewest rest samples for a tare: _MIN_WINDOW, or half a tare window at low rates (a 20 Hz
    # log has 10 samples per 0.5 s window, and a 1 s rest less the two gaps leaves 8)
    min_tare = min(_MIN_WINDOW, max(5, n_tare // 2))
    n_static = max(1, int(round(s.static_window_s * fs)))
    plateau_of = np.zeros(n, dtype=int)
    for j, pl in enumerate(plateaus):
        plateau_of[pl["a"]:pl["b"]] = j + 1
    return _PullWindows(rest_idx=np.flatnonzero(rest), plateau_of=plateau_of, n_tare=n_tare,
                        min_tare=min_tare, n_static=n_static)


def _kinetic_window(lg: _Log, s: ReduceSettings, a: int, b: int) -> tuple[int, int]:
    """Steady sliding window [ks, ke) of the pull [a, b): after the skipped travel (mm) or
    time (s), before the end trim (s)."""
    if lg.x is not None:
        travel = np.abs(lg.x[a:b] - lg.x[a])
        past = np.flatnonzero(travel >= s.skip_mm)
        ks = a + int(past[0]) if past.size else b
    else:
        ks = a + int(round(s.skip_s * lg.fs))
    ke = b - int(round(s.end_trim_s * lg.fs))
    return ks, ke


def _tare(lg: _Log, s: ReduceSettings, win: _PullWindows, a: int, b: int, t_mid: float
          ) -> tuple[NDArray[np.float64], list[tuple[float, float, int]]] | None:
    """Tare force (N) over the pull [a, b) from the rest windows before and after it, and its
    variance terms (weight, N^2, samples) at ``t_mid`` (s); None without a rest window."""
    t, f, fs = lg.t, lg.f, lg.fs
    i_a, i_b = np.searchsorted(win.rest_idx, (a, b))
    before = win.rest_idx[max(0, i_a - win.n_tare):i_a]
    after = win.rest_idx[i_b:i_b + win.n_tare]
    before = before[t[a] - t[before] <= s.tare_s + s.tare_gap_s + 2.0 / fs] \
        if before.size else before
    after = after[t[after] - t[b - 1] <= s.tare_s + s.tare_gap_s + 2.0 / fs] \
        if after.size else after
    sides = [_rest_mean(t[ix], f[ix]) for ix in (before, after) if ix.size >= win.min_tare]
    if not sides:
        return None
    if len(sides) == 2:
        (t0, f0, v0, n0), (t1, f1, v1, n1) = sides
        tare = f0 + (f1 - f0) * (t[a:b] - t0) / (t1 - t0)
        lam = (t_mid - t0) / (t1 - t0)
        tare_terms = [((1.0 - lam) ** 2, v0, n0), (lam**2, v1, n1)]
    else:
        tare = np.full(b - a, sides[0][1])
        tare_terms = [(1.0, sides[0][2], sides[0][3])]
    return tare, tare_terms


def _pull_row(lg: _Log, win: _PullWindows, pl: dict[str, Any], plateau: int, k_pull: int,
              pull: tuple[int, int, int], window: tuple[int, int],
              tared: tuple[NDArray[np.float64], list[tuple[float, float, int]]]
              ) -> dict[str, Any]:
    """One pull's statistics (N, MPa, s; signed forces ``kinetic_raw``/``static_raw``)."""
    from scipy.ndimage import uniform_filter1d

    t, p, f, x = lg.t, lg.p, lg.f, lg.x
    (a, b, d), (ks, ke), (tare, tare_terms) = pull, window, tared
    g = f[a:b] - tare
    wk = slice(ks - a, ke - a)
    mean, se, se_naive, slope, stick, n_eff = _window_mean(g[wk], t[ks:ke])
    # The tare's error: the same sensor noise, so its autocorrelation time is the one
    # measured over the (longer) steady window; a 0.5 s rest window alone would underrate it.
    tau = (ke - ks) / n_eff
    tare_var = sum(c * v * min(1.0, tau / m) for c, v, m in tare_terms)
    pre_win = g[: max(ks - a, 1)]
    smooth = uniform_filter1d(pre_win, size=min(win.n_static, pre_win.size), mode="nearest")
    k_peak = int(np.argmax(d * smooth))
    peak = float(smooth[k_peak])
    pp = p[ks:ke]
    tau_p = integrated_autocorr_time(pp - pp.mean())
    return {
        "pressure_mpa": float(pp.mean()), "static_raw": peak, "kinetic_raw": mean,
        "direction": "forward" if d > 0 else "backward", "sign": d,
        "branch": pl["branch"], "pull": k_pull, "plateau": plateau,
        "setpoint": pl["setpoint"], "t_start_s": float(t[a]), "t_end_s": float(t[b - 1]),
        "t_static_s": float(t[a + k_peak]), "t_kinetic_start_s": float(t[ks]),
        "t_kinetic_end_s": float(t[ke - 1]),
        "pressure_se_mpa": float(np.std(pp, ddof=1) * np.sqrt(tau_p / pp.size)),
        "kinetic_se_n": float(np.sqrt(se**2 + tare_var)), "kinetic_naive_se_n": se_naive,
        "force_kinetic_n": mean,
        "tare_n": float(np.mean(tare)), "stick_slip_n": stick, "slope_n_per_s": slope,
        "n_samples": int(ke - ks), "n_eff": n_eff,
        "travel_mm": float(np.ptp(x[a:b])) if x is not None else float("nan"),
    }


def _reduce_pull(lg: _Log, s: ReduceSettings, win: _PullWindows,
                 plateaus: list[dict[str, Any]], k_pull: int, pull: tuple[int, int, int]
                 ) -> tuple[dict[str, Any] | None, str]:
    """One pull's row, or None and the reason it is skipped."""
    t, p = lg.t, lg.p
    a, b, _ = pull
    if a == 0:
        return None, "the log starts during this pull (no breakaway and no rest before it)"
    if t[b - 1] - t[a] < s.min_pull_s:
        return None, (f"shorter than min_pull_s = {s.min_pull_s:g} s "
                      f"({t[b - 1] - t[a]:.3f} s)")
    ks, ke = _kinetic_window(lg, s, a, b)
    if ke - ks < _MIN_WINDOW:
        return None, ("steady sliding window too short (pull shorter than the skipped "
                      "travel/time plus end trim)")
    js = win.plateau_of[ks:ke]
    if js[0] == 0 or np.any(js != js[0]):
        return None, (f"pressure not steady during the pull "
                      f"({p[ks:ke].min():.4g}-{p[ks:ke].max():.4g} MPa)")
    tared = _tare(lg, s, win, a, b, 0.5 * (t[ks] + t[ke - 1]))
    if tared is None:
        return None, f"no rest window of {s.tare_s:g} s next to the pull for the tare"
    plateau = int(js[0])
    return _pull_row(lg, win, plateaus[plateau - 1], plateau, k_pull, pull, (ks, ke),
                     tared), ""


def _pooled_bias(rows: list[dict[str, Any]]) -> float:
    """The force bias (N) pooled over the plateaus pulled in both directions (0 if none)."""
    # Bias per plateau from the two directions (the curve's bias_n); each pull's friction
    # magnitude uses the bias pooled over those plateaus: the per-plateau value carries the
    # between-pull scatter, and a plateau's mean friction is (F_fwd - F_back) / 2 either way
    # when its directions are balanced.
    bias: dict[int, float] = {}
    weight: dict[int, float] = {}
    for j in {r["plateau"] for r in rows}:
        fw = np.array([r["kinetic_raw"] for r in rows if r["plateau"] == j and r["sign"] > 0])
        bw = np.array([r["kinetic_raw"] for r in rows if r["plateau"] == j and r["sign"] < 0])
        if fw.size and bw.size:
            bias[j] = 0.5 * (float(fw.mean()) + float(bw.mean()))
            se2 = float(np.mean([r["kinetic_se_n"] ** 2 for r in rows if r["plateau"] == j]))
            level = 0.5 * (float(fw.mean()) - float(bw.mean()))
            weight[j] = 1.0 / ((1.0 / fw.size + 1.0 / bw.size) * (level**2 + se2) + 1e-300)
    # Between-pull scatter grows with the friction, so the variance of a plateau's bias is taken
    # as ~ friction^2 (1/n_f + 1/n_b) (+ the pulls' own noise): low-force plateaus pin the bias.
    # (Weights from each plateau's own sample variance would rest on 2-5 pulls each and let one
    # plateau with an accidentally small spread dominate.)
    return (sum(weight[j] * bias[j] for j in weight) / sum(weight.values())) if weight \
        else 0.0


def _signed_pulls(rows: list[dict[str, Any]], pooled: float) -> list[dict[str, Any]]:
    """The pull table: friction magnitudes d (force - ``pooled`` bias) in N, in column order."""
    pulls = []
    for r in rows:
        d = r.pop("sign")
        r["bias_n"] = pooled
        r["kinetic_n"] = d * (r.pop("kinetic_raw") - pooled)
        r["static_n"] = d * (r.pop("static_raw") - pooled)
        pulls.append({c: r[c] for c in _PULL_COLUMNS})
    return pulls


def _drift_messages(pulls: list[dict[str, Any]], pre: str) -> list[str]:
    """Warnings for pulls whose force drifts (N) by more than the allowed share of friction."""
    out = []
    for r in pulls:
        drift = abs(r["slope_n_per_s"]) * (r["t_kinetic_end_s"] - r["t_kinetic_start_s"])
        if r["kinetic_n"] > 0 and drift > D.REDUCE_DRIFT_WARN_PCT / 100.0 * r["kinetic_n"]:
            out.append(
                f"{pre}pull {r['pull']} at {r['pressure_mpa']:.3g} MPa: the force drifts by "
                f"{drift:.3g} N ({100 * drift / r['kinetic_n']:.0f} % of its friction) over its "
                "steady window; the friction is not steady (wear, heating, or a pressure leak)")
    return out


def _plateau_table(lg: _Log, plateaus: list[dict[str, Any]], pulls: list[dict[str, Any]]
                   ) -> list[dict[str, Any]]:
    """One row per plateau: set point, branch, mean pressure (MPa), times (s), pulls."""
    t, p = lg.t, lg.p
    plats = []
    for j, pl in enumerate(plateaus, start=1):
        plats.append({"plateau": j, "setpoint": pl["setpoint"], "branch": pl["branch"],
                      "pressure_mpa": float(np.mean(p[pl["a"]:pl["b"]])),
                      "t_start_s": float(t[pl["a"]]), "t_end_s": float(t[pl["b"] - 1]),
                      "n_pulls": sum(1 for r in pulls if r["plateau"] == j)})
    return plats


def reduce_log(
    log: pd.DataFrame | Mapping[str, Any],
    settings: ReduceSettings | None = None,
    *,
    source: str = "",
) -> RigReduction:
    """Segment a raw rig log and reduce each pull (see module docstring).

    Parameters
    ----------
    log : DataFrame or mapping of arrays
        ``time_s`` (s, strictly increasing), ``pressure_mpa`` (MPa), ``force_n`` (N) and
        optionally ``displacement_mm`` (mm), as :func:`exofric.io.read_raw_log` returns.
    settings : ReduceSettings, optional
        Segmentation settings (defaults in :mod:`exofric.defaults`).
    source : str
        Name for messages (default ``log.attrs["source"]`` of a DataFrame).

    Returns
    -------
    RigReduction

    Raises
    ------
    InputError
        One line naming the time range: missing columns, non-increasing time, fewer than 4
        samples per ``tare_s`` (time in ms read as s?), a saturated force channel, pressure
        never steady or only ramping (never held), no pull found, no usable pull.

    Warns
    -----
    PlausibilityWarning
        A pull whose force drifts by more than ``REDUCE_DRIFT_WARN_PCT`` % of its friction over
        its steady window; pulls skipped (each listed in ``skipped``).

    Examples
    --------
    >>> from exofric.friction import RawRigConfig, simulate_raw_log
    >>> cfg = RawRigConfig(replicates=2, sweep="up-down")
    >>> red = reduce_log(simulate_raw_log([0.2, 0.4, 0.6], [80.0, 160.0, 240.0], 0.7,
    ...                                   config=cfg, seed=5).to_frame())
    >>> red.curve["branch"], len(red.hysteresis)
    (['up', 'up', 'up', 'down', 'down'], 2)
    """
    s = settings or ReduceSettings()
    if not source and hasattr(log, "attrs"):
        source = str(getattr(log, "attrs", {}).get("source", ""))
    pre = f"{source}: " if source else ""
    lg = _checked_log(log, s, pre)
    t = lg.t
    plateaus, found, detection = _segment(lg, s, pre)
    win = _pull_windows(lg, s, plateaus, found)
    rows: list[dict[str, Any]] = []
    skipped: list[dict[str, Any]] = []
    for k_pull, pull in enumerate(found, start=1):
        row, reason = _reduce_pull(lg, s, win, plateaus, k_pull, pull)
        if row is None:
            a, b, _ = pull
            skipped.append({"pull": k_pull, "t_start_s": float(t[a]),
                            "t_end_s": float(t[b - 1]), "reason": reason})
        else:
            rows.append(row)
    if not rows:
        first = skipped[0]["reason"] if skipped else "none"
        raise InputError(f"{pre}no usable pull in {t[0]:.2f}-{t[-1]:.2f} s: {len(found)} found, "
                         f"all skipped (first: {first})")
    pulls = _signed_pulls(rows, _pooled_bias(rows))
    for message in _drift_messages(pulls, pre):
        warn_implausible(message)
    if skipped:
        warn_implausible(f"{pre}{len(skipped)} of {len(found)} pulls skipped (listed in "
                         f"'skipped'; first: {skipped[0]['reason']})")
    plats = _plateau_table(lg, plateaus, pulls)
    curve, hyst = friction_curve(pulls, s)
    return RigReduction(
        pulls=tuple(pulls), skipped=tuple(skipped), plateaus=tuple(plats), curve=curve,
        hysteresis=hyst, source=source, pull_detection=detection, settings=s,
        time_s=t, pressure_mpa=lg.p, force_n=lg.f, displacement_mm=lg.x,
    )


def _samples_hash(red: RigReduction) -> str:
    """SHA-256 of a reduction's samples (time, pressure, force, displacement; float64 bytes)."""
    import hashlib

    h = hashlib.sha256()
    for arr in (red.time_s, red.pressure_mpa, red.force_n, red.displacement_mm):
        h.update(b"|" if arr is None else np.ascontiguousarray(arr, dtype=np.float64).tobytes())
    return h.hexdigest()


def pool_pulls(reductions: Sequence[RigReduction]) -> pd.DataFrame:
    """The pulls of several reduced logs in one table, with plateaus and pulls numbered apart.

    Each log's ``plateau`` and ``pull`` numbers are offset by those of the logs before it, so a
    plateau number names one cluster of replicate pulls across the table; a ``log`` column
    holds each reduction's ``source``.

    Parameters
    ----------
    reductions : sequence of RigReduction
        Results of :func:`reduce_log`, in order.

    Returns
    -------
    pandas.DataFrame
        The columns of :meth:`RigReduction.to_frame` plus ``log``.

    Raises
    ------
    InputError
        No reduction, or two reductions of identical samples (one log given twice, perhaps
        under two names or formats: its pulls would count twice as replicates).

    Examples
    --------
    >>> from exofric.friction import simulate_raw_log
    >>> logs = [simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=k).to_frame()
    ...         for k in (1, 2)]
    >>> df = pool_pulls([reduce_log(f, source=f"log{k}") for k, f in enumerate(logs)])
    >>> sorted(df["plateau"].unique().tolist()), len(df)
    ([1, 2, 3, 4], 40)
    """
    import pandas as pd

    if not reductions:
        raise InputError("pool_pulls needs at least one reduction")
    seen: dict[str, str] = {}
    for red in reductions:  # one log given twice would count every pull twice as replicates
        h = _samples_hash(red)
        if h in seen:
            raise InputError(f"{red.source or 'a log'} and {seen[h] or 'another log'} are the "
                             f"same log (identical samples, sha256 {h[:12]}): each pull would "
                             "count twice as a replicate; give each log once")
        seen[h] = red.source
    frames = []
    n_plat = n_pull = 0
    for red in reductions:
        df = red.to_frame()
        df["plateau"] += n_plat
        df["pull"] += n_pull
        df["log"] = red.source
        n_plat += len(red.plateaus)
        n_pull += len(red.pulls) + len(red.skipped)
        frames.append(df)
    return pd.concat(frames, ignore_index=True)


def friction_curve(
    pulls: pd.DataFrame | Sequence[Mapping[str, Any]],
    settings: ReduceSettings | None = None,
) -> tuple[dict[str, list[Any]], tuple[dict[str, Any], ...]]:
    """The friction curve and hysteresis of reduced pulls, from one log or several pooled.

    Pulls are grouped by plateau (``log`` and ``plateau`` columns); plateaus whose mean pull
    pressures lie within the plateau band (``plateau_tol_mpa``, ``plateau_tol_rel``) share a set
    point, and each set point has one curve point per branch. The point's friction is
    (F_fwd - F_back) / 2 of the mean signed tared forces (``force_kinetic_n``) when both
    directions were pulled, else the mean ``kinetic_n``; ``bias_n`` is (F_fwd + F_back) / 2 (NaN
    with one direction). The ``setpoint`` of each pull row is updated in place.

    Parameters
    ----------
    pulls : DataFrame or sequence of dict
        Rows as :meth:`RigReduction.to_frame` (``pressure_mpa``, ``kinetic_n``, ``static_n``,
        ``force_kinetic_n``, ``direction``, ``branch``, ``plateau`` and optionally ``log``).
    settings : ReduceSettings, optional
        For the plateau band (MPa, relative).

    Returns
    -------
    (curve, hysteresis)
        ``curve``: lists ``pressure_mpa``, ``kinetic_n``, ``kinetic_sd_n``, ``static_n``,
        ``n_pulls``, ``branch``, ``setpoint``, ``bias_n`` (MPa, N), up branch first by rising
        pressure, then down by falling pressure. ``hysteresis``: per set point on both branches,
        ``pressure_mpa``, ``kinetic_up_n``, ``kinetic_down_n``, ``hysteresis_n`` (down - up, N)
        and ``hysteresis_pct``.

    Examples
    --------
    >>> rows = [{"pressure_mpa": 0.3, "kinetic_n": 20.0, "static_n": 25.0, "plateau": 1,
    ...          "force_kinetic_n": 21.0, "direction": "forward", "branch": "up"},
    ...         {"pressure_mpa": 0.3, "kinetic_n": 19.0, "static_n": 24.0, "plateau": 1,
    ...          "force_kinetic_n": -18.0, "direction": "backward", "branch": "up"}]
    >>> curve, _ = friction_curve(rows)
    >>> curve["kinetic_n"], curve["bias_n"]
    ([19.5], [1.5])
    """
    s = settings or ReduceSettings()
    rows = pulls.to_dict("records") if hasattr(pulls, "to_dict") else [dict(r) for r in pulls]
    if not rows:
        raise InputError("friction_curve needs at least one pull")
    key = [(str(r.get("log", "")), int(r["plateau"])) for r in rows]
    plats = sorted(set(key))
    level = np.array([np.mean([r["pressure_mpa"] for r, k in zip(rows, key, strict=True)
                               if k == pk]) for pk in plats])
    sp_of = dict(zip(plats, _cluster_levels(level, s).tolist(), strict=True))
    for r, k in zip(rows, key, strict=True):
        r["setpoint"] = int(sp_of[k])
    if hasattr(pulls, "loc"):
        pulls.loc[:, "setpoint"] = [r["setpoint"] for r in rows]
    elif isinstance(pulls, list):
        for r, src in zip(rows, pulls, strict=True):
            if isinstance(src, dict):
                src["setpoint"] = r["setpoint"]
    groups = sorted({(r["branch"] != "up", r["setpoint"]) for r in rows},
                    key=lambda g: (g[0], -g[1] if g[0] else g[1]))
    curve: dict[str, list[Any]] = {c: [] for c in (
        "pressure_mpa", "kinetic_n", "kinetic_sd_n", "static_n", "n_pulls", "branch",
        "setpoint", "bias_n")}
    by_key: dict[tuple[str, int], tuple[float, float]] = {}
    for down, sp in groups:
        branch = "down" if down else "up"
        sel = [r for r in rows if r["setpoint"] == sp and (r["branch"] != "up") == down]
        kin = np.array([r["kinetic_n"] for r in sel], dtype=float)
        pr = float(np.mean([r["pressure_mpa"] for r in sel]))
        fw = [r["force_kinetic_n"] for r in sel if r["direction"] == "forward"]
        bw = [r["force_kinetic_n"] for r in sel if r["direction"] == "backward"]
        both = bool(fw and bw)
        friction = 0.5 * (float(np.mean(fw)) - float(np.mean(bw))) if both \
            else float(kin.mean())
        curve["pressure_mpa"].append(pr)
        curve["kinetic_n"].append(friction)
        curve["kinetic_sd_n"].append(float(np.std(kin, ddof=1)) if kin.size > 1
                                     else float("nan"))
        curve["static_n"].append(float(np.mean([r["static_n"] for r in sel])))
        curve["n_pulls"].append(int(kin.size))
        curve["branch"].append(branch)
        curve["setpoint"].append(int(sp))
        curve["bias_n"].append(0.5 * (float(np.mean(fw)) + float(np.mean(bw))) if both
                               else float("nan"))
        by_key[(branch, int(sp))] = (pr, friction)
    hyst = []
    for (branch, sp), (pr, up) in sorted(by_key.items(), key=lambda kv: kv[1][0]):
        if branch == "up" and ("down", sp) in by_key:
            down = by_key[("down", sp)][1]
            hyst.append({"pressure_mpa": pr, "setpoint": sp, "kinetic_up_n": up,
                         "kinetic_down_n": down, "hysteresis_n": down - up,
                         "hysteresis_pct": 100.0 * (down - up) / up if up else float("nan")})
    return curve, tuple(hyst)
