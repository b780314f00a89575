"""The equivalent coefficient gamma from rig data (paper Eq 7), its error measures and CI.

Given a squeeze curve N(P) (from the FE; N in N, P in MPa) and measured friction
points (P_i, F_i), the squeeze curve is interpolated onto the friction pressures with a
monotone PCHIP (only inside its pressure range; points outside are dropped and counted),
then gamma minimises Eq 7, sum (gamma N_i - F_i)^2, in closed form:
gamma = sum N_i F_i / sum N_i^2. The affine variant F = gamma N + F0 (for rigs with a
pressure-independent drag) is ordinary least squares on [N, 1]; it is never the default.

Relative error measures (the paper's "relative error of 10.68 %" in Sec. 3.5 is called an
"average error" in Sec. 6; see docs/paper-notes.md):

* ``relative_error_pct`` (primary) = mean_i |F^_i - F_i| / F_i x 100, the mean absolute
  relative error, in line with the "average error" of Table 1 and Sec. 6;
* ``max_relative_error_pct`` = the signed relative error (F^_i - F_i) / F_i of largest
  magnitude (the measure of Sec. 4, Figs 8-10);
* ``relative_rms_residual_pct`` = sqrt(sum e_i^2 / sum F_i^2) x 100: the RMS residual as a
  percentage of the RMS friction (not a mean of the relative errors: large forces dominate it,
  so it is usually smaller than ``relative_error_pct``).

Points with F_i = 0 are left out of the relative measures (undefined there).

Without replicates the 95 % confidence interval is ``analytic`` (what the default ``ci="auto"``
picks then): the t quantile (n - k dof; k = 1
for gamma alone, 2 for the affine fit) times the heteroscedasticity-robust HC3 sandwich
standard error, because load-cell noise usually scales with the reading. On the virtual rig
(9 points, 400 seeds) it covered the planted gamma in 93-97 % of runs for relative and for
absolute noise, where the classical OLS standard error (``ci="ols"``) covered only 84 % under
2 % relative noise. A seeded pairs ``bootstrap`` (percentile interval) is also available.

Replicates (several pulls at one pressure) are clusters: points with exactly the same pressure
form one by default, or ``groups`` labels them (e.g. the pressure plateau a pull belongs to).
Between-pull scatter is then usually the larger error, and the pulls of one plateau share it,
so with replicates the default ``ci="auto"`` becomes ``"cluster"``: a cluster-robust
covariance (by default CR2 with a t quantile on the Bell-McCaffrey dof; or CR3, the
leave-one-cluster-out jackknife of MacKinnon, Nielsen & Webb 2023, or CR1, the Liang-Zeger
sandwich with the small-sample factor of statsmodels' ``cov_type="cluster"``, both with t on
G - 1 dof for G clusters; :data:`_CLUSTER_VARIANT` selects). Every interval takes time and
memory linear in the number of points (per-cluster sums; no n x n matrix). Without
replicates ``"auto"`` is ``"analytic"``, so such fits are unchanged. ``ci="odr"`` fits
errors-in-variables (orthogonal distance regression, :func:`odrpack.odr_fit`) for a noisy
pressure reading, given the standard deviations of pressure and friction. With replicates
and more clusters than parameters, the residual sum of squares is split into pure error and
lack of fit (:class:`LackOfFit`, an F test of the model against the cluster means).
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._lsq import hc3_covariance, lsq_covariance, residual_variance
from exofric._validate import checked_init
from exofric.errors import (
    ConvergenceError,
    InputError,
    check_range,
    check_seed,
    check_series,
)
from exofric.friction._curve import SqueezeCurve
from exofric.friction._model import FrictionModel

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["GammaFit", "LackOfFit", "fit_gamma", "match_squeeze", "relative_errors"]

ModelKind = Literal["proportional", "affine"]
CiMethod = Literal["auto", "analytic", "ols", "bootstrap", "cluster", "odr"]
ClusterVariant = Literal["cr1", "cr3", "cr2bm"]

#: Cluster-robust covariance used by ``ci="cluster"``: "cr2bm" (CR2 with Bell-McCaffrey degrees
#: of freedom, working variance proportional to the fitted force; the default, chosen by the
#: coverage study in benchmarks/bench_rig_coverage.py), "cr3" (leave-one-cluster-out jackknife,
#: t on G - 1 dof) or "cr1" (Liang-Zeger sandwich x G/(G-1) x (n-1)/(n-k), t on G - 1 dof).
_CLUSTER_VARIANT: ClusterVariant = "cr2bm"
#: Bootstrap indices drawn per block (n_boot x m in blocks of rows): bounds the memory.
_BOOT_BLOCK = 1 << 21
_VARIANT_TEXT = {"cr1": "CR1 sandwich", "cr3": "CR3 jackknife",
                 "cr2bm": "CR2 with Bell-McCaffrey dof"}


def match_squeeze(
    squeeze_pressure_mpa: ArrayLike,
    squeeze_force_n: ArrayLike,
    pressure_mpa: ArrayLike,
    *,
    edge_tol_mpa: float = 0.005,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Squeezing force N (N) at the given pressures (MPa) by monotone PCHIP interpolation.

    Parameters
    ----------
    squeeze_pressure_mpa, squeeze_force_n : array_like
        The squeeze curve (strictly increasing pressures, MPa; forces in N), as for
        :class:`SqueezeCurve`, whose interpolant gives N.
    pressure_mpa : array_like
        Where N is wanted (MPa).
    edge_tol_mpa : float
        Pressures up to this far (MPa) beyond the curve's ends still count as inside and
        are extrapolated by the end PCHIP piece: a rig logging 0.6002 MPa at the 0.6 MPa set
        point is not dropped. 0 for a strict range.

    Returns
    -------
    (N, inside)
        N in N at the pressures (NaN outside) and the mask of pressures inside
        [min - tol, max + tol] of the curve.

    Examples
    --------
    >>> n, ok = match_squeeze([0.2, 0.4, 0.6], [10.0, 50.0, 90.0], [0.3, 0.7])
    >>> round(float(n[0]), 9), bool(ok[1])
    (30.0, False)
    """
    curve = SqueezeCurve(squeeze_pressure_mpa, squeeze_force_n)
    p, _ = check_series("pressure_mpa", pressure_mpa, x_unit="MPa", increasing=False,
                        min_points=1)
    tol = check_range("edge_tol_mpa", edge_tol_mpa, 0.0, 0.1, unit="MPa")
    lo, hi = curve.pressure_range_mpa
    inside = (p >= lo - tol) & (p <= hi + tol)
    out = np.full(p.shape, np.nan)
    out[inside] = curve(p[inside], edge_tol_mpa=tol)
    return out, inside


def relative_errors(predicted_n: ArrayLike, measured_n: ArrayLike) -> NDArray[np.float64]:
    """Signed relative errors (predicted - measured) / measured, in % (NaN where measured is 0).

    Parameters
    ----------
    predicted_n : array_like
        Predicted values, usually friction forces in N.
    measured_n : array_like
        Measured values in the same unit (N), same shape (or broadcastable).

    Returns
    -------
    ndarray
        100 (predicted - measured) / measured in %, NaN where ``measured_n`` is 0.

    Examples
    --------
    >>> relative_errors([110.0, 45.0], [100.0, 50.0]).round(6).tolist()
    [10.0, -10.0]
    """
    pr = np.asarray(predicted_n, dtype=float)
    me = np.asarray(measured_n, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(me != 0.0, 100.0 * (pr - me) / me, np.nan)


def _tuple(a: NDArray[Any]) -> tuple[Any, ...]:
    """The elements of a 1-D array as a tuple of Python scalars.

    A small function of its own: under ``tracemalloc`` each of the m allocations looks up the
    line number of the allocating frame, which costs time in proportion to the size of that
    frame's code (about 20x slower for 10^5 points inside :func:`fit_gamma`).
    """
    return tuple(a.tolist())


def _signed_max(err_pct: NDArray[np.float64]) -> float:
    ok = np.isfinite(err_pct)
    if not np.any(ok):
        return float("nan")
    e = err_pct[ok]
    return float(e[np.argmax(np.abs(e))])


@checked_init
@dataclass(frozen=True)
class LackOfFit:
    """Lack-of-fit F test of the least-squares fit against the cluster (replicate) means.

    The residual sum of squares of the fit splits into pure error, the scatter of the points
    about their cluster's mean friction (df n - G), and lack of fit, the rest (df G - k);
    F = (SS_lof / df_lof) / (SS_pe / df_pe) is F(df_lof, df_pe) distributed when the model
    holds and the cluster means are its only misfit. Identical to statsmodels'
    ``anova_lm(fit, fit on cluster dummies)``.

    Attributes
    ----------
    ss_lack_of_fit, ss_pure_error : float
        Sums of squares in N^2 (lack of fit is clamped at 0 when a cluster spans several
        pressures and the model happens to beat the cluster means).
    df_lack_of_fit, df_pure_error : int
        Their degrees of freedom, G - k and n - G (G clusters, n points, k parameters).
    f_stat : float
        F statistic (unitless; inf when the pure error is 0 and the lack of fit is not).
    p_value : float
        Upper tail probability of ``f_stat`` under F(df_lack_of_fit, df_pure_error).
    alpha : float
        Significance level of :attr:`significant` (unitless, default 0.05).

    Examples
    --------
    >>> lof = LackOfFit(12.0, 30.0, 3, 30, 4.0, 0.016)
    >>> lof.significant, lof.to_dict()["df_pure_error"]
    (True, 30)
    """

    ss_lack_of_fit: float
    ss_pure_error: float
    df_lack_of_fit: int
    df_pure_error: int
    f_stat: float
    p_value: float
    alpha: float = 0.05

    @property
    def significant(self) -> bool:
        """True when the lack of fit is significant at :attr:`alpha` (p < alpha)."""
        return bool(self.p_value < self.alpha)

    @property
    def verdict(self) -> str:
        """One sentence: the F test and what it means for the model."""
        test = (f"F = {self.f_stat:.3g} on {self.df_lack_of_fit} and {self.df_pure_error} dof, "
                f"p = {self.p_value:.3g}")
        if self.significant:
            return (f"significant lack of fit ({test}): the cluster means deviate from the "
                    "model by more than the scatter between replicates explains (a model "
                    "error, or a cluster-to-cluster effect such as re-seating, which the "
                    "cluster-robust interval allows for)")
        return (f"no significant lack of fit ({test}): the model explains the cluster means "
                "within the scatter between replicates")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of the fields plus ``significant`` and ``verdict`` (SS in N^2)."""
        return {
            "ss_lack_of_fit": self.ss_lack_of_fit, "ss_pure_error": self.ss_pure_error,
            "df_lack_of_fit": self.df_lack_of_fit, "df_pure_error": self.df_pure_error,
            "f_stat": self.f_stat, "p_value": self.p_value, "alpha": self.alpha,
            "significant": self.significant, "verdict": self.verdict,
        }


@checked_init
@dataclass(frozen=True)
class GammaFit(DisplayMixin):
    """Result of the Eq 7 least-squares fit of gamma (and F0 for the affine model).

    Attributes
    ----------
    model : FrictionModel
        gamma (unitless) and f0_n (N; 0 for the proportional model).
    kind : {"proportional", "affine"}
    gamma_ci95 : (lo, hi)
        95 % confidence interval of gamma.
    f0_ci95_n : (lo, hi) or None
        95 % confidence interval of F0 in N (affine only).
    ci_method : {"analytic", "ols", "bootstrap", "cluster", "odr"}
        How the interval was computed (``"auto"`` resolved).
    pressure_mpa, squeeze_force_n, friction_n, predicted_friction_n : tuple of float
        The matched points used (MPa, N), sorted by pressure.
    relative_error_pct : float
        Mean absolute relative error in % (primary measure; see module docstring).
    max_relative_error_pct, relative_rms_residual_pct : float
        Signed largest relative error and relative RMS residual, in %.
    n_dropped : int
        Friction points outside the squeeze curve's pressure range (not used).
    n_clusters : int
        Number of clusters G among the points used (distinct pressures, or distinct
        ``groups`` labels); 0 when not recorded.
    lack_of_fit : LackOfFit or None
        Lack-of-fit F test, when some cluster has >= 2 points and G exceeds the number of
        parameters; else None.
    ci_note : str
        One sentence: what the interval accounts for.
    group : tuple
        Cluster label of each point used (empty when not recorded).

    Examples
    --------
    >>> fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
    ...                 [100.0, 200.0, 268.55])
    >>> round(fit.gamma, 4), fit.n_points, fit.kind, fit.ci_method
    (0.7044, 3, 'proportional', 'analytic')
    >>> round(fit.relative_error_pct, 2), fit.n_clusters, fit.lack_of_fit is None
    (0.57, 3, True)
    """

    model: FrictionModel
    kind: ModelKind
    gamma_ci95: tuple[float, float]
    f0_ci95_n: tuple[float, float] | None
    ci_method: CiMethod
    pressure_mpa: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    friction_n: tuple[float, ...]
    predicted_friction_n: tuple[float, ...]
    relative_error_pct: float
    max_relative_error_pct: float
    relative_rms_residual_pct: float
    n_dropped: int
    n_clusters: int = 0
    lack_of_fit: LackOfFit | None = None
    ci_note: str = ""
    group: tuple[Any, ...] = ()

    @property
    def gamma(self) -> float:
        """Equivalent coefficient (unitless)."""
        return self.model.gamma

    @property
    def n_points(self) -> int:
        """Number of matched points used in the fit."""
        return len(self.pressure_mpa)

    @property
    def residual_n(self) -> NDArray[np.float64]:
        """Residuals F^_i - F_i in N."""
        return np.asarray(self.predicted_friction_n) - np.asarray(self.friction_n)

    @property
    def point_relative_error_pct(self) -> NDArray[np.float64]:
        """Signed relative error per point in % (NaN where F_i = 0)."""
        return relative_errors(self.predicted_friction_n, self.friction_n)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (gamma unitless, forces N, pressures MPa, errors %)."""
        d: dict[str, Any] = {
            "model": self.kind,
            "gamma": self.gamma,
            "gamma_ci95": list(self.gamma_ci95),
            "ci_method": self.ci_method,
            "ci_note": self.ci_note,
            "relative_error_pct": self.relative_error_pct,
            "max_relative_error_pct": self.max_relative_error_pct,
            "relative_rms_residual_pct": self.relative_rms_residual_pct,
            "n_points": self.n_points,
            "n_dropped": self.n_dropped,
            "n_clusters": self.n_clusters,
            "lack_of_fit": None if self.lack_of_fit is None else self.lack_of_fit.to_dict(),
            "pressure_mpa": list(self.pressure_mpa),
            "squeeze_force_n": list(self.squeeze_force_n),
            "friction_n": list(self.friction_n),
            "predicted_friction_n": list(self.predicted_friction_n),
            "residual_n": self.residual_n.tolist(),
            "point_relative_error_pct": self.point_relative_error_pct.tolist(),
        }
        if self.kind == "affine":
            d["f0_n"] = self.model.f0_n
            d["f0_ci95_n"] = None if self.f0_ci95_n is None else list(self.f0_ci95_n)
        return d

    def to_frame(self) -> pd.DataFrame:
        """The matched data points as a DataFrame: one row per point used (MPa, N, %).

        Columns: ``pressure_mpa``, ``squeeze_force_n``, ``friction_n`` (measured),
        ``predicted_friction_n``, ``residual_n``, ``relative_error_pct`` and ``group`` (the
        cluster label; the pressure when none was recorded).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
        ...                 [100.0, 200.0, 268.55])
        >>> fit.to_frame()[["pressure_mpa", "friction_n"]].values.tolist()
        [[0.2, 70.0], [0.4, 140.0], [0.6, 190.0]]
        """
        import pandas as pd

        return pd.DataFrame({
            "pressure_mpa": np.asarray(self.pressure_mpa, dtype=float),
            "squeeze_force_n": np.asarray(self.squeeze_force_n, dtype=float),
            "friction_n": np.asarray(self.friction_n, dtype=float),
            "predicted_friction_n": np.asarray(self.predicted_friction_n, dtype=float),
            "residual_n": self.residual_n,
            "relative_error_pct": self.point_relative_error_pct,
            "group": list(self.group) if self.group else list(self.pressure_mpa),
        })

    def plot(self, fig: Any | None = None, *, title: str = "") -> Any:
        """Draw measured vs fitted friction, residuals (N) and relative errors (%).

        Three Axes (:func:`exofric.plots.plot_gamma_fit`); write the figure with
        :func:`exofric.plots.save`.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on (default a new one).
        title : str
            Figure title.

        Returns
        -------
        matplotlib Figure

        Examples
        --------
        >>> fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
        ...                 [100.0, 200.0, 268.55])
        >>> len(fit.plot().axes)
        3
        """
        from exofric.plots import plot_gamma_fit

        return plot_gamma_fit(self, title, fig=fig)


def _solve(n: NDArray[np.float64], f: NDArray[np.float64], affine: bool) -> NDArray[np.float64]:
    """Closed-form least squares; n, f shaped (..., m). Returns (..., 2): gamma, f0."""
    if not affine:
        g = np.sum(n * f, axis=-1) / np.sum(n * n, axis=-1)
        return np.stack([g, np.zeros_like(g)], axis=-1)
    m = n.shape[-1]
    sn, sf = n.sum(-1), f.sum(-1)
    snn, snf = (n * n).sum(-1), (n * f).sum(-1)
    det = m * snn - sn * sn
    g = (m * snf - sn * sf) / det
    return np.stack([g, (sf - g * sn) / m], axis=-1)


def _covariance(
    n: NDArray[np.float64], res: NDArray[np.float64], affine: bool, robust: bool
) -> NDArray[np.float64]:
    """Covariance of (gamma[, F0]): HC3 sandwich if ``robust`` else classical OLS."""
    x = np.column_stack([n, np.ones_like(n)]) if affine else n[:, None]
    if robust:
        return hc3_covariance(x, res)
    return lsq_covariance(x, residual_variance(res, x.shape[1]))


def _factorize(labels: Any) -> tuple[NDArray[np.intp], int]:
    """Cluster codes 0..G-1 of any hashable labels (vectorised for numbers and strings)."""
    arr = np.asarray(labels)
    if arr.ndim == 1 and arr.dtype != object:
        _, codes = np.unique(arr, return_inverse=True)
    else:                       # objects (tuples, mixed types): hash them, in order of first use
        seen: dict[Hashable, int] = {}
        try:
            codes = np.array([seen.setdefault(v, len(seen)) for v in labels], dtype=np.intp)
        except TypeError:
            raise InputError("groups labels must be hashable (numbers, text or tuples)") from None
    codes = np.asarray(codes, dtype=np.intp).ravel()
    return codes, int(codes.max()) + 1 if codes.size else 0


def _labels(groups: Any, size: int) -> NDArray[Any]:
    """One cluster label per friction point as a 1-D array (object dtype for tuples etc.)."""
    arr = np.asarray(groups) if isinstance(groups, np.ndarray) else None
    if arr is None or arr.ndim != 1:
        items = list(groups) if np.ndim(groups) > 0 or isinstance(groups, (list, tuple)) else []
        arr = np.empty(len(items), dtype=object)
        arr[:] = items
        if items and (all(isinstance(v, str) for v in items) or all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in items)):
            arr = np.asarray(items)           # one plain type: np.unique can sort it
    if arr.size != size:
        raise InputError(f"groups has {arr.size} labels, need one per friction point ({size})")
    return arr


def _cluster_covariance(
    x: NDArray[np.float64],
    f: NDArray[np.float64],
    beta: NDArray[np.float64],
    codes: NDArray[np.intp],
    n_clusters: int,
    variant: ClusterVariant,
) -> NDArray[np.float64]:
    """Cluster-robust covariance of the OLS estimate ``beta`` of f on the design ``x`` (m, k).

    ``cr1``: (X'X)^-1 (sum_g s_g s_g') (X'X)^-1 x G/(G-1) x (m-1)/(m-k) with the cluster score
    s_g = sum_(i in g) x_i e_i (statsmodels' ``cov_type="cluster"``). ``cr3``: the
    leave-one-cluster-out jackknife (G-1)/G sum_g (b_(g) - b)(b_(g) - b)', each b_(g) solved
    in closed form from the per-cluster sums X_g'X_g and X_g'f_g (no refit loop). Raises
    InputError when leaving out a cluster leaves the parameters unidentified.
    """
    m, k = x.shape
    g = n_clusters
    xtx = x.T @ x
    if variant == "cr1":
        e = f - x @ beta
        s = np.stack([np.bincount(codes, weights=x[:, j] * e, minlength=g) for j in range(k)],
                     axis=1)                                            # (G, k) scores
        a = np.linalg.inv(xtx)
        c = g / (g - 1.0) * (m - 1.0) / (m - k)
        return np.asarray(c * a @ (s.T @ s) @ a)
    xtx_g = _cluster_gram(x, codes, g)
    xty_g = np.stack([np.bincount(codes, weights=x[:, j] * f, minlength=g) for j in range(k)],
                     axis=1)
    a_g = xtx[None] - xtx_g                                             # (G, k, k)
    det = np.linalg.det(a_g)
    bad = np.flatnonzero(~(np.abs(det) > 1e-10 * abs(float(np.linalg.det(xtx)))))
    if bad.size:
        raise InputError(f"ci cluster (CR3): leaving out cluster {int(bad[0]) + 1} of {g} "
                         "leaves too few distinct squeeze forces to fit the model; use more "
                         "clusters or the CR1 variant")
    b_g = np.linalg.solve(a_g, ((x.T @ f)[None] - xty_g)[..., None])[..., 0]  # (G, k)
    d = b_g - beta[None]
    return np.asarray((g - 1.0) / g * (d.T @ d))


def _cluster_gram(
    x: NDArray[np.float64], codes: NDArray[np.intp], n_clusters: int,
    weights: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """Per-cluster Gram matrices X_g' diag(w_g) X_g, shape (G, k, k), by ``np.bincount``.

    O(m k^2) time and O(G k^2) memory for m points of a k-column design (w = 1 without
    ``weights``); no n_g x n_g matrix.

    Examples
    --------
    >>> x = np.array([[1.0], [2.0], [3.0]])
    >>> _cluster_gram(x, np.array([0, 0, 1]), 2)[:, 0, 0].tolist()
    [5.0, 9.0]
    """
    k = x.shape[1]
    out = np.empty((n_clusters, k, k))
    for i in range(k):
        for j in range(i, k):
            prod = x[:, i] * x[:, j] if weights is None else weights * x[:, i] * x[:, j]
            out[:, i, j] = out[:, j, i] = np.bincount(codes, weights=prod, minlength=n_clusters)
    return out


def _cr2_bm(
    x: NDArray[np.float64], f: NDArray[np.float64], beta: NDArray[np.float64],
    codes: NDArray[np.intp], n_clusters: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """CR2 covariance and Bell-McCaffrey degrees of freedom per coefficient.

    CR2 (Bell & McCaffrey 2002): (X'X)^-1 sum_g X_g' A_g e_g e_g' A_g X_g (X'X)^-1 with
    A_g = (I - H_gg)^(-1/2), unbiased when the working model holds. The t quantile uses the
    Satterthwaite degrees of freedom of that variance, (sum lambda)^2 / sum lambda^2 over the
    eigenvalues of G' W G, G_g = (I - H)_(:,g) A_g X_g (X'X)^-1 l (Imbens & Kolesar 2016;
    Pustejovsky & Tipton 2018), with the working variance W proportional to the fitted force
    (scatter between constant and proportional to the force). With few clusters, or a few
    clusters of large force that dominate the fit, the dof fall well below G - 1 and the
    interval widens: that is what keeps its coverage at 95 %.

    Time and memory are linear in the number of points m (issue 31): only k x k per-cluster
    sums are formed, never an n_g x n_g or a G x G matrix. With the thin QR X = Q R (Q: m x k,
    orthonormal columns), H = Q Q' and H_gg = Q_g Q_g' has rank <= k. Let
    Q_g'Q_g = V diag(lambda) V' (k x k, 0 <= lambda <= 1). The thin SVD is
    Q_g = U diag(lambda)^(1/2) V' with U = Q_g V diag(lambda)^(-1/2), so
    I - H_gg = (I - UU') + U diag(1 - lambda) U' and

        (I - H_gg)^(-1/2) = I + U diag((1 - lambda)^(-1/2) - 1) U' = I + Q_g B_g Q_g',
        B_g = V diag(phi(lambda)) V',
        phi(lambda) = ((1 - lambda)^(-1/2) - 1) / lambda = 1 / (s (1 + s)), s = sqrt(1 - lambda).

    (This is the identity (I - X_g A X_g')^(-1/2) = I + X_g B X_g' with A = (X'X)^-1 written
    in the orthonormal basis Q, where the eigenvalues lambda are the cluster's leverages
    without the conditioning of X'X. phi(0) = 1/2 is finite and directions with lambda = 0
    are annihilated by Q_g, so clusters with fewer than k points are covered; 1 - lambda is
    clipped at 1e-12 as in the dense form.) With S_g = Q_g'Q_g, Q_g'A_g e_g =
    Q_g'e_g + S_g B_g Q_g'e_g =: u_g and the covariance is R^-1 (sum_g u_g u_g') R^-T.

    Degrees of freedom. For the coefficient picked by l, A_g X_g (X'X)^-1 l = Q_g c_g with
    c_g = (I + B_g S_g) R^-T l (a k-vector per cluster), and with E_g the m x n_g selection of
    cluster g's rows, G_g = E_g Q_g c_g - Q q_g, q_g = S_g c_g. With T_g = Q_g'W_g Q_g and
    T = sum_g T_g, M = G'WG has the entries

        M_gg = (c_g - q_g)' T_g (c_g - q_g) + q_g' (T - T_g) q_g   (two terms >= 0),
        M_gh = u_g' C u_h (g != h),  u_g = [T_g c_g; q_g],  C = [[0, -I], [-I, T]],

    i.e. a diagonal plus the rank <= 2k matrix U C U'. So tr M = sum_g M_gg and
    ||M||_F^2 = sum_g M_gg^2 + 2 sum_g (C u_g)' (sum_(h<g) u_h u_h') (C u_g), the inner sums
    running (exclusive cumulative) sums of the 2k x 2k outer products, O(G k^2) time. The
    diagonal and off-diagonal parts are summed separately, so the large c_g of clusters with
    leverage near 1 cancel only to first order, as in the dense n x n form.
    """
    k = x.shape[1]
    g = n_clusters
    qx, rx = np.linalg.qr(x)                                           # x = Q R, Q (m, k)
    r_inv = np.linalg.inv(rx)
    e = f - x @ beta
    w = np.abs(x @ beta)
    w = np.where(w > 0, w, max(float(w.max()), 1.0) * 1e-6)
    s_g = _cluster_gram(qx, codes, g)                                  # (G, k, k) Q_g'Q_g
    t_g = _cluster_gram(qx, codes, g, w)                               # (G, k, k) Q_g'W_g Q_g
    qe_g = np.stack([np.bincount(codes, weights=qx[:, j] * e, minlength=g) for j in range(k)],
                    axis=1)                                            # (G, k) Q_g'e_g
    lam, vec = np.linalg.eigh(s_g)                                     # (G, k), (G, k, k)
    s = np.sqrt(np.clip(1.0 - lam, 1e-12, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = np.where(lam > 0.5, (1.0 / s - 1.0) / lam, 1.0 / (s * (1.0 + s)))
    b_g = (vec * phi[:, None, :]) @ vec.transpose(0, 2, 1)             # (G, k, k)
    u = qe_g + np.einsum("gij,gj->gi", s_g, np.einsum("gij,gj->gi", b_g, qe_g))
    cov = r_inv @ (u.T @ u) @ r_inv.T
    big_t = t_g.sum(axis=0)
    cmat = np.zeros((2 * k, 2 * k))
    cmat[:k, k:] = cmat[k:, :k] = -np.eye(k)
    cmat[k:, k:] = big_t
    dof = np.empty(k)
    for j in range(k):
        ell = r_inv[j]                                                 # R^-T l
        c = ell[None] + np.einsum("gij,gj->gi", b_g, s_g @ ell)        # (G, k) c_g
        p_g = np.einsum("gij,gj->gi", t_g, c)                          # T_g c_g
        q_g = np.einsum("gij,gj->gi", s_g, c)                          # S_g c_g
        cq = c - q_g
        mgg = (np.einsum("gi,gij,gj->g", cq, t_g, cq)                  # diag(M), two terms
               + np.einsum("gi,gij,gj->g", q_g, big_t[None] - t_g, q_g))   # >= 0 each
        uu = np.concatenate([p_g, q_g], axis=1)                        # (G, 2k)
        yy = uu @ cmat                                                 # rows (C u_g)'
        off = 0.0                                                      # sum_(h<g) (y_g'u_h)^2
        for a_ in range(2 * k):
            for b_ in range(a_, 2 * k):
                prev = np.zeros(g)
                np.cumsum((uu[:, a_] * uu[:, b_])[:-1], out=prev[1:])
                off += (1.0 if a_ == b_ else 2.0) * float(yy[:, a_] * yy[:, b_] @ prev)
        frob2 = float(mgg @ mgg) + 2.0 * off
        dof[j] = float(mgg.sum()) ** 2 / frob2
    return np.asarray(cov), dof


def _lack_of_fit(
    f: NDArray[np.float64], res: NDArray[np.float64], codes: NDArray[np.intp], n_clusters: int,
    k: int,
) -> LackOfFit | None:
    """Pure-error / lack-of-fit split of the residual sum of squares, or None without replicates."""
    from scipy import stats

    m, g = f.size, n_clusters
    if g >= m or g <= k:
        return None
    size = np.bincount(codes, minlength=g)
    mean = np.bincount(codes, weights=f, minlength=g) / size
    ss_pe = float(np.sum((f - mean[codes]) ** 2))
    ss_lof = max(float(res @ res) - ss_pe, 0.0)
    df_lof, df_pe = g - k, m - g
    with np.errstate(divide="ignore", invalid="ignore"):
        fs = float(np.float64(ss_lof / df_lof) / np.float64(ss_pe / df_pe))
    p = float(stats.f.sf(fs, df_lof, df_pe)) if not np.isnan(fs) else float("nan")
    return LackOfFit(ss_lof, ss_pe, df_lof, df_pe, fs, p)


def _point_sd(name: str, value: ArrayLike | None, size: int, unit: str) -> NDArray[np.float64]:
    """A standard deviation per friction point (float or array), finite and > 0."""
    if value is None:
        raise InputError(f"{name} is required for ci='odr' (standard deviation in {unit}, a "
                         "number or one per friction point)")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or a list of numbers ({unit})") from None
    if a.ndim > 1 or (a.ndim == 1 and a.size != size):
        raise InputError(f"{name} must be a number or one value per friction point ({size}), "
                         f"got {a.size} values")
    if not np.all(np.isfinite(a) & (a > 0)):
        bad = a.ravel()[~(np.isfinite(a.ravel()) & (a.ravel() > 0))][0]
        raise InputError(f"{name} must be finite and > 0 {unit}, got {bad:g}")
    return np.broadcast_to(a, (size,)).astype(float)


def _sd_text(sd: NDArray[np.float64], unit: str) -> str:
    return f"{sd[0]:g} {unit}" if np.all(sd == sd[0]) else f"{sd.min():g}-{sd.max():g} {unit}"


def _odr(
    curve: SqueezeCurve, p: NDArray[np.float64], f: NDArray[np.float64],
    sd_p: NDArray[np.float64], sd_f: NDArray[np.float64], beta0: NDArray[np.float64],
    affine: bool, tol: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Errors-in-variables fit of F = gamma N(P) (+ F0) by odrpack: (beta, sd_beta)."""
    from odrpack import odr_fit

    lo, hi = curve.pressure_range_mpa
    lo, hi = lo - tol, hi + tol

    def clip(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.clip(x, lo, hi)        # N is flat beyond the matched range (+ edge tolerance)

    def fn(x: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
        y = b[0] * curve(clip(x), edge_tol_mpa=tol)
        return np.asarray(y + b[1] if affine else y, dtype=float)

    def jac_beta(x: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
        nx = curve(clip(x), edge_tol_mpa=tol)
        return np.vstack([nx, np.ones_like(nx)]) if affine else nx[None, :]

    def jac_x(x: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
        inside = (x >= lo) & (x <= hi)
        return np.asarray(b[0] * curve.slope(clip(x), edge_tol_mpa=tol) * inside, dtype=float)

    sol = odr_fit(fn, p, f, beta0 if affine else beta0[:1], weight_x=1.0 / sd_p**2,
                  weight_y=1.0 / sd_f**2, jac_beta=jac_beta, jac_x=jac_x)
    if not sol.success:
        raise ConvergenceError(f"errors-in-variables (ODR) fit of gamma did not converge: "
                               f"{sol.stopreason}")
    beta = np.asarray(sol.beta, dtype=float)
    sd = np.asarray(sol.sd_beta, dtype=float)
    if not affine:
        beta, sd = np.append(beta, 0.0), np.append(sd, 0.0)
    return beta, sd


def _check_gamma_options(model: str, ci: str) -> ClusterVariant:
    """Check ``model``, ``ci`` and the module's cluster variant; return the variant."""
    if model not in ("proportional", "affine"):
        raise InputError(f"model must be 'proportional' or 'affine', got {model!r}")
    methods = ("auto", "analytic", "ols", "bootstrap", "cluster", "odr")
    if ci not in methods:
        raise InputError(f"ci must be one of {', '.join(methods)}, got {ci!r}")
    variant = _CLUSTER_VARIANT
    if variant not in _VARIANT_TEXT:
        raise InputError(f"_CLUSTER_VARIANT must be 'cr1', 'cr3' or 'cr2bm', got {variant!r}")
    return variant


@dataclass(frozen=True)
class _GammaPoints:
    """The friction points a gamma fit uses (inside the squeeze curve, sorted by pressure).

    ``p`` in MPa; ``n`` (squeeze force at ``p``) and ``f`` (friction) in N; ``lab`` the cluster
    label per point, ``codes`` its code 0..g-1; ``sd_p`` (MPa) and ``sd_f`` (N) the points'
    standard deviations for ``ci="odr"`` (else None); ``n_given`` the points given in all.
    """

    p: NDArray[np.float64]
    n: NDArray[np.float64]
    f: NDArray[np.float64]
    lab: NDArray[Any]
    codes: NDArray[np.intp]
    g: int
    replicates: bool
    by_pressure: bool
    n_given: int
    sd_p: NDArray[np.float64] | None
    sd_f: NDArray[np.float64] | None

    @property
    def m(self) -> int:
        """Number of points used."""
        return int(self.p.size)

    @property
    def what(self) -> str:
        """What the clusters are, for the interval's note."""
        return "pressure clusters" if self.by_pressure else "clusters"


def _gamma_points(
    friction_pressure_mpa: ArrayLike, friction_n: ArrayLike, squeeze_pressure_mpa: ArrayLike,
    squeeze_force_n: ArrayLike, groups: ArrayLike | list[Hashable] | None, ci: str,
    pressure_sd_mpa: ArrayLike | None, friction_sd_n: ArrayLike | None, model: str,
    edge_tol: float,
) -> _GammaPoints:
    """Check the inputs, match N(P) (MPa, N) to the friction points and form the clusters."""
    pf, ff = check_series("friction_pressure_mpa", friction_pressure_mpa, "friction_n",
                          friction_n, x_unit="MPa", y_unit="N", increasing=False,
                          min_points=1)
    labels = None if groups is None else _labels(groups, pf.size)
    sd_p_all = sd_f_all = None
    if ci == "odr":
        sd_p_all = _point_sd("pressure_sd_mpa", pressure_sd_mpa, pf.size, "MPa")
        sd_f_all = _point_sd("friction_sd_n", friction_sd_n, pf.size, "N")
    elif pressure_sd_mpa is not None or friction_sd_n is not None:
        raise InputError("pressure_sd_mpa and friction_sd_n are only used with ci='odr', "
                         f"got ci={ci!r}")
    n_all, inside = match_squeeze(squeeze_pressure_mpa, squeeze_force_n, pf, edge_tol_mpa=edge_tol)
    affine = model == "affine"
    n_min = 3 if affine else 2
    if int(inside.sum()) < n_min:
        raise InputError(
            f"only {int(inside.sum())} friction points lie inside the squeeze curve's pressure "
            f"range; the {model} fit needs at least {n_min}"
        )
    order = np.argsort(pf[inside], kind="stable")
    p, n, f = pf[inside][order], n_all[inside][order], ff[inside][order]
    lab = p if labels is None else labels[inside][order]
    codes, g = _factorize(lab)
    replicates = bool(np.bincount(codes).max() >= 2)
    if not np.any(n != 0.0) or (affine and np.ptp(n) == 0.0):
        raise InputError("squeeze force is constant at the friction pressures; gamma is undefined")
    return _GammaPoints(
        p=p, n=n, f=f, lab=lab, codes=codes, g=g, replicates=replicates,
        by_pressure=labels is None, n_given=int(pf.size),
        sd_p=None if sd_p_all is None else sd_p_all[inside][order],
        sd_f=None if sd_f_all is None else sd_f_all[inside][order],
    )


def _gamma_method(ci: CiMethod, pts: _GammaPoints, n_min: int, model: str
                  ) -> tuple[CiMethod, str]:
    """The interval method (``"auto"`` resolved) and the note's fallback clause, if any."""
    g = pts.g
    fallback = ""
    method: CiMethod = ci
    if ci == "auto":
        method = "cluster" if pts.replicates and g >= n_min else "analytic"
        if pts.replicates and g < n_min:
            fallback = (f"; only {g} {pts.what} (a cluster-robust interval needs {n_min}), so "
                        "replicates are treated as independent")
    if method == "cluster" and g < n_min:
        raise InputError(f"ci cluster needs at least {n_min} clusters for the {model} fit, "
                         f"got {g}")
    return method, fallback


def _cluster_se(pts: _GammaPoints, beta: NDArray[np.float64], affine: bool,
                variant: ClusterVariant, dof: int
                ) -> tuple[NDArray[np.float64], NDArray[np.float64] | None, str]:
    """Cluster-robust standard errors (unitless, N), Bell-McCaffrey dof (CR2) and the note."""
    n, f, g = pts.n, pts.f, pts.g
    x = np.column_stack([n, np.ones_like(n)]) if affine else n[:, None]
    dofs = None
    if variant == "cr2bm":
        cov, dofs = _cr2_bm(x, f, beta, pts.codes, g)
        se = np.sqrt(np.diag(cov))
        dof_text = f"{dofs[0]:.1f} (Bell-McCaffrey)"
    else:
        se = np.sqrt(np.diag(_cluster_covariance(x, f, beta, pts.codes, g, variant)))
        dof_text = str(dof)
    note = (f"cluster-robust ({_VARIANT_TEXT[variant]}) over {g} {pts.what} of {pts.m} points; "
            f"t with {dof_text} dof")
    return se, dofs, note


def _odr_se(pts: _GammaPoints, beta: NDArray[np.float64], affine: bool,
            squeeze_pressure_mpa: ArrayLike, squeeze_force_n: ArrayLike, edge_tol: float,
            dof: int) -> tuple[NDArray[np.float64], NDArray[np.float64], str]:
    """The ODR estimate (gamma, F0 in N), its parameter sds and the note."""
    assert pts.sd_p is not None and pts.sd_f is not None
    curve = SqueezeCurve(squeeze_pressure_mpa, squeeze_force_n)
    sd_p, sd_f = pts.sd_p, pts.sd_f
    beta, sd = _odr(curve, pts.p, pts.f, sd_p, sd_f, beta, affine, edge_tol)
    if float(beta[0]) <= 0:
        raise InputError(f"ODR gamma = {float(beta[0]):.4g} is not positive; check the data")
    note = (f"errors-in-variables (ODR; pressure sd {_sd_text(sd_p, 'MPa')}, friction "
            f"sd {_sd_text(sd_f, 'N')}), parameter sd scaled by the residual variance; "
            f"t with {dof} dof; {pts.m} points treated as independent")
    return beta, sd, note


def _t_interval(
    method: CiMethod, pts: _GammaPoints, beta: NDArray[np.float64], affine: bool,
    variant: ClusterVariant, fallback: str, squeeze: tuple[ArrayLike, ArrayLike],
    edge_tol: float,
) -> tuple[float, float, tuple[float, float], tuple[float, float] | None, str]:
    """t x standard-error 95 % CIs: (gamma, F0 in N, gamma CI, F0 CI in N, note)."""
    from scipy import stats

    m, k = pts.m, (2 if affine else 1)
    gamma, f0 = (float(v) for v in beta)
    dof = (pts.g - 1) if method == "cluster" else (m - k)
    dofs = np.full(k, float(dof))
    if method == "cluster":
        se, bm_dofs, note = _cluster_se(pts, beta[:k], affine, variant, dof)
        if bm_dofs is not None:
            dofs = bm_dofs
    elif method == "odr":
        beta, sd, note = _odr_se(pts, beta, affine, *squeeze, edge_tol, dof)
        gamma, f0 = float(beta[0]), float(beta[1])
        se = sd[:k]
    else:
        se = np.sqrt(np.diag(_covariance(pts.n, gamma * pts.n + f0 - pts.f, affine,
                                         robust=method == "analytic")))
        note = (("HC3 heteroscedasticity-robust" if method == "analytic" else
                 "classical OLS (equal variances)")
                + f"; t with {dof} dof; {m} points treated as independent" + fallback)
    tq = [float(stats.t.ppf(0.975, d)) if d > 0 else float("nan") for d in dofs]
    g_ci = (gamma - tq[0] * float(se[0]), gamma + tq[0] * float(se[0]))
    f0_ci = (f0 - tq[1] * float(se[1]), f0 + tq[1] * float(se[1])) if affine else None
    return gamma, f0, g_ci, f0_ci, note


def _bootstrap_interval(pts: _GammaPoints, affine: bool, n_boot: int, seed: int
                        ) -> tuple[tuple[float, float], tuple[float, float] | None, str]:
    """Pairs-bootstrap percentile 95 % CIs of gamma and F0 (N), and the note."""
    n, f, m = pts.n, pts.f, pts.m
    rng = np.random.default_rng(seed)
    # resamples in blocks of rows (about 2^21 indices each): memory linear in m, and the
    # same index stream, so the same interval, as drawing all n_boot x m at once
    block = max(1, _BOOT_BLOCK // m)
    parts = []
    for start in range(0, int(n_boot), block):
        idx = rng.integers(0, m, size=(min(block, int(n_boot) - start), m))
        nb, fb = n[idx], f[idx]
        ok = (np.ptp(nb, axis=1) > 0) if affine else np.any(nb != 0, axis=1)
        parts.append(_solve(nb[ok], fb[ok], affine))
    est = np.concatenate(parts)
    lo, hi = np.percentile(est, [2.5, 97.5], axis=0)
    g_ci = (float(lo[0]), float(hi[0]))
    f0_ci = (float(lo[1]), float(hi[1])) if affine else None
    note = (f"pairs bootstrap over {m} points ({int(n_boot)} resamples, percentile); points "
            "treated as independent")
    return g_ci, f0_ci, note


def _gamma_result(
    pts: _GammaPoints, model: ModelKind, gamma: float, f0: float,
    g_ci: tuple[float, float], f0_ci: tuple[float, float] | None, method: CiMethod,
    note: str, lof: LackOfFit | None,
) -> GammaFit:
    """The :class:`GammaFit` of a fitted gamma (unitless) and F0 (N) with its error measures."""
    p, n, f = pts.p, pts.n, pts.f
    pred = gamma * n + f0
    res = pred - f
    rel = relative_errors(pred, f)
    ok = np.isfinite(rel)
    mean_rel = float(np.mean(np.abs(rel[ok]))) if np.any(ok) else float("nan")
    rms_rel = float(100.0 * np.sqrt(float(res @ res) / float(f @ f))) if np.any(f) else float("nan")
    p_tuple = _tuple(p)                 # shared by pressure_mpa and group (same values)
    return GammaFit(
        model=FrictionModel(gamma, f0),
        kind=model,
        gamma_ci95=g_ci,
        f0_ci95_n=f0_ci,
        ci_method=method,
        pressure_mpa=p_tuple,
        squeeze_force_n=_tuple(n),
        friction_n=_tuple(f),
        predicted_friction_n=_tuple(pred),
        relative_error_pct=mean_rel,
        max_relative_error_pct=_signed_max(rel),
        relative_rms_residual_pct=rms_rel,
        n_dropped=int(pts.n_given - pts.m),
        n_clusters=pts.g,
        lack_of_fit=lof,
        ci_note=note,
        group=p_tuple if pts.by_pressure else _tuple(np.asarray(pts.lab)),
    )


def fit_gamma(
    friction_pressure_mpa: ArrayLike | Any,
    friction_n: ArrayLike | Any,
    squeeze_pressure_mpa: ArrayLike | None = None,
    squeeze_force_n: ArrayLike | None = None,
    *,
    model: ModelKind = "proportional",
    ci: CiMethod = "auto",
    n_boot: int = 2000,
    seed: int = 0,
    groups: ArrayLike | list[Hashable] | None = None,
    pressure_sd_mpa: ArrayLike | None = None,
    friction_sd_n: ArrayLike | None = None,
) -> GammaFit:
    """Fit gamma (Eq 7) to friction points against a squeeze curve N(P).

    Two forms: ``fit_gamma(data, squeeze)`` with the natural objects, or the four arrays
    ``fit_gamma(friction_pressure_mpa, friction_n, squeeze_pressure_mpa, squeeze_force_n)``.

    Parameters
    ----------
    friction_pressure_mpa, friction_n : array_like
        Measured pressures (MPa) and friction forces (N); several tests may be pooled and
        pressures may repeat (replicate pulls). In the two-argument form, the first is the
        friction data (a :class:`RigRun`, a :class:`RigReduction` -- its pulls' kinetic
        friction, clustered by plateau --, or a DataFrame or mapping with ``pressure_mpa``
        and ``friction_n`` or ``kinetic_n``, and ``plateau`` or ``group`` when present) and
        the second the squeeze curve (a :class:`~exofric.simulate.SqueezeResult`, a
        :class:`SqueezeCurve`, or anything with ``pressure_mpa`` and ``squeeze_force_n``).
    squeeze_pressure_mpa, squeeze_force_n : array_like, optional
        Squeeze curve N(P) (MPa, N), e.g. from ``exofric squeeze`` (the four-array form).
    model : {"proportional", "affine"}
        F = gamma N (paper, default) or F = gamma N + F0.
    ci : {"auto", "analytic", "ols", "bootstrap", "cluster", "odr"}
        How the 95 % CI is computed:

        * ``"auto"`` (default): ``"cluster"`` when some cluster has >= 2 points (and there
          are enough clusters, see below), else ``"analytic"``;
        * ``"analytic"``: t (n - k dof) x HC3-robust standard error; ``"ols"``: classical;
        * ``"bootstrap"``: pairs bootstrap over points, percentile interval;
        * ``"cluster"``: t x cluster-robust standard error (CR2 on the Bell-McCaffrey dof
          by default, CR3 or CR1 on G - 1 dof, see the module docstring); needs G >= 2
          clusters (proportional) or 3 (affine). ``"auto"`` falls back to ``"analytic"``
          below that and says so in ``ci_note``;
        * ``"odr"``: errors-in-variables. The pressure is read with error: ODR (odrpack)
          minimises sum (dP_i / sd_P,i)^2 + (F_i - gamma N(P_i + dP_i) - F0)^2 / sd_F,i^2
          with N the PCHIP squeeze curve and dN/dP its slope in the Jacobian. Its estimate
          replaces the least-squares one; the interval is t (n - k dof) x the parameter sd
          that ODR reports, which is scaled by the residual variance (the weighted sum of
          squares / (n - k)), so only the ratio of the two sds matters for the width.
    n_boot, seed : int
        Bootstrap resamples and RNG seed (bootstrap only).
    groups : array_like, optional
        Cluster label of each friction point (any hashable, e.g. the pressure plateau of a
        pull). Default: points with exactly the same pressure form a cluster.
    pressure_sd_mpa, friction_sd_n : float or array_like, optional
        Standard deviations of the pressure reading (MPa) and of the friction (N), a number
        or one per friction point, > 0; required for (and only used by) ``ci="odr"``.

    Returns
    -------
    GammaFit
        With ``n_clusters``, ``ci_note`` and, when replicates exist, the ``lack_of_fit`` F
        test of the least-squares fit (also for ``ci="odr"``).

    Raises
    ------
    InputError
        Too few points inside the squeeze curve's range, a degenerate squeeze curve, too few
        clusters for ``ci="cluster"``, missing or bad sds for ``ci="odr"``.
    ConvergenceError
        The ODR fit did not converge.

    Examples
    --------
    >>> import numpy as np
    >>> p = np.linspace(0.2, 0.6, 5); n = 400 * p**2
    >>> fit = fit_gamma(p, 0.7 * n, p, n)
    >>> round(fit.gamma, 12), fit.relative_error_pct < 1e-9
    (0.7, True)

    Five pulls at each of five pressures: the interval is cluster-robust.

    >>> pr = np.repeat(p, 5); f = 0.7 * 400 * pr**2 * (1 + 0.02 * np.tile([-2, -1, 0, 1, 2], 5))
    >>> rep = fit_gamma(pr, f, p, n)
    >>> rep.ci_method, rep.n_clusters, rep.lack_of_fit.df_pure_error
    ('cluster', 5, 20)

    The same with the natural objects: friction data and a squeeze curve.

    >>> import pandas as pd
    >>> pulls = pd.DataFrame({"pressure_mpa": pr, "friction_n": f})
    >>> fit_gamma(pulls, {"pressure_mpa": p, "squeeze_force_n": n}).gamma == rep.gamma
    True
    """
    if squeeze_pressure_mpa is None and squeeze_force_n is None:
        friction_pressure_mpa, friction_n, squeeze_pressure_mpa, squeeze_force_n, groups = \
            _natural_inputs(friction_pressure_mpa, friction_n, groups)
    elif squeeze_pressure_mpa is None or squeeze_force_n is None:
        raise InputError("fit_gamma takes (data, squeeze_result) or four arrays: give both "
                         "squeeze_pressure_mpa and squeeze_force_n", param="squeeze_force_n")
    variant = _check_gamma_options(model, ci)
    seed = check_seed("seed", seed)
    edge_tol = 0.005
    pts = _gamma_points(friction_pressure_mpa, friction_n, squeeze_pressure_mpa,
                        squeeze_force_n, groups, ci, pressure_sd_mpa, friction_sd_n, model,
                        edge_tol)
    affine = model == "affine"
    n_min = 3 if affine else 2
    beta = _solve(pts.n, pts.f, affine)
    gamma, f0 = (float(v) for v in beta)
    if gamma <= 0:
        raise InputError(f"fitted gamma = {gamma:.4g} is not positive; check the data pairing")
    k = 2 if affine else 1
    lof = (_lack_of_fit(pts.f, pts.f - (gamma * pts.n + f0), pts.codes, pts.g, k)
           if pts.replicates else None)
    method, fallback = _gamma_method(ci, pts, n_min, model)
    if method in ("analytic", "ols", "cluster", "odr"):
        gamma, f0, g_ci, f0_ci, note = _t_interval(
            method, pts, beta, affine, variant, fallback,
            (squeeze_pressure_mpa, squeeze_force_n), edge_tol)
    else:
        g_ci, f0_ci, note = _bootstrap_interval(pts, affine, n_boot, seed)
    return _gamma_result(pts, model, gamma, f0, g_ci, f0_ci, method, note, lof)


def _column(obj: Any, *names: str) -> Any:
    """The first of ``names`` found on ``obj`` (a column, a key or an attribute), else None."""
    for name in names:
        try:
            if hasattr(obj, "columns") or isinstance(obj, Mapping):
                if name in obj:
                    return obj[name]
            elif hasattr(obj, name):
                return getattr(obj, name)
        except (TypeError, KeyError):
            continue
    return None


def _natural_inputs(data: Any, squeeze: Any, groups: Any) -> tuple[Any, Any, Any, Any, Any]:
    """``fit_gamma(data, squeeze)``: the four arrays (and the clusters) of the natural objects."""
    if hasattr(data, "pulls") and hasattr(data, "to_frame"):     # a RigReduction: its pulls
        data = data.to_frame()
    p = _column(data, "pressure_mpa")
    f = _column(data, "friction_n", "kinetic_n")
    if p is None or f is None:
        raise InputError("fit_gamma(data, squeeze): data must have pressure_mpa and friction_n "
                         f"(or kinetic_n), got {type(data).__name__}", param="data")
    if groups is None:
        groups = _column(data, "plateau", "group")
    sp = _column(squeeze, "pressure_mpa")
    sn = _column(squeeze, "squeeze_force_n")
    if sp is None or sn is None:
        raise InputError("fit_gamma(data, squeeze): squeeze must have pressure_mpa and "
                         f"squeeze_force_n (a squeeze result), got {type(squeeze).__name__}",
                         param="squeeze")
    return (np.asarray(p, dtype=float), np.asarray(f, dtype=float), np.asarray(sp, dtype=float),
            np.asarray(sn, dtype=float), None if groups is None else np.asarray(groups))
