"""``exofric calibrate``: Shore hardness (and tube ID) from an inflation test (paper §3.3), or,
with a hyperelastic ``--model``, a joint material calibration from inflation, tensile and ring
tests and a Shore prior (:func:`exofric.calibration.calibrate_material`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, ClassVar

import typer

from exofric.cli._common import (
    console,
    emit,
    kv_table,
    narrow_table,
    parse_floats,
    plot_path,
    save_figure,
)
from exofric.cli._options import OptionGroup, OutputOptions, TensileSpecimenOptions, grouped


class _TensileFiles(OptionGroup):
    """The tensile tests of the joint calibration: uniaxial, equibiaxial, planar CSVs."""

    tensile: Path | None
    tensile_biaxial: Path | None
    tensile_planar: Path | None
    OPTIONS: ClassVar[dict[str, Any]] = {
        "tensile": typer.Option(
            None, "--tensile", help="Uniaxial test CSV: stretch (or strain) and stress_mpa "
            "(joint calibration).",
        ),
        "tensile_biaxial": typer.Option(
            None, "--tensile-biaxial", help="Equibiaxial test CSV (same columns)."
        ),
        "tensile_planar": typer.Option(
            None, "--tensile-planar", help="Planar (pure shear) test CSV (same columns)."
        ),
    }


#: calibrate's wording of the tensile specimen group
_SPECIMEN = TensileSpecimenOptions.options(
    stress_kind=typer.Option(
        None, "--stress-kind", help="engineering or true stress in the tensile CSVs; wins "
        "over a file's '# stress_kind:' line (default engineering).",
    ),
    strain_kind=typer.Option(
        None, "--strain-kind", help="engineering or true strain in the tensile CSVs "
        "(as exofric material --fit reads them)."),
    gauge_length_mm=typer.Option(
        None, "--gauge-length", help="Tensile specimen gauge length (mm), for an "
        "extension column."),
    area_mm2=typer.Option(
        None, "--area", help="Tensile specimen cross-section (mm^2), for a load column."),
    width_mm=typer.Option(
        None, "--width", help="Tensile specimen width (mm; area = width x thickness)."),
    thickness_mm=typer.Option(
        None, "--thickness", help="Tensile specimen thickness (mm)."),
)


class _Ring(OptionGroup):
    """The ring test of the joint calibration: its CSV, width and pin (mm), FE section."""

    ring: Path | None
    ring_width: float | None
    pin: float | None
    ring_section: str | None
    OPTIONS: ClassVar[dict[str, Any]] = {
        "ring": typer.Option(
            None, "--ring", help="Ring test CSV: displacement_mm,force_n (mm, N), a ring cut "
            "from the tube pulled over two pins (sizes from --ring-width and --pin, or from "
            "'# width_mm: 5' and '# pin_mm: 3' lines in the file; '# ring_od_mm:' and "
            "'# ring_id_mm:' for a ring not of the tube's own sizes).",
        ),
        "ring_width": typer.Option(
            None, "--ring-width", help="Ring width, its axial length (mm)."
        ),
        "pin": typer.Option(None, "--pin", help="Pin diameter of the ring test (mm)."),
        "ring_section": typer.Option(
            None, "--ring-section", help="Ring FE section: plane-stress (default), "
            "generalised-plane-strain or plane-strain (docs/ring-test.md).",
        ),
    }


class _Weights(OptionGroup):
    """The joint calibration's Shore prior (Shore A) and the noise levels (fractions) that
    weight the data sets."""

    shore_prior: float | None
    shore_sd: float | None
    inflation_noise_rel: float | None
    tensile_noise_rel: float | None
    ring_noise_rel: float | None
    OPTIONS: ClassVar[dict[str, Any]] = {
        "shore_prior": typer.Option(
            None, "--shore-prior", help="Shore A hardness as a prior on the shear modulus, "
            "mu = E(Shore)/3 (joint calibration).",
        ),
        "shore_sd": typer.Option(
            None, "--shore-sd", help="Uncertainty of --shore-prior (Shore A; default 2.5)."
        ),
        "inflation_noise_rel": typer.Option(
            None, "--inflation-noise", help="Noise level of the outer diameters (fraction, "
            "default 0.005); any noise option makes the standard errors use the noise levels.",
        ),
        "tensile_noise_rel": typer.Option(
            None, "--tensile-noise", help="Noise level of the stresses (fraction of the "
            "largest, default 0.02).",
        ),
        "ring_noise_rel": typer.Option(
            None, "--ring-noise", help="Noise level of the ring forces (fraction of the "
            "largest, default 0.02).",
        ),
    }


class _ShoreSearch(OptionGroup):
    """The Shore calibration's search: method, Shore A bracket and stop (%)."""

    method: str | None
    bracket: str
    tol_pct: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "method": typer.Option(
            None, "--method", help="bisection (paper), bounded, joint or known-hardness "
            "(default: known-hardness with a shore column, joint with --fit-tube-id, else "
            "bisection).",
        ),
        "bracket": typer.Option("60,70", "--bracket", help="Shore A bracket lo,hi."),
        "tol_pct": typer.Option(
            0.5, "--tol-pct", help="Bisection stop: average relative diameter error (%)."
        ),
    }


@grouped
def calibrate_cmd(
    data: Path | None = typer.Option(
        None, "--data", help="Inflation CSV with pressure_mpa,outer_diameter_mm[,shore] "
        "(MPa, mm); with a shore column only the tube ID is fitted (known hardness). "
        "Optional with a hyperelastic --model when --tensile or --ring is given.",
    ),
    tube_od: float | None = typer.Option(
        None, "--tube-od", help="Undeformed tube outer diameter (mm); required with "
        "inflation or ring data (a hyperelastic --model also reads it from a "
        "'# tube_od_mm:' line of the inflation CSV or '# ring_od_mm:' of the ring CSV)."
    ),
    tube_id: float | None = typer.Option(
        None, "--tube-id", help="Tube inner diameter (mm): fixed for bisection/bounded, "
        "start value for joint/known hardness; with a hyperelastic --model fixed unless "
        "--fit-tube-id (then the start; without --tube-id the ID is fitted).",
    ),
    fit_tube_id: bool = typer.Option(
        False, "--fit-tube-id", help="Fit the tube inner diameter too (method joint)."
    ),
    search: _ShoreSearch = _ShoreSearch.options(),
    model: str = typer.Option(
        "fe", "--model", help="Shore calibration's forward model: fe (2D FE), 1d (radial "
        "BVP) or paper-table1 (the paper's ANSYS columns, no simulation); or a hyperelastic "
        "model for the joint material calibration: neo-hookean, mooney-rivlin, yeoh, "
        "ogden1, ogden2, ogden3.",
    ),
    ends: str = typer.Option(
        "plane-strain", "--ends", help="Tube ends of the inflation FE: plane-strain, "
        "closed or open (closed/open need the fe or a hyperelastic model).",
    ),
    tensile_files: _TensileFiles = _TensileFiles.options(),
    specimen: TensileSpecimenOptions = _SPECIMEN,
    ring_test: _Ring = _Ring.options(),
    weights: _Weights = _Weights.options(),
    allow_unstable: bool = typer.Option(
        False, "--allow-unstable", help="Accept a Drucker-unstable fitted model (joint "
        "calibration; a note instead of an error).",
    ),
    c10_convention: str = typer.Option(
        "eq4", "--c10-convention", help="eq4 (C10 = G/2/1.05) or paper-slip (the printed "
        "Table 2 value C10 = G/2/1.005).",
    ),
    correlation: str = typer.Option(
        "paper", "--correlation", help="Shore -> E0 correlation: paper (Eq 3), gent, qi, "
        "astm-log10.",
    ),
    output: OutputOptions = OutputOptions.options(plot=(Path | None, typer.Option(
        None, "--plot", help="Write Fig 5b (diameter vs pressure with trial curves) here."
    ))),
) -> None:
    """Identify Shore A hardness (and tube ID, mm) from inflation data, or calibrate a
    hyperelastic model jointly from inflation, tensile and ring tests. MPa, mm, N, %."""
    import numpy as np

    from exofric.calibration import MODEL_KINDS, InflationData, calibrate
    from exofric.errors import InputError
    from exofric.io import read_inflation_table
    from exofric.material import HYPERELASTIC_MODELS

    plot = None if output.plot is None else plot_path(output.plot)
    as_json = output.as_json
    method, bracket, tol_pct = search.method, search.bracket, search.tol_pct
    joint_opts = {**tensile_files.to_dict(), **specimen.to_dict(), **ring_test.to_dict(),
                  **weights.to_dict()}
    if model in HYPERELASTIC_MODELS:
        if method is not None or bracket != "60,70" or tol_pct != 0.5 \
                or c10_convention != "eq4":
            name = ("method" if method is not None else "bracket" if bracket != "60,70"
                    else "tol_pct" if tol_pct != 0.5 else "c10_convention")
            raise InputError(f"{name} applies to the Shore calibration (model "
                             f"{', '.join(MODEL_KINDS)}), not to a hyperelastic model",
                             param=name)
        _joint(model, data, tube_od, tube_id, fit_tube_id, ends, correlation,
               allow_unstable, plot, as_json, joint_opts)
        return
    if model not in MODEL_KINDS:
        raise InputError(f"model must be one of {', '.join(MODEL_KINDS)} (Shore calibration) "
                         f"or {', '.join(HYPERELASTIC_MODELS)} (joint material "
                         f"calibration), got {model!r}", param="model")
    given = [k for k, v in joint_opts.items() if v is not None]
    if given or allow_unstable:
        name = given[0] if given else "allow_unstable"
        raise InputError(f"{name} applies to the joint material calibration: give a "
                         f"hyperelastic model ({', '.join(HYPERELASTIC_MODELS)})",
                         param=name)
    if data is None:
        raise InputError("data is required (an inflation CSV) for the Shore calibration",
                         param="data")
    if tube_od is None:
        raise InputError("tube_od_mm is required (mm)", param="tube_od_mm")
    lohi = parse_floats("--bracket", bracket)
    if len(lohi) != 2:
        raise InputError(f"--bracket must be two Shore A values lo,hi, got {bracket!r}")
    if c10_convention not in ("eq4", "paper-slip"):
        raise InputError(f"--c10-convention must be eq4 or paper-slip, got {c10_convention!r}")
    frame = read_inflation_table(data)
    d = InflationData.from_frame(frame)
    from exofric import paper

    paper_data = bool(np.array_equal(
        frame["outer_diameter_mm"].to_numpy(float),
        np.asarray(paper.table1()["test_outer_diameter_mm"], float)))
    res = calibrate(
        d, tube_od, tube_id_mm=tube_id, method=method, fit_tube_id=fit_tube_id,
        bracket=(lohi[0], lohi[1]), tol_pct=tol_pct, model=model, correlation=correlation,
        c10_convention=c10_convention,  # type: ignore[arg-type]
        ends=ends,
    )
    out = res.to_dict()
    if paper_data:
        t1 = paper.table1()
        out["paper_table1_average_error_pct"] = dict(
            zip((f"{x:g}" for x in t1["simulated_shore"]), t1["average_error_pct"],
                strict=True))
    if plot is not None:
        out["plot_path"] = str(save_figure(res.plot(), plot))

    def render() -> None:
        def pm(v: float | None, se: float | None, fmt: str) -> str:
            if v is None:
                return "known"
            return format(v, fmt) + ("" if se is None else f" ± {se:{fmt}}")

        rows = [
            ("method / model", f"{res.method} / {res.model}", ""),
            ("Shore A hardness", pm(res.shore, res.shore_stderr, ".3f"), "Shore A"),
            ("tube inner diameter", pm(res.tube_id_mm, res.tube_id_stderr_mm, ".4f"), "mm"),
            ("average error", f"{res.average_error_pct:.3f}", "%"),
            ("max error", f"{res.max_error_pct:.3f}", "%"),
            ("status", res.status, ""),
            ("model evaluations", str(res.n_model_calls), f"in {res.elapsed_s:.2f} s"),
        ]
        if res.correlation is not None:
            rows.append(("correlation(Shore, ID)", f"{res.correlation:.4f}", ""))
        if res.material is not None:
            m = res.material
            rows.append(("C10 / C01 / d",
                         f"{m.c10_mpa:.5f} / {m.c01_mpa:.6f} / {m.d_per_mpa:.6f}",
                         "MPa / MPa / 1/MPa"))
        console.print(kv_table("Calibration from inflation test", rows))
        t1 = paper.table1()
        printed = dict(zip(t1["simulated_shore"], t1["average_error_pct"], strict=True))
        beside = paper_data and abs(res.tube_od_mm - t1["tube_od_mm"]) < 1e-9
        cols = ["trial", "Shore A", "ID mm", "avg err %"] + (["Table 1 %"] if beside else [])
        h = narrow_table("History: every trial, in order", cols)
        for i, tr in enumerate(res.history):
            row = [str(i + 1), "-" if tr.shore is None else f"{tr.shore:.4g}",
                   f"{tr.tube_id_mm:.4f}", f"{tr.average_error_pct:.3f}"]
            if beside:
                row.append(f"{printed[tr.shore]:g}" if tr.shore in printed else "")
            h.add_row(*row)
        console.print(h)
        if beside:
            console.print("Table 1 %: the paper's ANSYS average error at that Shore value "
                          "(its ID is not printed: docs/paper-notes.md)")
        for note in res.notes:
            console.print(f"note: {note}")
        if plot is not None:
            console.print(f"plot: {out['plot_path']}")

    emit(out, as_json, render)


def register(app: typer.Typer) -> None:
    """Add the ``calibrate`` command to ``app``."""
    app.command("calibrate")(calibrate_cmd)


def _joint(model: str, data: Path | None, tube_od: float | None, tube_id: float | None,
           fit_tube_id: bool, ends: str, correlation: str, allow_unstable: bool,
           plot: Path | None, as_json: bool, opts: dict[str, Any]) -> None:
    """The joint material calibration: read the files, fit, print a table or JSON."""
    from exofric.calibration import InflationData, RingTest, calibrate_material
    from exofric.errors import InputError
    from exofric.io import (
        RING_HEADER_KEYS,
        read_header_sizes,
        read_inflation_table,
        read_ring_test,
        read_stress_stretch,
    )

    if data is None and opts["ring"] is None and all(
            opts[k] is None for k in ("tensile", "tensile_biaxial", "tensile_planar")):
        raise InputError("data: the joint calibration needs at least one dataset: an inflation "
                         "CSV (--data), a tensile CSV (--tensile...) or a ring CSV (--ring)",
                         param="data")
    sk = opts["stress_kind"]
    if sk is not None and sk not in ("engineering", "true"):
        raise InputError(f"stress_kind must be engineering or true, got {sk!r}",
                         param="stress_kind")
    if opts["shore_sd"] is not None and opts["shore_prior"] is None:
        raise InputError("shore_sd applies only with --shore-prior (Shore A)", param="shore_sd")
    if opts["ring"] is None:
        for k in ("ring_width", "pin", "ring_section", "ring_noise_rel"):
            if opts[k] is not None:
                raise InputError(f"{k} applies only with ring (a ring test CSV)", param=k)
    sources: dict[str, str] = {}
    inflation = None
    if data is not None:
        frame = read_inflation_table(data)
        if tube_od is None:  # the file may state it: '# tube_od_mm: 8.3'
            tube_od = read_header_sizes(data, ("tube_od_mm",)).get("tube_od_mm")
        inflation = InflationData.from_frame(frame)
        if inflation.shore is not None:
            raise InputError(f"data: {Path(data).name} has a shore column; give the hardness "
                             "as --shore-prior for the joint calibration", param="data")
        sources["inflation"] = str(data)
    tens: dict[str, tuple[Any, Any]] = {}
    kinds: dict[str, str] = {}
    for mode, key in (("uniaxial", "tensile"), ("biaxial", "tensile_biaxial"),
                      ("planar", "tensile_planar")):
        path = opts[key]
        if path is None:
            continue
        if not str(path).strip():
            raise InputError(f"{key} must name a CSV file, got ''", param=key)
        df = read_stress_stretch(path, sk, **{k: opts[k] for k in (
            "strain_kind", "gauge_length_mm", "area_mm2", "width_mm", "thickness_mm")})
        tens[mode] = (df["stretch"].to_numpy(), df["stress_mpa"].to_numpy())
        kinds[mode] = df.attrs["stress_kind"]
        sources[mode] = str(path)
    ring = None
    if opts["ring"] is not None:
        # the ring file may state its sizes ('# width_mm: 5', '# pin_mm: 3', '# ring_od_mm:',
        # '# ring_id_mm:'); the options override them
        sizes = read_header_sizes(opts["ring"], RING_HEADER_KEYS)
        name = Path(opts["ring"]).name
        for k, key in (("ring_width", "width_mm"), ("pin", "pin_mm")):
            if opts[k] is None:
                if key not in sizes:
                    raise InputError(f"{k}_mm is required with ring (mm): --{k.replace('_', '-')}"
                                     f", or a comment line '{key}: ...' (after '#') at the top "
                                     f"of {name}", param=f"{k}_mm")
                opts[k] = sizes[key]
        if tube_od is None and "ring_od_mm" in sizes:
            tube_od = sizes["ring_od_mm"]  # a ring cut from the tube
        d, f = read_ring_test(opts["ring"])
        ring = RingTest(d, f, ring_width_mm=opts["ring_width"], pin_mm=opts["pin"],
                        ring_od_mm=sizes.get("ring_od_mm"), ring_id_mm=sizes.get("ring_id_mm"),
                        section=opts["ring_section"] or "plane-stress")
        sources["ring"] = str(opts["ring"])
    fit_id = tube_id is None or fit_tube_id
    res = calibrate_material(
        model, inflation=inflation, tube_od_mm=tube_od, tube_id_mm=tube_id, fit_tube_id=fit_id,
        tensile=tens or None, stress_kind=kinds or "engineering", ring=ring,
        shore_prior=opts["shore_prior"],
        shore_sd=opts["shore_sd"] if opts["shore_sd"] is not None else 2.5,
        correlation=correlation, ends=ends, inflation_noise_rel=opts["inflation_noise_rel"],
        tensile_noise_rel=opts["tensile_noise_rel"], ring_noise_rel=opts["ring_noise_rel"],
        allow_unstable=allow_unstable)
    out = res.to_dict()
    out["data_sources"] = sources
    if plot is not None:
        out["plot_path"] = str(save_figure(res.plot(), plot))

    def render() -> None:
        rows: list[tuple[str, str, str]] = [("model", res.model.name, "")]
        se = dict(zip(res.names, res.stderr, strict=True))
        for n, v in zip(res.model.param_names, res.model.params, strict=True):
            unit = "MPa" if n.endswith("_mpa") else "unitless"
            rows.append((n, f"{v:.6g} ± {se[n]:.3g}", unit))
        rows.append(("shear modulus mu", f"{res.model.shear_modulus_mpa:.6g} ± "
                     f"{res.shear_modulus_stderr_mpa:.3g}", "MPa"))
        rows.append(("d", f"{res.model.d_per_mpa:.6g}", "1/MPa"))
        if res.tube_id_mm is not None:
            tid = (f"{res.tube_id_mm:.4f} ± {res.tube_id_stderr_mm:.4f}" if res.tube_id_fitted
                   else f"{res.tube_id_mm:.4f} (given)")
            rows.append(("tube inner diameter", tid, "mm"))
        rows.append(("standard errors from", res.stderr_from, ""))
        rows.append(("model evaluations", str(res.n_model_evaluations),
                     f"in {res.elapsed_s:.2f} s"))
        console.print(kv_table(f"Joint material calibration ({res.model.name}, {res.ends})",
                               rows))
        t = narrow_table("Per dataset", ["dataset", "points", "RMS", "unit", "RMS %",
                                         "chi^2"])
        for k, dsf in res.datasets.items():
            dd = dsf.to_dict()
            t.add_row(k, str(dsf.n_points), f"{dsf.rms:.4g}", dsf.unit, f"{dsf.rms_pct:.3g}",
                      f"{dd['chi2']:.3g}")
        console.print(t)
        ident = res.identifiability
        worst = ", ".join(f"{c:+.3f} {n}" for n, c in zip(ident.names, ident.worst_direction,
                                                          strict=True))
        irows = [("identifiable", "yes" if ident.identifiable else "NO", ""),
                 ("condition number", f"{ident.condition_number:.3g}", "")]
        if ident.max_correlation_pair:
            irows.append((f"correlation({', '.join(ident.max_correlation_pair)})",
                          f"{ident.max_correlation:.4f}", ""))
        irows.append(("worst direction", worst, "relative"))
        irows.append(("its standard deviation", f"{100 * ident.worst_sd_rel:.3g}", "%"))
        if ident.profile is not None:
            irows.append(("profile delta chi^2 at the ends",
                          f"{ident.profile.delta_chi2[0]:.3g} / "
                          f"{ident.profile.delta_chi2[-1]:.3g}",
                          f"at ±{100 * ident.profile.step_rel[-1]:.3g} %"))
        console.print(kv_table("Identifiability", irows))
        for note in res.notes:
            console.print(f"note: {note}")
        if plot is not None:
            console.print(f"plot: {out['plot_path']}")

    emit(out, as_json, render)
