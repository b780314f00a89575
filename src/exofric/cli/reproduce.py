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
                                  help="Coarse meshes (for CI); default: the draft "
                                  "accuracy's squeeze mesh."),
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


#: The rows ``exofric reproduce`` prints: (start of the comparison's quantity, short label).
#: Short labels keep the table readable at 80 columns; all rows are in report.html.
_PICKS = (
    ("tube inner diameter", "tube ID (fitted, not printed)"),
    ("Shore hardness", "Shore (bisection, Table 1)"),
    ("squeezing force N at 0.6", "N at 0.6 MPa, base (Fig 7)"),
    ("gamma from the published", "gamma = 180.49 N / our N(0.6)"),
    ("test 5: N at 0.6", "test 5: N at 0.6 MPa (Eq 8)"),
    ("pressure for 54.4 N from Eq 9", "P for 54.4 N, Eq 9 (Sec 5)"),
    ("pressure for 54.4 N, our FE", "P for 54.4 N, our FE curve"),
    ("PI: settling-time", "PI: settling-time cut (model)"),
    ("PID: settling-time", "PID: settling-time cut (model)"),
    ("test 3 torque", "test 3 torque (Sec 4)"),
)


def _summary(res: Any, files: Any, total: float) -> None:
    from rich import box
    from rich.table import Table

    from exofric.report import comparison_cells

    t = Table(title="Paper beside exofric (selection; all rows in the report)",
              show_header=True, header_style="bold", box=box.SIMPLE_HEAD, pad_edge=False)
    t.add_column("quantity", overflow="fold")
    t.add_column("unit", overflow="fold")
    for head in ("paper", "exofric", "ours - paper"):
        t.add_column(head, justify="right", no_wrap=True)
    rows = [c for _, c in res.comparisons()]
    for prefix, label in _PICKS:
        row = next((c for c in rows if c.quantity.startswith(prefix)), None)
        if row is not None:
            t.add_row(label, row.unit or "-", *comparison_cells(row.to_dict()))
    console.print(t)
    console.print("to the paper's digits; ours - paper in the unit (% of paper), pp = points",
                  style="dim")
    console.print(f"stages {res.wall_time_s:.1f} s, report {files.report_time_s:.1f} s, "
                  f"total {total:.1f} s ({'fast' if res.config.fast else 'default'} meshes)")
    console.print(f"report: [bold]{files.report_html}[/]  (figures and results.json in "
                  f"{files.out_dir})")
