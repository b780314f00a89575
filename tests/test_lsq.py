"""The least-squares covariances of exofric._lsq against statsmodels (an independent code).

On a linear model the Jacobian of the residuals is the design matrix, so s^2 (J^T J)^-1 must
equal statsmodels' classical OLS covariance and the HC3 sandwich its ``cov_type='HC3'``; both to
1e-10 relative (round-off of two different factorisations of a well-conditioned problem).
"""

from __future__ import annotations

import numpy as np
import pytest

from exofric._lsq import (
    correlation,
    hc3_covariance,
    lsq_covariance,
    residual_variance,
    standard_errors,
)

sm = pytest.importorskip("statsmodels.api")


@pytest.mark.parametrize("seed", range(4))
def test_against_statsmodels_ols_and_hc3(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = 30 + 10 * seed
    x = np.c_[np.ones(n), rng.uniform(0, 1, n), rng.normal(0, 1, n)]
    y = x @ [1.0, 2.0, -0.5] + rng.normal(0, 0.1 + 0.3 * x[:, 1], n)  # heteroscedastic
    ols = sm.OLS(y, x).fit()
    e = ols.resid
    s2 = residual_variance(e, x.shape[1])
    cov = lsq_covariance(x, s2)
    np.testing.assert_allclose(cov, ols.cov_params(), rtol=1e-10)
    np.testing.assert_allclose(standard_errors(cov), ols.bse, rtol=1e-10)
    hc3 = sm.OLS(y, x).fit(cov_type="HC3").cov_params()
    np.testing.assert_allclose(hc3_covariance(x, e), hc3, rtol=1e-10)
    c = correlation(cov)
    assert np.allclose(np.diag(c), 1.0) and np.allclose(c, c.T)


def test_rank_deficient_jacobian_gets_no_overflow() -> None:
    # two identical columns: the data fix only their sum; the pseudo-inverse splits it evenly
    j = np.c_[np.ones(5), np.ones(5)]
    cov = lsq_covariance(j, 1.0)
    np.testing.assert_allclose(cov, np.full((2, 2), 0.05), rtol=1e-12)
    assert np.isnan(residual_variance([1.0, 2.0], 2))
