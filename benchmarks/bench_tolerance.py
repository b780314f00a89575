"""Tolerance propagation: Sobol QMC against brute-force Monte Carlo (issue 19 acceptance).

Run: ``python benchmarks/bench_tolerance.py [--mc 1000] [--qmc 64] [--json]``.
Single-threaded. Units: N, MPa, mm, Shore A; CPU seconds.

The base group at 0.6 MPa (draft mesh, so 1000 FE samples fit in minutes) with tube ID +-0.1 mm
and hardness +-2 Shore A (1 sd, normal): the 5/50/95 % percentiles of N from
``squeeze_tolerances`` (scrambled Sobol, ``--qmc`` samples) against plain NumPy Monte Carlo with
``--mc`` samples (the reference); then plain MC with as many samples as the QMC run, repeated
with 5 seeds, to show which method is more accurate at equal cost. Acceptance: QMC percentiles
within 1 % of N(0.6 MPa) of the brute-force ones.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from dataclasses import replace  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric.geometry import BASE  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import squeeze, squeeze_tolerances  # noqa: E402

TOL = {"tube_id_mm": 0.1, "shore": 2.0}
P = [0.6]
PCTS = (5, 50, 95)


def _mc(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    out = []
    for z in rng.standard_normal((n, 2)):
        st = replace(BASE, tube_id_mm=BASE.tube_id_mm + TOL["tube_id_mm"] * float(z[0]))
        mat = MooneyRivlin.from_shore(62.5 + TOL["shore"] * float(z[1]))
        out.append(squeeze(st, mat, P, accuracy="draft", keep_fields=False).squeeze_force_n[0])
    return np.asarray(out)


def main() -> dict[str, Any]:
    """Print the comparison; return it (``benchmarks/run.py``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mc", type=int, default=1000)
    ap.add_argument("--qmc", type=int, default=64)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    t0 = time.process_time()
    ref = _mc(args.mc, 0)
    t_mc = time.process_time() - t0
    ref_p = np.percentile(ref, PCTS)
    t0 = time.process_time()
    q = squeeze_tolerances(BASE, 62.5, P, TOL, samples=args.qmc, accuracy="draft")
    t_q = time.process_time() - t0
    q_p = np.array([q.percentiles_n[k][0] for k in PCTS])
    scale = float(q.nominal_n[0])
    err_q = np.abs(q_p - ref_p) / scale * 100
    err_mc = []
    for seed in range(1, 6):
        small = np.percentile(_mc(args.qmc, seed), PCTS)
        err_mc.append(np.abs(small - ref_p) / scale * 100)
    err_mc_arr = np.array(err_mc)
    res = {"n_mc": args.mc, "n_qmc": args.qmc, "mc_cpu_s": t_mc, "qmc_cpu_s": t_q,
           "reference_percentiles_n": ref_p.tolist(), "qmc_percentiles_n": q_p.tolist(),
           "qmc_error_pct_of_n": err_q.tolist(),
           "plain_mc_same_n_error_pct_of_n_median": np.median(err_mc_arr, axis=0).tolist(),
           "plain_mc_same_n_error_pct_of_n_max": err_mc_arr.max(axis=0).tolist(),
           "nominal_n": scale, "ranking": [k for k, _ in q.ranking]}
    if args.json:
        print(json.dumps(res))
        return res
    print(f"base group, N(0.6 MPa) = {scale:.1f} N nominal; tolerances {TOL} (1 sd)")
    print(f"brute-force MC, {args.mc} FE samples ({t_mc:.0f} s CPU): 5/50/95 % = "
          + " / ".join(f"{v:.2f}" for v in ref_p) + " N")
    print(f"Sobol QMC, {args.qmc} samples ({t_q:.0f} s CPU incl. the ranking): "
          + " / ".join(f"{v:.2f}" for v in q_p) + " N; error "
          + " / ".join(f"{v:.2f}" for v in err_q) + " % of N (target < 1 %)")
    print(f"plain MC with {args.qmc} samples, 5 seeds: median error "
          + " / ".join(f"{v:.2f}" for v in res["plain_mc_same_n_error_pct_of_n_median"])
          + " %, max " + " / ".join(f"{v:.2f}" for v in res["plain_mc_same_n_error_pct_of_n_max"])
          + " % of N")
    print("ranking (first-order variance share at 0.6 MPa):", res["ranking"])
    return res


if __name__ == "__main__":
    main()
