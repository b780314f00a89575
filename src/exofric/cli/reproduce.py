"""``exofric reproduce``: the paper's whole study in one command, with an HTML report.

Writes into ``--out`` (default ``./exofric-report``): ``report.html`` (self-contained),
every figure as PNG and ``results.json`` (every number, stage wall times, software
versions). Units: mm, N, MPa, s, Nm.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import typer

from exofric.cli._common import JSON_OPTION, console


def register(app: typer.Typer) -> None:
    """Add the ``reproduce`` command."""

    @app.command("reproduce")
    def reproduce_cmd(
        out: Path = typer.Option(Path("exofric-report"), "--out",
                                 help="Output directory (created)."),
        fast: bool = typer.Option(False, "--fast",
                                  help="Coarse meshes (for CI); default: converged meshes."),
        notes_dir: Path = typer.Option(None, "--notes-dir", help="Directory of "
                                       "paper-notes*.md (default: ./docs or the source tree)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Redo the paper (Tables 1-4, Figs 4-12) and write report.html, PNGs, results.json."""
        import time

        from exofric.errors import InputError
        from exofric.io import jsonable
        from exofric.report import write_report
        from exofric.reproduction import STAGES, ReproduceConfig, reproduce

        if notes_dir is not None and not notes_dir.is_dir():
            raise InputError(f"--notes-dir {notes_dir}: not a directory")
        if out.exists() and not out.is_dir():
            raise InputError(f"--out {out}: exists and is not a directory")
        try:  # fail before the 20 s of computing, not after
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"--out {out}: cannot create the directory ({exc.strerror})") from None
        t0 = time.perf_counter()
        cfg = ReproduceConfig.for_mode(fast)
        if as_json:
            res = reproduce(cfg)
            files = write_report(res, out, notes_dir=notes_dir)
        else:
            from rich.progress import (
                BarColumn,
                Progress,
                SpinnerColumn,
                TextColumn,
                TimeElapsedColumn,
            )

            with Progress(SpinnerColumn(), TextColumn("[progress.description]{task.description}"),
                          BarColumn(), TextColumn("{task.completed}/{task.total}"),
                          TimeElapsedColumn(), console=console, transient=False) as prog:
                task = prog.add_task("exofric reproduce", total=len(STAGES) + 1)

                def on_stage(key: str, title: str, i: int, n: int, done: bool,
                             dt: float | None) -> None:
                    if done:
                        prog.console.print(f"  [green]done[/] {i + 1}/{n} {title} "
                                           f"[dim]({dt:.2f} s)[/]")
                        prog.advance(task)
                    else:
                        prog.update(task, description=f"{i + 1}/{n} {title}")

                res = reproduce(cfg, on_stage=on_stage)
                prog.update(task, description="figures and report.html")
                files = write_report(res, out, notes_dir=notes_dir)
                prog.console.print(f"  [green]done[/] figures and report "
                                   f"[dim]({files.report_time_s:.2f} s)[/]")
                prog.advance(task)
        total = time.perf_counter() - t0
        if as_json:
            d: dict[str, Any] = json.loads(files.results_json.read_text(encoding="utf-8"))
            d["files"] = files.to_dict()
            d["total_wall_time_s"] = total
            print(json.dumps(jsonable(d)))
            return
        _summary(res, files, total)


def _summary(res: Any, files: Any, total: float) -> None:
    from rich.table import Table

    t = Table(title="Paper beside exofric (selection; all rows in the report)",
              show_header=True, header_style="bold")
    for c in ("quantity", "paper", "exofric", "diff. %"):
        t.add_column(c, justify="left" if c == "quantity" else "right")
    picks = ("squeezing force N at 0.6", "gamma from the published", "test 5: N at 0.6",
             "pressure for", "PI: settling-time", "PID: settling-time", "test 3 torque",
             "Shore hardness", "tube inner")
    for _, c in res.comparisons():
        if any(c.quantity.startswith(p) for p in picks):
            d = c.difference_pct
            t.add_row(f"{c.quantity} ({c.unit})" if c.unit else c.quantity,
                      "-" if c.paper_value is None else f"{c.paper_value:.5g}",
                      "-" if c.our_value is None else f"{c.our_value:.5g}",
                      "-" if d is None else f"{d:+.2f}")
    console.print(t)
    console.print(f"stages {res.wall_time_s:.1f} s, report {files.report_time_s:.1f} s, "
                  f"total {total:.1f} s ({'fast' if res.config.fast else 'default'} meshes)")
    console.print(f"report: [bold]{files.report_html}[/]  (figures and results.json in "
                  f"{files.out_dir})")
