"""Controllers beyond fixed PID on the simulated base-group plant (issue 17): a strategy table.

Run: ``.venv/bin/python benchmarks/bench_control_schedule.py [--json]``.

The paper's Fig 12 setup (:func:`exofric.reproduction.ControlSetup.default`: Eq 9 map, the
default FOPDT supply, gains by the IMC/SIMC rule at 54.4 N, 2-DOF model feedforward, 2 %
band, dt 0.01 s, 15 s per step) is run through :func:`exofric.control.compare_strategies`:

A. {PD, PI, PID} x {no feedforward, model inverse} x {fixed, scheduled} at 54.4 N (the
   paper's target), 10 N (near contact onset, 0.144 MPa) and 150 N (high on the map);
B. the same with a hysteretic true friction (backlash of 0.01 MPa in pressure), adding the
   hysteresis-aware inverse, on a step up to 54.4 N and a step down 150 -> 54.4 N;
C. PI/PID fixed vs scheduled with tight tuning (SIMC tau_c = theta = 0.2 s) at 10/54.4/150 N,
   where a fixed loop has less gain margin to spare;
D. scheduling on the measured pressure instead of the target (PI/PID, no feedforward);
E. table A on ``exofric.control.PneumaticPlant`` when that class exists (its FOPDT
   approximation identified from an open-loop step for the tuning and the 2-DOF model).

The paper's settling times are printed beside (test 5, 54.4 N: PD with the model 4.41 s,
PI 5.73 -> 4.20 s, PID 6.17 -> 4.39 s, PD without the model keeps a steady-state error).
The simulations are deterministic: the numbers do not depend on the machine; the CPU time
(time.process_time) of each table is printed for information only.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
from typing import Any

from exofric.control import (
    PlantParams,
    StrategyOptions,
    StrategyTable,
    compare_strategies,
    identify_step,
)
from exofric.reproduction import PAPER_SETTLING_S, ControlSetup

#: Backlash half-width of the hysteretic plant in MPa (table B).
HYSTERESIS_MPA = 0.01
#: Targets of table A/C in N: the paper's, near onset, high on the map.
TARGETS_N = (54.4, 10.0, 150.0)


def _paper(row: Any) -> str:
    if row.scenario != "up 54.4 N" or row.feedforward == "hysteresis" or row.scheduled:
        return ""
    v = PAPER_SETTLING_S.get((row.controller, row.feedforward == "model"))
    return "paper: steady-state error" if v is None else f"paper: {v:.2f} s"


def _print(title: str, table: StrategyTable, cpu_s: float) -> None:
    print(f"\n{title}  [{table.plant}; tuned at {table.tune_target_n:g} N, "
          f"slope {table.slope_ref_n_per_mpa:.1f} N/MPa; CPU {cpu_s:.2f} s]", file=sys.stderr)
    lines = table.format().splitlines()
    print(lines[0], file=sys.stderr)
    for line, row in zip(lines[1:], table.rows, strict=True):
        print(f"{line}   {_paper(row)}", file=sys.stderr)


_OPTION_NAMES = {f.name for f in dataclasses.fields(StrategyOptions)}


def _timed(**kw: Any) -> tuple[StrategyTable, float]:
    """compare_strategies with its options given flat (they go into StrategyOptions), timed."""
    opts = StrategyOptions(**{k: kw.pop(k) for k in list(kw) if k in _OPTION_NAMES})
    t0 = time.process_time()
    t = compare_strategies(**kw, options=opts)
    return t, time.process_time() - t0


def _pneumatic(setup: ControlSetup, ctl: Any = None) -> dict[str, Any] | None:
    """Table A on the physical pneumatic plant, if ``exofric.control.PneumaticPlant`` exists.

    Its default parameters (``PneumaticParams()``) are used; ``ctl`` is the namespace to take
    the classes from (default :mod:`exofric.control`).
    """
    if ctl is None:
        import exofric.control as ctl

    cls = getattr(ctl, "PneumaticPlant", None)
    if cls is None:
        print("\nE. PneumaticPlant not available: skipped", file=sys.stderr)
        return None
    params_cls = getattr(ctl, "PneumaticParams", None)

    def factory() -> Any:
        return cls() if params_cls is None else cls(params_cls())

    try:
        probe = factory()
    except Exception as exc:  # noqa: BLE001 - another module's constructor: report, not crash
        print(f"\nE. PneumaticPlant could not be built with defaults ({exc}): skipped",
              file=sys.stderr)
        return None
    import numpy as np

    dt, u = 0.01, 0.3
    t = np.arange(0.0, 10.0 + dt / 2, dt)
    p = [float(probe.pressure_mpa)] + [float(probe.advance(u, dt)) for _ in t[1:]]
    ident = identify_step(t, np.array(p))          # step of u MPa at t = 0
    fopdt = PlantParams(gain=ident.gain, time_constant_s=ident.time_constant_s,
                        delay_s=ident.delay_s, p_max_mpa=setup.plant.p_max_mpa)
    table, cpu = _timed(plant=fopdt, model_map=setup.model_map, targets_n=TARGETS_N,
                        plant_factory=factory, plant_label=(
                            f"PneumaticPlant (FOPDT fit: gain {ident.gain:.3f}, tau "
                            f"{ident.time_constant_s:.3f} s, delay {ident.delay_s:.3f} s)"))
    _print("E. physical pneumatic plant", table, cpu)
    return table.to_dict()


def main() -> dict[str, Any]:
    """Print tables A-E to stderr; return them as a dict (JSON-ready)."""
    setup = ControlSetup.default()
    base = {"plant": setup.plant, "model_map": setup.model_map}
    out: dict[str, Any] = {}
    ta, cpu = _timed(**base, targets_n=TARGETS_N)
    _print("A. Eq 9 map, FOPDT plant, paper tuning (tau_c = tau + theta)", ta, cpu)
    out["a_fopdt"] = ta.to_dict()
    tb, cpu = _timed(**base, targets_n=(54.4,), steps_n=((150.0, 54.4),),
                     hysteresis_mpa=HYSTERESIS_MPA)
    _print(f"B. hysteretic friction (backlash {HYSTERESIS_MPA:g} MPa)", tb, cpu)
    out["b_hysteresis"] = tb.to_dict()
    tc, cpu = _timed(**base, targets_n=TARGETS_N, controllers=("pi", "pid"),
                     feedforwards=("none",), tau_c_s=setup.plant.delay_s)
    _print("C. tight tuning (SIMC tau_c = theta)", tc, cpu)
    out["c_tight"] = tc.to_dict()
    td, cpu = _timed(**base, targets_n=TARGETS_N, controllers=("pi", "pid"),
                     feedforwards=("none",), schedules=(True,), schedule_on="measured")
    _print("D. scheduled on the measured pressure", td, cpu)
    out["d_measured"] = td.to_dict()
    out["e_pneumatic"] = _pneumatic(setup)
    out["paper_settling_s"] = {f"{k}{'+model' if m else ''}": v
                               for (k, m), v in PAPER_SETTLING_S.items()}
    return out


if __name__ == "__main__":
    res = main()
    if "--json" in sys.argv[1:]:
        print(json.dumps(res))
