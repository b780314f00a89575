"""``exofric fit-friction``: the friction law fitted to friction data (paper Eq 7).

Units: pressure MPa, forces N. Files are read by :mod:`exofric.io`: squeeze curves
(``exofric squeeze --json`` output or a ``pressure_mpa,squeeze_force_n`` CSV), friction CSVs
(``pressure_mpa,friction_n`` with an optional ``test`` column), per-pull tables of
``exofric reduce`` and raw rig logs.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from exofric.cli._common import console, emit, kv_table, narrow_table, plot_path, save_figure
from exofric.cli._friction_inputs import choice, interface_curves, squeeze_curve
from exofric.cli._options import OutputOptions, grouped

__all__ = ["register"]


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


def _fit_interfaces_cmd(squeeze: list[str], friction: list[str], model: str, ci: str,
                        columns: str | None, out: OutputOptions) -> None:
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
        curves = interface_curves(sq, used)
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
    if out.plot:
        from exofric.plots import plot_interface_fit

        title = ("SYNTHETIC rig data" if synthetic else
                 ", ".join(Path(f).name for f in friction))
        d["plot"] = str(save_figure(plot_interface_fit(
            fit, title, data_label="synthetic" if synthetic else "measured"), out.plot))

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

    emit(d, out.as_json, render)


def _fit_gamma_cmd(squeeze_file: str, friction_file: str, model: str, ci: str,
                   sd: tuple[float | None, float | None], columns: str | None, seed: int,
                   out: OutputOptions) -> None:
    """``fit-friction --law gamma``: gamma (and F0) of one structure; ``sd`` the given
    (pressure MPa, friction N) error sds of --ci odr."""
    import numpy as np

    from exofric.errors import InputError
    from exofric.friction import fit_gamma

    ps, ns = squeeze_curve(squeeze_file)
    data = _fit_inputs(friction_file, columns)
    pressure_sd, friction_sd = sd
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
    if out.plot:
        from exofric.plots import plot_gamma_fit

        title = "SYNTHETIC rig data" if synthetic else Path(friction_file).name
        d["plot"] = str(save_figure(plot_gamma_fit(
            fit, title, data_label="synthetic (virtual rig)" if synthetic else "measured"),
            out.plot))

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

    emit(d, out.as_json, render)


@grouped
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
    out: OutputOptions = OutputOptions.options(
        plot=typer.Option(None, help="Write a PNG of the fit and residuals.")),
) -> None:
    """Fit the equivalent coefficient gamma (Eq 7) to friction data. MPa, N.

    With --law interfaces: mu_tube and mu_wall of F = mu_tube S_wire + mu_wall N from one
    or more structures (repeat --squeeze S.json --friction F.csv per structure), with CIs,
    their correlation and whether the data can separate them.
    """
    from exofric.errors import InputError, check_seed

    choice("--law", law, ("gamma", "interfaces"))
    choice("--model", model, ("proportional", "affine"))
    choice("--ci", ci, ("auto", "analytic", "ols", "bootstrap", "cluster", "odr"))
    check_seed("seed", seed)
    if out.plot:
        plot_path(out.plot)
    if ci != "odr" and (pressure_sd is not None or friction_sd is not None):
        raise InputError("pressure_sd and friction_sd are for --ci odr only",
                         param="pressure_sd")
    if len(squeeze) != len(friction):
        raise InputError(f"squeeze and friction must come in pairs (one per structure), "
                         f"got {len(squeeze)} --squeeze and {len(friction)} --friction",
                         param="squeeze")
    if law == "interfaces":
        _fit_interfaces_cmd(squeeze, friction, model, ci, columns, out)
        return
    if len(squeeze) != 1:
        raise InputError(f"law gamma fits one structure: give one --squeeze and one "
                         f"--friction, got {len(squeeze)} pairs (several structures: --law "
                         "interfaces)", param="squeeze")
    _fit_gamma_cmd(squeeze[0], friction[0], model, ci, (pressure_sd, friction_sd), columns,
                   seed, out)


def register(app: typer.Typer) -> None:
    """Add the ``fit-friction`` command."""
    app.command("fit-friction")(fit_friction)
