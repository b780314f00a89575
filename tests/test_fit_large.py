"""fit_gamma on 200,000 friction points: memory linear in the number of points (issue 31).

Before issue 31 the CR2 interval formed an n_g x n_g matrix per cluster: 9 plateaus of ~22,000
pulls each would take 3.9 GB per cluster here, and a pairs bootstrap drew all n_boot x m
indices at once. The peak is measured with ``tracemalloc`` (NumPy reports its buffers to it)
and must stay under 200 MB; the interval is checked against the closed form of CR2 with
Bell-McCaffrey dof for the proportional model (one regressor), written here from per-cluster
sums.
"""

from __future__ import annotations

import tracemalloc
from collections.abc import Callable
from typing import TypeVar

import numpy as np
import pytest
from scipy import stats

from exofric.friction import GammaFit, fit_gamma

T = TypeVar("T")

M = 200_000
GAMMA = 0.7
CURVE_P = np.linspace(0.1, 0.7, 25)
CURVE_N = 600.0 * CURVE_P**1.5
SET_P = np.round(np.linspace(0.2, 0.6, 9), 3)
PEAK_MAX_MB = 200.0


def _pulls(seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """M pulls at 9 set pressures (exact repeats: 9 clusters), plateau and pull scatter."""
    rng = np.random.default_rng(seed)
    code = rng.integers(0, SET_P.size, M)
    p = SET_P[code]
    plateau = 1.0 + 0.01 * rng.normal(0.0, 1.0, SET_P.size)
    f = GAMMA * 600.0 * p**1.5 * plateau[code] * (1.0 + 0.02 * rng.normal(0.0, 1.0, M))
    return p, f


def _peak_mb(fn: Callable[[], T]) -> tuple[T, float]:
    """fn() and the peak of traced memory while it ran, in MB (2^20 bytes)."""
    tracemalloc.start()
    try:
        out = fn()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return out, peak / 2**20


def _cr2_bm_one_regressor(n: np.ndarray, f: np.ndarray, codes: np.ndarray
                          ) -> tuple[float, float]:
    """Closed form of CR2 + Bell-McCaffrey for F = gamma N (one regressor x = N): se, dof.

    H_gg = x_g x_g' / x'x has the one eigenvalue lambda_g = x_g'x_g / x'x, so
    x_g' A_g e_g = x_g'e_g / sqrt(1 - lambda_g) and var = sum_g (x_g'e_g)^2 / (1 - lambda_g)
    / (x'x)^2. With c_g = 1 / (sqrt(x'x) sqrt(1 - lambda_g)), tau_g = x_g'W_g x_g / x'x and
    tau = sum tau_g, G'WG = c_g c_h (delta_gh tau_g - lambda_h tau_g - lambda_g tau_h +
    lambda_g lambda_h tau), a G x G matrix; dof = (sum of its eigenvalues)^2 / sum of squares.
    """
    xx = float(n @ n)
    gamma = float(n @ f) / xx
    e = f - gamma * n
    w = np.abs(gamma * n)
    lam = np.bincount(codes, weights=n * n) / xx
    xe = np.bincount(codes, weights=n * e)
    var = float(np.sum(xe**2 / (1.0 - lam))) / xx**2
    tau = np.bincount(codes, weights=w * n * n) / xx
    c = 1.0 / np.sqrt(xx * (1.0 - lam))
    mat = (np.diag(tau) - np.outer(tau, lam) - np.outer(lam, tau)
           + tau.sum() * np.outer(lam, lam)) * np.outer(c, c)
    ev = np.linalg.eigvalsh(mat)
    return float(np.sqrt(var)), float(ev.sum() ** 2 / (ev @ ev))


def test_cr2_interval_on_200k_points_in_linear_memory() -> None:
    # Default interval (auto -> cluster CR2 + Bell-McCaffrey over the 9 pressure clusters):
    # peak < 200 MB (measured ~46 MB) and the same half-width as the closed form (rel 1e-9:
    # sums of 2e5 terms in a different order).
    p, f = _pulls(1)
    fit, peak = _peak_mb(lambda: fit_gamma(p, f, CURVE_P, CURVE_N))
    assert peak < PEAK_MAX_MB, f"peak {peak:.0f} MB"
    assert fit.ci_method == "cluster" and fit.n_clusters == 9 and fit.n_points == M
    assert "Bell-McCaffrey" in fit.ci_note
    codes = np.searchsorted(SET_P, np.asarray(fit.pressure_mpa))
    se, dof = _cr2_bm_one_regressor(np.asarray(fit.squeeze_force_n), np.asarray(fit.friction_n),
                                    codes)
    half = (fit.gamma_ci95[1] - fit.gamma_ci95[0]) / 2
    assert half == pytest.approx(float(stats.t.ppf(0.975, dof)) * se, rel=1e-9)
    assert 1.0 < dof < 8.0                  # well below G - 1 = 8: few, unequal clusters


@pytest.mark.parametrize(("model", "ci"), [("affine", "auto"), ("proportional", "bootstrap")])
def test_other_intervals_on_200k_points_in_linear_memory(model: str, ci: str) -> None:
    # The affine CR2 path, and a 100-resample pairs bootstrap (all indices at once would be
    # 3 x 100 x 2e5 x 8 B = 0.48 GB): peak < 200 MB; the interval covers the fit.
    p, f = _pulls(2)
    def run() -> GammaFit:
        return fit_gamma(p, f, CURVE_P, CURVE_N, model=model, ci=ci, n_boot=100)

    fit, peak = _peak_mb(run)
    assert peak < PEAK_MAX_MB, f"peak {peak:.0f} MB"
    assert fit.n_points == M and fit.gamma_ci95[0] < fit.gamma < fit.gamma_ci95[1]
