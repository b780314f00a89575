"""A surrogate of the squeeze curve N(P) over the dimensionless groups, for design search.

Units: sizes mm, pressure and shear modulus MPa, force N, torque Nm, time s.

The surrogate (:func:`fit_surrogate`) is trained on the rows of a sweep
(:func:`exofric.design.run_sweep` ``.frame``) and works in the groups of
:mod:`exofric.design._dimensionless`, so that it is exact for geometrically similar designs
and a design's size and tube length only scale its output. It has two stages, both radial
basis function interpolants (polyharmonic kernel -r^5 plus a quadratic polynomial, each
input scaled to its training range):

1. the contact onset q_on = P_on / G, interpolated as the onset per unit clearance
   h = q_on / (c/d1) over (c/d1, t/d1, d2/d1); q_on = (c/d1) h;
2. after onset, the secant contact stiffness k = N / (G L d2 s) with s = P/G - q_on,
   interpolated over (q_on, t/d1, d2/d1, sqrt(s)) (the last weighted by
   :data:`PRESSURE_WEIGHT`); N = k s G L d2, and N = 0 for P <= P_on.

Why these variables (held-out error of ``benchmarks/bench_surrogate.py``, % of each design's
FE N(0.6 MPa), largest over the designs at 256 / 400 / 512 designs; 2.04 / 1.83 / 2.71 with
q_on and N / (P L d2) over (c/d1, t/d1, d2/d1, s), 1.28 / 0.93 / 1.30 with these):

* Shifting the pressure by the onset removes the kink of N(P) at first contact, which a
  smooth interpolant cannot follow (a single interpolant over P/G has ~10x the error).
* A tube with no clearance touches the wire at P = 0: q_on -> 0 as c -> 0 while the onset per
  clearance h stays finite (1.3-5.7 over the benchmark's box), so h needs no bend at the box's
  edge. Largest held-out onset error 0.27-0.50 kPa instead of 1.4-3.1 kPa (the FE brackets
  the onset to 0.2 kPa).
* N grows like s from contact on, so k is finite at the onset and N = 0 there exactly; and an
  error of k is the same fraction of N at every pressure, the measure the design search
  needs. N / (P L d2) = k s / (q_on + s) carries the steep factor s / (q_on + s), so a given
  error of it is a large fraction of the small N of a design that touches late.
* k rises steeply over the first ~0.01 of s (the contact patch forming on the wire) and
  slowly after; sqrt(s) spreads that start over more of the input range.
* After contact the clearance acts through how far the tube had inflated to touch: designs of
  equal q_on and t/d1, d2/d1 have close stiffnesses, so the curve stage takes q_on (the
  training designs' FE onset; the predicted one for a new design) in place of c/d1.
  Each matters: with c/d1 in place of q_on 1.28 / 1.06 / 2.69, with s in place of sqrt(s)
  1.92 / 5.01 / 3.53, with N / (P L d2) in place of k 1.40 / 0.98 / 3.12 (the onset itself
  interpolated: 1.14 / 0.78 / 1.55).
* Rows with s below :data:`ONSET_GAP` s_max are left out of the curve stage: there N / s is
  mostly the error of the FE onset.

What remains is mostly the FE's own: on the default mesh (2 x 24 quad9) k within ~0.01 of
s after onset moves by up to ~10 % as contact reaches the next node (against a 3 x 48 mesh),
which no smooth surrogate follows; it counts in % of N(0.6) for designs touching after
~0.55 MPa.

Leave-one-design-out errors are exact and cheap: removing a design's rows from an
interpolant is a rank update of the inverse of its system (Rippa's formula per block), and
the updated coefficients predict the left-out design's whole curve at its left-out onset
(input scalings: those of the full fit).

:func:`surrogate_search` explores thousands of candidate designs (quasi-random in the
sweep's box, or a given list) with the surrogate in about a second, ranks them with
:func:`exofric.design.search_designs` and confirms the best ones with the FE solver.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import pandas as pd
import scipy.linalg
import scipy.spatial.distance

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.design._dimensionless import (
    GROUPS,
    _add_geometric_groups,
    applicability,
    sweep_groups,
)
from exofric.design._runner import _deviation, solve_design
from exofric.design._search import DesignSearch, search_designs
from exofric.design._spec import Design, SweepSpec
from exofric.errors import ConvergenceError, InputError

__all__ = ["SqueezeSurrogate", "SurrogateSearch", "fit_surrogate", "surrogate_search",
           "candidate_designs"]

#: Weight of the pressure coordinate sqrt(s / s_max) of the curve stage, s = P/G - q_on and
#: s_max its largest training value, relative to q_on, t/d1 and d2/d1 (each scaled to
#: [0, 1]): chosen on ``benchmarks/bench_surrogate.py`` (4-fold held-out error at 256, 400 and
#: 512 designs, 4 draws of the folds: mean of the largest errors 1.46 / 1.48 / 1.49 % at
#: weight 3.5 / 4 / 5; the benchmark's draw 2.8 % at 2, 13 % at 1).
PRESSURE_WEIGHT = 4.0
#: Rows of the curve stage closer to the onset than this fraction of s_max (~1e-3 MPa / G) are
#: left out: the FE onset is bracketed to 2e-4 MPa (:func:`exofric.simulate.squeeze`
#: ``onset_tol_mpa``), so N / s there is mostly that error.
ONSET_GAP = 1e-3
#: Clearance ratio c/d1 below which the onset per clearance is taken per this clearance (a
#: design built with no clearance touches at ~0).
CLEARANCE_FLOOR = 1e-4
#: Candidates drawn by :func:`surrogate_search` when none are given, and designs confirmed.
N_CANDIDATES = 4096
N_CONFIRM = 5
#: Fewest solved designs a surrogate is fitted on.
MIN_DESIGNS = 4


class _RBF:
    """Polyharmonic (-r^5, or r^3 with few points) RBF interpolant + polynomial, with block LOO."""

    def __init__(self, z: np.ndarray, y: np.ndarray, blocks: np.ndarray | None = None) -> None:
        n, k = z.shape
        deg = 2 if n >= 3 * _n_mono(k, 2) else 1
        self.power, self.degree = (5, 2) if deg == 2 else (3, 1)
        self.sign = -1.0 if self.power == 5 else 1.0
        self.z = z
        self.exps = [e for d in range(self.degree + 1)
                     for e in itertools.product(range(d + 1), repeat=k) if sum(e) == d]
        a = self.sign * self._kernel(z)
        p = self._poly(z)
        m = p.shape[1]
        mat = np.zeros((n + m, n + m))
        mat[:n, :n], mat[:n, n:], mat[n:, :n] = a, p, p.T
        rhs = np.concatenate([y, np.zeros(m)])
        try:
            lu = scipy.linalg.lu_factor(mat, check_finite=True)
        except (ValueError, np.linalg.LinAlgError) as exc:   # pragma: no cover - guarded
            raise InputError(f"surrogate: singular interpolation system ({exc})") from None
        self.coef = scipy.linalg.lu_solve(lu, rhs)
        self.n = n
        self._lu = lu
        self._blocks = blocks

    def _kernel(self, z: np.ndarray) -> np.ndarray:
        """r^power to the centres (the sign is applied by the callers), by products in place."""
        r = scipy.spatial.distance.cdist(z, self.z)
        k = r * r
        if self.power == 5:
            k *= k
        k *= r
        return k

    def _poly(self, z: np.ndarray) -> np.ndarray:
        return np.column_stack([np.prod(z ** np.array(e), axis=1) for e in self.exps])

    def __call__(self, z: np.ndarray, coef: np.ndarray | None = None) -> np.ndarray:
        c = self.coef if coef is None else coef
        w = self.sign * c[:self.n]
        out = np.empty(len(z))
        step = max(64, (1 << 20) // max(self.n, 1))  # chunks of ~8 MB: n_eval x n_centres
        for i in range(0, len(z), step):
            zz = z[i:i + step]
            out[i:i + step] = self._kernel(zz) @ w + self._poly(zz) @ c[self.n:]
        return out

    def loo_coefficients(self, rows: np.ndarray) -> np.ndarray:
        """Coefficients of the interpolant without the data ``rows`` (exact rank update)."""
        e = np.zeros((len(self.coef), len(rows)))
        e[rows, np.arange(len(rows))] = 1.0
        cols = scipy.linalg.lu_solve(self._lu, e)       # columns of the inverse (symmetric)
        w = np.linalg.solve(cols[rows], self.coef[rows])
        return self.coef - cols @ w


def _n_mono(k: int, degree: int) -> int:
    from math import comb

    return comb(k + degree, degree)


def _box(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lower bounds, spans and the mask of non-constant columns of ``x``."""
    lo, hi = x.min(axis=0), x.max(axis=0)
    span = hi - lo
    keep = span > 1e-6 * np.maximum(1.0, np.abs(hi))
    return lo, np.where(keep, span, 1.0), keep


@checked_init
@dataclass(frozen=True)
class SqueezeSurrogate:
    """A fitted surrogate of N(P) (see the module docstring); build with :func:`fit_surrogate`.

    Attributes
    ----------
    pressures_mpa : tuple of float
        The pressures of the training sweep (MPa).
    n_designs : int
        Designs trained on.
    group_min, group_max : dict
        Training range of each group (``clearance_ratio``, ``wall_ratio``, ``wire_ratio``,
        unitless; ``shear_modulus_mpa`` in MPa): the surrogate's domain.
    loo : DataFrame
        Per training design (``key``, ``name``): ``loo_max_error_n`` (N), the largest
        |N_loo(P) - N_FE(P)| over the pressures, ``n_pmax_n`` (N), the FE force at the
        largest pressure, and ``loo_error_pct`` (% of that force).
    fit_time_s : float
        CPU time of the fit including the LOO errors (s).
    _onset, _curve : object
        The fitted interpolants of the onset per clearance and of the contact stiffness
        (internal; unitless inputs and outputs).
    _scales : dict
        The scaling of their inputs to the training ranges (internal, unitless).

    Examples
    --------
    See :func:`fit_surrogate`.
    """

    pressures_mpa: tuple[float, ...]
    n_designs: int
    group_min: dict[str, float]
    group_max: dict[str, float]
    loo: pd.DataFrame = field(repr=False)
    fit_time_s: float
    _onset: Any = field(repr=False)
    _curve: Any = field(repr=False)
    _scales: dict[str, Any] = field(repr=False)

    @property
    def loo_error_pct(self) -> dict[str, float]:
        """Leave-one-design-out error, % of each design's N at the largest pressure:
        ``max``, ``p95`` and ``median`` over the designs with contact by then."""
        e = self.loo["loo_error_pct"].dropna().to_numpy()
        if not len(e):
            return {"max": float("nan"), "p95": float("nan"), "median": float("nan")}
        return {"max": float(e.max()), "p95": float(np.percentile(e, 95)),
                "median": float(np.median(e))}

    def in_domain(self, groups: pd.DataFrame) -> np.ndarray:
        """True for rows whose groups lie in the training box (no extrapolation).

        Parameters
        ----------
        groups : DataFrame
            Columns ``clearance_ratio``, ``wall_ratio``, ``wire_ratio`` (unitless) and
            ``shear_modulus_mpa`` (MPa).

        Returns
        -------
        ndarray of bool
        """
        ok = np.ones(len(groups), bool)
        for k in (*GROUPS, "shear_modulus_mpa"):
            tol = 1e-9 * max(1.0, abs(self.group_max[k]))
            v = groups[k].to_numpy(float)
            ok &= (v >= self.group_min[k] - tol) & (v <= self.group_max[k] + tol)
        return ok

    def predict(self, designs: pd.DataFrame, pressures_mpa: Sequence[float]) -> np.ndarray:
        """Predicted squeeze force N (N), one row per design and one column per pressure.

        Parameters
        ----------
        designs : DataFrame
            ``hole_mm``, ``tube_od_mm``, ``tube_id_mm``, ``wire_mm``, ``length_mm`` (mm) and
            ``shear_modulus_mpa`` (MPa) per design.
        pressures_mpa : sequence of float
            Pressures (MPa), > 0.

        Returns
        -------
        ndarray, shape (designs, pressures)
            N (N); 0 below the predicted contact onset.
        """
        return self._predict(designs, pressures_mpa)[0]

    def _geo(self, g: pd.DataFrame) -> np.ndarray:
        """The onset stage's inputs: (c/d1, t/d1, d2/d1) scaled to the training box."""
        s = self._scales
        x = g[list(GROUPS)].to_numpy(float)
        return ((x - s["geo_lo"]) / s["geo_span"])[:, s["geo_keep"]]

    def _predict(self, designs: pd.DataFrame, pressures_mpa: Sequence[float] | np.ndarray,
                 onset_coef: np.ndarray | None = None, curve_coef: np.ndarray | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
        p = np.asarray(pressures_mpa, float)
        if np.any(~(p > 0)):
            raise InputError("pressures_mpa must be > 0 MPa for the surrogate")
        g = _design_groups(designs)
        if self._onset is not None:
            per_c = self._onset(self._geo(g), onset_coef)
            q_on = np.maximum(per_c * _clearance(g), 0.0)
        else:
            q_on = np.zeros(len(g))
        gm = g["shear_modulus_mpa"].to_numpy(float)
        s = p[None, :] / gm[:, None] - q_on[:, None]
        n = np.zeros_like(s)
        hit = s > 0
        if hit.any():
            i, j = np.nonzero(hit)
            zd = _curve_design(q_on, g, self._scales)
            z = np.column_stack([zd[i], _pressure_coord(s[i, j], self._scales["s_max"])])
            k = np.maximum(self._curve(z, curve_coef), 0.0)
            lw = g["length_mm"].to_numpy(float) * g["wire_mm"].to_numpy(float)
            n[i, j] = k * s[i, j] * gm[i] * lw[i]
        return n, q_on * gm


def _clearance(g: pd.DataFrame) -> np.ndarray:
    """c/d1 of each row, at least :data:`CLEARANCE_FLOOR` (the onset stage's divisor)."""
    return np.maximum(g["clearance_ratio"].to_numpy(float), CLEARANCE_FLOOR)


def _curve_design(q_on: np.ndarray, g: pd.DataFrame, scales: dict[str, Any]) -> np.ndarray:
    """The curve stage's design inputs: (q_on, t/d1, d2/d1) scaled to their training ranges."""
    x = np.column_stack([q_on, g["wall_ratio"].to_numpy(float),
                         g["wire_ratio"].to_numpy(float)])
    return ((x - scales["cur_lo"]) / scales["cur_span"])[:, scales["cur_keep"]]


def _pressure_coord(s: np.ndarray, s_max: float) -> np.ndarray:
    """The curve stage's pressure input PRESSURE_WEIGHT sqrt(s / s_max), s = P/G - q_on."""
    return PRESSURE_WEIGHT * np.sqrt(s / s_max)


def _design_groups(designs: pd.DataFrame) -> pd.DataFrame:
    need = ("hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm", "length_mm", "shear_modulus_mpa")
    missing = [c for c in need if c not in designs]
    if missing:
        raise InputError(f"surrogate designs need columns {', '.join(missing)}")
    g = designs.copy()
    _add_geometric_groups(g)
    return g


def fit_surrogate(frame: pd.DataFrame, *, loo: bool = True) -> SqueezeSurrogate:
    """Fit the two-stage surrogate of N(P) on the solved designs of a sweep.

    Parameters
    ----------
    frame : DataFrame
        Sweep rows (:func:`exofric.design.run_sweep` ``.frame``): sizes (mm), ``c10_mpa``,
        ``c01_mpa`` (MPa), ``pressure_mpa`` (MPa), ``squeeze_force_n`` (N),
        ``contact_onset_pressure_mpa`` (MPa), ``status``, ``key``.
    loo : bool
        Compute the leave-one-design-out errors (cost ~ one more solve of the system per
        design; a few seconds for 200 designs x 12 pressures).

    Returns
    -------
    SqueezeSurrogate

    Raises
    ------
    InputError
        Fewer than :data:`MIN_DESIGNS` solved designs, or none with contact.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> rows = []
    >>> for k, (c, w) in enumerate([(0.0, 1.1), (0.1, 1.6), (0.3, 1.3), (0.2, 1.9),
    ...                             (0.05, 1.4), (0.25, 1.7)]):
    ...     on = 0.5 * c                       # a made-up law: onset 0.5 MPa per mm of gap
    ...     for p in (0.2, 0.4, 0.6):
    ...         rows.append({"key": str(k), "name": str(k), "status": "ok",
    ...             "hole_mm": 8.3 + w + c, "tube_od_mm": 8.3, "tube_id_mm": 4.97,
    ...             "wire_mm": w, "length_mm": 116.0, "c10_mpa": 0.6, "c01_mpa": 0.03,
    ...             "pressure_mpa": p, "contact_onset_pressure_mpa": on,
    ...             "squeeze_force_n": 400.0 * max(p - on, 0.0) * w})
    >>> s = fit_surrogate(pd.DataFrame(rows))
    >>> s.n_designs, bool(s.loo_error_pct["max"] < 50.0)
    (6, True)
    """
    t0 = time.process_time()
    if "status" in frame:
        frame = frame[frame["status"] == "ok"]
    f = sweep_groups(frame)
    f = f[np.isfinite(f["squeeze_force_n"].to_numpy(float))].reset_index(drop=True)
    keys = list(dict.fromkeys(f["key"]))
    if len(keys) < MIN_DESIGNS:
        raise InputError(f"the surrogate needs at least {MIN_DESIGNS} solved designs, "
                         f"the sweep has {len(keys)}")
    gm = f["shear_modulus_mpa"].to_numpy(float)
    q_on = f["contact_onset_pressure_mpa"].to_numpy(float) / gm
    s_all = f["pressure_ratio"].to_numpy(float) - np.where(np.isfinite(q_on), q_on, np.inf)
    contact = s_all > 0
    if not contact.any():
        raise InputError("the surrogate needs designs with contact: no design of the sweep "
                         "touches the wire at its pressures")
    s_max = float(s_all[contact].max())
    rows = s_all > ONSET_GAP * s_max            # the curve stage's rows
    one = f.drop_duplicates("key")
    geo = one[list(GROUPS)].to_numpy(float)
    lo, span, keep = _box(geo)
    q_one = (one["contact_onset_pressure_mpa"].to_numpy(float)
             / one["shear_modulus_mpa"].to_numpy(float))
    on_ok = np.isfinite(q_one)
    cur_lo, cur_span, cur_keep = _box(np.column_stack(
        [q_one, one["wall_ratio"].to_numpy(float), one["wire_ratio"].to_numpy(float)])[on_ok])
    scales: dict[str, Any] = {"geo_lo": lo, "geo_span": span, "geo_keep": keep,
                              "cur_lo": cur_lo, "cur_span": cur_span, "cur_keep": cur_keep,
                              "s_max": s_max}
    zg_one = ((geo - lo) / span)[:, keep]
    onset = (_RBF(zg_one[on_ok], q_one[on_ok] / _clearance(one)[on_ok])
             if on_ok.sum() >= 3 else None)
    fr = f[rows]
    zc = np.column_stack([_curve_design(q_on[rows], fr, scales),
                          _pressure_coord(s_all[rows], s_max)])
    stiffness = (fr["squeeze_force_n"].to_numpy(float)         # k = N / (G L d2 s)
                 / (gm[rows] * fr["length_mm"].to_numpy(float) * fr["wire_mm"].to_numpy(float)
                    * s_all[rows]))
    curve = _RBF(zc, stiffness)
    gmin = {k: float(one[k].min()) for k in (*GROUPS, "shear_modulus_mpa")}
    gmax = {k: float(one[k].max()) for k in (*GROUPS, "shear_modulus_mpa")}
    pressures = tuple(sorted({float(x) for x in f["pressure_mpa"]}))
    sur = SqueezeSurrogate(pressures, len(keys), gmin, gmax, pd.DataFrame(), 0.0, onset, curve,
                           scales)
    table = _loo(sur, f, rows, on_ok, one) if loo else pd.DataFrame(
        columns=["key", "name", "loo_max_error_n", "n_pmax_n", "loo_error_pct"])
    return replace(sur, loo=table, fit_time_s=time.process_time() - t0)


def _loo(sur: SqueezeSurrogate, f: pd.DataFrame, curve_rows: np.ndarray, on_ok: np.ndarray,
         one: pd.DataFrame) -> pd.DataFrame:
    """Leave-one-design-out curves of every training design (exact rank updates);
    ``curve_rows``: the rows of ``f`` in the curve stage."""
    key_c = f["key"].to_numpy()[curve_rows]
    onset_row = {k: i for i, k in enumerate(one["key"].to_numpy()[on_ok])}
    rows = []
    for key, g in f.groupby("key", sort=False):
        b = np.flatnonzero(key_c == key)
        cc = sur._curve.loo_coefficients(b) if len(b) else None
        oc = (sur._onset.loo_coefficients(np.array([onset_row[key]]))
              if sur._onset is not None and key in onset_row else None)
        p = g["pressure_mpa"].to_numpy(float)
        n_fe = g["squeeze_force_n"].to_numpy(float)
        n_loo = sur._predict(g.iloc[:1], p, oc, cc)[0][0]
        n_top = float(n_fe[np.argmax(p)])
        err = float(np.max(np.abs(n_loo - n_fe)))
        rows.append({"key": key, "name": g["name"].iloc[0] if "name" in g else key,
                     "loo_max_error_n": err, "n_pmax_n": n_top,
                     "loo_error_pct": 100.0 * err / n_top if n_top > 0 else np.nan})
    return pd.DataFrame(rows)


def candidate_designs(spec: SweepSpec, n: int = N_CANDIDATES, seed: int = 0) -> list[Design]:
    """Quasi-random designs in the box of a sweep's possible designs, plus those designs.

    The box spans the smallest to the largest hole D, tube OD d1, wall-to-OD ratio t/d1, wire
    d2, Shore and length L of ``spec.runnable`` (a scrambled Sobol sequence; constant axes
    stay fixed); designs that cannot exist (tube and wire wider than the hole) are left out.

    Parameters
    ----------
    spec : SweepSpec
        The sweep (its possible designs give the box).
    n : int
        Quasi-random designs to draw (>= 0).
    seed : int
        Seed of the scrambled Sobol sequence.

    Returns
    -------
    list of Design
        The sweep's possible designs first, then the possible drawn ones (``family``
        ``"candidate"``, sizes in mm rounded to 1 um, ID to 1 nm).

    Examples
    --------
    >>> from exofric.design import parse_sweep
    >>> spec = parse_sweep({"pressures_mpa": [0.6], "grid": {"hole_mm": [10.0, 10.5]}})
    >>> c = candidate_designs(spec, 64)
    >>> len(c), all(10.0 <= d.hole_mm <= 10.5 for d in c)
    (66, True)
    """
    from scipy.stats import qmc

    if n < 0:
        raise InputError(f"n (candidates) must be >= 0, got {n}")
    base = list(spec.runnable)
    if not base:
        raise InputError("the sweep has no possible design to draw candidates around")
    cols = np.array([[d.hole_mm, d.tube_od_mm, 0.5 * (1.0 - d.tube_id_mm / d.tube_od_mm),
                      d.wire_mm, d.shore, d.length_mm] for d in base])
    lo, hi = cols.min(axis=0), cols.max(axis=0)
    out = list(base)
    if n == 0:
        return out
    u = qmc.Sobol(6, scramble=True, seed=seed).random(n)
    x = lo + u * (hi - lo)
    for i, (hole, od, ratio, wire, shore, length) in enumerate(x):
        hole, od, wire = round(hole, 3), round(od, 3), round(wire, 3)
        if od + wire > hole:
            continue
        out.append(Design(len(out), f"candidate {i + 1}", "candidate", hole, od,
                          round(od * (1.0 - 2.0 * ratio), 6), wire, round(length, 3),
                          round(shore, 3), key=f"candidate-{i + 1}"))
    return out


@checked_init
@dataclass(frozen=True)
class SurrogateSearch(DisplayMixin):
    """A design search on the surrogate, its best designs confirmed with the FE solver.

    Attributes
    ----------
    predicted : DesignSearch
        Every in-domain candidate ranked on the surrogate's N(P).
    confirmed : DesignSearch
        The confirmed designs ranked on their FE N(P).
    comparison : DataFrame
        Per confirmed design: sizes (mm), Shore, predicted and FE N at pmax (N), predicted
        and FE least pressure (MPa), ``applicability_distance`` and ``deviation_pct``.
    loo_error_pct : dict
        The surrogate's leave-one-design-out error (% of N at the largest pressure).
    candidates : int
        Candidates evaluated on the surrogate (in its domain).
    out_of_domain : int
        Candidates left out because their groups are outside the training box.
    predict_time_s, confirm_time_s : float
        CPU time of the surrogate exploration and of the FE confirmation (s).

    Examples
    --------
    See :func:`surrogate_search`.
    """

    predicted: DesignSearch = field(repr=False)
    confirmed: DesignSearch = field(repr=False)
    comparison: pd.DataFrame = field(repr=False)
    loo_error_pct: dict[str, float]
    candidates: int
    out_of_domain: int
    predict_time_s: float
    confirm_time_s: float

    @property
    def best(self) -> dict[str, Any] | None:
        """The best confirmed design (FE), None if no confirmed design reaches the target."""
        return self.confirmed.best

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (N, MPa, Nm, mm, %, s)."""
        comp = self.comparison.replace({np.nan: None}).to_dict(orient="records")
        return {"loo_error_pct": self.loo_error_pct, "candidates": self.candidates,
                "out_of_domain": self.out_of_domain, "predict_time_s": self.predict_time_s,
                "confirm_time_s": self.confirm_time_s, "best": self.best,
                "predicted_best": self.predicted.best, "confirmed": comp}


def _rows(designs: Sequence[Design], spec: SweepSpec, pressures: Sequence[float],
          n: np.ndarray, onset: np.ndarray) -> pd.DataFrame:
    """Sweep-like rows (what :func:`search_designs` reads) for designs with forces ``n``."""
    rows = []
    for i, d in enumerate(designs):
        dev_pct, valid = _deviation(d, spec)
        for j, p in enumerate(pressures):
            rows.append({"key": d.key or f"design-{i}", "design_index": i, "name": d.name,
                         "family": d.family, "status": "ok", "pressure_mpa": float(p),
                         "squeeze_force_n": float(n[i, j]), "hole_mm": d.hole_mm,
                         "tube_od_mm": d.tube_od_mm, "tube_id_mm": d.tube_id_mm,
                         "wire_mm": d.wire_mm, "length_mm": d.length_mm, "shore": d.shore,
                         "deviation_pct": dev_pct, "in_validated_region": valid,
                         "contact_onset_pressure_mpa": float(onset[i])})
    return pd.DataFrame(rows)


def surrogate_search(
    surrogate: SqueezeSurrogate,
    spec: SweepSpec,
    target_torque_nm: float,
    arm_radius_m: float,
    pmax_mpa: float,
    *,
    candidates: int | Sequence[Design] = N_CANDIDATES,
    confirm: int = N_CONFIRM,
    gamma: float | None = None,
    f0_n: float | None = None,
    objective: str = "pressure",
    validated_only: bool = False,
    seed: int = 0,
) -> SurrogateSearch:
    """Explore candidate designs on the surrogate; confirm the best with the FE solver.

    Parameters
    ----------
    surrogate : SqueezeSurrogate
        From :func:`fit_surrogate`.
    spec : SweepSpec
        Pressures (MPa), material and solver settings of the FE confirmation, friction
        model, base design; its possible designs span the candidate box.
    target_torque_nm, arm_radius_m, pmax_mpa : float
        Target torque (Nm), lever arm (m), pressure limit (MPa), as for
        :func:`exofric.design.search_designs`.
    candidates : int or sequence of Design
        How many quasi-random candidates to draw (:func:`candidate_designs`), or the
        candidates themselves.
    confirm : int
        How many of the best-ranked candidates to solve with the FE (>= 1); when none
        reaches the target, the closest ones.
    gamma, f0_n : float, optional
        Friction model F = gamma N + F0 (default the sweep's).
    objective : {'pressure', 'margin'}
        Ranking, as for :func:`exofric.design.search_designs`.
    validated_only : bool
        Rank only designs inside the validated deviation region.
    seed : int
        Seed of the candidate draw.

    Returns
    -------
    SurrogateSearch

    Examples
    --------
    See ``tests/test_surrogate.py`` and ``benchmarks/bench_surrogate.py`` (FE solves).
    """
    if confirm < 1:
        raise InputError(f"confirm must be >= 1, got {confirm}")
    g = spec.gamma if gamma is None else gamma
    f0 = spec.f0_n if f0_n is None else f0_n
    t0 = time.process_time()
    cands = (candidate_designs(spec, candidates, seed) if isinstance(candidates, int)
             else list(candidates))
    if not cands:
        raise InputError("no candidate designs to search")
    table = pd.DataFrame([{"hole_mm": d.hole_mm, "tube_od_mm": d.tube_od_mm,
                           "tube_id_mm": d.tube_id_mm, "wire_mm": d.wire_mm,
                           "length_mm": d.length_mm,
                           "shear_modulus_mpa": spec.material.material(d.shore).shear_modulus}
                          for d in cands])
    inside = surrogate.in_domain(_design_groups(table))
    if not inside.any():
        raise InputError("every candidate lies outside the surrogate's training domain")
    cands = [c for c, ok in zip(cands, inside, strict=True) if ok]
    n, onset = surrogate._predict(table[inside].reset_index(drop=True), spec.pressures_mpa)
    def rank(rows: pd.DataFrame) -> DesignSearch:
        return search_designs(rows, target_torque_nm, arm_radius_m, pmax_mpa, gamma=g, f0_n=f0,
                              objective=objective, validated_only=validated_only)

    pred = rank(_rows(cands, spec, spec.pressures_mpa, n, onset))
    t_pred = time.process_time() - t0
    picked = pred.ranked if len(pred.ranked) else pred.closest
    idx = [int(i) for i in picked["design_index"].head(confirm)]
    t1 = time.process_time()
    fe_n, fe_on = [], []
    for i in idx:
        try:
            r = solve_design(cands[i], spec.pressures_mpa, spec.material, spec.solver,
                             raise_errors=True)
        except ConvergenceError as exc:      # a solver failure stays one (CLI exit 3)
            raise ConvergenceError(f"FE confirmation of {cands[i].name}: {exc}",
                                   reached=exc.reached) from None
        except InputError as exc:
            raise InputError(f"FE confirmation of {cands[i].name}: {exc}") from None
        fe_n.append(r["squeeze_force_n"])
        fe_on.append(r["contact_onset_pressure_mpa"])
    chosen = [cands[i] for i in idx]
    conf = rank(_rows(chosen, spec, spec.pressures_mpa, np.array(fe_n), np.array(fe_on)))
    t_conf = time.process_time() - t1
    p_req = dict(zip(pred.table["design_index"], pred.table["required_pressure_mpa"],
                     strict=True))
    c_req = dict(zip(conf.table["design_index"], conf.table["required_pressure_mpa"],
                     strict=True))
    comp = []
    for k, d in enumerate(chosen):
        gm = spec.material.material(d.shore).shear_modulus
        a = applicability(d.structure(), gm)
        comp.append({"name": d.name, "hole_mm": d.hole_mm, "tube_od_mm": d.tube_od_mm,
                     "tube_id_mm": d.tube_id_mm, "wire_mm": d.wire_mm,
                     "length_mm": d.length_mm, "shore": d.shore,
                     "predicted_n_pmax_n": float(np.interp(pmax_mpa, spec.pressures_mpa,
                                                           n[idx[k]])),
                     "fe_n_pmax_n": float(np.interp(pmax_mpa, spec.pressures_mpa, fe_n[k])),
                     "predicted_required_pressure_mpa": float(p_req[idx[k]]),
                     "fe_required_pressure_mpa": float(c_req[k]),
                     "applicability_distance": a.distance,
                     "inside_applicability_domain": a.inside,
                     "deviation_pct": a.deviation_pct})
    return SurrogateSearch(pred, conf, pd.DataFrame(comp), surrogate.loo_error_pct,
                           len(cands), int((~inside).sum()), t_pred, t_conf)
