"""Figure content checks for issue 20 (no image golden files): legends off the data, markers,
the paper's printed values marked, every design on the map, sizes for the report column."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from exofric.friction import MeasuredCurve, fit_gamma, paper_structures, predict
from exofric.plots import plot_control_cases, plot_gamma_fit, plot_predictions, plot_torque

mpl = pytest.importorskip("matplotlib")
mpl.use("Agg")


def _fake(s, m, p):  # type: ignore[no-untyped-def]
    return SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * np.asarray(p))


def test_torque_legend_is_off_the_limit_line() -> None:
    ax = plot_torque([f"test {i}" for i in range(1, 8)], [17, 12, 21, 16, 18, 11, 14],
                     reference=([0, 2], [18.05, 30.0], "paper"), limit_nm=40.0)
    fig = ax.figure
    r = fig.canvas.get_renderer()
    fig.draw(r)
    leg = ax.get_legend().get_window_extent(r)
    y40 = ax.transData.transform((0.0, 40.0))[1]
    assert leg.y0 > y40 and leg.y0 >= ax.get_window_extent(r).y1 - 1


def test_predictions_show_both_curves_and_the_paper_max_error() -> None:
    meas = {"test 2": MeasuredCurve.of([0.3, 0.6], [80.0, 170.0])}
    r = predict(paper_structures()[1:2], 0.7, None, [0.3, 0.6], squeeze_fn=_fake,
                measured=meas)
    fig = plot_predictions(r.predictions, "SYNTHETIC", paper_max_error_pct={"test 2": -12.0})
    a1, a2 = fig.axes
    pred = next(ln for ln in a1.lines if ln.get_label().startswith("predicted"))
    tested = next(ln for ln in a1.lines if ln is not pred)
    assert pred.get_marker() == "s" and tested.get_marker() == "o"
    assert tested.get_markersize() > pred.get_markersize()     # red circles show around it
    assert tested.get_label().startswith("synthetic")
    assert any(np.allclose(ln.get_ydata(), -12.0) for ln in a2.lines)


@pytest.mark.filterwarnings("ignore::exofric.friction.ApplicabilityWarning")
def test_predictions_without_measured_curves_draw_one_panel() -> None:
    r = predict(paper_structures(), 0.7, None, [0.3, 0.6], squeeze_fn=_fake)
    fig = plot_predictions(r.predictions)
    assert len(fig.axes) == 1 and len(fig.axes[0].lines) == 7


def test_gamma_fit_labels_synthetic_data_and_the_paper_point() -> None:
    fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
                    [100.0, 200.0, 268.55])
    fig = plot_gamma_fit(fit, "", data_label="synthetic (virtual rig)",
                         paper_point=(0.6, 180.49, "paper: 180.49 N at 0.6 MPa"))
    texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert texts[0] == "synthetic (virtual rig) F" and "paper: 180.49 N at 0.6 MPa" in texts
    assert fig.get_size_inches()[0] * 130 <= 1400


def test_control_legend_covers_no_axes() -> None:
    from exofric.reproduction import ControlSetup, compare

    c = compare(ControlSetup.default(duration_s=8.0))
    for pressure in (True, False):
        fig = plot_control_cases(c.cases, pressure=pressure)
        r = fig.canvas.get_renderer()
        fig.draw(r)
        leg = fig.legends[0].get_window_extent(r)
        assert not any(leg.overlaps(a.get_window_extent(r)) for a in fig.axes)
        assert "paper: without 5.73 s, with 4.20 s" in fig.axes[1].get_title()
        assert fig.get_size_inches()[0] * 130 <= 1400


def test_design_map_draws_every_design_with_a_legend() -> None:
    import pandas as pd

    from exofric.design import search_designs
    from exofric.plots import plot_design_map

    p = [0.2, 0.4, 0.6]
    rows = []
    for k, (hole, od, forces) in enumerate([(10.0, 8.3, [200, 400, 600]),
                                            (10.5, 8.3, [50, 100, 150]),
                                            (10.0, 8.8, [60, 120, 180])]):
        rows.append(pd.DataFrame({"key": str(k), "design_index": k, "name": str(k), "family": "",
                                  "status": "ok", "pressure_mpa": p,
                                  "squeeze_force_n": [float(f) for f in forces],
                                  "hole_mm": hole, "tube_od_mm": od, "tube_id_mm": 4.97,
                                  "wire_mm": 1.6, "length_mm": 116.0, "shore": 62.5,
                                  "deviation_pct": 0.0, "in_validated_region": True,
                                  "contact_onset_pressure_mpa": 0.0}))
    s = search_designs(pd.concat(rows, ignore_index=True), 40.0, 0.1, 0.6, gamma=1.0)
    ax = plot_design_map(s)
    panels = [a for a in ax.figure.axes if a.get_xlabel() or a.get_title()]
    drawn = sum(len(c.get_offsets()) for a in panels for c in a.collections)
    assert drawn == 3 + (s.best is not None)   # 3 designs in 2 panels (D), plus the star
    labels = [t.get_text() for t in ax.figure.legends[0].get_texts()]
    assert any(t.startswith("square: reaches 40 Nm") for t in labels)
    assert any(t.startswith("black edge") for t in labels)
