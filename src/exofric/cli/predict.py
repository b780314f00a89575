"""``exofric predict``: friction F(P) of other structures via the FE (paper Sec. 4, Eq 9).

Units: pressure MPa, forces N, torque Nm, arm radius m, diameters mm. Files are read by
:mod:`exofric.io`: structure TOMLs, friction CSVs (``pressure_mpa,friction_n,test``) and
clearance profiles (``position_mm,clearance_mm``).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import typer

from exofric.cli._common import (
    JSON_OPTION,
    console,
    emit,
    narrow_table,
    parse_floats,
    plot_path,
    save_figure,
)
from exofric.cli._friction_inputs import both_mus, choice
from exofric.cli._options import (
    FrictionLawOptions,
    OptionGroup,
    StructureOptions,
    grouped,
)

if TYPE_CHECKING:
    import numpy as np

__all__ = ["register"]


def _friction_data(path: str | Path) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """(pressure MPa, friction N, test labels, SYNTHETIC flag) of a friction CSV."""
    from exofric.io import read_friction_table

    df = read_friction_table(path)
    return (df["pressure_mpa"].to_numpy(float), df["friction_n"].to_numpy(float),
            df["test"].to_numpy(str), bool(df.attrs["synthetic"]))


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


def _predict_laws(law: str, gamma: float | None, mu_tube: float | None,
                  mu_wall: float | None, f0: float) -> tuple[Any, Any]:
    """The law used by ``predict`` and the other law to compare with (or None)."""
    from exofric.errors import InputError
    from exofric.friction import FrictionModel, InterfaceFrictionModel

    choice("--law", law, ("gamma", "interfaces"))
    both_mus(mu_tube, mu_wall)
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


def _clearance_of(clearance_sd: float | None, clearance_profile: str | None) -> Any:
    """``structure -> ClearanceDistribution`` of --clearance-sd / --clearance-profile, or
    None (one clearance, today's squeeze)."""
    from exofric.errors import InputError

    if clearance_sd is not None and clearance_profile is not None:
        raise InputError("give --clearance-sd or --clearance-profile, not both",
                         param="clearance_sd")
    from exofric.simulate import ClearanceDistribution

    if clearance_sd is not None:
        sd = float(clearance_sd)
        if not sd > 0:
            raise InputError(f"clearance_sd must be > 0 mm, got {clearance_sd:g}",
                             param="clearance_sd")
        return lambda s: ClearanceDistribution.normal(max(s.clearance_mm, 1e-3), sd)
    if clearance_profile is not None:
        from exofric.io import read_table

        prof = read_table(str(clearance_profile), ["position_mm", "clearance_mm"],
                          unique_within=("position_mm", None))
        return lambda s: ClearanceDistribution.profile(prof["position_mm"],
                                                       prof["clearance_mm"], s.length_mm)
    return None


def _tolerances(tolerance: list[str]) -> dict[str, float]:
    """The --tolerance name=sd items as {python name: sd}; a name given twice is an error."""
    from exofric.errors import InputError

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
            v = float(value)
        except ValueError:
            raise InputError(f"tolerance {item!r}: the value must be a number (mm or Shore "
                             "A)", param="tolerance") from None
        if names[key] in tols:
            raise InputError(f"tolerance {key} is given twice ({tols[names[key]]:g} and "
                             f"{v:g}): give each name once", param="tolerance")
        tols[names[key]] = v
    return tols


def _scatter_options(clearance_sd: float | None, clearance_profile: str | None,
                     tolerance: list[str], structures: tuple[Any, ...]
                     ) -> tuple[Any, dict[str, float]]:
    """The squeeze to use (over a clearance distribution, or None) and the tolerances (sd);
    each structure's clearances are checked against its hole first (issue 38)."""
    dist_of = _clearance_of(clearance_sd, clearance_profile)
    tols = _tolerances(tolerance)
    if dist_of is None:
        return None, tols
    from exofric.simulate import squeeze_with_clearance

    for s in structures:
        dist_of(s).check_fits(s)

    def solver(s: Any, m: Any, p: Any) -> Any:
        return squeeze_with_clearance(s, m, p, dist_of(s))

    return solver, tols


class _OneStructure(StructureOptions):
    """predict's one structure (mm): the structure group, optional here, and its length."""

    length: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "hole": typer.Option(None, help="One structure: hole diameter D in mm (with --tube-od, "
                             "--tube-id, --wire)."),
        "tube_od": typer.Option(None, help="One structure: tube OD d1 in mm."),
        "tube_id": typer.Option(None, help="One structure: tube ID in mm."),
        "wire": typer.Option(None, help="One structure: wire diameter d2 in mm."),
        "length": typer.Option(116.0, help="One structure: tube length L in mm."),
    }

    def given(self) -> bool:
        """True when any of the four diameters was given."""
        return any(v is not None for v in (self.hole, self.tube_od, self.tube_id, self.wire))


class _Assessment(OptionGroup):
    """How predictions are judged: validated deviation %, lever arm m, torque Nm, ANOVA."""

    threshold: float
    arm_radius: float
    torque_max: float
    alpha: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "threshold": typer.Option(20.0, help="Validated deviation in % (paper: 20)."),
        "arm_radius": typer.Option(0.10, help="Lever arm R in m for T = F R."),
        "torque_max": typer.Option(40.0, help="Required torque in Nm (knee: 40)."),
        "alpha": typer.Option(0.05, help="ANOVA significance level."),
    }


class _Scatter(OptionGroup):
    """Clearance along the tube (sd or profile, mm) and tolerance bands (1 sd, QMC samples)."""

    clearance_sd: float | None
    clearance_profile: str | None
    tolerance: list[str]
    samples: int
    OPTIONS: ClassVar[dict[str, Any]] = {
        "clearance_sd": typer.Option(None, "--clearance-sd", help="Clearance spread along the "
                                     "tube: normal sd in mm around each structure's "
                                     "clearance."),
        "clearance_profile": typer.Option(None, "--clearance-profile", help="Measured "
                                          "clearance along the tube: CSV "
                                          "position_mm,clearance_mm covering 0..L."),
        "tolerance": typer.Option([], "--tolerance", help="A tolerance (1 sd) as name=value: "
                                  "hole=, tube_od=, tube_id=, wire= (mm) or shore= (Shore A); "
                                  "repeat for several."),
        "samples": typer.Option(64, help="Quasi-Monte Carlo samples for --tolerance."),
    }


#: predict's wording of the friction-law group
_LAW = FrictionLawOptions.options(
    law=typer.Option("gamma", help="gamma (F = gamma N, the paper's model) or interfaces (F = "
                     "mu_tube S_wire + mu_wall N; needs --mu-tube, --mu-wall)."),
    mu_tube=typer.Option(None, "--mu-tube", help="Wire-on-tube friction coefficient "
                         "(unitless) of the interface law."),
    mu_wall=typer.Option(None, "--mu-wall", help="Wire-on-wall friction coefficient "
                         "(unitless) of the interface law."),
)


def _structures(use_paper: bool, structures: str | None, one: _OneStructure
                ) -> tuple[tuple[Any, ...], Any]:
    """The structures to predict and their base group (the paper's, a TOML's or one; the
    caller checked that exactly one is given)."""
    from exofric.errors import InputError
    from exofric.friction import paper_structures, structures_from_dict
    from exofric.geometry import BASE
    from exofric.io import read_toml

    if use_paper:
        return paper_structures(BASE), BASE
    if structures is not None:
        if not Path(str(structures)).is_file():
            raise InputError(f"{structures}: file not found")
        try:
            return structures_from_dict(read_toml(str(structures)), BASE)
        except InputError as exc:   # about the file: its keys (hole_mm) are not flags (--hole)
            why = str(exc).removeprefix("structures file: ")
            raise InputError(f"{Path(str(structures)).name}: {why}", param="structures") \
                from None
    if any(v is None for v in (one.hole, one.tube_od, one.tube_id, one.wire)):
        raise InputError("one structure needs all of --hole, --tube-od, --tube-id and "
                         "--wire (mm)", param="hole")
    from exofric.geometry import Structure

    return (Structure(float(one.hole), float(one.tube_od), float(one.tube_id),
                      float(one.wire), one.length, name="structure"),), BASE


def _progress(label: str) -> Any:
    """``progress(done, total, stage)`` printing on stderr: the start (the solves take
    seconds each), then once the work has taken > 2 s at most a line a second, and the last."""
    import sys
    import time

    t0 = time.perf_counter()
    last = [0.0]

    def show(done: int, total: int, stage: str) -> None:
        now = time.perf_counter() - t0
        if done == 0:
            print(f"exofric: tolerance bands of {label}: {total} solves ({stage})...",
                  file=sys.stderr, flush=True)
        elif now > 2.0 and (now - last[0] >= 1.0 or done == total):
            last[0] = now
            print(f"exofric: tolerance bands of {label}: {done}/{total} solves ({stage}, "
                  f"{now:.0f} s)", file=sys.stderr, flush=True)

    return show


def _bands(structs: tuple[Any, ...], meas: dict[str, Any] | None, grid: list[float],
           shore: float, tols: dict[str, float], samples: int, solver: Any) -> dict[str, Any]:
    """Per structure name, its :class:`ToleranceResult` at predict's pressures (the grid and
    the structure's measured pressures)."""
    import numpy as np

    from exofric.simulate import squeeze_tolerances

    out = {}
    for s in structs:
        m = (meas or {}).get(s.name)
        p = np.asarray(grid, float) if m is None else np.union1d(grid, m.pressure_mpa)
        out[s.name] = squeeze_tolerances(s, shore, p, tols, samples=samples, solver=solver,
                                         progress=_progress(s.name or "the structure"))
    return out


def _reuse_nominal(bands: dict[str, Any], solver: Any) -> Any:
    """predict's squeeze: the nominal N the tolerance study solved, else ``solver``."""
    from types import SimpleNamespace

    def squeeze_fn(s: Any, m: Any, p: Any) -> Any:
        tr = bands.get(s.name)
        if tr is not None and list(tr.pressure_mpa) == [float(x) for x in p]:
            return SimpleNamespace(pressure_mpa=tr.pressure_mpa, squeeze_force_n=tr.nominal_n,
                                   contact_onset_pressure_mpa=tr.nominal_onset_mpa)
        if solver is not None:
            return solver(s, m, p)
        from exofric.simulate import squeeze

        return squeeze(s, m, p, keep_fields=False)

    return squeeze_fn


def _add_bands(d: dict[str, Any], res: Any, model: Any, bands: dict[str, Any]) -> None:
    """Tolerance bands (5/50/95 % of N and F) and sensitivities into ``d['structures']``."""
    for entry, pr in zip(d["structures"], res.predictions, strict=True):
        tr = bands[pr.structure.name]
        for q, v in tr.percentiles_n.items():
            entry[f"squeeze_force_n_p{q:02d}"] = list(v)
            entry[f"friction_n_p{q:02d}"] = [float(model.friction(x)) for x in v]
        td = tr.to_dict()
        entry["sensitivity"] = td["sensitivity"]
        entry["tolerance_samples_failed"] = tr.failed
        entry["tolerance_method"] = {k: td[k] for k in ("method", "method_note",
                                                        "held_out_error_pct_of_n", "solves")}


def _warnings_once() -> Any:
    """Context: the warnings raised inside it, each kind once (the first of the messages that
    differ only in their measured numbers, not in a structure's name: issue 34,
    :func:`exofric.errors.warning_key`), issued when it ends."""
    import warnings
    from contextlib import contextmanager

    from exofric.errors import warning_key

    @contextmanager
    def ctx() -> Any:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                yield
            finally:
                pending = list(caught)
        seen: dict[Any, Any] = {}
        for w in pending:
            seen.setdefault(warning_key(w.category, str(w.message)), w)
        for w in seen.values():
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, registry=None)

    return ctx()


def _tolerance_text(tols: dict[str, float]) -> str:
    """E.g. ``tube_id +-0.1 mm, shore +-2 Shore A``."""
    return ", ".join(f"{k.removesuffix('_mm')} +-{v:g} " + ("Shore A" if k == "shore" else "mm")
                     for k, v in tols.items())


def _paper_columns(use_paper: bool) -> tuple[dict[str, Any], dict[Any, Any], dict[Any, Any]]:
    """Table 3 rows by name, Table 4 p-values and the Figs 8-10 errors (empty without
    --paper)."""
    from exofric import paper

    printed = {f"test {r['test']}": r for r in paper.table3()} if use_paper else {}
    p4 = paper.table4() if use_paper else {}
    errs = paper.load()["max_relative_error"] if use_paper else {"test": [],
                                                                 "max_relative_error_pct": []}
    return printed, p4, dict(zip(errs["test"], errs["max_relative_error_pct"], strict=True))


def _table(res: Any, use_paper: bool, title: str) -> Any:
    """The predictions as a narrow table (with the paper's columns with --paper)."""
    printed, p4, p_err = _paper_columns(use_paper)
    measured_any = any(p.max_relative_error_pct is not None for p in res.predictions)
    cols = ["name", "D/d1/d2 mm", "F N", *([] if use_paper else ["T Nm"]), "dev %",
            "rec. %", "T3 %", "ok"]
    if measured_any:
        cols.append("err %")
    if use_paper:
        cols += ["F8-10 %", "T4 p"]
    t = narrow_table(title, cols)
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
    return t


def _render(d: dict[str, Any], res: Any, use_paper: bool, grid: list[float], law_text: str,
            base: Any, tols: dict[str, float]) -> None:
    """The human-readable answer of ``predict``."""
    measured_any = any(p.max_relative_error_pct is not None for p in res.predictions)
    console.print(_table(res, use_paper, f"Friction at {grid[-1]:g} MPa, {law_text}; base: "
                         f"{base.name or 'the base group'}"))
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
        c = d["clearance"]
        console.print("clearance varies along the tube: " + (
            f"normal, sd {c['normal_sd_mm']:g} mm around each structure's D - d1 - d2"
            if "normal_sd_mm" in c else f"measured profile {c['profile']}"))
    for entry in d["structures"]:
        if "friction_n_p05" in entry:
            top = entry["sensitivity"][0]
            how = entry["tolerance_method"]
            console.print(
                f"{entry['name']}: F at {grid[-1]:g} MPa 5/50/95 % = "
                f"{entry['friction_n_p05'][-1]:.1f} / {entry['friction_n_p50'][-1]:.1f}"
                f" / {entry['friction_n_p95'][-1]:.1f} N (tolerances, 1 sd: "
                f"{_tolerance_text(tols)}); largest share of the variance: "
                f"{top['tolerance'].removesuffix('_mm')} "
                f"{100 * top['variance_share'][-1]:.0f} %; method {how['method']}: "
                f"{how['method_note']}")


@grouped
def predict_cmd(
    gamma: float | None = typer.Option(None, help="Equivalent coefficient gamma (paper: "
                                       "0.7168); needed by --law gamma, compared with "
                                       "--law interfaces."),
    f0: float = typer.Option(0.0, "--f0", help="Affine offset F0 in N (0: paper's model)."),
    friction_law: FrictionLawOptions = _LAW,
    structures: str | None = typer.Option(None, help="Structures TOML file "
                                          "(see examples/structures-paper.toml)."),
    use_paper: bool = typer.Option(False, "--paper", help="The 7 structures of Table 3."),
    measured: str | None = typer.Option(None, help="Measured friction CSV "
                                        "pressure_mpa,friction_n,test."),
    pressures: str = typer.Option("0.1,0.2,0.3,0.4,0.5,0.6", help="Pressures in MPa."),
    shore: float = typer.Option(62.5, help="Tube Shore A hardness (material, Eqs 3-6)."),
    assess: _Assessment = _Assessment.options(),
    plot: str | None = typer.Option(None, help="Write a PNG: predicted vs tested, errors."),
    one: _OneStructure = _OneStructure.options(),
    scatter: _Scatter = _Scatter.options(),
    as_json: bool = JSON_OPTION,
) -> None:
    """Predict friction F = gamma N(P) for other structures via the FE (Sec. 4). MPa, N.

    With --law interfaces: F = mu_tube S_wire(P) + mu_wall N(P) (+ F0); giving both
    --gamma and the mu's compares the two laws side by side (JSON: law_comparison). With
    --clearance-sd or --clearance-profile the clearance varies along the tube; with
    --tolerance the answers get 5/50/95 % bands (JSON: friction_n_p05, _p50, _p95).
    """
    from exofric.errors import InputError
    from exofric.friction import predict
    from exofric.material import MooneyRivlin

    if plot:
        plot_path(plot)
    if sum([use_paper, structures is not None, one.given()]) != 1:
        raise InputError("give exactly one of --paper, --structures FILE.toml or one "
                         "structure (--hole --tube-od --tube-id --wire)")
    law, mu_tube, mu_wall = friction_law.law, friction_law.mu_tube, friction_law.mu_wall
    model, other = _predict_laws(law, gamma, mu_tube, mu_wall, f0)
    if scatter.tolerance and law == "interfaces":
        raise InputError("tolerance bands are for --law gamma only (the tolerance study "
                         "samples N, not S_wire)", param="tolerance")
    grid = parse_floats("--pressures", pressures)
    structs, base = _structures(use_paper, structures, one)
    with _warnings_once():
        solver, tols = _scatter_options(scatter.clearance_sd, scatter.clearance_profile,
                                        scatter.tolerance, structs)
        meas = _measured_map(measured, [s.name for s in structs]) if measured else None
        bands = (_bands(structs, meas, grid, shore, tols, scatter.samples, solver) if tols
                 else {})
        res = predict(structs, model, MooneyRivlin.from_shore(shore), grid, measured=meas,
                      base=base, threshold_pct=assess.threshold,
                      arm_radius_m=assess.arm_radius,
                      required_torque_nm=(0.0, assess.torque_max), alpha=assess.alpha,
                      squeeze_fn=_reuse_nominal(bands, solver) if bands else solver,
                      compare=other)
    d = res.to_dict()
    for entry, pr in zip(d["structures"], res.predictions, strict=True):
        entry["friction_n"] = list(pr.predicted_friction_n)
        entry["squeeze_force_n"] = list(pr.squeeze_force_n)
    if bands:
        _add_bands(d, res, model, bands)
    if scatter.clearance_sd is not None or scatter.clearance_profile is not None:
        d["clearance"] = ({"normal_sd_mm": scatter.clearance_sd}
                          if scatter.clearance_sd is not None
                          else {"profile": str(scatter.clearance_profile)})
    if use_paper:
        _, p4, p_err = _paper_columns(use_paper)
        d["tube_id_note"] = "Table 3 prints no tube IDs: ID = base ID x d1 / base d1"
        d["paper_max_relative_error_pct"] = {f"test {k}": v for k, v in p_err.items()}
        d["paper_anova_p"] = {f"test {k}": v for k, v in p4.items()}
    if plot:
        from exofric.plots import plot_predictions

        bands = {e["name"]: (e["friction_n_p05"], e["friction_n_p95"])
                 for e in d["structures"] if "friction_n_p05" in e}
        d["plot"] = str(save_figure(plot_predictions(res.predictions, bands=bands or None),
                                    plot))
    law_text = (f"gamma = {gamma:g}" if law == "gamma" else
                f"mu_tube = {mu_tube:g}, mu_wall = {mu_wall:g}")
    emit(d, as_json, lambda: _render(d, res, use_paper, grid, law_text, base, tols))


def register(app: typer.Typer) -> None:
    """Add the ``predict`` command."""
    app.command("predict")(predict_cmd)
