"""One-way ANOVA of prediction errors (paper Sec. 4, Table 4).

The paper treats the prediction error as the dependent variable and tests, for each test
structure, whether its errors differ significantly from the base group's (p < alpha: the
model does not transfer to that structure). :func:`one_way_anova` computes the full table
(sums of squares, degrees of freedom, mean squares, F, p from the F distribution);
:func:`anova_vs_base` runs it for the base group against each test.

Errors are usually relative errors in %, but any unit works (ANOVA is unit-free in F and p).

Examples
--------
>>> r = one_way_anova([6, 8, 4, 5, 3, 4], [8, 12, 9, 11, 6, 8], [13, 9, 11, 8, 7, 12])
>>> round(r.f_stat, 4), r.df_between, r.df_within
(9.2647, 2, 15)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_range

__all__ = ["AnovaResult", "one_way_anova", "anova_vs_base"]


@checked_init
@dataclass(frozen=True)
class AnovaResult(DisplayMixin):
    """One-way ANOVA table for k groups (errors in any unit, usually %).

    Attributes
    ----------
    name : str
        Label (e.g. ``"test 2 vs base"``).
    ss_between, ss_within : float
        Sums of squares between and within groups (unit^2).
    df_between, df_within : int
        k - 1 and n - k.
    f_stat, p_value : float
        F = MS_between / MS_within and its upper-tail probability.
    alpha : float
        Significance level of the verdict.
    n_per_group : tuple of int
    means : tuple of float
        Group means (unit of the errors).

    Examples
    --------
    >>> r = one_way_anova([1.0, 2.0, 3.0], [2.0, 3.0, 4.0], name="demo")
    >>> r.df_between, r.df_within, r.f_stat, r.significant
    (1, 4, 1.5, False)
    """

    name: str
    ss_between: float
    ss_within: float
    df_between: int
    df_within: int
    f_stat: float
    p_value: float
    alpha: float
    n_per_group: tuple[int, ...]
    means: tuple[float, ...]

    @property
    def ms_between(self) -> float:
        """Mean square between groups."""
        return self.ss_between / self.df_between

    @property
    def ms_within(self) -> float:
        """Mean square within groups."""
        return self.ss_within / self.df_within

    @property
    def significant(self) -> bool:
        """True when p < alpha (the groups' mean errors differ)."""
        return bool(self.p_value < self.alpha)

    @property
    def verdict(self) -> str:
        """One-line reading of the test at ``alpha``."""
        if self.significant:
            return (f"significant difference (p = {self.p_value:.4g} < {self.alpha:g}): "
                    "the model is not applicable")
        return (f"no significant difference (p = {self.p_value:.4g} >= {self.alpha:g}): "
                "the model is applicable")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unitless F, p; sums of squares in the errors' unit squared)."""
        return {
            "name": self.name,
            "ss_between": self.ss_between,
            "ss_within": self.ss_within,
            "df_between": self.df_between,
            "df_within": self.df_within,
            "ms_between": self.ms_between,
            "ms_within": self.ms_within,
            "f_stat": self.f_stat,
            "p_value": self.p_value,
            "alpha": self.alpha,
            "significant": self.significant,
            "verdict": self.verdict,
            "n_per_group": list(self.n_per_group),
            "means": list(self.means),
        }


def one_way_anova(*groups: ArrayLike, alpha: float = 0.05, name: str = "") -> AnovaResult:
    """One-way ANOVA of two or more groups (NaNs dropped).

    Parameters
    ----------
    *groups : array_like
        Observations per group (e.g. relative prediction errors in %).
    alpha : float
        Significance level in (0, 1) for :attr:`AnovaResult.verdict`.
    name : str
        Label stored in the result.

    Returns
    -------
    AnovaResult
        Agrees with ``scipy.stats.f_oneway`` (tested).

    Raises
    ------
    InputError
        Fewer than 2 groups, an empty group, or no within-group freedom (n <= k).

    Examples
    --------
    >>> r = one_way_anova([6, 8, 4, 5, 3, 4], [8, 12, 9, 11, 6, 8], [13, 9, 11, 8, 7, 12])
    >>> round(r.f_stat, 4), round(r.p_value, 4), r.significant
    (9.2647, 0.0024, True)
    """
    from scipy import stats

    a = check_range("alpha (significance level)", alpha, 0.0, 1.0, lo_open=True, hi_open=True)
    if len(groups) < 2:
        raise InputError(f"ANOVA needs at least 2 groups, got {len(groups)}")
    gs = []
    for i, g in enumerate(groups):
        x = np.asarray(g, dtype=float).ravel()
        x = x[np.isfinite(x)]
        if x.size == 0:
            raise InputError(f"ANOVA group {i + 1} has no finite values")
        gs.append(x)
    sizes = np.array([x.size for x in gs])
    n, k = int(sizes.sum()), len(gs)
    if n <= k:
        raise InputError(f"ANOVA needs more observations ({n}) than groups ({k})")
    means = np.array([x.mean() for x in gs])
    grand = float(np.concatenate(gs).mean())
    ssb = float(np.sum(sizes * (means - grand) ** 2))
    ssw = float(sum(float(np.sum((x - m) ** 2)) for x, m in zip(gs, means, strict=True)))
    dfb, dfw = k - 1, n - k
    if ssw == 0.0:
        f = float("inf") if ssb > 0 else float("nan")
        p = 0.0 if ssb > 0 else float("nan")
    else:
        f = (ssb / dfb) / (ssw / dfw)
        p = float(stats.f.sf(f, dfb, dfw))
    return AnovaResult(name, ssb, ssw, dfb, dfw, float(f), p, a,
                       tuple(int(s) for s in sizes), tuple(float(m) for m in means))


def anova_vs_base(
    base_errors: ArrayLike,
    tests: Mapping[str, ArrayLike],
    *,
    alpha: float = 0.05,
) -> tuple[AnovaResult, ...]:
    """ANOVA of each test's prediction errors against the base group's (paper Table 4).

    Parameters
    ----------
    base_errors : array_like
        Base-group errors (e.g. relative errors of the gamma fit, %).
    tests : mapping name -> array_like
        Prediction errors per test structure (same unit).
    alpha : float
        Significance level.

    Returns
    -------
    tuple of AnovaResult
        One per test, named ``"<test> vs base"``.

    Examples
    --------
    >>> res = anova_vs_base([1.0, -1.0, 2.0, 0.0], {"t": [30.0, 28.0, 33.0, 31.0]})
    >>> res[0].significant
    True
    """
    return tuple(
        one_way_anova(base_errors, errs, alpha=alpha, name=f"{name} vs base")
        for name, errs in tests.items()
    )
