"""Benchmark of the gait simulation: 10 strides per controller, median time, real-time factor.

Run: ``.venv/bin/python benchmarks/bench_gait.py`` (prints a short summary).
The default scenario (shipped OpenSim stride, 1.14 s; physical pneumatic plant; 2 ms control
step; Eq 9 friction map) must run at least 20x faster than real time for 10 strides (issue 33):
a design sweep of a few hundred valve/line/controller cases then takes minutes.
"""

from __future__ import annotations

import statistics
import time

from exofric.control import GAIT_CONTROLLERS, GaitSetup, simulate_gait
from exofric.io import gait_data_path, read_gait

REPEATS = 5
STRIDES = 10
REQUIRED_RTF = 20.0


def main() -> dict[str, float]:
    """Median wall time (s) and real-time factor of 10 strides for each controller."""
    walk = read_gait(gait_data_path())
    setup = GaitSetup(strides=STRIDES)
    simulate_gait(walk, GaitSetup(strides=1), controller="ff")   # imports, supply model
    out: dict[str, float] = {}
    print(f"exofric gait benchmark: {STRIDES} strides of {walk.duration_s:.2f} s, "
          f"dt {setup.dt_s * 1e3:g} ms, median of {REPEATS} (plain Python, one core)")
    for c in GAIT_CONTROLLERS:
        times = []
        for _ in range(REPEATS):
            t0 = time.perf_counter()
            r = simulate_gait(walk, setup, controller=c)
            times.append(time.perf_counter() - t0)
        med = statistics.median(times)
        simulated = float(r.time_s.size * r.dt_s)
        out[f"{c}_median_s"] = med
        out[f"{c}_real_time_factor"] = simulated / med
        flag = "" if simulated / med >= REQUIRED_RTF else f"   BELOW {REQUIRED_RTF:g}x"
        print(f"  {c:<8} {r.time_s.size:6d} samples ({simulated:5.2f} s simulated): median "
              f"{med:6.3f} s, {simulated / med:6.1f}x real time{flag}")
    return out


if __name__ == "__main__":
    main()
