"""``exofric sweep`` (design-space sweeps: serial, worker processes or Dask) and ``exofric design``
(target torque search).

Only typer and the CLI helpers are imported at start-up: exofric.design (pandas, pyarrow),
Dask and rich's progress bar are imported inside the commands, so ``--help`` stays light.
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, ClassVar

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table, narrow_table, save_figure
from exofric.cli._options import OptionGroup, grouped

WORKERS = typer.Option(None, "--workers",
                       help="Local worker processes (default: chosen by the work size).")
SCHEDULER = typer.Option(None, "--scheduler",
                         help="Address of a running Dask scheduler, e.g. tcp://10.0.0.1:8786.")
SERIAL = typer.Option(False, "--serial", help="Plain in-process loop, no worker processes.")
EXECUTOR = typer.Option("auto", "--executor",
                        help="auto (serial or worker processes, by the predicted times), "
                        "serial, processes (one per CPU) or dask (a LocalCluster).")
TIMEOUT = typer.Option(60.0, "--timeout",
                       help="Seconds to wait for --scheduler and its first worker (finite, > 0).")
RETRY = typer.Option(False, "--retry-failed", help="Solve designs recorded as failed again.")
QUIET = typer.Option(False, "--quiet", help="No progress bar on stderr (it is also left out "
                     "when stderr is not a terminal; --json keeps it).")


class _Execution(OptionGroup):
    """Where the designs are solved: worker processes, a Dask scheduler, serial, executor."""

    workers: int | None
    scheduler: str | None
    serial: bool
    executor: str
    OPTIONS: ClassVar[dict[str, Any]] = {"workers": WORKERS, "scheduler": SCHEDULER,
                                         "serial": SERIAL, "executor": EXECUTOR}


class _Search(OptionGroup):
    """design's search: the target torque (Nm), lever arm (m), highest pressure (MPa), the
    friction law's gamma and F0 (N), the objective and how many candidates to list."""

    target_torque: float
    arm: float | None
    pmax: float
    gamma: float | None
    f0: float | None
    objective: str
    validated_only: bool
    top: int
    OPTIONS: ClassVar[dict[str, Any]] = {
        "target_torque": typer.Option(40.0, "--target-torque",
                                      help="Required joint torque (Nm)."),
        "arm": typer.Option(None, "--arm", help="Lever arm R (m); default the sweep's."),
        "pmax": typer.Option(0.6, "--pmax", help="Highest allowed pressure (MPa)."),
        "gamma": typer.Option(None, "--gamma", help="Equivalent coefficient; default the "
                              "sweep's (0.7168)."),
        "f0": typer.Option(None, "--f0", help="Friction offset F0 (N)."),
        "objective": typer.Option("pressure", "--objective", help="'pressure' (least P "
                                  "reaching the torque) or 'margin' (most torque margin at "
                                  "pmax)."),
        "validated_only": typer.Option(False, "--validated-only", help="Rank only designs "
                                       "inside the validated region."),
        "top": typer.Option(10, "--top", help="Candidates to list."),
    }

    def check(self) -> None:
        """The search options, checked before any work (one line, exit 2)."""
        from exofric.errors import InputError, check_finite, check_positive, check_range

        check_positive("--target-torque", self.target_torque, "Nm")
        check_range("--pmax", self.pmax, 0.0, 2.0, lo_open=True, unit="MPa")
        if self.arm is not None:
            check_positive("--arm", self.arm, "m")
        if self.gamma is not None:
            check_positive("--gamma", self.gamma)
        if self.f0 is not None:
            check_finite("--f0 (N)", self.f0)
        if self.objective not in ("pressure", "margin"):
            raise InputError(f"--objective must be 'pressure' or 'margin', got "
                             f"{self.objective!r}")
        if self.top < 1:
            raise InputError(f"--top must be >= 1, got {self.top}")


@contextlib.contextmanager
def _progress(quiet: bool) -> Iterator[Callable[[int, int, str], None] | None]:
    """A rich progress bar on stderr (None when ``quiet`` or stderr is not a terminal: a log
    file gets no bar; ``--json`` keeps it, stdout stays one JSON object), started at its first
    update: the
    sweep starts its worker processes before that, while this process runs no other thread."""
    if quiet or not sys.stderr.isatty():
        yield None
        return
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    bar = Progress(TextColumn("[bold]solving designs"), BarColumn(), MofNCompleteColumn(),
                   TimeElapsedColumn(), TimeRemainingColumn(), TextColumn("{task.description}"),
                   console=Console(stderr=True), transient=False)
    task = bar.add_task("", total=None)

    def update(done: int, total: int, label: str) -> None:
        if not bar.live.is_started:
            bar.start()
        bar.update(task, completed=done, total=total, description=label, visible=total > 0)

    try:
        yield update
    finally:
        if bar.live.is_started:
            bar.stop()


def _check_options(workers: int | None, scheduler: str | None, timeout: float,
                   executor: str) -> None:
    """The execution options, checked before anything is loaded or solved (one line, exit 2);
    the scheduler's reachability is checked by the sweep itself, right before Dask."""
    import math

    from exofric.design import EXECUTORS, check_scheduler
    from exofric.errors import InputError

    if executor not in EXECUTORS:
        raise InputError(f"--executor must be one of {', '.join(EXECUTORS)}, got {executor!r}")
    if workers is not None and workers < 1:
        raise InputError(f"--workers must be >= 1, got {workers}")
    if not (math.isfinite(timeout) and timeout > 0):
        raise InputError(f"--timeout must be a finite number of seconds > 0, got {timeout}")
    if scheduler is not None:
        check_scheduler(scheduler)


def _load(config: Path | None) -> Any:
    """The sweep of ``config``, or the built-in design space."""
    from exofric.design import load_sweep, parse_sweep

    if config is None:
        from exofric.design import DEFAULT_SPACE

        return parse_sweep(DEFAULT_SPACE)
    return load_sweep(config)


def _run(config: Path | None, out: Path | None, ex: _Execution, retry: bool, quiet: bool,
         timeout: float, spec: Any = None) -> Any:
    """Run the sweep of ``config`` (or ``spec``) into ``out`` as ``ex`` asks."""
    from exofric.design import run_sweep

    _check_options(ex.workers, ex.scheduler, timeout, ex.executor)
    spec = spec if spec is not None else _load(config)
    out = out or Path(".exofric-sweeps") / spec.name
    with _progress(quiet) as progress:
        return run_sweep(spec, out, workers=ex.workers, scheduler=ex.scheduler,
                         serial=ex.serial, executor=ex.executor, retry_failed=retry,
                         progress=progress, timeout_s=timeout)


@grouped
def sweep_cmd(
    config: Path = typer.Argument(None, help="Sweep definition (TOML), see examples/."),
    out: Path = typer.Option(None, "--out", help="Result directory (Parquet dataset, cache)."),
    verify: Path = typer.Option(None, "--verify", help="Check the sweep folder VERIFY "
                                "(checksums, files, derived columns) without solving: "
                                "exit 0 all ok, 1 damaged or missing designs, 2 not a "
                                "sweep folder.", metavar="OUT"),
    execution: _Execution = _Execution.options(),
    retry_failed: bool = RETRY,
    timeout: float = TIMEOUT,
    quiet: bool = QUIET,
    as_json: bool = JSON_OPTION,
) -> None:
    """Solve N(P) for every design of a sweep; rows go to Parquet (mm, MPa, N, Nm).

    By default the designs are solved in this process or on local worker processes,
    whichever is predicted faster for the work size (the output says which and why).
    Finished designs in OUT are reused (cache keyed by inputs + solver settings), so a
    killed sweep resumes where it stopped; a damaged design file is moved to
    OUT/_quarantine/, named in one warning line and solved again. ``--verify OUT`` only
    checks the folder.
    """
    from exofric.errors import InputError

    if verify is not None:
        if config is not None or out is not None:
            raise InputError("--verify takes the folder alone: exofric sweep --verify OUT")
        _verify(verify, as_json)
        return
    if config is None or out is None:
        raise InputError("sweep needs CONFIG and --out OUT (or --verify OUT)",
                         param="config")
    run = _run(config, out, execution, retry_failed, quiet, timeout)
    d = run.to_dict()

    def render() -> None:
        s = run.summary
        console.print(kv_table(f"Sweep {config.name}", [
            ("designs", str(s.designs), ""), ("computed now", str(s.computed), ""),
            ("cached", str(s.cached), ""), ("skipped (impossible)", str(s.skipped), ""),
            ("failed", str(s.failed), ""), ("rows", str(d["rows"]), ""),
            ("execution", f"{s.execution}: {s.scheduler}", ""),
            ("why", s.execution_reason, ""), ("wall time", f"{s.wall_time_s:.2f}", "s"),
            ("dataset", s.out, "")]))
        for x in d["skipped_designs"]:
            console.print(f"skipped {x['name']}: {x['reason']}")
        for x in d["failures"]:
            console.print(f"[red]failed[/red] {x['name']}: {x['error']}")

    emit(d, as_json, render)


@grouped
def design_cmd(
    config: Path = typer.Argument(None, help="Sweep definition (TOML); default: d1 x d2 "
                                  "around the base group."),
    search: _Search = _Search.options(),
    out: Path = typer.Option(None, "--out", help="Sweep result directory (cache); default "
                             ".exofric-sweeps/<sweep name>."),
    plot: Path = typer.Option(None, "--plot",
                              help="Design map PNG (default OUT/design-map.png)."),
    no_plot: bool = typer.Option(False, "--no-plot", help="Do not write the design map."),
    surrogate: bool = typer.Option(False, "--surrogate",
                                   help="Also fit a surrogate of N(P) on the sweep "
                                   "(leave-one-out error), explore 4096 candidates in the "
                                   "sweep's box on it and confirm the best 5 with the FE."),
    execution: _Execution = _Execution.options(),
    timeout: float = TIMEOUT,
    quiet: bool = QUIET,
    as_json: bool = JSON_OPTION,
) -> None:
    """Find swept designs reaching a target torque with the least pressure (Nm, MPa, mm)."""
    from exofric.design import search_designs
    from exofric.errors import InputError

    # validate the search before any work: options, then the sweep definition (cheap),
    # then pmax against its pressures, all before a single design is solved or read
    search.check()
    _check_options(execution.workers, execution.scheduler, timeout, execution.executor)
    spec = _load(config)
    p_top = max(spec.pressures_mpa)
    if search.pmax > p_top + 1e-12:
        raise InputError(f"--pmax {search.pmax:g} MPa is above the sweep's largest pressure "
                         f"{p_top:g} MPa; allowed range (0, {p_top:g}] MPa")
    run = _run(config, out, execution, False, quiet, timeout, spec=spec)
    frame = run.frame
    found = search_designs(frame, search.target_torque, search.arm if search.arm is not None
                           else float(frame["arm_radius_m"].iloc[0]), search.pmax,
                           gamma=search.gamma, f0_n=search.f0, objective=search.objective,
                           validated_only=search.validated_only)
    d = found.to_dict(top=search.top)
    d["sweep"] = run.summary.to_dict()
    d["warnings"] = list(run.warnings)
    if surrogate:
        d["surrogate"] = _surrogate(frame, spec, found, search.target_torque, search.pmax,
                                    search.gamma, search.f0, search.objective,
                                    search.validated_only)
    if not no_plot:
        from exofric.plots import plot_design_map

        skipped = frame[frame["status"] == "skipped"]
        d["plot"] = str(save_figure(plot_design_map(found, skipped=skipped),
                                    plot or Path(run.summary.out) / "design-map.png"))

    emit(d, as_json, lambda: _render_design(d))


def register(app: typer.Typer) -> None:
    """Add the ``sweep`` and ``design`` commands."""
    app.command("sweep")(sweep_cmd)
    app.command("design")(design_cmd)


def _surrogate(frame: Any, spec: Any, search: Any, target: float, pmax: float,
               gamma: float | None, f0: float | None, objective: str,
               validated_only: bool) -> dict[str, Any]:
    """``exofric design --surrogate``: fit on the sweep, explore, confirm with FE (JSON part)."""
    from exofric.design import fit_surrogate, surrogate_search

    sur = fit_surrogate(frame)
    res = surrogate_search(sur, spec, target, search.arm_radius_m, pmax, gamma=gamma, f0_n=f0,
                           objective=objective, validated_only=validated_only)
    d = res.to_dict()
    d["trained_designs"] = sur.n_designs
    d["fit_time_s"] = sur.fit_time_s
    fe_best = search.best
    d["sweep_best_required_pressure_mpa"] = fe_best["required_pressure_mpa"] if fe_best else None
    return d


def _verify(out: Path, as_json: bool) -> None:
    """``exofric sweep --verify OUT``: exit 0 all ok, 1 damaged/missing, 2 not a sweep folder.

    Imports exofric.design's store only (pandas, pyarrow), never Dask.
    """
    import sys

    from exofric.design import verify_sweep

    check = verify_sweep(out)
    d = check.to_dict()

    def render() -> None:
        from rich.table import Table

        c = check.counts
        t = Table(title=f"Sweep folder {out}: {c['ok']} ok, {c['quarantined']} quarantined, "
                  f"{c['missing']} missing; manifest {check.manifest}")
        for col in ("design", "state", "status", "reason"):
            t.add_column(col, overflow="fold")
        for x in check.designs:
            if x["state"] != "ok":
                t.add_row(x["name"] or x["key"][:12], f"[red]{x['state']}[/red]", x["status"],
                          x["reason"])
        console.print(t)
        console.print("all designs verified" if check.ok else "[red]not all verified[/red]: "
                      "a rerun of the sweep solves the quarantined and missing designs")

    for line in check.warnings:
        print(f"exofric: warning: {line}", file=sys.stderr)
    emit(d, as_json, render)
    if check.exit_code:
        raise typer.Exit(check.exit_code)


def _render_design(d: dict[str, Any]) -> None:
    """Rich table of the ranked (or, if none reaches, the closest) designs."""

    reach = bool(d["candidates"])
    cands = d["candidates"] or d["closest"]
    title = (f"{'Designs reaching' if reach else 'None reaches; closest to'} "
             f"{d['target_torque_nm']:g} Nm by {d['pmax_mpa']:g} MPa (R = {d['arm_radius_m']:g} m,"
             f" gamma = {d['gamma']:g}; {d['reaching']} of {d['evaluated']}; "
             f"ranked by {d['objective']})")
    cols = [("D mm", "hole_mm", "g"), ("d1 mm", "tube_od_mm", "g"),
            ("ID mm", "tube_id_mm", ".3g"), ("d2 mm", "wire_mm", "g"),
            ("Shore", "shore", "g"), ("L mm", "length_mm", "g")]
    cols = [c for c in cols if len({x[c[1]] for x in cands}) > 1 or c[1] in
            ("hole_mm", "tube_od_mm", "wire_mm")
            or (c[1] == "length_mm" and any(x[c[1]] != 116.0 for x in cands))]
    cols += [("P* MPa", "required_pressure_mpa", ".3f")] if reach else []
    cols += [("T(pmax) Nm", "torque_at_pmax_nm", ".1f"), ("dev %", "deviation_pct", ".1f")]
    # the sizes are the design's name: a numbered row, no name column to wrap (80 columns)
    t = narrow_table(title, ["#", *(label for label, _, _ in cols), "ok"])
    for i, c in enumerate(cands, start=1):
        t.add_row(str(i), *(format(c[k], f) for _, k, f in cols),
                  "yes" if c["in_validated_region"] else "[red]NO[/red]")
    console.print(t)
    console.print("P*: least pressure reaching the target; T(pmax): torque at the highest "
                  "allowed pressure; ok: inside the validated deviation (paper: 20 %)."
                  if reach else "T(pmax): torque at the highest allowed pressure; ok: inside "
                  "the validated deviation (paper: 20 %).")
    if not reach:
        console.print(f"no design reaches {d['target_torque_nm']:g} Nm by {d['pmax_mpa']:g} MPa")
    elif not d["best"]["in_validated_region"]:
        bv = d["best_validated"]
        console.print("[yellow]the best design is outside the validated region: its friction "
                      "prediction is an extrapolation[/yellow]; best validated: "
                      + (bv["name"] if bv else "none"))
    if "surrogate" in d:
        s = d["surrogate"]
        loo = s["loo_error_pct"]
        console.print(f"surrogate: {s['trained_designs']} designs, leave-one-out error max "
                      f"{loo['max']:.2g} % (median {loo['median']:.2g} %) of N(pmax); "
                      f"{s['candidates']} candidates in {s['predict_time_s']:.2f} s, "
                      f"{len(s['confirmed'])} confirmed by FE in {s['confirm_time_s']:.2f} s")
        b = s["best"]
        if b is None:
            console.print("surrogate search: no confirmed design reaches the target")
        else:
            console.print(f"surrogate best (FE-confirmed): D {b['hole_mm']:g}, d1 "
                          f"{b['tube_od_mm']:g}, ID {b['tube_id_mm']:.3g}, d2 {b['wire_mm']:g} "
                          f"mm, Shore {b['shore']:g}: P* {b['required_pressure_mpa']:.3f} MPa")
    if "plot" in d:
        console.print(f"wrote {d['plot']}")
