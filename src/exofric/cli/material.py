"""``exofric material``: Shore A hardness to Mooney-Rivlin constants (Eqs 3-6), or a
hyperelastic model fitted to test data (``--fit``, ``--treloar``)."""

from __future__ import annotations

from typing import Any

import typer

from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    kv_table,
    narrow_table,
    plot_path,
    save_figure,
)


def register(app: typer.Typer) -> None:
    """Add the ``material`` command to ``app``."""

    @app.command("material")
    def material(
        shore: float | None = typer.Option(
            None, help="Shore A hardness, in (0, 100) (Mooney-Rivlin by Eqs 3-6)."),
        correlation: str = typer.Option(
            "paper", help="Shore -> E0 correlation: paper (Eq 3), gent, qi, astm-log10."
        ),
        c01_ratio: float = typer.Option(0.05, help="C01/C10 ratio (Eq 5), in [0, 1]."),
        poisson: float = typer.Option(0.498, help="Poisson's ratio nu (Eq 6), in (0, 0.5)."),
        model: str | None = typer.Option(
            None, help="With --fit/--treloar: neo-hookean, mooney-rivlin, yeoh, ogden1, ogden2, "
            "ogden3."),
        fit: str | None = typer.Option(
            None, help="Uniaxial test CSV: stretch (or strain) and stress_mpa columns."),
        fit_biaxial: str | None = typer.Option(None, help="Equibiaxial test CSV (same columns)."),
        fit_planar: str | None = typer.Option(
            None, help="Planar (pure shear) test CSV (same columns)."),
        treloar: bool = typer.Option(
            False, "--treloar", help="Fit Treloar's 1944 natural rubber data (all three modes)."),
        stress_kind: str | None = typer.Option(
            None, help="engineering or true stress in the CSVs; wins over a file's "
            "'# stress_kind:' line (default engineering)."),
        residuals: str = typer.Option(
            "absolute", help="absolute (MPa) or relative residuals in the least squares."),
        allow_unstable: bool = typer.Option(
            False, "--allow-unstable",
            help="Accept a fit that is Drucker-unstable in the data's range (warns)."),
        plot: str | None = typer.Option(None, help="Write the fit figure here (.png/.svg/.pdf)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Mooney-Rivlin constants from Shore A hardness (paper Eqs 3-6), or a hyperelastic
        model fitted to uniaxial/biaxial/planar test data (--fit, --treloar). MPa, 1/MPa."""
        from exofric.errors import InputError
        from exofric.material import MooneyRivlin

        fitting = treloar or any(f is not None for f in (fit, fit_biaxial, fit_planar))
        if fitting:
            if shore is not None:
                raise InputError("shore gives Mooney-Rivlin by Eqs 3-6; it does not combine "
                                 "with fit or treloar", param="shore")
            _fit_command(model, fit, fit_biaxial, fit_planar, treloar, stress_kind, residuals,
                         allow_unstable, plot, as_json)
            return
        for name, value in (("model", model), ("stress_kind", stress_kind), ("plot", plot)):
            if value is not None:
                raise InputError(f"{name} applies only with fit, fit_biaxial, fit_planar or "
                                 "treloar", param=name)
        if allow_unstable or residuals != "absolute":
            raise InputError("residuals and allow_unstable apply only with fit or treloar",
                             param="residuals" if residuals != "absolute" else "allow_unstable")
        if shore is None:
            raise InputError("shore is required (Shore A, in (0, 100)), or fit a model to test "
                             "data with fit / treloar", param="shore")

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


def _fit_command(model: str | None, fit: str | None, fit_biaxial: str | None,
                 fit_planar: str | None, treloar: bool, stress_kind: str | None,
                 residuals: str, allow_unstable: bool, plot: str | None, as_json: bool) -> None:
    """``--fit`` / ``--treloar``: least-squares fit, JSON or a table, optional figure."""
    from exofric.errors import InputError
    from exofric.material import HYPERELASTIC_MODELS, TRELOAR_SOURCE, fit_material, treloar_1944

    if model is None:
        raise InputError(f"model is required with fit or treloar: one of "
                         f"{', '.join(HYPERELASTIC_MODELS)}", param="model")
    if model not in HYPERELASTIC_MODELS:
        raise InputError(f"model must be one of {', '.join(HYPERELASTIC_MODELS)}, got {model!r}",
                         param="model")
    if stress_kind is not None and stress_kind not in ("engineering", "true"):
        raise InputError(f"stress_kind must be engineering or true, got {stress_kind!r}",
                         param="stress_kind")
    if residuals not in ("absolute", "relative"):
        raise InputError(f"residuals must be absolute or relative, got {residuals!r}",
                         param="residuals")
    out = plot_path(plot) if plot is not None else None
    data: dict[str, Any] = {}
    kinds: dict[str, str] = {}
    sources: dict[str, str] = {}
    if treloar:
        if any(f is not None for f in (fit, fit_biaxial, fit_planar)):
            raise InputError("treloar fits the shipped data; it does not combine with fit, "
                             "fit_biaxial or fit_planar", param="treloar")
        data = dict(treloar_1944())
        kinds = dict.fromkeys(data, "engineering")
        sources = dict.fromkeys(data, "Treloar 1944 (shipped)")
    else:
        from exofric.io import read_stress_stretch

        for mode, opt, path in (("uniaxial", "fit", fit), ("biaxial", "fit_biaxial", fit_biaxial),
                                ("planar", "fit_planar", fit_planar)):
            if path is None:
                continue
            if not str(path).strip():
                raise InputError(f"{opt} must name a CSV file, got ''", param=opt)
            df = read_stress_stretch(path, stress_kind)
            data[mode] = (df["stretch"].to_numpy(), df["stress_mpa"].to_numpy())
            kinds[mode] = df.attrs["stress_kind"]
            sources[mode] = df.attrs["source"]
    res = fit_material(model, **data, stress_kind=kinds, residuals=residuals,
                       allow_unstable=allow_unstable)
    d: dict[str, Any] = res.to_dict()
    for mode, src in sources.items():
        d["modes"][mode]["source"] = src
    if treloar:
        d["data_source"] = TRELOAR_SOURCE
    if out is not None:
        d["plot"] = str(save_figure(res.plot(), out))

    def render() -> None:
        t = narrow_table(f"{model} fitted ({residuals} residuals)",
                         ["parameter", "value", "std. error", "unit"])
        for n, v in d["params"].items():
            t.add_row(n, f"{v:.6g}", f"{d['stderr'][n]:.3g}", d["param_units"][n])
        t.add_row("shear modulus mu", f"{d['shear_modulus_mpa']:.6g}", "", "MPa")
        t.add_row("d", f"{d['d_per_mpa']:.6g}", "", "1/MPa")
        console.print(t)
        m = narrow_table("per mode", ["mode", "points", "stretch", "R^2", "RMS (MPa)"])
        for k, v in d["modes"].items():
            m.add_row(k, str(v["n_points"]), f"{v['stretch_min']:.3g}-{v['stretch_max']:.3g}",
                      f"{v['r2']:.4f}", f"{v['rms_mpa']:.4f}")
        console.print(m)
        st = d["stability"]
        console.print(f"Drucker stability ({st['criterion']}) over stretch "
                      f"{st['stretch_min']:.3g}-{st['stretch_max']:.3g}: "
                      f"{'stable' if st['stable'] else 'UNSTABLE'}")
        if "plot" in d:
            console.print(f"figure: {d['plot']}")

    emit(d, as_json, render)
