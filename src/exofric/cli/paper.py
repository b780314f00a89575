"""``exofric paper``: print the paper's reported numbers with provenance."""

from __future__ import annotations

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table


def register(app: typer.Typer) -> None:
    """Add the ``paper`` command to ``app``."""

    @app.command("paper")
    def paper_cmd(as_json: bool = JSON_OPTION) -> None:
        """The numbers printed in Ma et al. 2021 (tables, scalars, Eq 8), with provenance."""
        from exofric import paper

        data = paper.to_dict()

        def render() -> None:
            raw = paper.load()["scalars"]
            console.print(
                kv_table(
                    "Ma et al. 2021: reported scalars",
                    [
                        (k, f"{v['value']:g}", v["unit"] + f"  [{v['provenance']}]")
                        for k, v in raw.items()
                    ],
                )
            )
            t2 = paper.table2()
            console.print(
                kv_table("Table 2 (as printed)", [(k, f"{v:g}", "") for k, v in t2.items()])
            )
            rows = [
                (
                    f"test {r['test']} ({r['group']})",
                    f"D={r['hole_mm']:g} d1={r['tube_od_mm']:g} d2={r['wire_mm']:g}",
                    "mm; max dev "
                    + (
                        f"{r['max_relative_deviation_pct']:g}%"
                        if r["max_relative_deviation_pct"] is not None
                        else "-"
                    ),
                )
                for r in paper.table3()
            ]
            console.print(kv_table("Table 3", rows))
            console.print(
                kv_table(
                    "Table 4 (ANOVA p)",
                    [(f"test {k}", f"{v:g}", "") for k, v in paper.table4().items()],
                )
            )
            c = paper.eq8()
            console.print(
                f"Eq 8: N = {c[0]:g} P^3 + {c[1]:g} P^2 + {c[2]:g} P + {c[3]:g}  (N, MPa)"
            )

        emit(data, as_json, render)
