"""Issue 37's targets in one table (``make bench``), or every ``bench_*.py`` through its ``main()``.

Usage:

* ``python benchmarks/run.py [--quick] [--json] [--only KEY ...]``: every target of issue 37,
  measured here through the benchmark modules' functions, in ONE table: the measured value
  (median) with its range (min-max over the runs), the target, and whether it holds. FElupe
  and CalculiX are measured interleaved with exofric in the same run (each round runs every
  code once, the order rotating). ``--quick``: fewer runs and the meshes up to 6 x 96 (a smoke
  run, about 3 min on the 2-core machine); the default run takes about 8-10 min there
  (dominated by the README's uncertainty example, 3 runs, and the FElupe solves).
  ``--only`` measures some rows (keys: tolerance, ogden3, felupe, friction, failed, startup,
  inflate_ccx, sweep).
* ``python benchmarks/run.py --all [--json]`` or ``python benchmarks/run.py NAME ...``: run
  every ``bench_*.py`` (or those whose name contains a NAME) through its ``main()``; with
  ``--json`` their prints go to stderr and one JSON object ``{bench_name: value returned by
  main()}`` is printed on stdout.

Times: CPU seconds where the target is about one process's work (a loaded shared machine
stretches wall time, not CPU time), wall seconds where it is about parallelism or a user's
wait (the sweep's speed-up, the README example); the "judged on" column says which. Threads
are pinned to 1 before NumPy is imported. Exit code 1 if a benchmark raised.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"
os.environ.setdefault("CCX_NPROC_EQUATION_SOLVER", "1")

import contextlib  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import traceback  # noqa: E402
from collections.abc import Callable  # noqa: E402
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


def _bench(name: str) -> Any:
    """The module ``benchmarks/<name>.py`` (loaded once)."""
    if name not in sys.modules:
        sys.path.insert(0, str(HERE))
        _load(HERE / f"{name}.py")
    return sys.modules[name]


# --------------------------------------------------------------------------- one target
class Row:
    """One target: the measured values (one per run), how they are judged, a note."""

    def __init__(self, key: str, label: str, values: list[float], unit: str, target: float,
                 at_most: bool, judged: str, note: str = "") -> None:
        self.key, self.label, self.values, self.unit = key, label, values, unit
        self.target, self.at_most, self.judged, self.note = target, at_most, judged, note

    @property
    def median(self) -> float:
        """The judged value: the median over the runs (the failed-attempt row: the maximum
        over the meshes, "on every mesh")."""
        if self.key == "failed":
            return float(max(self.values))
        return float(statistics.median(self.values))

    @property
    def holds(self) -> bool:
        """The judged value meets the target (``<=`` / ``>=``; the failed share ``<``)."""
        if self.key == "failed":
            return self.median < self.target
        return self.median <= self.target if self.at_most else self.median >= self.target

    def to_dict(self) -> dict[str, Any]:
        return {"label": self.label, "values": self.values, "judged_value": self.median,
                "min": min(self.values), "max": max(self.values), "unit": self.unit,
                "target": self.target, "at_most": self.at_most, "holds": self.holds,
                "judged_on": self.judged, "note": self.note}


def tolerance_row(quick: bool) -> Row:
    """The README's uncertainty example as a whole process (wall s), bands vs brute force."""
    bt = _bench("bench_tolerance")
    ref = json.loads((bt.DATA / "tolerance_reference_readme.json").read_text())
    runs = [bt._time_readme() for _ in range(1 if quick else 3)]
    entry, scale = runs[-1][2], ref["squeeze_force_n"][-1]
    err = max(100 * abs(entry[k][-1] - ref[k][-1]) / (scale * (0.7168 if "fric" in k else 1))
              for k in bt.KEYS)
    return Row("tolerance", "uncertainty README example (64 samples)", [r[0] for r in runs],
               "s", 15.0, True, "wall",
               f"CPU {statistics.median(r[1] for r in runs):.1f} s; bands within {err:.3f} % "
               "of N(0.6 MPa) of brute force (target 1 %)")


def ogden3_row(quick: bool) -> Row:
    """Ogden-3 fit on the 1,000-point Ecoflex curve (CPU s per fit, multi-start included)."""
    import warnings

    from exofric.material import fit_material

    lam, p = _bench("bench_material_fit").curve(1000)
    cpu, fit = [], None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit_material("neo-hookean", uniaxial=(lam, p))  # imports (SciPy), once
        for _ in range(2 if quick else 5):
            c0 = time.process_time()
            fit = fit_material("ogden3", uniaxial=(lam, p))
            cpu.append(time.process_time() - c0)
    assert fit is not None
    return Row("ogden3", "Ogden-3 fit, 1,000 points", cpu, "s", 2.0, True, "CPU",
               f"RMS {fit.modes['uniaxial'].rms_mpa:.4g} MPa, "
               f"{fit.multistart.get('n_starts', 1)} starts")


def friction_row(quick: bool) -> Row:
    """Default squeeze with mu 0.3 on both contacts / frictionless, CPU, interleaved pairs."""
    import numpy as np

    from exofric.geometry import BASE
    from exofric.material import MooneyRivlin
    from exofric.simulate import squeeze

    mat, p = MooneyRivlin.from_shore(62.5), np.round(np.arange(1, 13) * 0.05, 2)
    squeeze(BASE, mat, [0.3])   # warm-up (imports)
    ratios: list[float] = []
    its: dict[float, int] = {}
    for _ in range(2 if quick else 5):
        t = []
        for mu in (0.0, 0.3):
            c0 = time.process_time()
            r = squeeze(BASE, mat, p, mu_wall=mu, mu_wire=mu)
            t.append(time.process_time() - c0)
            its[mu] = r.solver_stats.iterations
        ratios.append(t[1] / t[0])
    return Row("friction", "frictional / frictionless squeeze", ratios, "x", 2.0, True, "CPU",
               f"default accuracy, mu 0.3 on wall and wire; Newton iterations {its[0.3]} "
               f"against {its[0.0]}")


def failed_row(quick: bool) -> Row:
    """Failed Newton attempts' share of the solve time on every mesh 2 x 24 .. 8 x 128 (%)."""
    bs = _bench("bench_solver")
    meshes = bs.MESHES[:-1] if quick else bs.MESHES
    pct = {f"{nr}x{nc}": bs._solve(nr, nc, "now")["failed_time_pct"] for nr, nc in meshes}
    worst = max(pct, key=lambda k: pct[k])
    return Row("failed", "failed-attempt time, worst mesh", list(pct.values()), "%", 5.0,
               True, "CPU, max",
               f"range over the meshes {', '.join(pct)}; worst {worst}")


def startup_rows(quick: bool) -> list[Row]:
    """``exofric material`` and the default squeeze as whole processes (CPU s)."""
    bst = _bench("bench_startup")
    res = bst.measure(3 if quick else 7, [bst.MATERIAL_ROW, bst.SQUEEZE_ROW])
    out = []
    for key, label, row, target in (("material", "exofric material --shore 62.5",
                                     bst.MATERIAL_ROW, 0.2),
                                    ("squeeze", "exofric squeeze (base), whole process",
                                     bst.SQUEEZE_ROW, 0.6)):
        r = res["rows"][row]
        if "error" in r:
            raise RuntimeError(f"{label}: {r['error']}")
        out.append(Row(key, label, r["cpu_s"], "s", target, True, "CPU",
                       f"wall {r['median_s']:.2f} s (min {r['min_s']:.2f})"))
    return out


def peer_rows(quick: bool) -> list[Row]:
    """exofric vs FElupe (squeeze solve, matched accuracy) and vs CalculiX (free inflation as
    whole processes), every code in every round, the order rotating; per-round ratios."""
    bp = _bench("bench_peers")
    from exofric.material import MooneyRivlin

    mat = MooneyRivlin.from_shore(bp.SHORE)
    ccx = bp.ccxm.ccx_available()
    rows: list[Row] = []
    with tempfile.TemporaryDirectory(prefix="exofric-run-") as tmp:
        notes: dict[str, str] = {}
        sq = {c.name: c for c in bp._squeeze_codes(mat, Path(tmp), ccx, notes)}
        inf = {c.name: c for c in bp._inflate_codes(mat, Path(tmp), ccx, notes)}
        for c in sq.values():
            c.first = c.solve()     # results; warms the in-process libraries up
        for k in range(2 if quick else 5):
            order = list(sq)[k % len(sq):] + list(sq)[:k % len(sq)]
            for name in order:
                sq[name].solve_cpu.append(sq[name].solve()["cpu"])
            order = list(inf)[k % len(inf):] + list(inf)[:k % len(inf)]
            for name in order:
                r = inf[name].whole()
                inf[name].whole_cpu.append(r["cpu"])
                inf[name].whole_wall.append(r["wall"])
    ex = sq["exofric"].solve_cpu
    if "FElupe" in sq:
        fe = sq["FElupe"].solve_cpu
        extra = ""
        if "CalculiX" in sq:
            cx = statistics.median(a / b for a, b in zip(sq["CalculiX"].solve_cpu, ex,
                                                          strict=True))
            extra = f"; CalculiX / exofric {cx:.1f}x"
        rows.append(Row("felupe", "squeeze solve: FElupe / exofric", [
            a / b for a, b in zip(fe, ex, strict=True)], "x", 10.0, False, "CPU",
            f"exofric {statistics.median(ex):.2f} s, FElupe {statistics.median(fe):.2f} s"
            + extra))
    if "CalculiX" in inf:
        e, c = inf["exofric"], inf["CalculiX"]
        rows.append(Row("inflate_ccx", "free inflation process: exofric / CalculiX", [
            a / b for a, b in zip(e.whole_cpu, c.whole_cpu, strict=True)], "x", 2.0, True,
            "CPU", f"exofric {statistics.median(e.whole_cpu):.2f} s, CalculiX "
            f"{statistics.median(c.whole_cpu):.2f} s CPU; wall ratio "
            f"{statistics.median(e.whole_wall) / statistics.median(c.whole_wall):.2f}"))
    for name, note in notes.items():
        print(f"[peers] {name}: {note}", file=sys.stderr)
    return rows


def sweep_row(quick: bool) -> Row:
    """2 worker processes / 1 on the 16-design sweep, whole processes, interleaved pairs."""
    res = _bench("bench_sweep").ratio_2_vs_1(2 if quick else 5)
    return Row("sweep", "2-worker sweep / 1 worker (16 designs)", res["ratios"], "x", 1.6,
               False, "wall",
               f"1 worker {statistics.median(res['workers1_wall_s']):.2f} s, 2 workers "
               f"{statistics.median(res['workers2_wall_s']):.2f} s; load "
               f"{min(res['load']):.1f}-{max(res['load']):.1f}")


#: key -> the function measuring it (one or several rows), in the table's order
MEASURES: dict[str, Callable[[bool], Row | list[Row]]] = {
    "tolerance": tolerance_row, "ogden3": ogden3_row, "felupe": peer_rows,
    "friction": friction_row, "failed": failed_row, "startup": startup_rows,
    "sweep": sweep_row,
}
ALIASES = {"inflate_ccx": "felupe", "material": "startup", "squeeze": "startup"}
ORDER = ("tolerance", "ogden3", "felupe", "friction", "failed", "material", "squeeze",
         "inflate_ccx", "sweep")


def targets(quick: bool, only: list[str] | None = None) -> tuple[list[Row], dict[str, str]]:
    """Measure the targets (``only``: some keys); return the rows and the errors by key."""
    keys = [ALIASES.get(k, k) for k in (only or list(MEASURES))]
    rows: list[Row] = []
    errors: dict[str, str] = {}
    for key in dict.fromkeys(keys):
        t0 = time.perf_counter()
        try:
            got = MEASURES[key](quick)
        except Exception:  # report it in the table and go on
            errors[key] = traceback.format_exc(limit=3)
            print(f"[{key}] FAILED\n{errors[key]}", file=sys.stderr)
            continue
        rows += got if isinstance(got, list) else [got]
        print(f"[{key}] measured in {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    rows.sort(key=lambda r: ORDER.index(r.key))
    return rows, errors


def render(rows: list[Row], errors: dict[str, str], quick: bool, wall_s: float) -> str:
    """The one table."""
    head = (f"{'target (issue 37)':<44}{'measured':>9} {'range':>15} {'target':>9}  "
            f"{'':<5} {'judged on':<10}")
    lines = [f"Issue 37 targets ({'--quick' if quick else 'default'} run, {wall_s:.0f} s; "
             f"load average {os.getloadavg()[0]:.1f}; measured = median, range = min-max "
             "over the runs)",
             head, "-" * len(head)]
    for r in rows:
        unit = r.unit if r.unit != "x" else "x"
        fmt = (lambda v: f"{v:.2f}") if r.unit in ("x", "s") else (lambda v: f"{v:.1f}")
        rel = "<=" if r.at_most and r.key != "failed" else "<" if r.key == "failed" else ">="
        lines.append(f"{r.label[:43]:<44}{fmt(r.median) + unit:>9} "
                     f"{fmt(min(r.values)) + '-' + fmt(max(r.values)) + unit:>15} "
                     f"{rel + ' ' + f'{r.target:g}' + unit:>9}  "
                     f"{'holds' if r.holds else 'SHORT':<5} {r.judged:<10}")
        if r.note:
            lines.append(f"{'':<4}{r.note}")
    for key, err in errors.items():
        lines.append(f"{key:<44}FAILED: {err.strip().splitlines()[-1][:60]}")
    return "\n".join(lines)


def run_all(names: list[str], as_json: bool) -> int:
    """Every ``bench_*.py`` (or those matching ``names``) through its ``main()``."""
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


def main(argv: list[str] | None = None) -> int:
    """The target table (default) or the benchmarks' own mains (``--all`` / names)."""
    args = list(sys.argv[1:] if argv is None else argv)
    if {"-h", "--help"} & set(args):
        print(__doc__)
        return 0
    stray = [a for a in args if a.startswith("-") and a not in ("--json", "--quick", "--only",
                                                                 "--all")]
    if stray:
        print(f"run.py: error: unknown option(s) {stray}; options: --quick, --json, --only KEY "
              "..., --all, NAME ... (--help)", file=sys.stderr)
        return 2
    as_json, quick = "--json" in args, "--quick" in args
    only = None
    if "--only" in args:
        i = args.index("--only")
        only = [a for a in args[i + 1:] if not a.startswith("-")]
        args = args[:i] + args[i + 1 + len(only):]
    names = [a for a in args if not a.startswith("-")]
    if "--all" in args or names:
        return run_all(names, as_json)
    unknown = [k for k in only or [] if ALIASES.get(k, k) not in MEASURES]
    if unknown:
        print(f"run.py: error: unknown --only key(s) {unknown}; keys: {', '.join(ORDER)}",
              file=sys.stderr)
        return 2
    sys.argv = [sys.argv[0]]   # the bench modules' parsers see no options of ours
    t0 = time.perf_counter()
    rows, errors = targets(quick, only)
    wall = time.perf_counter() - t0
    if as_json:
        print(json.dumps({"quick": quick, "wall_s": wall, "rows": {r.key: r.to_dict()
                                                                    for r in rows},
                          "errors": errors}))
    else:
        print(render(rows, errors, quick, wall))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
