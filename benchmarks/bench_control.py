"""Benchmark of the friction controller: cost of one ``Controller.step()`` and of a loop.

Run: ``.venv/bin/python benchmarks/bench_control.py`` (prints a short summary).
A real rig at 1 kHz leaves 1000 us per sample; the step must cost well under that.
"""

from __future__ import annotations

import time
import timeit

from exofric.control import Controller
from exofric.reproduction import ControlSetup, compare, run_case


def _per_call_us(fn: object, number: int = 20000, repeat: int = 5) -> float:
    """Best-of-``repeat`` mean cost of one call in microseconds."""
    return min(timeit.repeat(fn, number=number, repeat=repeat)) / number * 1e6  # type: ignore[arg-type]


def main() -> dict[str, float]:
    """Time Controller.step (plain PID, PID + 2-DOF model feedforward) and closed loops."""
    setup = ControlSetup.default()
    gains = setup.tuning("pid").gains
    plain = Controller(gains, u_max=setup.plant.p_max_mpa)
    with_ff = Controller(gains, u_max=setup.plant.p_max_mpa, feedforward=setup.make_feedforward())
    meas = iter(range(10**9))

    def step_plain() -> float:
        return plain.step(54.4, 50.0 + (next(meas) % 7) * 0.1, 0.001)

    def step_ff() -> float:
        return with_ff.step(54.4, 50.0 + (next(meas) % 7) * 0.1, 0.001)

    out = {"step_pid_us": _per_call_us(step_plain), "step_pid_2dof_ff_us": _per_call_us(step_ff)}
    t0 = time.perf_counter()
    res = run_case(setup, "pid", feedforward=True)
    out["closed_loop_15s_at_100hz_ms"] = (time.perf_counter() - t0) * 1e3
    n = res.simulation.time_s.size - 1
    out["closed_loop_us_per_sample"] = out["closed_loop_15s_at_100hz_ms"] * 1e3 / n
    t0 = time.perf_counter()
    compare(setup)
    out["compare_six_cases_ms"] = (time.perf_counter() - t0) * 1e3
    out.update(_real_time_jitter())
    print("exofric control benchmark (plain Python, one core)")
    print(f"  Controller.step, PID                   : {out['step_pid_us']:8.2f} us")
    print(f"  Controller.step, PID + 2-DOF model FF  : {out['step_pid_2dof_ff_us']:8.2f} us"
          "   (1 kHz loop budget: 1000 us)")
    print(f"  closed loop, 15 s at 100 Hz (1500 smp) : {out['closed_loop_15s_at_100hz_ms']:8.1f} ms"
          f"   ({out['closed_loop_us_per_sample']:.1f} us/sample incl. plant)")
    print(f"  compare (six Fig 12 cases)             : {out['compare_six_cases_ms']:8.1f} ms")
    print(f"  real-time loop on sim:// at 100 Hz, 2 s: jitter p50 {out['jitter_p50_ms']:.3f} ms, "
          f"p99 {out['jitter_p99_ms']:.3f} ms, max {out['jitter_max_ms']:.3f} ms, "
          f"{out['achieved_rate_hz']:.1f} Hz achieved")
    return out


def _real_time_jitter() -> dict[str, float]:
    """Wake-up jitter of the real-time loop (a figure of this machine, not a pass/fail test)."""
    from exofric.hardware import open_device, run_loop

    setup = ControlSetup.default()
    ctrl = Controller(setup.tuning("pi").gains, u_max=setup.plant.p_max_mpa,
                      feedforward=setup.make_feedforward())
    with open_device("sim://?speed=1") as dev:
        res = run_loop(dev, ctrl, 54.4, duration_s=2.0, rate_hz=100.0)
    return {"jitter_p50_ms": res.jitter_p50_ms, "jitter_p99_ms": res.jitter_p99_ms,
            "jitter_max_ms": res.jitter_max_ms, "achieved_rate_hz": res.achieved_rate_hz}


if __name__ == "__main__":
    main()
