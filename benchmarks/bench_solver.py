"""Newton and the banded solve over meshes: failed-attempt time and the solve-time exponent.

``python benchmarks/bench_solver.py [--runs 3] [--quick] [--json]``

The base group's squeeze (Shore 62.5, 0.05..0.6 MPa in 12 outputs, gravity "none") on explicit
meshes from 2 x 24 to 8 x 128, solved by today's solver ("now") and, in the same run and
interleaved, by the solver as it was before issue 22 ("before": plain Newton directions, no
early cut-back, reverse Cuthill-McKee ordering only; the old behaviour is restored by settings
and by hiding the line-by-line ordering). Reported per mesh: dofs, the band of the ordering
used, CPU time of the solve (median, ``time.process_time``, so other processes on the machine
matter less), Newton attempts, failed attempts and the share of the Newton time they took,
iterations and linear solves. The solve-time exponent is the least-squares slope of
log(time) against log(dofs). Targets (issue 22): failed-attempt time < 10% on every mesh and
an exponent <= 1.35. N(0.6 MPa) of both solvers is printed to show they reach the same answer.

``--against issue37``: "before" is today's solver with a tangent assembled and factorised at
every iterate (``chord_step`` 0: no residual-only trials where the step is short, no reuse of
the last factorisation; issue 37), same ordering.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import contextlib  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
from collections.abc import Iterator  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric import defaults  # noqa: E402
from exofric.fe import MeshSpec, NewtonSettings  # noqa: E402
from exofric.geometry import BASE  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import squeeze  # noqa: E402

MESHES = [(2, 24), (4, 32), (4, 48), (4, 64), (6, 96), (8, 128)]
PRESSURES = np.linspace(0.05, 0.6, 12)
NOW = NewtonSettings(**defaults.SQUEEZE_NEWTON)
BEFORE = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "active_set_iterations": 0,
                           "stagnation_ratio": 0.0})
BEFORE_37 = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "chord_step": 0.0})
_AGAINST = {"issue22": BEFORE, "issue37": BEFORE_37}


@contextlib.contextmanager
def _rcm_only() -> Iterator[None]:
    """The ordering of before issue 22: hide the line-by-line candidate (RCM alone)."""
    from exofric.fe import _inflation

    keep = _inflation._line_order
    _inflation._line_order = lambda mesh: np.arange(0)  # not a permutation: ignored
    try:
        yield
    finally:
        _inflation._line_order = keep


def _solve(nr: int, nc: int, variant: str, against: str = "issue22") -> dict[str, Any]:
    mat = MooneyRivlin.from_shore(62.5)
    old = variant == "before"
    ctx = _rcm_only() if old and against == "issue22" else contextlib.nullcontext()
    with ctx:
        t0 = time.process_time()
        r = squeeze(BASE, mat, PRESSURES, mesh=MeshSpec(nr, nc), keep_fields=False,
                    settings=_AGAINST[against] if old else NOW)
        cpu = time.process_time() - t0
        from exofric.fe import SqueezeProblem

        band = SqueezeProblem(BASE, mat, MeshSpec(nr, nc), defaults.CONTACT_PENALTY_N_PER_MM3,
                              defaults.SILICONE_DENSITY_T_PER_MM3).assembler.band
    st = r.solver_stats
    return {"cpu_s": cpu, "dofs": r.dofs, "band": band, "attempts": st.attempts,
            "failed_attempts": st.failed_attempts, "failed_time_pct": st.failed_time_pct,
            "iterations": st.iterations, "linear_solves": st.linear_solves,
            "n_06_n": float(r.squeeze_force_n[-1])}


def _exponent(rows: list[dict[str, Any]]) -> float:
    x = np.log([r["dofs"] for r in rows])
    y = np.log([r["cpu_s"] for r in rows])
    return float(np.polyfit(x, y, 1)[0])


def main() -> dict[str, Any]:
    """Run the study; print the table; return the numbers."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="1 run, meshes up to 6 x 96")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--against", choices=sorted(_AGAINST), default="issue22",
                    help="the 'before' solver: before issue 22 or before issue 37")
    a = ap.parse_args()
    runs = 1 if a.quick else a.runs
    meshes = MESHES[:-1] if a.quick else MESHES
    squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3], mesh=MeshSpec(1, 12))  # warm-up
    out: dict[str, list[dict[str, Any]]] = {"before": [], "now": []}
    for nr, nc in meshes:
        samples: dict[str, list[dict[str, Any]]] = {"before": [], "now": []}
        for _ in range(runs):  # interleaved
            for v in ("before", "now"):
                samples[v].append(_solve(nr, nc, v, a.against))
        for v in ("before", "now"):
            row = dict(samples[v][0])
            row["cpu_s"] = statistics.median(s["cpu_s"] for s in samples[v])
            row["mesh"] = f"{nr}x{nc}"
            out[v].append(row)
    res: dict[str, Any] = {"runs": runs, "against": a.against,
                           "load_avg_1min": os.getloadavg()[0], **out,
                           "exponent_before": _exponent(out["before"]),
                           "exponent_now": _exponent(out["now"])}
    hdr = (f"{'mesh':>6} {'dofs':>5} | {'band':>9} {'CPU s':>13} {'x':>5} | "
           f"{'attempts (failed)':>17} {'failed %':>13} | {'iterations':>9} | N(0.6) N")
    print(f"Newton and banded solve, base-group squeeze, CPU medians of {runs} "
          f"(load {res['load_avg_1min']:.1f}); columns: before ({a.against}) -> now")
    print(hdr)
    for b, n in zip(out["before"], out["now"], strict=True):
        print(f"{n['mesh']:>6} {n['dofs']:>5} | {b['band']:>4}->{n['band']:<4} "
              f"{b['cpu_s']:6.2f}->{n['cpu_s']:<6.2f} {b['cpu_s'] / n['cpu_s']:5.2f} | "
              f"{b['attempts']:>3}({b['failed_attempts']})->{n['attempts']:>3}"
              f"({n['failed_attempts']}) {b['failed_time_pct']:5.1f}->{n['failed_time_pct']:<5.1f}"
              f" | {b['iterations']:>3}->{n['iterations']:<4} | "
              f"{b['n_06_n']:.3f} / {n['n_06_n']:.3f}")
    print(f"solve-time exponent (time ~ dofs^k): before {res['exponent_before']:.2f}, "
          f"now {res['exponent_now']:.2f} (target <= 1.35); failed-attempt time now at most "
          f"{max(r['failed_time_pct'] for r in out['now']):.1f}% (target < 10%)")
    if a.json:
        print(json.dumps(res))
    return res


if __name__ == "__main__":
    main()
