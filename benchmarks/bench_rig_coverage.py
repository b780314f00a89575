"""Coverage study: does gamma's 95 % interval from raw rig logs hold? (issue 14 acceptance)

Run: ``python benchmarks/bench_rig_coverage.py [--seeds 400] [--json]``.
Single-threaded. Units: MPa, N, s; gamma unitless.

For each seed the virtual rig (:func:`exofric.friction.simulate_raw_log`) writes a raw log with a
planted gamma (0.7) on the squeeze curve N = 600 P^1.5 N at 9 set points 0.2-0.6 MPa, 3 pulls
per direction per plateau, between-pull scatter 1.5 %, plateau-to-plateau scatter 1 %,
autocorrelated load-cell noise, tare offset, drift and a gravity bias. The log is reduced
(:func:`exofric.friction.reduce_log`) and gamma fitted on the pulls (:func:`fit_gamma`) with:

* ``cluster`` (CR2 over plateaus with Bell-McCaffrey degrees of freedom) -- exofric's default
  with replicates (``ci="auto"``);
* ``cluster CR3`` (leave-one-plateau-out jackknife) and ``cluster CR1`` (the Liang-Zeger
  sandwich statsmodels' ``cov_type="cluster"`` gives), both with t on G - 1 dof;
* ``pulls HC3`` and ``pulls OLS`` -- the naive intervals that treat every pull as independent;
* ``samples`` -- the naive interval of a spreadsheet: each pull's mean with sd/sqrt(n) over its
  samples (autocorrelated, between-pull scatter ignored), weighted least squares.

Reported: coverage of the planted gamma (%) with its binomial standard error, the median
interval half-width (% of gamma), the largest gamma error, and the largest per-pull kinetic and
static errors against the planted values (%). Acceptance: the default covers 93-97 %.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402

from exofric.friction import (  # noqa: E402
    RawRigConfig,
    _fit,
    fit_gamma,
    reduce_log,
    simulate_raw_log,
)

GAMMA = 0.7
SQUEEZE_P = np.linspace(0.1, 0.7, 25)
SQUEEZE_N = 600.0 * SQUEEZE_P**1.5
SETPOINTS = np.linspace(0.2, 0.6, 9)
CONFIG = RawRigConfig(sample_rate_hz=200.0, pull_mm=6.0, replicates=3)


def one_seed(seed: int, config: RawRigConfig = CONFIG) -> dict[str, Any]:
    """Simulate, reduce and fit one log; the intervals of each method and the errors."""
    log = simulate_raw_log(SQUEEZE_P, SQUEEZE_N, GAMMA, SETPOINTS, config=config, seed=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        red = reduce_log(log.to_frame())
    pulls = red.to_frame()
    truth = log.truth_frame().set_index("pull").loc[pulls["pull"]]
    kin_err = 100 * (pulls["kinetic_n"].to_numpy() / truth["kinetic_n"].to_numpy() - 1)
    sta_err = 100 * (pulls["static_n"].to_numpy() / truth["static_n"].to_numpy() - 1)
    p, f, g = (pulls["pressure_mpa"].to_numpy(), pulls["kinetic_n"].to_numpy(),
               pulls["plateau"].to_numpy())
    out: dict[str, Any] = {"kinetic_err_pct": float(np.abs(kin_err).max()),
                           "static_err_pct": float(np.abs(sta_err).max()), "ci": {}}
    fit = fit_gamma(p, f, SQUEEZE_P, SQUEEZE_N, groups=g)          # the default (auto)
    out["gamma"] = fit.gamma
    out["default_method"] = fit.ci_method
    out["ci"]["cluster"] = fit.gamma_ci95
    saved = _fit._CLUSTER_VARIANT
    try:
        for variant in ("cr3", "cr1"):
            _fit._CLUSTER_VARIANT = variant  # type: ignore[assignment]
            out["ci"][f"cluster {variant.upper()}"] = fit_gamma(
                p, f, SQUEEZE_P, SQUEEZE_N, groups=g, ci="cluster").gamma_ci95
    finally:
        _fit._CLUSTER_VARIANT = saved
    out["ci"]["pulls HC3"] = fit_gamma(p, f, SQUEEZE_P, SQUEEZE_N, ci="analytic").gamma_ci95
    out["ci"]["pulls OLS"] = fit_gamma(p, f, SQUEEZE_P, SQUEEZE_N, ci="ols").gamma_ci95
    # the spreadsheet interval: WLS with each pull's sd/sqrt(n) as its known error
    n = np.interp(p, SQUEEZE_P, SQUEEZE_N)
    w = 1.0 / pulls["kinetic_naive_se_n"].to_numpy() ** 2
    gam = float(np.sum(w * n * f) / np.sum(w * n * n))
    se = float(1.0 / np.sqrt(np.sum(w * n * n)))
    z = float(stats.norm.ppf(0.975))
    out["ci"]["samples sd/sqrt(n)"] = (gam - z * se, gam + z * se)
    return out


def study(seeds: int) -> dict[str, Any]:
    """Run ``seeds`` seeds; coverage per method (%)."""
    rows = [one_seed(s) for s in range(seeds)]
    methods = list(rows[0]["ci"])
    res: dict[str, Any] = {"seeds": seeds, "gamma_true": GAMMA,
                           "default_method": rows[0]["default_method"], "methods": {}}
    for m in methods:
        cover = np.array([lo <= GAMMA <= hi for lo, hi in (r["ci"][m] for r in rows)])
        half = np.array([(hi - lo) / 2 / GAMMA * 100 for lo, hi in (r["ci"][m] for r in rows)])
        c = float(cover.mean() * 100)
        res["methods"][m] = {"coverage_pct": c,
                             "coverage_se_pct": float(np.sqrt(c * (100 - c) / seeds)),
                             "median_half_width_pct": float(np.median(half))}
    res["max_gamma_err_pct"] = float(max(abs(r["gamma"] / GAMMA - 1) * 100 for r in rows))
    res["max_kinetic_err_pct"] = float(max(r["kinetic_err_pct"] for r in rows))
    res["max_static_err_pct"] = float(max(r["static_err_pct"] for r in rows))
    return res


def main() -> dict[str, Any]:
    """Print the coverage table; return it (``benchmarks/run.py``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=400)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    t0 = time.perf_counter()
    res = study(args.seeds)
    res["wall_s"] = time.perf_counter() - t0
    if args.json:
        print(json.dumps(res))
        return res
    print(f"gamma 95 % interval coverage, {res['seeds']} seeds of the virtual rig "
          f"(planted gamma {GAMMA}; 9 plateaus x 6 pulls); {res['wall_s']:.0f} s")
    print(f"{'method':<22}{'coverage %':>12}{'+-':>6}{'half-width % gamma':>20}")
    for m, v in res["methods"].items():
        tag = "  <- default" if m == "cluster" else ""
        print(f"{m:<22}{v['coverage_pct']:>12.1f}{v['coverage_se_pct']:>6.1f}"
              f"{v['median_half_width_pct']:>20.3f}{tag}")
    print(f"largest errors: gamma {res['max_gamma_err_pct']:.2f} %, kinetic per pull "
          f"{res['max_kinetic_err_pct']:.2f} %, static per pull {res['max_static_err_pct']:.2f} %")
    return res


if __name__ == "__main__":
    main()
