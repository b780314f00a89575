"""``exofric fit-friction | predict | invert | rig``: the friction model (paper Eqs 1, 7-9).

Units: pressure MPa, forces N, torque Nm, arm radius m. Files are read by :mod:`exofric.io`:
squeeze curves (``exofric squeeze --json`` output or a ``pressure_mpa,squeeze_force_n`` CSV),
friction CSVs (``pressure_mpa,friction_n`` with an optional ``test`` column) and structure
TOMLs.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import typer

from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    kv_table,
    narrow_table,
    out_file,
    parse_floats,
    plot_path,
    save_figure,
)

if TYPE_CHECKING:
    import numpy as np

__all__ = ["register"]


def _squeeze_curve(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """(pressure MPa, squeezing force N) of a squeeze curve file (JSON or CSV), sorted."""
    from exofric.io import read_squeeze_curve

    df = read_squeeze_curve(path)
    return df["pressure_mpa"].to_numpy(float), df["squeeze_force_n"].to_numpy(float)


def _friction_data(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """(pressure MPa, friction N, test labels, SYNTHETIC flag) of a friction CSV."""
    from exofric.io import read_friction_table

    df = read_friction_table(path)
    return (df["pressure_mpa"].to_numpy(float), df["friction_n"].to_numpy(float),
            df["test"].to_numpy(str), bool(df.attrs["synthetic"]))


#: Columns a friction table may map with --columns (the rest are raw-log quantities).
_FRICTION_COLUMNS = ("pressure_mpa", "friction_n", "kinetic_n", "test", "branch", "plateau")


def _fit_inputs(path: str, columns: str | None) -> dict[str, Any]:
    """Friction points for fit-friction from a raw log (reduced here), a pull table or a
    pressure_mpa,friction_n[,test] table: pressures (MPa), friction (N), cluster labels, and
    per-point standard deviations for errors-in-variables when the data give them."""
    import numpy as np

    from exofric.cli._rawlogs import reduce_files
    from exofric.errors import InputError
    from exofric.friction import ReduceSettings, friction_curve
    from exofric.io import is_raw_log, parse_column_map, read_friction_table

    if not Path(path).is_file():
        raise InputError(f"{path}: file not found", param="friction")
    if is_raw_log(path, columns):
        reds, pulls, meta = reduce_files([path], columns, ReduceSettings())
        curve, _ = friction_curve(pulls)
        sd_at = {(b, sp): sd for b, sp, sd in zip(curve["branch"], curve["setpoint"],
                                                   curve["kinetic_sd_n"], strict=True)}
        fsd = np.array([sd_at[(b if b == "up" else "down", sp)]
                        for b, sp in zip(pulls["branch"], pulls["setpoint"], strict=True)])
        return {"kind": "raw log", "pressure": pulls["pressure_mpa"].to_numpy(float),
                "friction": pulls["kinetic_n"].to_numpy(float),
                "groups": pulls["plateau"].to_numpy(), "tests": np.zeros(len(pulls), str),
                "synthetic": any("SYNTHETIC" in m.upper() for m in meta),
                "pressure_sd": np.maximum(pulls["pressure_se_mpa"].to_numpy(float), 1e-6),
                "friction_sd": fsd, "reduction": {"n_pulls": len(pulls),
                                                  "n_skipped": len(reds[0].skipped),
                                                  "curve": curve}}
    mapping = parse_column_map(columns, _FRICTION_COLUMNS) if columns else None
    df = read_friction_table(path, mapping)
    return {"kind": str(df.attrs.get("kind", "points")),
            "pressure": df["pressure_mpa"].to_numpy(float),
            "friction": df["friction_n"].to_numpy(float), "groups": df["group"].to_numpy(str),
            "tests": df["test"].to_numpy(str), "synthetic": bool(df.attrs["synthetic"]),
            "pressure_sd": None, "friction_sd": None, "reduction": None}


def _two(name: str, text: str) -> tuple[float, float]:
    from exofric.errors import InputError

    v = parse_floats(name, text)
    if len(v) != 2:
        raise InputError(f"{name} must be two numbers 'low,high', got {len(v)}")
    return (v[0], v[1])


def _choice(name: str, value: str, allowed: tuple[str, ...]) -> str:
    from exofric.errors import InputError

    if value not in allowed:
        raise InputError(f"{name} must be one of {', '.join(allowed)}, got {value!r}")
    return value


def _interface_curves(path: str, used: set[str]) -> Any:
    """A structure's FE curves S_wire(P), N(P) from an ``exofric squeeze --json`` file."""
    from exofric.errors import InputError
    from exofric.friction import InterfaceCurves
    from exofric.io import read_json

    p = Path(path)
    if not p.is_file():
        raise InputError(f"{path}: file not found", param="squeeze")
    if p.suffix.lower() != ".json":
        raise InputError(f"{p.name}: the interface law needs the JSON of `exofric squeeze ... "
                         "--json` (with 'wire_pressure_integral_n_per_mm'); a CSV holds N(P) "
                         "only", param="squeeze")
    obj = read_json(p)
    if not isinstance(obj, dict):
        raise InputError(f"{p.name}: expected the JSON object of `exofric squeeze --json`",
                         param="squeeze")
    name = p.stem
    k = 2
    while name in used:
        name, k = f"{p.stem}#{k}", k + 1
    used.add(name)
    try:
        return InterfaceCurves.from_squeeze(obj, name=name)
    except InputError as exc:
        raise InputError(f"{p.name}: {exc}", param=exc.param) from None


def _fit_interfaces_cmd(squeeze: list[str], friction: list[str], model: str, ci: str,
                        columns: str | None, plot: str | None, as_json: bool) -> None:
    """``fit-friction --law interfaces``: mu_tube, mu_wall from one or more structures."""
    import numpy as np

    from exofric.errors import InputError
    from exofric.friction import InterfaceTest, fit_interfaces

    if ci not in ("auto", "analytic", "ols", "cluster"):
        raise InputError(f"ci must be auto, analytic, ols or cluster with --law interfaces, "
                         f"got {ci!r} (bootstrap and odr are for --law gamma)", param="ci")
    used: set[str] = set()
    tests, kinds, synthetic, n_tests = [], [], False, 0
    for sq, fr in zip(squeeze, friction, strict=True):
        curves = _interface_curves(sq, used)
        data = _fit_inputs(fr, columns)
        tests.append(InterfaceTest(curves, data["pressure"], data["friction"],
                                   groups=data["groups"]))
        kinds.append(data["kind"])
        synthetic = synthetic or data["synthetic"]
        n_tests += int(np.unique(data["tests"]).size)
    fit = fit_interfaces(tests, model=model, ci=ci)  # type: ignore[arg-type]
    d = fit.to_dict()
    d.update({"synthetic": synthetic, "n_tests": n_tests, "data_kind": kinds,
              "squeeze_files": list(squeeze), "friction_files": list(friction)})
    if plot:
        from exofric.plots import plot_interface_fit

        title = ("SYNTHETIC rig data" if synthetic else
                 ", ".join(Path(f).name for f in friction))
        d["plot"] = str(save_figure(plot_interface_fit(
            fit, title, data_label="synthetic" if synthetic else "measured"), plot))

    def render() -> None:
        ci_t, ci_w = fit.mu_tube_ci, fit.mu_wall_ci
        rows = [
            ("model", f"interfaces, {fit.kind}", ""),
            ("mu_tube (wire on tube)", f"{fit.mu_tube:.5f}", ""),
            ("mu_tube 95% CI", f"[{ci_t[0]:.5f}, {ci_t[1]:.5f}]", fit.ci_method),
            ("mu_wall (wire on wall)", f"{fit.mu_wall:.5f}", ""),
            ("mu_wall 95% CI", f"[{ci_w[0]:.5f}, {ci_w[1]:.5f}]", fit.ci_method),
            ("correlation of estimates", f"{fit.correlation:.4f}", ""),
            ("condition number", f"{fit.condition_number:.3g}",
             f"max {fit.condition_number_max:g}"),
            ("identifiable", "yes" if fit.identifiable else "NO", ""),
        ]
        if fit.kind == "affine":
            rows.append(("F0", f"{fit.f0_n:.3f}", "N"))
        rows += [
            ("mean |rel. error|", f"{fit.relative_error_pct:.2f}", "%"),
            ("pooled gamma", f"{fit.gamma_pooled:.5f}", ""),
            ("pooled gamma |rel. error|", f"{fit.gamma_relative_error_pct:.2f}", "%"),
            ("structures / points", f"{len(fit.structures)} / {fit.n_points}", ""),
            ("points dropped", str(fit.n_dropped), ""),
        ]
        title = "Interface friction law" + (" (SYNTHETIC data)" if synthetic else "")
        console.print(kv_table(title, rows))
        t = narrow_table("Per structure (mean |relative error|)",
                         ["structure", "points", "S/N", "interfaces %", "gamma %"])
        for e in fit.per_structure():
            lo, hi = e["wrap_ratio_min"], e["wrap_ratio_max"]
            t.add_row(e["name"], str(e["n_points"]),
                      "-" if lo is None else f"{lo:.3f}-{hi:.3f}",
                      "-" if e["relative_error_pct"] is None
                      else f"{e['relative_error_pct']:.2f}",
                      "-" if e["gamma_relative_error_pct"] is None
                      else f"{e['gamma_relative_error_pct']:.2f}")
        console.print(t)
        console.print(f"identifiability: {fit.identifiability_reason}")
        console.print(f"CI: {fit.ci_note}")

    emit(d, as_json, render)


def _register_fit(app: typer.Typer) -> None:
    @app.command("fit-friction")
    def fit_friction(
        squeeze: list[str] = typer.Option(..., help="Squeeze curve N(P): JSON from `exofric "
                                          "squeeze --json` or CSV pressure_mpa,squeeze_force_n. "
                                          "--law interfaces: one JSON per structure, repeated "
                                          "(paired in order with --friction)."),
        friction: list[str] = typer.Option(..., help="Friction data: CSV pressure_mpa,"
                                           "friction_n[,test] (replicates allowed), the per-pull "
                                           "table of `exofric reduce --out`, or a raw rig log "
                                           "(reduced first). Repeat with --squeeze for several "
                                           "structures (--law interfaces)."),
        law: str = typer.Option("gamma", help="gamma (F = gamma N, paper Eq 7; one structure) "
                                "or interfaces (F = mu_tube S_wire + mu_wall N, one or more "
                                "structures)."),
        model: str = typer.Option("proportional", help="proportional (F = gamma N, paper) or "
                                  "affine (F = gamma N + F0)."),
        ci: str = typer.Option("auto", help="95% CI: auto (cluster with replicates, else "
                               "analytic), analytic (t x HC3), ols, bootstrap (pairs), cluster "
                               "(CR2, Bell-McCaffrey dof, over pressure plateaus) or odr (errors "
                               "in pressure too)."),
        pressure_sd: float | None = typer.Option(None, "--pressure-sd", help="Pressure error sd "
                                                 "in MPa for --ci odr (raw logs: each pull's "
                                                 "standard error)."),
        friction_sd: float | None = typer.Option(None, "--friction-sd", help="Friction error sd "
                                                 "in N for --ci odr (raw logs: the between-pull "
                                                 "sd at the pull's set point)."),
        columns: str | None = typer.Option(None, "--columns", help="Header map: for a raw log "
                                           "see `exofric reduce --help`; for a friction table "
                                           "pressure_<unit>=H,friction_<unit>=H[,test=H]."),
        seed: int = typer.Option(0, help="Bootstrap RNG seed."),
        plot: str | None = typer.Option(None, help="Write a PNG of the fit and residuals."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Fit the equivalent coefficient gamma (Eq 7) to friction data. MPa, N.

        With --law interfaces: mu_tube and mu_wall of F = mu_tube S_wire + mu_wall N from one
        or more structures (repeat --squeeze S.json --friction F.csv per structure), with CIs,
        their correlation and whether the data can separate them.
        """
        import numpy as np

        from exofric.errors import InputError, check_seed
        from exofric.friction import fit_gamma

        _choice("--law", law, ("gamma", "interfaces"))
        _choice("--model", model, ("proportional", "affine"))
        _choice("--ci", ci, ("auto", "analytic", "ols", "bootstrap", "cluster", "odr"))
        check_seed("seed", seed)
        if plot:
            plot_path(plot)
        if ci != "odr" and (pressure_sd is not None or friction_sd is not None):
            raise InputError("pressure_sd and friction_sd are for --ci odr only",
                             param="pressure_sd")
        if len(squeeze) != len(friction):
            raise InputError(f"squeeze and friction must come in pairs (one per structure), "
                             f"got {len(squeeze)} --squeeze and {len(friction)} --friction",
                             param="squeeze")
        if law == "interfaces":
            _fit_interfaces_cmd(squeeze, friction, model, ci, columns, plot, as_json)
            return
        if len(squeeze) != 1:
            raise InputError(f"law gamma fits one structure: give one --squeeze and one "
                             f"--friction, got {len(squeeze)} pairs (several structures: --law "
                             "interfaces)", param="squeeze")
        squeeze_file, friction_file = squeeze[0], friction[0]
        ps, ns = _squeeze_curve(squeeze_file)
        data = _fit_inputs(friction_file, columns)
        kw: dict[str, Any] = {}
        if ci == "odr":
            psd = pressure_sd if pressure_sd is not None else data["pressure_sd"]
            fsd = friction_sd if friction_sd is not None else data["friction_sd"]
            if psd is None or fsd is None:
                raise InputError("--ci odr needs --pressure-sd MPa and --friction-sd N (a raw "
                                 "log gives both)", param="pressure_sd")
            if fsd is not None and np.ndim(fsd) and not np.all(np.isfinite(fsd)):
                raise InputError("--ci odr: a set point has a single pull, so no between-pull "
                                 "sd; give --friction-sd N", param="friction_sd")
            kw = {"pressure_sd_mpa": psd, "friction_sd_n": fsd}
        fit = fit_gamma(data["pressure"], data["friction"], ps, ns, model=model,  # type: ignore[arg-type]
                        ci=ci, seed=seed, groups=data["groups"], **kw)  # type: ignore[arg-type]
        d = fit.to_dict()
        synthetic = data["synthetic"]
        d["synthetic"] = synthetic
        d["n_tests"] = int(np.unique(data["tests"]).size)
        d["data_kind"] = data["kind"]
        d["law"] = "gamma"
        if data["reduction"] is not None:
            d["reduction"] = data["reduction"]
        if plot:
            from exofric.plots import plot_gamma_fit

            title = "SYNTHETIC rig data" if synthetic else Path(friction_file).name
            d["plot"] = str(save_figure(plot_gamma_fit(
                fit, title, data_label="synthetic (virtual rig)" if synthetic else "measured"),
                plot))

        def render() -> None:
            rows = [
                ("model", fit.kind, ""),
                ("gamma (Eq 7)", f"{fit.gamma:.5f}", ""),
                ("gamma 95% CI", f"[{fit.gamma_ci95[0]:.5f}, {fit.gamma_ci95[1]:.5f}]",
                 fit.ci_method),
            ]
            if fit.kind == "affine":
                rows.append(("F0", f"{fit.model.f0_n:.3f}", "N"))
            rows += [
                ("mean |relative error|", f"{fit.relative_error_pct:.2f}", "%"),
                ("max relative error", f"{fit.max_relative_error_pct:.2f}", "%"),
                ("points used / dropped", f"{fit.n_points} / {fit.n_dropped}", ""),
                ("pressure clusters", str(fit.n_clusters), ""),
            ]
            title = "Equivalent coefficient" + (" (SYNTHETIC data)" if synthetic else "")
            console.print(kv_table(title, rows))
            if fit.ci_note:
                console.print(f"CI: {fit.ci_note}")
            if fit.lack_of_fit is not None:
                console.print(f"lack of fit: {fit.lack_of_fit.verdict}")

        emit(d, as_json, render)


def _measured_map(path: str, names: list[str]) -> dict[str, Any]:
    import numpy as np

    from exofric.errors import InputError
    from exofric.friction import MeasuredCurve

    pf, ff, tests, _ = _friction_data(path)
    labels = [str(t) for t in np.unique(tests)]
    if labels == [""]:
        if len(names) != 1:
            raise InputError(f"{Path(path).name}: needs a 'test' column naming the structure "
                             f"({', '.join(names)})")
        return {names[0]: MeasuredCurve.of(pf, ff)}
    out = {}
    for lab in labels:
        name = lab if lab in names else (f"test {lab}" if f"test {lab}" in names else None)
        if name is None:
            raise InputError(f"{Path(path).name}: test {lab!r} matches no structure "
                             f"({', '.join(names)})")
        m = tests == lab
        out[name] = MeasuredCurve.of(pf[m], ff[m])
    return out


def _register_predict(app: typer.Typer) -> None:
    @app.command("predict")
    def predict_cmd(
        gamma: float | None = typer.Option(None, help="Equivalent coefficient gamma (paper: "
                                           "0.7168); needed by --law gamma, compared with "
                                           "--law interfaces."),
        f0: float = typer.Option(0.0, "--f0", help="Affine offset F0 in N (0: paper's model)."),
        law: str = typer.Option("gamma", help="gamma (F = gamma N, the paper's model) or "
                                "interfaces (F = mu_tube S_wire + mu_wall N; needs "
                                "--mu-tube, --mu-wall)."),
        mu_tube: float | None = typer.Option(None, "--mu-tube", help="Wire-on-tube friction "
                                             "coefficient (unitless) of the interface law."),
        mu_wall: float | None = typer.Option(None, "--mu-wall", help="Wire-on-wall friction "
                                             "coefficient (unitless) of the interface law."),
        structures: str | None = typer.Option(None, help="Structures TOML file "
                                              "(see examples/structures-paper.toml)."),
        use_paper: bool = typer.Option(False, "--paper", help="The 7 structures of Table 3."),
        measured: str | None = typer.Option(None, help="Measured friction CSV "
                                            "pressure_mpa,friction_n,test."),
        pressures: str = typer.Option("0.1,0.2,0.3,0.4,0.5,0.6", help="Pressures in MPa."),
        shore: float = typer.Option(62.5, help="Tube Shore A hardness (material, Eqs 3-6)."),
        threshold: float = typer.Option(20.0, help="Validated deviation in % (paper: 20)."),
        arm_radius: float = typer.Option(0.10, help="Lever arm R in m for T = F R."),
        torque_max: float = typer.Option(40.0, help="Required torque in Nm (knee: 40)."),
        alpha: float = typer.Option(0.05, help="ANOVA significance level."),
        plot: str | None = typer.Option(None, help="Write a PNG: predicted vs tested, errors."),
        hole: float | None = typer.Option(None, help="One structure: hole diameter D in mm "
                                          "(with --tube-od, --tube-id, --wire)."),
        tube_od: float | None = typer.Option(None, help="One structure: tube OD d1 in mm."),
        tube_id: float | None = typer.Option(None, help="One structure: tube ID in mm."),
        wire: float | None = typer.Option(None, help="One structure: wire diameter d2 in mm."),
        length: float = typer.Option(116.0, help="One structure: tube length L in mm."),
        clearance_sd: float | None = typer.Option(None, "--clearance-sd", help="Clearance "
                                                  "spread along the tube: normal sd in mm "
                                                  "around each structure's clearance."),
        clearance_profile: str | None = typer.Option(None, "--clearance-profile",
                                                     help="Measured clearance along the tube: "
                                                     "CSV position_mm,clearance_mm covering "
                                                     "0..L."),
        tolerance: list[str] = typer.Option([], "--tolerance", help="A tolerance (1 sd) as "
                                            "name=value: hole=, tube_od=, tube_id=, wire= (mm) "
                                            "or shore= (Shore A); repeat for several."),
        samples: int = typer.Option(64, help="Quasi-Monte Carlo samples for --tolerance."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Predict friction F = gamma N(P) for other structures via the FE (Sec. 4). MPa, N.

        With --law interfaces: F = mu_tube S_wire(P) + mu_wall N(P) (+ F0); giving both
        --gamma and the mu's compares the two laws side by side (JSON: law_comparison). With
        --clearance-sd or --clearance-profile the clearance varies along the tube; with
        --tolerance the answers get 5/50/95 % bands (JSON: friction_n_p05, _p50, _p95).
        """
        from exofric import paper
        from exofric.errors import InputError
        from exofric.friction import paper_structures, predict, structures_from_dict
        from exofric.geometry import BASE
        from exofric.io import read_toml
        from exofric.material import MooneyRivlin

        if plot:
            plot_path(plot)
        one = [hole, tube_od, tube_id, wire]
        if sum([use_paper, structures is not None, any(v is not None for v in one)]) != 1:
            raise InputError("give exactly one of --paper, --structures FILE.toml or one "
                             "structure (--hole --tube-od --tube-id --wire)")
        model, other = _predict_laws(law, gamma, mu_tube, mu_wall, f0)
        if tolerance and law == "interfaces":
            raise InputError("tolerance bands are for --law gamma only (the tolerance study "
                             "samples N, not S_wire)", param="tolerance")
        grid = parse_floats("--pressures", pressures)
        base = BASE
        if use_paper:
            structs = paper_structures(BASE)
        elif structures is not None:
            if not Path(str(structures)).is_file():
                raise InputError(f"{structures}: file not found")
            structs, base = structures_from_dict(read_toml(str(structures)), BASE)
        else:
            if any(v is None for v in one):
                raise InputError("one structure needs all of --hole, --tube-od, --tube-id and "
                                 "--wire (mm)", param="hole")
            from exofric.geometry import Structure

            structs = (Structure(float(hole), float(tube_od), float(tube_id),  # type: ignore[arg-type]
                                 float(wire), length, name="structure"),)  # type: ignore[arg-type]
        solver, tols = _scatter_options(clearance_sd, clearance_profile, tolerance, samples)
        names = [s.name for s in structs]
        meas = _measured_map(measured, names) if measured else None
        material = MooneyRivlin.from_shore(shore)
        res = predict(structs, model, material, grid, measured=meas, base=base,
                      threshold_pct=threshold, arm_radius_m=arm_radius,
                      required_torque_nm=(0.0, torque_max), alpha=alpha, squeeze_fn=solver,
                      compare=other)
        printed = {f"test {r['test']}": r for r in paper.table3()} if use_paper else {}
        p4 = paper.table4() if use_paper else {}
        errs = paper.load()["max_relative_error"] if use_paper else {"test": [],
                                                                     "max_relative_error_pct": []}
        p_err = dict(zip(errs["test"], errs["max_relative_error_pct"], strict=True))
        d = res.to_dict()
        for entry, pr in zip(d["structures"], res.predictions, strict=True):
            entry["friction_n"] = list(pr.predicted_friction_n)
            entry["squeeze_force_n"] = list(pr.squeeze_force_n)
        if tols:
            from exofric.simulate import squeeze_tolerances

            for entry, pr in zip(d["structures"], res.predictions, strict=True):
                tr = squeeze_tolerances(pr.structure, shore, pr.pressure_mpa, tols,
                                        samples=samples, solver=solver)
                for q, v in tr.percentiles_n.items():
                    entry[f"squeeze_force_n_p{q:02d}"] = list(v)
                    entry[f"friction_n_p{q:02d}"] = [float(model.friction(x))
                                                     for x in v]
                entry["sensitivity"] = tr.to_dict()["sensitivity"]
                entry["tolerance_samples_failed"] = tr.failed
        if clearance_sd is not None or clearance_profile is not None:
            d["clearance"] = ({"normal_sd_mm": clearance_sd} if clearance_sd is not None
                              else {"profile": str(clearance_profile)})
        if use_paper:
            d["tube_id_note"] = "Table 3 prints no tube IDs: ID = base ID x d1 / base d1"
            d["paper_max_relative_error_pct"] = {f"test {k}": v for k, v in p_err.items()}
            d["paper_anova_p"] = {f"test {k}": v for k, v in p4.items()}
        if plot:
            from exofric.plots import plot_predictions

            bands = {e["name"]: (e["friction_n_p05"], e["friction_n_p95"])
                     for e in d["structures"] if "friction_n_p05" in e}
            d["plot"] = str(save_figure(plot_predictions(res.predictions, bands=bands or None),
                                        plot))

        def render() -> None:
            measured_any = any(p.max_relative_error_pct is not None for p in res.predictions)
            cols = ["name", "D/d1/d2 mm", "F N", *([] if use_paper else ["T Nm"]), "dev %",
                    "rec. %", "T3 %", "ok"]
            if measured_any:
                cols.append("err %")
            if use_paper:
                cols += ["F8-10 %", "T4 p"]
            law_text = (f"gamma = {gamma:g}" if law == "gamma" else
                        f"mu_tube = {mu_tube:g}, mu_wall = {mu_wall:g}")
            t = narrow_table(f"Friction at {grid[-1]:g} MPa, {law_text}; base: "
                             f"{base.name or 'the base group'}", cols)
            for p in res.predictions:
                s = p.structure
                m = p.max_relative_error_pct
                row_p = printed.get(s.name, {})
                pr = row_p.get("max_relative_deviation_pct")
                cells = [s.name, f"{s.hole_mm:g}/{s.tube_od_mm:g}/{s.wire_mm:g}",
                         f"{p.predicted_friction_n[-1]:.1f}",
                         *([] if use_paper else [f"{p.torque.torque_nm:.1f}"]),
                         f"{p.deviation.deviation_pct:.1f}",
                         f"{p.deviation.paper_deviation_pct:.1f}",
                         "-" if pr is None else f"{pr:.1f}",
                         "yes" if p.deviation.in_validated_region else "NO"]
                if measured_any:
                    cells.append("-" if m is None else f"{m:.2f}")
                if use_paper:
                    k = row_p.get("test")
                    cells.append(f"{p_err[k]:g}" if k in p_err else "-")
                    cells.append(f"{p4[k]:.4g}" if k in p4 else "-")
                t.add_row(*cells)
            console.print(t)
            console.print(
                ("F: friction at the highest pressure (torques in --json); " if use_paper else
                 "F, T: friction and torque at the highest pressure; ")
                + "dev %: exofric's deviation "
                "max(s)/min(s) - 1 of the scale factors; rec. %: the paper's max|s - 1| "
                "recomputed by exofric; T3 %: Table 3 as printed (tests 2-3 used another "
                "formula: docs/paper-notes.md); ok: inside the validated 20 %"
                + ("; err %: largest relative error against the measured curve" if measured_any
                   else "")
                + ("; F8-10 %: the paper's maximum relative error read from Figs 8-10; T4 p: "
                   "its ANOVA p-value (Table 4)" if use_paper else "") + ".")
            for a in res.anova:
                console.print(f"ANOVA {a.name}: F = {a.f_stat:.3f}, {a.verdict}")
            if "law_comparison" in d:
                parts = []
                for name, v in d["law_comparison"].items():
                    e = v["mean_abs_relative_error_pct"]
                    parts.append(f"{name} " + ("-" if e is None else f"{e:.2f} %"))
                console.print("laws compared, mean |relative error| over the measured points: "
                              + ", ".join(parts) + " (per structure: --json law_comparison)")
            if "clearance" in d:
                console.print(f"clearance varies along the tube: {d['clearance']}")
            for entry in d["structures"]:
                if "friction_n_p05" in entry:
                    top = entry["sensitivity"][0]
                    console.print(
                        f"{entry['name']}: F at {grid[-1]:g} MPa 5/50/95 % = "
                        f"{entry['friction_n_p05'][-1]:.1f} / {entry['friction_n_p50'][-1]:.1f}"
                        f" / {entry['friction_n_p95'][-1]:.1f} N (tolerances {dict(tols)}); "
                        f"largest share of the variance: {top['tolerance']} "
                        f"{100 * top['variance_share'][-1]:.0f} %")

        emit(d, as_json, render)


def _predict_laws(law: str, gamma: float | None, mu_tube: float | None,
                  mu_wall: float | None, f0: float) -> tuple[Any, Any]:
    """The law used by ``predict`` and the other law to compare with (or None)."""
    from exofric.errors import InputError
    from exofric.friction import FrictionModel, InterfaceFrictionModel

    _choice("--law", law, ("gamma", "interfaces"))
    if (mu_tube is None) != (mu_wall is None):
        missing = "mu_wall" if mu_wall is None else "mu_tube"
        raise InputError(f"{missing} is needed too: the interface law takes both --mu-tube "
                         "and --mu-wall", param=missing)
    inter = (None if mu_tube is None or mu_wall is None
             else InterfaceFrictionModel(mu_tube, mu_wall, f0))
    if law == "gamma":
        if gamma is None:
            raise InputError("gamma is required with --law gamma (paper: 0.7168)", param="gamma")
        return FrictionModel(gamma, f0), inter
    if inter is None:
        raise InputError("mu_tube and mu_wall are required with --law interfaces",
                         param="mu_tube")
    return inter, None if gamma is None else FrictionModel(gamma, f0)


def _scatter_options(clearance_sd: float | None, clearance_profile: str | None,
                     tolerance: list[str], samples: int) -> tuple[Any, dict[str, float]]:
    """The squeeze to use (a clearance distribution or None) and the tolerances (sd)."""
    from exofric.errors import InputError

    if clearance_sd is not None and clearance_profile is not None:
        raise InputError("give --clearance-sd or --clearance-profile, not both",
                         param="clearance_sd")
    solver = None
    if clearance_sd is not None or clearance_profile is not None:
        from exofric.simulate import ClearanceDistribution, squeeze_with_clearance

        if clearance_sd is not None:
            sd = float(clearance_sd)
            if not sd > 0:
                raise InputError(f"clearance_sd must be > 0 mm, got {clearance_sd:g}",
                                 param="clearance_sd")

            def solver(s: Any, m: Any, p: Any) -> Any:
                return squeeze_with_clearance(s, m, p, ClearanceDistribution.normal(
                    max(s.clearance_mm, 1e-3), sd))
        else:
            from exofric.io import read_table

            prof = read_table(str(clearance_profile), ["position_mm", "clearance_mm"],
                              unique_within=("position_mm", None))

            def solver(s: Any, m: Any, p: Any) -> Any:
                return squeeze_with_clearance(s, m, p, ClearanceDistribution.profile(
                    prof["position_mm"], prof["clearance_mm"], s.length_mm))
    names = {"hole": "hole_mm", "tube_od": "tube_od_mm", "tube_id": "tube_id_mm",
             "wire": "wire_mm", "shore": "shore"}
    tols: dict[str, float] = {}
    for item in tolerance:
        key, sep, value = item.partition("=")
        key = key.strip()
        if not sep or key not in names:
            raise InputError(f"tolerance {item!r}: expected name=value with name one of "
                             f"{', '.join(names)}", param="tolerance")
        try:
            tols[names[key]] = float(value)
        except ValueError:
            raise InputError(f"tolerance {item!r}: the value must be a number (mm or Shore "
                             "A)", param="tolerance") from None
    return solver, tols


def _register_invert(app: typer.Typer) -> None:
    @app.command("invert")
    def invert(
        gamma: float = typer.Option(..., help="Equivalent coefficient gamma."),
        target_friction: float = typer.Option(..., help="Required friction force in N."),
        cubic: str | None = typer.Option(None, help="Cubic N(P) coefficients c3,c2,c1,c0 "
                                         "(N, MPa), e.g. Eq 8."),
        squeeze: str | None = typer.Option(None, help="Squeeze curve file: exact (PCHIP) "
                                           "inverse, plus a cubic fitted over --range."),
        p_range: str = typer.Option("0.2,0.6", "--range", help="Pressure range low,high in "
                                    "MPa (paper: 0.2,0.6)."),
        f0: float = typer.Option(0.0, "--f0", help="Affine offset F0 in N."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Pressure (MPa) that gives a target friction (N): inverse of Eq 9 (Sec. 5)."""
        from exofric.errors import InputError
        from exofric.friction import CubicFit, FrictionModel, SqueezeCurve, pressure_for_friction

        if (cubic is None) == (squeeze is None):
            raise InputError("give exactly one of --cubic c3,c2,c1,c0 or --squeeze FILE")
        lo, hi = _two("--range", p_range)
        model = FrictionModel(gamma, f0)
        d: dict[str, Any] = {"target_friction_n": target_friction, "gamma": gamma, "f0_n": f0,
                             "target_squeeze_force_n": model.squeeze(target_friction)}
        if cubic is not None:
            c = parse_floats("--cubic", cubic)
            if len(c) != 4:
                raise InputError(f"--cubic must be 4 numbers c3,c2,c1,c0, got {len(c)}")
            fit = CubicFit((c[0], c[1], c[2], c[3]), lo, hi)
            d["method"] = "cubic"
            d["pressure_mpa"] = pressure_for_friction(target_friction, fit, model)
        else:
            ps, ns = _squeeze_curve(str(squeeze))
            d["method"] = "curve (PCHIP)"
            d["pressure_mpa"] = SqueezeCurve(ps, ns).pressure_for_friction(target_friction,
                                                                          model)
            fit = CubicFit.fit(ps, ns, (lo, hi))
            try:
                d["cubic_pressure_mpa"] = pressure_for_friction(target_friction, fit, model)
            except InputError:
                d["cubic_pressure_mpa"] = None
        d["cubic"] = fit.to_dict()
        d["p_min_mpa"], d["p_max_mpa"] = fit.p_min_mpa, fit.p_max_mpa
        from exofric import paper

        is_paper = (cubic is not None and all(
            abs(a - b) <= 1e-6 * max(1.0, abs(b)) for a, b in zip(fit.coefficients, paper.eq8(),
                                                                  strict=True))
            and abs(target_friction - paper.scalar("target_friction_n")) < 1e-9
            and abs(gamma - paper.scalar("gamma")) < 1e-9 and f0 == 0.0)
        if is_paper:
            d["paper_pressure_mpa"] = paper.scalar("target_pressure_mpa")

        def render() -> None:
            rows = [("target friction F", f"{target_friction:g}", "N"),
                    ("squeezing force N = (F - F0)/gamma", f"{d['target_squeeze_force_n']:.4f}",
                     "N"),
                    (f"pressure ({d['method']})", f"{d['pressure_mpa']:.4f}", "MPa")]
            if d.get("cubic_pressure_mpa") is not None:
                rows.append(("pressure (fitted cubic)", f"{d['cubic_pressure_mpa']:.4f}", "MPa"))
            console.print(kv_table("Inverse of Eq 9", rows))
            if "paper_pressure_mpa" in d:
                console.print(f"paper (Sec 5): {d['paper_pressure_mpa']:g} MPa for this target; "
                              f"Eq 9 as printed has its root at {d['pressure_mpa']:.4f} MPa "
                              "(docs/paper-notes.md)")

        emit(d, as_json, render)


def _register_rig(app: typer.Typer) -> None:
    @app.command("rig")
    def rig(
        squeeze: str = typer.Option(..., help="Squeeze curve N(P) (JSON or CSV; --law "
                                    "interfaces: the JSON of `exofric squeeze --json`)."),
        gamma_true: float | None = typer.Option(None, help="Planted equivalent coefficient "
                                                "gamma (--law gamma)."),
        law: str = typer.Option("gamma", help="Planted law: gamma (F = gamma_true N) or "
                                "interfaces (F = mu_tube S_wire + mu_wall N; not with --raw)."),
        mu_tube: float | None = typer.Option(None, "--mu-tube", help="Planted wire-on-tube "
                                             "coefficient (unitless), --law interfaces."),
        mu_wall: float | None = typer.Option(None, "--mu-wall", help="Planted wire-on-wall "
                                             "coefficient (unitless), --law interfaces."),
        out: str = typer.Option(..., help="Output: friction CSV, or with --raw a raw log "
                                "(.csv or .parquet) plus OUT-stem.truth.json (labelled "
                                "SYNTHETIC)."),
        pressures: str | None = typer.Option(None, help="Set points in MPa (default: the "
                                             "curve's pressures with N > 0)."),
        raw: bool = typer.Option(False, "--raw", help="Write the raw time series (time, "
                                 "pressure, force, displacement) with planted truths."),
        noise_pct: float | None = typer.Option(None, help="Load-cell noise, % of force (1 "
                                               "sigma; default 2, raw 0.3)."),
        noise_n: float | None = typer.Option(None, help="Load-cell noise in N (1 sigma; "
                                             "default 0, raw 0.1)."),
        offset_n: float | None = typer.Option(None, help="Load-cell zero offset in N (tared; "
                                              "default 0, raw 5)."),
        drift: float | None = typer.Option(None, help="Load-cell drift in N/s (default 0, "
                                           "raw 0.01)."),
        drag_n: float = typer.Option(0.0, help="Pressure-independent drag F0 in N."),
        pressure_noise: float | None = typer.Option(None, help="Pressure sensor noise in MPa "
                                                    "(default 0, raw 0.002)."),
        sample_rate: float | None = typer.Option(None, help="Logger rate in Hz (default 100, "
                                                 "raw 500)."),
        pull_speed: float = typer.Option(2.0, help="Wire speed in mm/s."),
        repeats: int | None = typer.Option(None, help="Repeated tests (adds a test column); "
                                           "raw: pulls per direction and plateau (default 5)."),
        directions: str = typer.Option("both", help="raw: both (forward and backward pulls) "
                                       "or forward."),
        sweep: str = typer.Option("up", help="raw: up, or up-down (two branches)."),
        static_ratio: float = typer.Option(1.3, help="raw: static / kinetic friction."),
        stick_slip_pct: float = typer.Option(1.0, help="raw: stick-slip amplitude, % of "
                                             "friction."),
        bias_n: float = typer.Option(1.5, "--bias-n", help="raw: force of constant sign while "
                                     "moving (gravity) in N."),
        hysteresis_pct: float = typer.Option(0.0, help="raw: down-branch friction above the "
                                             "up branch, %."),
        noise_tau: float = typer.Option(0.02, help="raw: load-cell noise correlation time "
                                        "in s."),
        pull_scatter_pct: float = typer.Option(1.5, help="raw: per-pull friction scatter "
                                               "(1 sigma), %."),
        plateau_scatter_pct: float = typer.Option(1.0, help="raw: per-plateau friction "
                                                  "scatter (1 sigma), %."),
        seed: int = typer.Option(0, help="RNG seed (deterministic output)."),
        as_json: bool = JSON_OPTION,
    ) -> None:
        """Virtual friction rig: SYNTHETIC friction data F = gamma_true N(P) + errors. MPa, N.

        With --law interfaces the planted friction is F = mu_tube S_wire(P) + mu_wall N(P).
        """
        from exofric.errors import InputError, check_seed
        from exofric.friction import RawRigConfig, RigConfig, simulate_raw_log, simulate_rig
        from exofric.io import write_json, write_raw_log, write_text

        check_seed("seed", seed)
        _choice("--law", law, ("gamma", "interfaces"))
        op = out_file("out", out)
        curves = None
        if law == "interfaces":
            from exofric.friction import InterfaceFrictionModel

            if gamma_true is not None:
                raise InputError("gamma_true is for --law gamma; --law interfaces plants "
                                 "--mu-tube and --mu-wall", param="gamma_true")
            if mu_tube is None or mu_wall is None:
                raise InputError("mu_tube and mu_wall are required with --law interfaces",
                                 param="mu_tube" if mu_tube is None else "mu_wall")
            planted = InterfaceFrictionModel(mu_tube, mu_wall)
            if raw:
                raise InputError("raw logs plant gamma only; drop --raw for --law interfaces",
                                 param="raw")
            curves = _interface_curves(squeeze, set())
        else:
            if gamma_true is None:
                raise InputError("gamma_true is required with --law gamma", param="gamma_true")
            if mu_tube is not None or mu_wall is not None:
                raise InputError("mu_tube and mu_wall go with --law interfaces",
                                 param="mu_tube")
        ps, ns = (None, None) if curves is not None else _squeeze_curve(squeeze)
        sp = parse_floats("--pressures", pressures) if pressures else None
        given: dict[str, Any] = {k: v for k, v in {
            "noise_pct": noise_pct, "noise_n": noise_n, "drift_n_per_s": drift,
            "pressure_noise_mpa": pressure_noise, "sample_rate_hz": sample_rate}.items()
            if v is not None}
        if raw:
            if op.suffix.lower() not in (".csv", ".parquet"):
                raise InputError(f"out must end in .csv or .parquet with --raw, got {out!r}",
                                 param="out")
            if offset_n is not None:
                given["tare_offset_n"] = offset_n
            _choice("--directions", directions, ("both", "forward"))
            _choice("--sweep", sweep, ("up", "up-down"))
            rcfg = RawRigConfig(
                pull_speed_mm_per_s=pull_speed, replicates=5 if repeats is None else repeats,
                directions=directions, sweep=sweep,  # type: ignore[arg-type]
                static_ratio=static_ratio, stick_slip_pct=stick_slip_pct, bias_n=bias_n,
                drag_n=drag_n, hysteresis_pct=hysteresis_pct, noise_tau_s=noise_tau,
                pull_scatter_pct=pull_scatter_pct, plateau_scatter_pct=plateau_scatter_pct,
                **given)
            log = simulate_raw_log(ps, ns, gamma_true, sp, config=rcfg,  # type: ignore[arg-type]
                                   seed=seed)
            truth_path = op.with_name(op.stem + ".truth.json")
            try:
                write_raw_log(op, log.to_frame(), log.metadata())
                write_json(log.to_dict(), truth_path)
            except OSError as exc:
                why = " ".join(str(exc.strerror or exc).split())
                raise InputError(f"--out {out}: cannot write ({why})") from None
            d = {k: v for k, v in log.to_dict().items() if k != "pulls"}
            d.update({"n_pulls": log.n_pulls, "out": str(op), "truth": str(truth_path)})

            def render_raw() -> None:
                console.print(kv_table("Virtual rig, raw log (SYNTHETIC)", [
                    ("gamma_true", f"{gamma_true:g}", ""),
                    ("plateaus / pulls", f"{len(log.setpoints_mpa)} / {log.n_pulls}", ""),
                    ("samples logged", str(d["n_samples"]), ""),
                    ("duration", f"{d['duration_s']:.1f}", "s"),
                    ("log written", str(op), ""),
                    ("truths written", str(truth_path), "")]))

            emit(d, as_json, render_raw)
            return
        if offset_n is not None:
            given["offset_n"] = offset_n
        cfg = RigConfig(drag_n=drag_n, pull_speed_mm_per_s=pull_speed, **given)
        if curves is not None:
            from exofric.friction import simulate_interface_rig

            irun = simulate_interface_rig(curves, planted.mu_tube, planted.mu_wall, sp,
                                          config=cfg, seed=seed,
                                          repeats=1 if repeats is None else repeats)
            run, text, d = irun.run, irun.to_csv_text(), irun.to_dict()
            what = ("mu_tube, mu_wall", f"{planted.mu_tube:g}, {planted.mu_wall:g}")
        else:
            run = simulate_rig(ps, ns, gamma_true, sp, config=cfg,  # type: ignore[arg-type]
                               seed=seed, repeats=1 if repeats is None else repeats)
            text, d = run.to_csv_text(), run.to_dict()
            what = ("gamma_true", f"{gamma_true:g}")
        try:
            write_text(op, text)
        except OSError as exc:
            why = " ".join(str(exc.strerror or exc).split())
            raise InputError(f"--out {out}: cannot write ({why})") from None
        d["out"] = str(op)
        d["law"] = law

        def render() -> None:
            console.print(kv_table("Virtual rig (SYNTHETIC)", [
                (what[0], what[1], ""),
                ("points", str(len(run.pressure_mpa)), ""),
                ("samples logged", str(d["n_samples"]), ""),
                ("written", str(op), "")]))

        emit(d, as_json, render)


def register(app: typer.Typer) -> None:
    """Add ``fit-friction``, ``predict``, ``invert`` and ``rig`` to ``app``."""
    _register_fit(app)
    _register_predict(app)
    _register_invert(app)
    _register_rig(app)
