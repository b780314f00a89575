"""Tolerance bands: the README example's time and its bands against brute force (issue 37).

Run: ``python benchmarks/bench_tolerance.py [--repeat 3] [--json]`` to time the README's
``exofric predict ... --clearance-sd 0.1 --tolerance tube_id=0.1 --tolerance shore=2
--samples 64`` as a whole process (wall and CPU seconds, children included) and compare its
5/50/95 % bands with the stored brute-force answer ``tests/data/tolerance_reference_readme.json``
(target: <= 15 s wall on the 2-core machine, bands within 1 % of N(0.6 MPa)).

``--save`` stores the last run's bands in ``tests/data/tolerance_readme_grid.json`` (compared
with the brute-force file by ``tests/test_tolerance.py``). ``--reference readme`` regenerates
the brute-force file (one clearance integral per Sobol sample, as
before issue 37; about 6 min of CPU on 2 workers), ``--reference draft`` the draft-mesh
reference ``tests/data/tolerance_reference_draft.json`` that ``tests/test_tolerance.py``
compares the grid interpolant with (the same 64 Sobol samples solved one by one, and 256
plain Monte Carlo samples from NumPy's generator: a different sampler).

Units: N, MPa, mm, Shore A; seconds.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
README_ARGS = ["predict", "--gamma", "0.7168", "--hole", "10", "--tube-od", "8.3",
               "--tube-id", "4.97", "--wire", "1.6", "--clearance-sd", "0.1",
               "--tolerance", "tube_id=0.1", "--tolerance", "shore=2", "--samples", "64"]
README_TOL = {"tube_id_mm": 0.1, "shore": 2.0}
DRAFT_TOL = {"tube_id_mm": 0.1, "shore": 2.0}
DRAFT_P = [0.3, 0.6]
PCTS = (5, 50, 95)
KEYS = [f"{k}_p{q:02d}" for k in ("squeeze_force_n", "friction_n") for q in PCTS]


def _readme_reference() -> dict[str, Any]:
    """The README example's bands, every Sobol sample solved (brute force, 2 workers)."""
    from exofric.geometry import Structure
    from exofric.simulate import ClearanceDistribution, squeeze_tolerances, squeeze_with_clearance

    st = Structure(10.0, 8.3, 4.97, 1.6, 116.0, name="structure")

    def solver(s: Any, m: Any, p: Any) -> Any:
        return squeeze_with_clearance(s, m, p, ClearanceDistribution.normal(
            max(s.clearance_mm, 1e-3), 0.1))

    p = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
    t0 = time.perf_counter()
    r = squeeze_tolerances(st, 62.5, p, README_TOL, samples=64, solver=solver,
                           method="brute-force", workers=2)
    out = {"pressure_mpa": p, "squeeze_force_n": list(r.nominal_n), "gamma": 0.7168,
           "wall_s": time.perf_counter() - t0}
    for q, v in r.percentiles_n.items():
        out[f"squeeze_force_n_p{q:02d}"] = list(v)
        out[f"friction_n_p{q:02d}"] = [0.7168 * x for x in v]
    return out


def _draft_reference() -> dict[str, Any]:
    """Draft mesh, base group: the 64 Sobol samples one by one and 256 plain MC samples."""
    from exofric.geometry import BASE
    from exofric.material import MooneyRivlin
    from exofric.simulate import squeeze, squeeze_tolerances

    r = squeeze_tolerances(BASE, 62.5, DRAFT_P, DRAFT_TOL, samples=64, accuracy="draft",
                           method="brute-force", workers=2)
    rng = np.random.default_rng(1)
    mc = []
    for z in rng.standard_normal((256, 2)):
        st = replace(BASE, tube_id_mm=BASE.tube_id_mm + DRAFT_TOL["tube_id_mm"] * float(z[0]))
        mat = MooneyRivlin.from_shore(62.5 + DRAFT_TOL["shore"] * float(z[1]))
        mc.append(squeeze(st, mat, DRAFT_P, accuracy="draft", keep_fields=False).squeeze_force_n)
    arr = np.asarray(mc)
    return {"pressure_mpa": DRAFT_P, "tolerances": DRAFT_TOL, "samples": 64,
            "nominal_n": list(r.nominal_n),
            "sobol_brute_force": {f"p{q:02d}": list(v) for q, v in r.percentiles_n.items()},
            "sobol_ranking": [[k, list(v)] for k, v in r.ranking],
            "plain_mc_256": {f"p{q:02d}": np.percentile(arr, q, axis=0).tolist()
                             for q in PCTS}}


def _time_readme() -> tuple[float, float, dict[str, Any]]:
    """Wall and CPU (s, children included) of the README example, and its JSON."""
    exe = Path(sys.executable).with_name("exofric")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run([str(exe), *README_ARGS, "--json"], capture_output=True, text=True,
                         check=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(out.stdout)["structures"][0]


def main() -> dict[str, Any]:
    """Time the README example (or regenerate a reference); return the numbers."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--reference", choices=("readme", "draft"))
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--save", action="store_true",
                    help="write the last run's bands to tests/data/tolerance_readme_grid.json")
    args = ap.parse_args()
    if args.reference:
        ref = _readme_reference() if args.reference == "readme" else _draft_reference()
        path = DATA / f"tolerance_reference_{args.reference}.json"
        path.write_text(json.dumps(ref, indent=1) + "\n")
        print(f"wrote {path}")
        return ref
    ref = json.loads((DATA / "tolerance_reference_readme.json").read_text())
    runs = [_time_readme() for _ in range(args.repeat)]
    entry = runs[-1][2]
    scale = ref["squeeze_force_n"][-1]
    err = {k: 100 * abs(entry[k][-1] - ref[k][-1]) / (scale * (0.7168 if "fric" in k else 1))
           for k in KEYS}
    res = {"wall_s": [r[0] for r in runs], "cpu_s": [r[1] for r in runs],
           "wall_s_median": float(np.median([r[0] for r in runs])),
           "error_pct_of_n06": err, "method": entry.get("tolerance_method"),
           "reference_wall_s": ref.get("wall_s")}
    if args.save:
        keep = {k: entry[k] for k in ("pressure_mpa", "squeeze_force_n", *KEYS,
                                      "tolerance_method", "sensitivity") if k in entry}
        keep["pressure_mpa"] = ref["pressure_mpa"]
        keep.update(wall_s=res["wall_s"], cpu_s=res["cpu_s"])
        (DATA / "tolerance_readme_grid.json").write_text(json.dumps(keep, indent=1) + "\n")
    if args.json:
        print(json.dumps(res))
        return res
    print(f"README tolerance example: wall {res['wall_s_median']:.1f} s median of "
          f"{args.repeat} (runs " + ", ".join(f"{w:.1f}" for w in res["wall_s"])
          + " s; CPU " + ", ".join(f"{c:.1f}" for c in res["cpu_s"]) + " s); target <= 15 s")
    print("bands at 0.6 MPa against brute force, % of N(0.6 MPa) (target <= 1 %): "
          + ", ".join(f"{k} {v:.3f}" for k, v in err.items()))
    print(f"method: {res['method']}")
    return res


if __name__ == "__main__":
    main()
