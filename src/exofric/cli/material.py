"""``exofric material``: Shore A hardness to Mooney-Rivlin constants (Eqs 3-6)."""

from __future__ import annotations

from typing import Any

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table, narrow_table


def register(app: typer.Typer) -> None:
    """Add the ``material`` command to ``app``."""

    @app.command("material")
    def material(
        shore: float = typer.Option(..., help="Shore A hardness, in (0, 100)."),
        correlation: str = typer.Option(
            "paper", help="Shore -> E0 correlation: paper (Eq 3), gent, qi, astm-log10."
        ),
        c01_ratio: float = typer.Option(0.05, help="C01/C10 ratio (Eq 5), in [0, 1]."),
        poisson: float = typer.Option(0.498, help="Poisson's ratio nu (Eq 6), in (0, 0.5)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Mooney-Rivlin constants from Shore A hardness (paper Eqs 3-6). MPa, 1/MPa."""
        from exofric.material import MooneyRivlin

        m = MooneyRivlin.from_shore(shore, correlation, c01_ratio=c01_ratio, poisson=poisson)
        d: dict[str, Any] = dict(m.to_dict())
        t2 = _paper_table2(shore, correlation, c01_ratio, poisson)
        if t2:
            d["paper_table2"] = t2

        def render() -> None:
            rows = [("E0 (Eq 3)", "e0_mpa", ".5f", "MPa"),
                    ("G = E0/3 (Eq 4)", "g_mpa", ".5f", "MPa"),
                    ("C10", "c10_mpa", ".5f", "MPa"), ("C01", "c01_mpa", ".6f", "MPa"),
                    ("d (Eq 6)", "d_per_mpa", ".6f", "1/MPa"), ("K = 2/d", "k_mpa", ".2f", "MPa")]
            title = f"Mooney-Rivlin from Shore {shore:g} ({correlation})"
            if not t2:
                console.print(kv_table(title, [(q, f"{d[k]:{f}}", u) for q, k, f, u in rows]))
                return
            t = narrow_table(f"Shore {shore:g} -> Mooney-Rivlin, beside Table 2",
                             ["quantity", "exofric", "Table 2", "unit"])
            for q, k, f, u in rows:
                t.add_row(q, f"{d[k]:{f}}", "-" if k not in t2 else f"{t2[k]:g}", u)
            console.print(t)
            console.print("Table 2 prints C10 = 0.6639 MPa, but its own Eq 4 gives G/2/1.05 = "
                          f"{d['c10_mpa']:.4f} MPa: a /1.005 for /1.05 slip; its C01 and d follow "
                          "the slipped C10 (docs/paper-notes.md, M1). exofric uses Eq 4; "
                          "`--c10 0.6639 --c01 0.0332 --d 0.00575` on the FE commands uses the "
                          "printed values.")

        emit(d, as_json, render)


def _paper_table2(shore: float, correlation: str, c01_ratio: float,
                  poisson: float) -> dict[str, float]:
    """Table 2's printed constants when the inputs are the paper's (else {})."""
    from exofric import paper

    t2 = paper.table2()
    if (abs(shore - t2["shore"]) > 1e-9 or correlation != "paper" or abs(c01_ratio - 0.05) > 1e-12
            or abs(poisson - t2["poisson"]) > 1e-12):
        return {}
    return {k: float(v) for k, v in t2.items() if k.endswith(("_mpa", "_per_mpa"))}
