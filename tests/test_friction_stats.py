"""One-way ANOVA (Table 4): textbook example, scipy and statsmodels, planted groups."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from exofric.errors import InputError
from exofric.friction import anova_vs_base, one_way_anova

# Textbook example (Wikipedia, "One-way analysis of variance", worked example):
# a1 = 6 8 4 5 3 4, a2 = 8 12 9 11 6 8, a3 = 13 9 11 8 7 12.
# Means 5, 9, 10; grand mean 8. SS_between = 6(9 + 1 + 4) = 84, df 2, MS = 42.
# SS_within = 16 + 24 + 28 = 68, df 15, MS = 4.5333. F = 42/4.5333 = 9.2647.
A1 = [6, 8, 4, 5, 3, 4]
A2 = [8, 12, 9, 11, 6, 8]
A3 = [13, 9, 11, 8, 7, 12]


def test_textbook_example_by_hand() -> None:
    r = one_way_anova(A1, A2, A3)
    assert r.ss_between == pytest.approx(84.0, rel=1e-12)
    assert r.ss_within == pytest.approx(68.0, rel=1e-12)
    assert (r.df_between, r.df_within) == (2, 15)
    assert r.f_stat == pytest.approx(42.0 / (68.0 / 15.0), rel=1e-12)
    # p = P(F(2,15) > 9.2647); for 2 numerator dof the survival function is closed form:
    # (1 + 2F/15)^(-15/2) = (1 + 18.5294/15)^(-7.5) = 0.002399...
    assert r.p_value == pytest.approx((1 + 2 * r.f_stat / 15) ** (-7.5), rel=1e-10)
    assert r.p_value == pytest.approx(0.0024, abs=5e-5)
    assert r.significant and "not applicable" in r.verdict
    assert r.means == (5.0, 9.0, 10.0)


def test_matches_scipy_and_statsmodels() -> None:
    # Independent references: scipy.stats.f_oneway and statsmodels' anova_lm table.
    import statsmodels.api as sm
    from statsmodels.formula.api import ols

    rng = np.random.default_rng(11)
    g = [rng.normal(0, 5, 9), rng.normal(2, 5, 7), rng.normal(1, 4, 11)]
    r = one_way_anova(*g)
    ref = stats.f_oneway(*g)
    assert r.f_stat == pytest.approx(ref.statistic, rel=1e-10)
    assert r.p_value == pytest.approx(ref.pvalue, rel=1e-9)
    df = pd.DataFrame({"e": np.concatenate(g), "grp": np.repeat(["a", "b", "c"], [9, 7, 11])})
    tab = sm.stats.anova_lm(ols("e ~ C(grp)", df).fit())
    assert r.ss_between == pytest.approx(tab["sum_sq"].iloc[0], rel=1e-10)
    assert r.ss_within == pytest.approx(tab["sum_sq"].iloc[1], rel=1e-10)
    assert r.p_value == pytest.approx(tab["PR(>F)"].iloc[0], rel=1e-9)


def test_planted_equal_and_shifted_groups() -> None:
    # Base errors ~ N(0, 5) %, 9 points per test (a pressure sweep). A test with the same mean
    # error: p is uniform under H0, so with this fixed seed we require p > 0.2 (it is 0.97);
    # a test shifted by 30 % (6 sd): p < 1e-6.
    rng = np.random.default_rng(5)
    base = rng.normal(0, 5, 9)
    same = rng.normal(0, 5, 9)
    shifted = rng.normal(30, 5, 9)
    res = anova_vs_base(base, {"same": same, "shifted": shifted}, alpha=0.05)
    assert res[0].name == "same vs base" and res[0].p_value > 0.2 and not res[0].significant
    assert res[1].p_value < 1e-6 and res[1].significant
    assert res[0].to_dict()["verdict"].startswith("no significant difference")


def test_two_groups_equals_squared_t_test() -> None:
    # With two groups, F = t^2 of the pooled two-sample t test (an identity, not scipy's ANOVA).
    a, b = [1.0, 2.0, 3.5, 0.5], [2.5, 4.0, 3.0, 5.5, 4.5]
    t = stats.ttest_ind(a, b, equal_var=True)
    r = one_way_anova(a, b)
    assert r.f_stat == pytest.approx(t.statistic**2, rel=1e-12)
    assert r.p_value == pytest.approx(t.pvalue, rel=1e-10)


def test_anova_input_errors() -> None:
    with pytest.raises(InputError, match="at least 2 groups"):
        one_way_anova([1, 2, 3])
    with pytest.raises(InputError, match="no finite"):
        one_way_anova([1, 2], [np.nan])
    with pytest.raises(InputError, match="more observations"):
        one_way_anova([1], [2])
    with pytest.raises(InputError, match="alpha"):
        one_way_anova([1, 2], [3, 4], alpha=1.5)
