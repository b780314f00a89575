"""``exofric paper``: print the paper's reported numbers with provenance."""

from __future__ import annotations

import typer

from exofric.cli._common import JSON_OPTION, console, emit, narrow_table


def register(app: typer.Typer) -> None:
    """Add the ``paper`` command to ``app``."""

    @app.command("paper")
    def paper_cmd(as_json: bool = JSON_OPTION) -> None:
        """The numbers printed in Ma et al. 2021 (tables, scalars, Eq 8), with provenance."""
        from exofric import paper

        data = paper.to_dict()

        def render() -> None:
            raw = paper.load()["scalars"]
            t = narrow_table("Ma et al. 2021: reported scalars", ["quantity", "value", "unit",
                                                                    "where"])
            t.columns[0].no_wrap = True    # a key is one word: never split over two lines
            t.columns[3].justify = "left"
            for k, v in raw.items():
                t.add_row(k, f"{v['value']:g}", v["unit"], v["provenance"])
            console.print(t)
            t1 = paper.table1()
            t = narrow_table("Table 1: tube outer diameter (mm) vs pressure (MPa), OD "
                             f"{t1['tube_od_mm']:g} mm",
                             ["", *[f"{p:g} MPa" for p in t1["pressure_mpa"]], "avg err %"])
            t.add_row("test", *[f"{x:g}" for x in t1["test_outer_diameter_mm"]], "")
            for sh, row, err in zip(t1["simulated_shore"], t1["simulated_outer_diameter_mm"],
                                    t1["average_error_pct"], strict=True):
                t.add_row(f"ANSYS Shore {sh:g}", *[f"{x:g}" for x in row], f"{err:g}")
            console.print(t)
            t2 = paper.table2()
            t = narrow_table("Table 2 as printed (C10 slip: notes M1)",
                             ["quantity", "value", "unit"])
            for k, v in t2.items():
                unit = "1/MPa" if k.endswith("_per_mpa") else "MPa" if k.endswith("_mpa") else \
                    "Shore A" if k == "shore" else ""
                t.add_row(k.removesuffix("_per_mpa").removesuffix("_mpa"), f"{v:g}", unit)
            console.print(t)
            t4 = paper.table4()
            errs = paper.load()["max_relative_error"]
            err_of = dict(zip(errs["test"], errs["max_relative_error_pct"], strict=True))
            t = narrow_table("Tables 3-4 and Figs 8-10: the test structures",
                             ["test", "group", "D/d1/d2 mm", "dev %", "max err %", "ANOVA p"])
            for r in paper.table3():
                k = r["test"]
                dev = r["max_relative_deviation_pct"]
                t.add_row(str(k), r["group"], f"{r['hole_mm']:g}/{r['tube_od_mm']:g}/"
                          f"{r['wire_mm']:g}", "-" if dev is None else f"{dev:g}",
                          f"{err_of[k]:g}" if k in err_of else "-",
                          f"{t4[k]:g}" if k in t4 else "-")
            console.print(t)
            console.print("dev %: Table 3's maximum relative deviation; max err %: the largest "
                          "relative prediction error read from Figs 8-10; ANOVA p: Table 4.")
            c = paper.eq8()
            console.print(
                f"Eq 8: N = {c[0]:g} P^3 + {c[1]:g} P^2 + {c[2]:g} P + {c[3]:g}  (N, MPa)"
            )

        emit(data, as_json, render)
