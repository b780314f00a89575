"""Benchmark of the argument-kind checks of the public functions (exofric._validate, issue 38).

Run: ``.venv/bin/python benchmarks/bench_validate.py [--runs 7] [--json]``.

Each row times one call of a public function through its checked wrapper (what
``exofric.friction.torque`` is) and of the function itself (``inspect.unwrap``), interleaved,
``--runs`` rounds of ``timeit`` loops, and reports the medians in microseconds and the overhead
(checked - raw). The rows span the kinds of checks: numbers only (``check_friction``, two
arguments), a light function (``torque``), a squeeze's arguments (a Structure, a material, a
pressure list of 13, keyword floats; only the check, ``_bind``, since a solve takes seconds),
and an array of 100,000 pressures (a list: every element's type is looked at; an ndarray: its
dtype only), and the construction of the dataclasses built per step (``checked_init``). The
reference scale is an empty Python function call, printed too: on a shared
machine absolute times move with the load, the ratio to it does not.
"""

from __future__ import annotations

import argparse
import inspect
import json
import statistics
import timeit
from collections.abc import Callable
from typing import Any


def _median_us(fn: Callable[[], Any], number: int, runs: int) -> float:
    return statistics.median(timeit.repeat(fn, number=number, repeat=runs)) / number * 1e6


def rows(runs: int) -> list[dict[str, Any]]:
    """(name, checked us, raw us, overhead us) per case."""
    import numpy as np

    import exofric as ef
    import exofric._validate as v
    from exofric.simulate import check_friction

    mat = ef.MooneyRivlin.from_shore(62.5)
    sq_plan = v._plan(inspect.unwrap(ef.squeeze), "squeeze")
    fg_plan = v._plan(inspect.unwrap(ef.fit_gamma), "fit_gamma")
    p13 = [0.05 * i for i in range(13)]
    big_list = [0.3] * 100_000
    big_arr = np.full(100_000, 0.3)

    def empty() -> None:
        return None

    cases: list[tuple[str, Callable[[], Any], Callable[[], Any] | None, int]] = [
        ("empty function call (scale)", empty, None, 20000),
        ("check_friction('mu', 0.3)", lambda: check_friction("mu", 0.3),
         lambda: inspect.unwrap(check_friction)("mu", 0.3), 20000),
        ("torque(180.49)", lambda: ef.torque(180.49),
         lambda: inspect.unwrap(ef.torque)(180.49), 2000),
        ("squeeze arguments: check only", lambda: v._bind(
            sq_plan, (ef.BASE, mat, p13), {"mu_wall": 0.2, "accuracy": "draft"}), None, 5000),
        ("fit_gamma pressure_sd_mpa: list, 1e5", lambda: v._bind(
            fg_plan, ([0.3], [1.0]), {"pressure_sd_mpa": big_list}), None, 20),
        ("fit_gamma pressure_sd_mpa: ndarray, 1e5", lambda: v._bind(
            fg_plan, ([0.3], [1.0]), {"pressure_sd_mpa": big_arr}), None, 5000),
    ]
    cases += _construction_cases()
    out = []
    for name, checked, raw, number in cases:
        checked()
        c = _median_us(checked, number, runs)
        r = _median_us(raw, number, runs) if raw is not None else 0.0
        out.append({"case": name, "checked_us": c, "raw_us": r if raw else None,
                    "overhead_us": c - r})
    return out


def _construction_cases() -> list[tuple[str, Callable[[], Any], Callable[[], Any] | None, int]]:
    """Dataclass construction (issue 38): a checked constructor against the raw one, for the
    classes built per step (Reading per device sample; PathPoint per load step), and the
    per-Newton-iteration ContactState through ``unchecked`` (what the contact code does)."""
    import numpy as np

    from exofric._validate import unchecked
    from exofric.fe import ContactState, PathPoint
    from exofric.hardware import Reading

    a = np.zeros(200)

    def raw_of(cls: type, *args: Any) -> Callable[[], Any]:
        init, obj = inspect.unwrap(cls.__init__), object.__new__(cls)
        return lambda: init(obj, *args)

    return [
        ("Reading(0.3, 12.0, 5)", lambda: Reading(0.3, 12.0, 5), raw_of(Reading, 0.3, 12.0, 5),
         20000),
        ("PathPoint(0.5, u, 3, 1)", lambda: PathPoint(0.5, a, 3, 1),
         raw_of(PathPoint, 0.5, a, 3, 1), 20000),
        ("unchecked(ContactState, ...)", lambda: unchecked(ContactState, 0.0, a, a, a, a),
         raw_of(ContactState, 0.0, a, a, a, a), 20000),
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    res = rows(args.runs)
    if args.json:
        print(json.dumps(res))
        return
    print(f"{'case':40s} {'checked us':>11s} {'raw us':>9s} {'overhead us':>12s}")
    for r in res:
        raw = "" if r["raw_us"] is None else f"{r['raw_us']:9.2f}"
        print(f"{r['case']:40s} {r['checked_us']:11.2f} {raw:>9s} {r['overhead_us']:12.2f}")


if __name__ == "__main__":
    main()
