"""Pull-out benchmark (issue 39): a full K(P) curve (6 pressures) and the section solve.

Targets on the 2-core CI machine: K(P) < 10 s, the per-unit-length solve < 1 s per pressure
(after the squeeze). Run: ``python benchmarks/bench_pullout.py``.

Measured 2026-11-27 (session 43, held end zones on, load average ~5 on the 2 cores): K(P) 7.6 s,
section 0.26 s per pressure; a profile of the curve (5.6 s) gives the held zones 1.4 s (25 %).
2026-11-28 (session 46, the vector held zone, load ~1.4 with a CI run beside it): K(P) 5.37 s,
section 0.24 s; in a profile of the curve (5.8 s) the vector zone's section matrices take 0.8 s
and its modes 0.8 s. Session 49 (idle, one BLAS thread; the held zones' z grid from 0.125 mm x
1.25): K(P) 6.3-8.1 s, section 0.17-0.28 s; with the friction solve's secant predictor 4.2-6.5 s
and 0.14-0.22 s.
"""

from __future__ import annotations

import time


def main() -> dict[str, float]:
    """Time joint_stiffness over 0.1..0.6 MPa and section_pullout per pressure (s)."""
    from exofric.friction import joint_stiffness
    from exofric.geometry import BASE
    from exofric.material import MooneyRivlin
    from exofric.simulate import PulloutSetup, SqueezeSetup, section_pullout

    mat = MooneyRivlin.from_shore(62.5)
    mu = {"mu_wire": 0.3, "mu_wall": 0.5, "mu_wire_wall": 0.2}
    p = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
    t0 = time.perf_counter()
    setup = PulloutSetup(BASE, mat, **mu)
    joint_stiffness(setup, p, radius_m=0.1, displacement_mm=2.0)
    t_curve = time.perf_counter() - t0
    sq = SqueezeSetup(BASE, mat).solve(p)
    t0 = time.perf_counter()
    for k in range(len(p)):
        section_pullout(setup, p[k], squeeze_result=sq, squeeze_index=k)
    t_sec = (time.perf_counter() - t0) / len(p)
    out = {"k_of_p_curve_s": t_curve, "section_per_pressure_s": t_sec}
    print(f"K(P) curve, 6 pressures: {t_curve:.2f} s (target < 10 s); section solve per "
          f"pressure: {t_sec:.3f} s (target < 1 s)")
    return out


if __name__ == "__main__":
    main()
