"""Shared command line and target line of the FE benchmarks (bench_inflate, bench_squeeze)."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from typing import Any


def target_line(out: dict[str, Any]) -> str:
    """The FElupe/exofric ratio and whether the issue's targets are met."""
    return (f"  ratio felupe/exofric = {out['ratio_felupe_over_exofric']:.1f}x "
            f"(targets: exofric <= {out['target_time_s']} s, >= {out['target_ratio']:g}x): "
            f"{'met' if out['meets_targets'] else 'NOT met'}")


def cli_main(run: Callable[[int, int], dict[str, Any]], render: Callable[[dict[str, Any]], str],
             doc: str | None, felupe_runs: int, argv: list[str] | None = None) -> dict[str, Any]:
    """Parse ``--runs/--felupe-runs/--json/--quiet``, run, print, return the summary."""
    ap = argparse.ArgumentParser(description=doc)
    ap.add_argument("--runs", type=int, default=7, help="exofric repetitions (median)")
    ap.add_argument("--felupe-runs", type=int, default=felupe_runs,
                    help="FElupe repetitions (median)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--quiet", action="store_true", help="print nothing (return only)")
    args = ap.parse_args(argv)
    out = run(args.runs, args.felupe_runs)
    if not args.quiet:
        print(json.dumps(out) if args.json else render(out))
    return out
