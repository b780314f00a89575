"""Coverage and cost of the pull-out calibration's intervals (``fit_pullout``; issue 39).

A Monte Carlo of planted pulls: 2 pressures (0.3, 0.6 MPa) x 3 pulls of the base group (Shore
62.5, draft mesh, 20 cable elements, 30 load steps), each pull scaled by its own (1 + 0.02 e)
and sampled with 0.2 N white noise, planted mu_wire 0.3, mu_wall 0.5 (held), mu_wire_wall 0.15.
Each replicate is fitted from the truth (this measures the intervals, not the search). The
share of 95 % intervals that cover the truth must not fall below the 0.1 % quantile of
Binomial(n, 0.95); the iid intervals (about 3x narrower) are counted beside them.

Run: ``python benchmarks/bench_pullfit.py [--replicates 40]`` (about 6 s CPU a replicate).
Too slow for the test suite (tests/test_pullfit.py checks recovery, identifiability and the
linear part against statsmodels); measured 39/40 (mu_wire) and 37/40 (mu_wire_wall), floor 33.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
import warnings
from typing import Any

import numpy as np
from scipy import stats

from exofric.friction import IdentifiabilityWarning, PullFitSettings, fit_pullout
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import PulloutNumerics, PulloutSetup, SqueezeSetup, pullout

MAT = MooneyRivlin.from_shore(62.5)
CHEAP = {"n_z": 20, "n_path": 30}
TRUTH = {"mu_wire": 0.3, "mu_wall": 0.5, "mu_wire_wall": 0.15}
PRESSURES = (0.3, 0.6)


def clean_curves(travel: float = 1.5, n: int = 60) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The planted model's first loading at each pressure: (P in MPa, x in mm, F in N)."""
    sq = SqueezeSetup(BASE, MAT, accuracy="draft").solve(list(PRESSURES))
    out = []
    for k, p in enumerate(PRESSURES):
        r = pullout(PulloutSetup(BASE, MAT, numerics=PulloutNumerics(**CHEAP), **TRUTH), p,
                    displacement_mm=travel, first_loading=True, squeeze_result=sq,
                    squeeze_index=k)
        x = np.linspace(0.0, travel, n)
        out.append((p, x, np.interp(x, r.displacement_mm, r.force_n)))
    return out


def replicate(curves: list[tuple[float, np.ndarray, np.ndarray]], seed: int,
              reps: int = 3) -> list[dict[str, Any]]:
    """``reps`` noisy pulls per pressure (2 % pull-to-pull scatter, 0.2 N noise)."""
    rng = np.random.default_rng(seed)
    return [{"label": f"{p}-{j}", "pressure_mpa": p, "displacement_mm": x,
             "force_n": np.abs(f * (1 + 0.02 * rng.standard_normal())
                               + 0.2 * rng.standard_normal(x.size))}
            for p, x, f in curves for j in range(reps)]


def main(replicates: int = 40) -> dict[str, Any]:
    """Coverage of the 95 % intervals (CR2 and iid) over ``replicates`` fits, and their cost."""
    curves = clean_curves()
    settings = PullFitSettings(accuracy="draft", start={"mu_wire": 0.3, "mu_wire_wall": 0.15},
                               **CHEAP)
    names = ("mu_wire", "mu_wire_wall")
    hits = dict.fromkeys(names, 0)
    hits_iid = dict.fromkeys(names, 0)
    cpu = []
    for rep in range(replicates):
        pulls = replicate(curves, 1000 + rep)
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", IdentifiabilityWarning)
            fit = fit_pullout(BASE, MAT, pulls, mu_wall=0.5, settings=settings)
        cpu.append(time.process_time() - t0)
        for k in names:
            hits[k] += int(fit.ci_low[k] <= TRUTH[k] <= fit.ci_high[k])
            half = (fit.ci_high[k] - fit.ci_low[k]) / 2 * fit.std_error_iid[k] / fit.std_error[k]
            hits_iid[k] += int(abs(fit.estimate[k] - TRUTH[k]) <= half)
    floor = int(stats.binom.ppf(0.001, replicates, 0.95))
    out = {"replicates": replicates, "covered": hits, "covered_iid": hits_iid,
           "binomial_floor_0p1pct": floor, "ok": min(hits.values()) >= floor,
           "cpu_s_per_fit_median": statistics.median(cpu)}
    print(f"fit_pullout coverage over {replicates} replicates (floor {floor}): CR2 {hits}, "
          f"iid {hits_iid}; median CPU {out['cpu_s_per_fit_median']:.1f} s per fit",
          file=sys.stderr)
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--replicates", type=int, default=40)
    print(json.dumps(main(ap.parse_args().replicates), indent=1))
