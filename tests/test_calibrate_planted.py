"""Joint calibration against planted truths with noise, the 1D model, and its speed (issue 5).

Truth: Shore 57, tube ID 5.3 mm (8.3 mm OD), ten pressures 0.04-0.4 MPa, data generated
by the same forward model that is then fitted (so the only error is the planted noise).
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from exofric.calibrate import CachedModel, InflationData, calibrate, make_model

P = np.linspace(0.04, 0.4, 10)
TRUTH = (57.0, 5.3)


@pytest.fixture(scope="module")
def fe() -> CachedModel:
    """Memoised FE model for an 8.3 mm tube (Eq 4 constants)."""
    return make_model("fe", 8.3)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_joint_noisy_truth_within_three_stderrs(fe, seed) -> None:
    clean = fe(*TRUTH, P)
    rng = np.random.default_rng(seed)
    noisy = clean * (1 + 5e-4 * rng.standard_normal(P.size))  # 0.05 % Gaussian noise
    r = calibrate(InflationData(P, noisy), 8.3, method="joint", model=fe)
    assert r.converged
    # 3 reported standard errors: with 8 degrees of freedom a t-variate exceeds 3 with
    # probability 1.7%, so five fixed seeds pass unless the stderrs are wrong.
    assert abs(r.shore - TRUTH[0]) < 3 * r.shore_stderr
    assert abs(r.tube_id_mm - TRUTH[1]) < 3 * r.tube_id_stderr_mm
    # the stderrs are meaningful (not inflated to pass): 0.05% noise -> < 1 Shore, < 0.1 mm
    assert r.shore_stderr < 1.0 and r.tube_id_stderr_mm < 0.1
    assert r.correlation > 0.99
    assert any("nearly interchangeable" in n for n in r.notes)


def test_joint_on_table1_speed() -> None:
    # Issue target: a joint calibration of the Table 1 test data with the FE model in the
    # loop in < 10 s on this machine (measured ~1.5 s, 29 FE solves); fresh cache.
    t0 = time.perf_counter()
    r = calibrate(InflationData.paper_test(), 8.3, method="joint", model="fe",
                  tube_id_mm=4.97)
    elapsed = time.perf_counter() - t0
    assert r.model == "fe" and r.n_model_calls > 5
    assert elapsed < 10.0, f"joint calibration took {elapsed:.2f} s"
    assert r.elapsed_s <= elapsed
