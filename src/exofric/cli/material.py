"""``exofric material``: Shore A hardness to Mooney-Rivlin constants (Eqs 3-6), or a
hyperelastic model fitted to test data (``--fit``, ``--treloar``)."""

from __future__ import annotations

from typing import Any

import typer

from exofric import defaults as D
from exofric.cli._common import (
    console,
    emit,
    kv_table,
    narrow_table,
    plot_path,
    save_figure,
)
from exofric.cli._options import OutputOptions, TensileSpecimenOptions, grouped


@grouped
def material(
    shore: float | None = typer.Option(
        None, help="Shore A hardness, in (0, 100) (Mooney-Rivlin by Eqs 3-6)."),
    correlation: str = typer.Option(
        "paper", help="Shore -> E0 correlation: paper (Eq 3), gent, qi, astm-log10."
    ),
    c01_ratio: float = typer.Option(0.05, help="C01/C10 ratio (Eq 5), in [0, 1]."),
    poisson: float = typer.Option(D.POISSON, help="Poisson's ratio nu (Eq 6), in (0, 0.5)."),
    model: str | None = typer.Option(
        None, help="With --fit/--treloar: neo-hookean, mooney-rivlin, yeoh, ogden (with "
        "--terms), ogden1, ogden2, ogden3."),
    terms: int | None = typer.Option(
        None, "--terms", help="Ogden terms with --model ogden: 1, 2 or 3 (default 3)."),
    fit: str | None = typer.Option(
        None, help="Uniaxial test CSV as a machine writes it: stretch, strain (%, true or "
        "engineering) or extension (mm), and stress (MPa, kPa, psi; true or engineering) "
        "or load (N); units read from headers like 'Load (N)'."),
    fit_biaxial: str | None = typer.Option(None, help="Equibiaxial test CSV (same columns)."),
    fit_planar: str | None = typer.Option(
        None, help="Planar (pure shear) test CSV (same columns)."),
    treloar: bool = typer.Option(
        False, "--treloar", help="Fit Treloar's 1944 natural rubber data (all three modes)."),
    specimen: TensileSpecimenOptions = TensileSpecimenOptions.options(),
    columns: str | None = typer.Option(
        None, "--columns", help="Odd headers: role=header pairs, e.g. "
        "'force=Kraft (kN),extension=Weg'; roles stretch, strain, extension, stress, force."),
    stability_range: str | None = typer.Option(
        None, "--stability-range", help="Stretch range lo,hi of the per-mode stability "
        "report (default the data's range + 10 %); unmeasured modes only warn."),
    unconstrained: bool = typer.Option(
        False, "--unconstrained", help="Least squares with bounds only (no stability "
        "constraints); a fit unstable within the data is refused unless --allow-unstable."),
    residuals: str = typer.Option(
        "absolute", help="absolute (MPa) or relative residuals in the least squares."),
    allow_unstable: bool = typer.Option(
        False, "--allow-unstable",
        help="Fit without the stability constraints and accept a fit that is "
        "Drucker-unstable in the data's range (warns)."),
    out: OutputOptions = OutputOptions.options(
        plot=typer.Option(None, help="Write the fit figure here (.png/.svg/.pdf).")),
) -> None:
    """Mooney-Rivlin constants from Shore A hardness (paper Eqs 3-6), or a hyperelastic
    model fitted to uniaxial/biaxial/planar test data (--fit, --treloar). MPa, 1/MPa."""
    from exofric.errors import InputError
    from exofric.material import MooneyRivlin

    plot, as_json, stress_kind = out.plot, out.as_json, specimen.stress_kind
    fitting = treloar or any(f is not None for f in (fit, fit_biaxial, fit_planar))
    if fitting:
        if shore is not None:
            raise InputError("shore gives Mooney-Rivlin by Eqs 3-6; it does not combine "
                             "with --fit or --treloar", param="shore")
        tensile = {**{k: v for k, v in specimen.to_dict().items() if k != "stress_kind"},
                   "columns": columns}
        _fit_command(model, fit, fit_biaxial, fit_planar, treloar, stress_kind, residuals,
                     allow_unstable, plot, as_json, terms=terms, tensile=tensile,
                     stability_range=stability_range, unconstrained=unconstrained)
        return
    for name, value in (("model", model), ("stress_kind", stress_kind), ("plot", plot),
                        ("terms", terms), ("strain_kind", specimen.strain_kind),
                        ("gauge_length_mm", specimen.gauge_length_mm),
                        ("area_mm2", specimen.area_mm2), ("width_mm", specimen.width_mm),
                        ("thickness_mm", specimen.thickness_mm),
                        ("columns", columns), ("stability_range", stability_range)):
        if value is not None:
            raise InputError(f"{name} applies only with --fit, --fit-biaxial, --fit-planar or "
                             "--treloar", param=name)
    if allow_unstable or unconstrained or residuals != "absolute":
        which = ("residuals" if residuals != "absolute" else
                 "allow_unstable" if allow_unstable else "unconstrained")
        raise InputError(f"{which} applies only with --fit or --treloar", param=which)
    if shore is None:
        raise InputError("shore is required (Shore A, in (0, 100)), or fit a model to test "
                         "data with --fit / --treloar", param="shore")

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


def register(app: typer.Typer) -> None:
    """Add the ``material`` command to ``app``."""
    app.command("material")(material)


def _paper_table2(shore: float, correlation: str, c01_ratio: float,
                  poisson: float) -> dict[str, float]:
    """Table 2's printed constants when the inputs are the paper's (else {})."""
    from exofric import paper

    t2 = paper.table2()
    if (abs(shore - t2["shore"]) > 1e-9 or correlation != "paper" or abs(c01_ratio - 0.05) > 1e-12
            or abs(poisson - t2["poisson"]) > 1e-12):
        return {}
    return {k: float(v) for k, v in t2.items() if k.endswith(("_mpa", "_per_mpa"))}


def _column_map(text: str) -> dict[str, str]:
    """``"force=Kraft (kN),extension=Weg"`` -> ``{"force": "Kraft (kN)", "extension": "Weg"}``."""
    from exofric.errors import InputError

    out: dict[str, str] = {}
    for part in text.split(","):
        if not part.strip():
            continue
        role, sep, header = part.partition("=")
        if not sep or not role.strip() or not header.strip():
            raise InputError(f"columns must be role=header pairs separated by commas, got "
                             f"{part.strip()!r}", param="columns")
        out[role.strip().lower()] = header.strip()
    if not out:
        raise InputError("columns must list at least one role=header pair", param="columns")
    return out


def _fit_command(model: str | None, fit: str | None, fit_biaxial: str | None,
                 fit_planar: str | None, treloar: bool, stress_kind: str | None,
                 residuals: str, allow_unstable: bool, plot: str | None, as_json: bool, *,
                 terms: int | None = None, tensile: dict[str, Any] | None = None,
                 stability_range: str | None = None, unconstrained: bool = False) -> None:
    """``--fit`` / ``--treloar``: least-squares fit, JSON or a table, optional figure."""
    from exofric.cli._common import parse_floats
    from exofric.errors import InputError
    from exofric.material import HYPERELASTIC_MODELS, TRELOAR_SOURCE, fit_material, treloar_1944

    names = (*HYPERELASTIC_MODELS, "ogden")
    if model is None:
        raise InputError(f"model is required with --fit or --treloar: one of {', '.join(names)}",
                         param="model")
    if model not in names:
        raise InputError(f"model must be one of {', '.join(names)}, got {model!r}",
                         param="model")
    if stress_kind is not None and stress_kind not in ("engineering", "true"):
        raise InputError(f"stress_kind must be engineering or true, got {stress_kind!r}",
                         param="stress_kind")
    if residuals not in ("absolute", "relative"):
        raise InputError(f"residuals must be absolute or relative, got {residuals!r}",
                         param="residuals")
    srange = None
    if stability_range is not None:
        vals = parse_floats("stability_range", stability_range)
        if len(vals) != 2:
            raise InputError(f"stability_range must be two stretches lo,hi, got "
                             f"{stability_range!r}", param="stability_range")
        srange = (vals[0], vals[1])
    opts = dict(tensile or {})
    if opts.get("columns") is not None:
        opts["columns"] = _column_map(opts["columns"])
    out = plot_path(plot) if plot is not None else None
    data: dict[str, Any] = {}
    kinds: dict[str, str] = {}
    sources: dict[str, str] = {}
    tables: dict[str, dict[str, Any]] = {}
    if treloar:
        if any(f is not None for f in (fit, fit_biaxial, fit_planar)):
            raise InputError("treloar fits the shipped data; it does not combine with --fit, "
                             "--fit-biaxial or --fit-planar", param="treloar")
        for k, v in opts.items():
            if v is not None:
                raise InputError(f"{k} applies to test files (--fit, --fit-biaxial, --fit-planar), "
                                 "not to treloar", param=k)
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
            df = read_stress_stretch(path, stress_kind, **opts)
            data[mode] = (df["stretch"].to_numpy(), df["stress_mpa"].to_numpy())
            kinds[mode] = df.attrs["stress_kind"]
            sources[mode] = df.attrs["source"]
            tables[mode] = {"columns": df.attrs["columns"],
                            "conversion": df.attrs["conversion"],
                            "strain_kind": df.attrs["strain_kind"],
                            "gauge_length_mm": df.attrs["gauge_length_mm"],
                            "area_mm2": df.attrs["area_mm2"]}
    res = fit_material(model, **data, stress_kind=kinds, residuals=residuals,
                       allow_unstable=allow_unstable, terms=terms,
                       constrain=not unconstrained, stability_range=srange)
    d: dict[str, Any] = res.to_dict()
    for mode, src in sources.items():
        d["modes"][mode]["source"] = src
        if mode in tables:
            d["modes"][mode].update({k: v for k, v in tables[mode].items() if k != "columns"})
    d["columns"] = {mode: tab["columns"] for mode, tab in tables.items()}
    if treloar:
        d["data_source"] = TRELOAR_SOURCE
    if out is not None:
        d["plot"] = str(save_figure(res.plot(), out))

    def render() -> None:
        from rich.markup import escape

        for mode, tab in tables.items():
            c = narrow_table(escape(f"{mode}: {sources[mode]}"),
                             ["column", "role", "unit", "used"])
            for col in tab["columns"]:
                c.add_row(escape(col["column"]), (col["role"] or "-") + (
                    f" ({col['kind']})" if col["kind"] else ""),
                          escape(str(col["unit"])), "yes" if col["used"] else "no")
            console.print(c)
            for line in tab["conversion"]:
                console.print(f"  {escape(line)}")
        t = narrow_table(f"{d['model']} fitted ({residuals} residuals"
                         + (", constrained" if d["constrained"] else "") + ")",
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
        s = narrow_table(f"Drucker stability (dP/dl > 0), margin {d['stability_margin_pct']:g} %",
                         ["mode", "measured", "stretch", "stable"])
        for k, v in d["stability_modes"].items():
            s.add_row(k, "yes" if v["measured"] else "no",
                      f"{v['stretch_min']:.3g}-{v['stretch_max']:.3g}",
                      "yes" if v["stable"] else f"NO, from {v['unstable_from']:.3g}")
        console.print(s)
        console.print(f"admissible: {'yes' if d['admissible'] else 'NO'}; constrained: "
                      + (escape("; ".join(d["active_constraints"])) if d["constrained"]
                         else "no"))
        ms = d["multistart"]
        if ms.get("n_starts", 0) > 1:
            unit = "MPa" if residuals == "absolute" else "relative"
            key = "mpa" if residuals == "absolute" else "rel"
            console.print(f"starts: {ms['n_starts']}, RMS best {ms[f'rms_min_{key}']:.4g} / "
                          f"median {ms[f'rms_median_{key}']:.4g} / worst "
                          f"{ms[f'rms_max_{key}']:.4g} {unit}; {ms['n_within_1pct']} within 1 % "
                          "of the best")
        if "plot" in d:
            console.print(f"figure: {d['plot']}")

    emit(d, as_json, render)
