"""Run every ``bench_*.py`` in this folder through its ``main()`` (``make bench``).

Usage: ``python benchmarks/run.py [--json] [NAME ...]`` where NAME filters the
benchmarks by substring (e.g. ``inflate``). Each ``main()`` is called without
arguments and prints its own summary; with ``--json`` those prints go to stderr and
one JSON object ``{bench_name: value returned by main()}`` is printed on stdout.
Threads are pinned to 1 before NumPy is imported. Exit code 1 if a benchmark raised.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import contextlib  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import sys  # noqa: E402
import traceback  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

HERE = Path(__file__).resolve().parent


def _load(path: Path) -> Any:
    spec = importlib.util.spec_from_file_location(path.stem, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = module  # registered first, as an import would (dataclasses need it)
    spec.loader.exec_module(module)
    return module


def main(argv: list[str] | None = None) -> int:
    """Run the selected benchmarks; return the exit code."""
    args = list(sys.argv[1:] if argv is None else argv)
    as_json = "--json" in args
    names = [a for a in args if not a.startswith("-")]
    sys.path.insert(0, str(HERE))
    results: dict[str, Any] = {}
    failed = False
    for path in sorted(HERE.glob("bench_*.py")):
        if names and not any(n in path.stem for n in names):
            continue
        sys.argv = [str(path)]  # each main() parses its own (empty) command line
        out = sys.stderr if as_json else sys.stdout
        try:
            with contextlib.redirect_stdout(out):
                results[path.stem] = _load(path).main()
        except Exception:  # report and go on with the other benchmarks
            failed = True
            results[path.stem] = {"error": traceback.format_exc(limit=3)}
            print(f"[{path.stem}] FAILED\n{results[path.stem]['error']}", file=sys.stderr)
    if as_json:
        print(json.dumps(results, default=str))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
