"""The result objects' table and picture API: ``.to_frame()`` and ``.plot()``, and plots.save.

Structural checks: every frame has unit-suffixed columns whose values are the result's own
arrays (one row per pressure / time sample / trial / design), every ``.plot()`` returns the
Axes or Figure it drew on with the expected artists and leaves the matplotlib backend alone,
``plots.save`` writes one non-empty PNG and nothing else, and no library module selects a
backend.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import matplotlib
import numpy as np
import pandas as pd
import pytest

from exofric import plots
from exofric.calibration import InflationData, calibrate
from exofric.control import Controller, PIDGains, PlantParams, simulate
from exofric.design import parse_sweep, run_sweep, search_designs
from exofric.fe import MeshSpec
from exofric.friction import MeasuredCurve, fit_gamma, paper_structures, predict
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.reproduction import ControlSetup, compare, run_case
from exofric.simulate import inflate, squeeze

SRC = Path(__file__).resolve().parents[1] / "src" / "exofric"


def assert_display(obj) -> None:
    """A result's notebook display (issue 34): ``_repr_html_`` is one small table of its
    ``to_dict()`` (name, value, unit; at most 40 rows plus a count of the rest), long arrays
    summarised (no more than a screen: < 12000 characters); ``summary()``, where the class has
    it, the same as text."""
    from exofric._display import MAX_ROWS

    page = obj._repr_html_()
    assert page.startswith("<div><strong>" + type(obj).__name__)
    assert "<table>" in page and "unavailable" not in page, page[:300]
    assert page.count("<tr>") <= MAX_ROWS + 2 and len(page) < 12_000, len(page)
    summary = getattr(obj, "summary", None)
    if callable(summary) and isinstance(text := summary(), str):
        assert text.splitlines()[0].startswith(type(obj).__name__)
        assert len(text.splitlines()) <= MAX_ROWS + 2

UNIT_SUFFIXES = ("_mpa", "_per_mpa", "_n", "_n_per_mm", "_mm", "_s", "_pct", "_nm", "_m")
# numeric columns that carry no unit (ratios, counts, indices, hardness, coefficients)
UNITLESS = {"group", "n_measured", "max_stretch", "axial_stretch", "newton_iterations", "trial",
            "shore", "gamma", "design_index", "dofs", "n_error_estimate_reliable",
            "stick_fraction_wire", "stick_fraction_wall"}

MAT = MooneyRivlin.from_shore(62.5)


def assert_unit_columns(df: pd.DataFrame) -> None:
    """Every numeric (non-bool) column names its unit, or is a known unitless quantity."""
    for col in df.columns:
        s = df[col]
        if pd.api.types.is_bool_dtype(s) or not pd.api.types.is_numeric_dtype(s):
            continue
        assert col.endswith(UNIT_SUFFIXES) or col in UNITLESS, f"column {col!r} has no unit"


def assert_columns_equal(df: pd.DataFrame, pairs: dict[str, object]) -> None:
    for col, values in pairs.items():
        np.testing.assert_array_equal(df[col].to_numpy(), np.asarray(values, dtype=float),
                                      err_msg=col)


@pytest.fixture(autouse=True)
def _close_figures():
    import matplotlib.pyplot as plt

    yield
    plt.close("all")


@pytest.fixture
def same_backend():
    """Fails the test if anything it called switched the matplotlib backend."""
    before = matplotlib.get_backend()
    yield
    assert matplotlib.get_backend() == before


# ----------------------------------------------------------------------------- FE results


@pytest.fixture(scope="module")
def squeezed():
    return squeeze(BASE, MAT, [0.3, 0.6], mesh=MeshSpec(2, 12))


@pytest.fixture(scope="module")
def inflated():
    return inflate(8.3, 4.97, MAT, [0.1, 0.2, 0.3])


def test_squeeze_frame_and_plot(squeezed, same_backend) -> None:
    assert_display(squeezed)
    r = squeezed
    df = r.to_frame()
    assert len(df) == r.pressure_mpa.size
    assert_unit_columns(df)
    assert_columns_equal(df, {
        "pressure_mpa": r.pressure_mpa, "squeeze_force_n": r.squeeze_force_n,
        "squeeze_force_per_depth_n_per_mm": r.squeeze_force_n_per_mm,
        "wall_force_n": r.wall_force_n, "wall_force_per_depth_n_per_mm": r.wall_force_n_per_mm,
        "wire_contact_halfwidth_mm": r.contact.wire_contact_halfwidth_mm,
        "max_penetration_mm": r.contact.max_penetration_mm,
        "newton_iterations": r.newton_iterations})
    ax = r.plot()
    assert len(ax.lines) == 1 + (r.contact_onset_pressure_mpa is not None)
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), r.squeeze_force_n)
    # Figs 6-7: one section per distinct nearest pressure (0.3, 0.6), N(P), one colour bar
    fig = plots.plot_squeeze(r)
    assert len(fig.axes) == 2 + 1 + 1
    assert r.to_dict()["squeeze_force_n"] == r.squeeze_force_n.tolist()


def test_inflation_frame_and_plot(inflated, same_backend) -> None:
    assert_display(inflated)
    r = inflated
    df = r.to_frame()
    assert_unit_columns(df)
    assert_columns_equal(df, {
        "pressure_mpa": r.pressure_mpa, "outer_diameter_mm": r.outer_diameter_mm,
        "inner_diameter_mm": r.inner_diameter_mm,
        "analytic_outer_diameter_mm": r.analytic_outer_diameter_mm(),
        "max_stretch": r.max_stretch})
    ax = r.plot()
    assert len(ax.lines) == 2          # FE and the closed form
    fig = plots.plot_inflation(r)
    assert len(fig.axes) == 3          # section, OD(P), colour bar


def test_plot_draws_on_a_given_axes_or_figure(squeezed, same_backend) -> None:
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2)
    assert squeezed.plot(ax=a2) is a2 and not a1.lines
    empty = plt.figure()
    assert plots.plot_squeeze(squeezed, empty) is empty


# ----------------------------------------------------------------------------- calibration


def test_calibration_frame_and_plot(same_backend) -> None:
    r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=4.97, model="paper-table1")
    assert_display(r)
    df = r.to_frame()
    assert len(df) == len(r.history)
    assert_unit_columns(df)
    assert_columns_equal(df, {
        "trial": np.arange(1, len(r.history) + 1),
        "shore": [t.shore for t in r.history],
        "tube_id_mm": [t.tube_id_mm for t in r.history],
        "average_error_pct": [t.average_error_pct for t in r.history],
        "max_error_pct": [t.max_error_pct for t in r.history]})
    ax = r.plot()
    assert len(ax.lines) == len(r.history) + 2     # trials, measured points, final curve


# ----------------------------------------------------------------------------- friction


def _fake_squeeze(structure, material, p):
    p = np.asarray(p, dtype=float)
    return SimpleNamespace(pressure_mpa=p, squeeze_force_n=400.0 * p * structure.tube_od_mm / 8.3)


def test_gamma_fit_frame_and_plot(same_backend) -> None:
    fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
                    [100.0, 200.0, 268.55])
    assert_display(fit)
    df = fit.to_frame()
    assert len(df) == fit.n_points
    assert_unit_columns(df)
    assert_columns_equal(df, {
        "pressure_mpa": fit.pressure_mpa, "squeeze_force_n": fit.squeeze_force_n,
        "friction_n": fit.friction_n, "predicted_friction_n": fit.predicted_friction_n,
        "residual_n": fit.residual_n, "relative_error_pct": fit.point_relative_error_pct})
    fig = fit.plot()
    assert len(fig.axes) == 3 and len(fig.axes[0].lines) == 2


def test_predictions_frame_and_plot(same_backend) -> None:
    structs = paper_structures()[:2]
    meas = {structs[0].name: MeasuredCurve.of([0.25, 0.5], [40.0, 81.0])}
    res = predict(structs, 0.5, None, [0.2, 0.4, 0.6], squeeze_fn=_fake_squeeze, measured=meas)
    one = res.predictions[0]
    assert_display(res)
    assert_display(one)
    df1 = one.to_frame()
    assert_unit_columns(df1)
    assert len(df1) == len(one.pressure_mpa) == 5          # grid + the measured pressures
    assert_columns_equal(df1, {"pressure_mpa": one.pressure_mpa,
                               "squeeze_force_n": one.squeeze_force_n,
                               "predicted_friction_n": one.predicted_friction_n})
    at = df1["measured_friction_n"].notna()
    assert df1.loc[at, "pressure_mpa"].tolist() == [0.25, 0.5]
    assert df1.loc[at, "measured_friction_n"].tolist() == [40.0, 81.0]
    np.testing.assert_array_equal(df1.loc[at, "relative_error_pct"], one.relative_error_pct)
    df = res.to_frame()
    assert len(df) == sum(len(p.pressure_mpa) for p in res.predictions)
    assert df["structure"].unique().tolist() == [s.name for s in structs]
    assert_unit_columns(df)
    fig = res.plot()
    assert len(fig.axes) == 2 * len(structs)
    assert len(fig.axes[0].lines) == 2                     # predicted and tested


# ----------------------------------------------------------------------------- control


def test_simulation_frame_and_plot(same_backend) -> None:
    sim = simulate(Controller(PIDGains(0.002, 0.01, 0.0), u_max=0.6), PlantParams(),
                   lambda p: 200.0 * p, 50.0, duration_s=1.0, dt=0.01)
    assert_display(sim)
    assert "101 values" in sim.summary()           # a long trajectory: its size and range
    df = sim.to_frame()
    assert len(df) == sim.time_s.size
    assert_unit_columns(df)
    assert_columns_equal(df, {
        "time_s": sim.time_s, "setpoint_n": sim.setpoint_n, "friction_n": sim.friction_n,
        "measured_friction_n": sim.measured_n, "command_mpa": sim.command_mpa,
        "pressure_mpa": sim.pressure_mpa})
    assert len(sim.plot().lines) == 2


def test_fig12_case_and_compare(same_backend) -> None:
    setup = ControlSetup.default(duration_s=3.0)
    case = run_case(setup, "pid", feedforward=False)
    assert_display(case)
    df = case.to_frame()
    assert_unit_columns(df)
    assert_columns_equal(df, {"time_s": case.simulation.time_s,
                              "friction_n": case.simulation.friction_n})
    fig = case.plot()
    assert len(fig.axes) == 2                    # friction, pressure
    assert len(fig.axes[0].lines) == 1 + 1       # response and the target line
    assert len(fig.axes[1].lines) == 2           # pressure and command
    cmp = compare(setup)
    assert_display(cmp)
    big = cmp.to_frame()
    assert len(big) == 6 * case.simulation.time_s.size
    assert_unit_columns(big)
    fig = cmp.plot()
    assert len(fig.axes) == 6
    assert all(len(ax.lines) == 3 for ax in fig.axes[:3])   # without, with, target
    assert len(cmp.plot(pressure=False).axes) == 3


# ----------------------------------------------------------------------------- design


def test_design_search_and_sweep_frames(tmp_path, same_backend) -> None:
    spec = parse_sweep({"pressures_mpa": [0.3, 0.6], "grid": {"tube_od_mm": [7.8, 8.3]},
                        "solver": {"n_radial": 1, "n_circ": 12}})
    run = run_sweep(spec, tmp_path / "sweep", serial=True)
    assert_display(run)
    assert_display(run.summary)
    rows = run.to_frame()
    pd.testing.assert_frame_equal(rows, run.frame)
    assert rows is not run.frame                       # a copy: editing it leaves the run
    assert len(rows) == 2 * 2                          # one row per design and pressure
    assert_unit_columns(rows)
    s = search_designs(run.frame, 5.0, 0.1, 0.6, gamma=0.7168)
    assert_display(s)
    t = s.to_frame()
    pd.testing.assert_frame_equal(t, s.table)
    assert len(t) == 2
    assert_unit_columns(t)
    ax = s.plot()
    assert ax.get_xlabel() == "tube OD d1 (mm)"
    assert len(ax.collections) >= 1                    # the map's cells (and the best star)


# ----------------------------------------------------------------------------- save, backend


def test_save_writes_one_png_and_nothing_else(tmp_path, inflated, same_backend) -> None:
    out = plots.save(inflated.plot(), tmp_path / "od.png")
    assert out == tmp_path / "od.png"
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 1000
    assert sorted(p.name for p in tmp_path.iterdir()) == ["od.png"]
    with pytest.raises(FileNotFoundError):          # creates no directory
        plots.save(inflated.plot(), tmp_path / "missing" / "od.png")
    assert not (tmp_path / "missing").exists()


def test_no_library_module_selects_a_backend() -> None:
    hits = [f"{p.relative_to(SRC)}:{i}" for p in SRC.rglob("*.py")
            for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
            if re.search(r"matplotlib\.use\(|mpl\.use\(", line)]
    assert hits == []


def test_cli_selects_agg_without_importing_matplotlib() -> None:
    code = ("import os, sys; os.environ.pop('MPLBACKEND', None); from exofric.cli import run; "
            "run(['--version']); print(os.environ['MPLBACKEND'], 'matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={k: v for k, v in os.environ.items() if k != "MPLBACKEND"},
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split()[-2:] == ["Agg", "False"]


# ----------------------------------------------------------------------------- issue 34

#: Every public result class (what a computation returns) and its notebook display.
RESULT_CLASSES = {
    "exofric.simulate": "InflationResult PulloutResult RingResult SqueezeResult ToleranceResult "
                        "ClearanceSqueeze",
    "exofric.friction": "GammaFit InterfaceFit Prediction PredictionSet PulloutFit RigReduction "
                        "RigRun AnovaResult JointStiffness TorqueCheck RawRigLog InterfaceRigRun "
                        "CubicFit",
    "exofric.calibration": "CalibrationResult MaterialCalibration",
    "exofric.control": "GaitResult GaitComparison IdentifiedPlant StepMetrics ChargeFit "
                       "SimulationResult TuningResult StrategyTable ClosedLoopResult",
    "exofric.material": "MaterialFit",
    "exofric.design": "SweepRun SweepSummary DesignSearch SurrogateSearch",
    "exofric.reproduction": "CaseResult CompareResult ReproduceResult",
    "exofric.hardware": "LoopResult",
}


def test_every_result_class_has_a_notebook_display() -> None:
    """Each result class mixes in the display (``_repr_html_``; ``summary()`` except where a
    field or method of that name came first: SweepRun.summary, GaitResult.summary), and every
    public dataclass named ``*Result`` is in the list above."""
    import dataclasses
    import importlib

    from exofric._display import DisplayMixin, HtmlReprMixin

    for pkg, names in RESULT_CLASSES.items():
        mod = importlib.import_module(pkg)
        for name in names.split():
            cls = getattr(mod, name)
            assert issubclass(cls, HtmlReprMixin), name
            assert issubclass(cls, DisplayMixin) or name in ("SweepRun", "GaitResult"), name
        for name in mod.__all__:
            obj = getattr(mod, name)
            if isinstance(obj, type) and dataclasses.is_dataclass(obj) and \
                    name.endswith("Result"):
                assert name in names.split(), f"{pkg}.{name}: add it to RESULT_CLASSES"
            # any public result-like dataclass (it has a table form) displays in a notebook
            # (SectionPullout had none: found by tests/test_notebook.py)
            if isinstance(obj, type) and dataclasses.is_dataclass(obj) and \
                    hasattr(obj, "to_frame"):
                assert issubclass(obj, HtmlReprMixin), f"{pkg}.{name}: no notebook display"


def test_an_unnamed_structure_is_labelled_by_its_diameters() -> None:
    """predict(...).to_frame() of a Structure without a name: its diameters, not ''."""
    from exofric.geometry import Structure

    res = predict([Structure(10.0, 8.3, 4.97, 1.6)], 0.5, None, [0.3, 0.6],
                  squeeze_fn=_fake_squeeze)
    assert res.to_frame()["structure"].unique().tolist() == ["D 10 / d1 8.3 / ID 4.97 / d2 1.6 mm"]


def test_fit_gamma_takes_the_natural_objects() -> None:
    """fit_gamma(data, squeeze_result) gives exactly the four-array fit: a squeeze result and
    rig data (attributes), a DataFrame of pulls (clustered by its plateau column, as the CLI
    does) and a mapping. Reference: the same fit with the arrays (and groups) given by hand."""
    from exofric.friction import simulate_rig

    sq = squeeze(BASE, MAT, [0.2, 0.4, 0.6], mesh=MeshSpec(1, 12))
    run = simulate_rig(sq.pressure_mpa, sq.squeeze_force_n, 0.7, seed=2, repeats=3)
    by_hand = fit_gamma(run.pressure_mpa, run.friction_n, sq.pressure_mpa, sq.squeeze_force_n)
    assert fit_gamma(run, sq).gamma == by_hand.gamma
    pulls = pd.DataFrame({"pressure_mpa": run.pressure_mpa, "kinetic_n": run.friction_n,
                          "plateau": np.repeat([1, 2, 3, 4, 5, 6, 7, 8, 9], 1)[: len(run.test)]})
    groups = pulls["plateau"].to_numpy()
    ref = fit_gamma(run.pressure_mpa, run.friction_n, sq.pressure_mpa, sq.squeeze_force_n,
                    groups=groups)
    nat = fit_gamma(pulls, {"pressure_mpa": sq.pressure_mpa,
                            "squeeze_force_n": sq.squeeze_force_n})
    assert (nat.gamma, nat.gamma_ci95) == (ref.gamma, ref.gamma_ci95)
    from exofric.errors import InputError

    with pytest.raises(InputError, match="friction_n"):
        fit_gamma({"pressure_mpa": [0.3]}, sq)
    with pytest.raises(InputError, match="squeeze_pressure_mpa"):
        fit_gamma([0.3, 0.4], [1.0, 2.0], [0.3, 0.4])


def test_design_map_panels_show_ticks_and_the_star_leaves_the_number(same_backend) -> None:
    """Four panels on a 2 x 3 grid: each panel with an axis label also has tick values (the
    top-row panels above the gap had none); the best design's star sits at its marker's corner,
    not on the torque number (issue 34)."""
    from matplotlib.figure import Figure

    p = [0.2, 0.4, 0.6]
    designs = [(h, ln, od, w) for h in (10.0, 10.5) for ln in (116.0, 300.0)
               for od in (8.3, 8.8) for w in (1.1, 1.6) if not (h == 10.5 and ln == 300.0)]
    rows = pd.DataFrame([
        {"key": f"k{i}", "design_index": i, "name": f"d{i}", "family": "", "status": "ok",
         "pressure_mpa": pi, "squeeze_force_n": (100.0 + 20 * i) * pi / 0.6, "hole_mm": h,
         "tube_od_mm": od, "tube_id_mm": od - 3.3, "wire_mm": w, "length_mm": ln,
         "shore": 62.5, "deviation_pct": 0.0, "in_validated_region": True,
         "contact_onset_pressure_mpa": 0.0}
        for i, (h, ln, od, w) in enumerate(designs) for pi in p])
    search = search_designs(rows, 15.0, 0.1, 0.6, gamma=1.0)
    best = search.best
    assert best is not None
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = Figure(figsize=(10, 7))
    FigureCanvasAgg(fig)
    plots.plot_design_map(search, fig.subplots())
    fig.canvas.draw()
    panels = [a for a in fig.axes if a.get_label() != "<colorbar>"]
    assert len(panels) == 3   # 3 panels (the fourth combination is missing)
    for a in panels:
        if a.get_xlabel():
            assert any(t.get_visible() and t.get_text() for t in a.get_xticklabels()), a
        if a.get_ylabel():
            assert any(t.get_visible() and t.get_text() for t in a.get_yticklabels()), a
    star_panel = next(a for a in panels if any(
        getattr(c, "get_sizes", lambda: [])() is not None and len(c.get_offsets()) == 1
        and c.get_sizes()[0] == 170 for c in a.collections))
    star = next(c for c in star_panel.collections if len(c.get_offsets()) == 1
                and c.get_sizes()[0] == 170)
    number = next(t for t in star_panel.texts if t.get_text() == f"{best['torque_at_pmax_nm']:.0f}")
    box = number.get_window_extent(fig.canvas.get_renderer())           # display pixels
    cx, cy = star.get_offset_transform().transform(star.get_offsets())[0]
    half = 0.5 * np.sqrt(170.0) * fig.dpi / 72.0                        # the star's half size
    gap_x = max(box.x0 - cx, cx - box.x1, 0.0)
    gap_y = max(box.y0 - cy, cy - box.y1, 0.0)
    assert np.hypot(gap_x, gap_y) > 0.5 * half, (box, cx, cy)   # the star leaves the number
