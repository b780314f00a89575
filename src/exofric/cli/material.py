"""``exofric material``: Shore A hardness to Mooney-Rivlin constants (Eqs 3-6)."""

from __future__ import annotations

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table


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
        d = m.to_dict()

        def render() -> None:
            console.print(
                kv_table(
                    f"Mooney-Rivlin from Shore {shore:g} ({correlation})",
                    [
                        ("E0 (Eq 3)", f"{d['e0_mpa']:.5f}", "MPa"),
                        ("G = E0/3 (Eq 4)", f"{d['g_mpa']:.5f}", "MPa"),
                        ("C10", f"{d['c10_mpa']:.5f}", "MPa"),
                        ("C01", f"{d['c01_mpa']:.6f}", "MPa"),
                        ("d (Eq 6)", f"{d['d_per_mpa']:.6f}", "1/MPa"),
                        ("K = 2/d", f"{d['k_mpa']:.2f}", "MPa"),
                    ],
                )
            )

        emit(d, as_json, render)
