"""Calibration figures: Fig 5b (diameter against pressure with the trials) and Table 1.

Presentation only: results are read through their attributes (MPa, mm, %); each function
draws on a given Axes/Figure or a new one, which it returns.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, new_axes, new_figure

if TYPE_CHECKING:
    from exofric.calibration import CalibrationResult
    from exofric.reproduction import CalibrationStage

__all__ = ["plot_calibration", "plot_table1"]


def plot_calibration(result: CalibrationResult, ax: Any | None = None) -> Any:
    """Fig 5b: measured and simulated outer diameter (mm) against pressure (MPa).

    Per hardness group: the measured points and the final model curve (bold); without
    known hardness also every finite trial of the history (thin, grey), each hardness
    labelled once with its Shore A in a margin on the right, spread so labels never overlap.
    Simulated curves start from the undeformed OD at 0 MPa.
    Returns the Axes.

    Parameters
    ----------
    result : CalibrationResult
        From :func:`exofric.calibration.calibrate` (pressures in MPa, diameters in mm).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.calibration import InflationData, calibrate
    >>> r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=5.0, model="paper-table1",
    ...               method="bounded")
    >>> ax = plot_calibration(r, Figure().subplots())
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('inflation pressure P (MPa)', 'tube outer diameter (mm)')
    """
    ax, created = new_axes(ax, (7.0, 4.6))
    labels: list[tuple[float, dict[str, float]]] = []
    d = result.data
    od = result.tube_od_mm
    for gi, (g, idx) in enumerate(d.groups()):
        p = d.pressure_mpa[idx]
        pc = p if p[0] == 0.0 else np.concatenate([[0.0], p])

        def curve(sim: np.ndarray, p: np.ndarray = p) -> np.ndarray:
            return sim if p[0] == 0.0 else np.concatenate([[od], sim])

        colour = f"C{gi % 10}"
        if g is None:
            ends: dict[str, float] = {}
            for t in result.history:
                sim = np.asarray(t.outer_diameter_mm)[idx]
                if not np.all(np.isfinite(sim)):
                    continue
                ax.plot(pc, curve(sim), "-", color="0.7", lw=0.8, zorder=1)
                ends.setdefault(f"{t.shore:.4g}", float(sim[-1]))  # one label per hardness
            labels.append((float(p[-1]), ends))
        label = "" if g is None else f" (Shore {g:g})"
        ax.plot(p, d.outer_diameter_mm[idx], "o", color=colour, label=f"measured{label}",
                zorder=3)
        ax.plot(pc, curve(result.simulated_mm[idx]), "-", color=colour, lw=2, zorder=2,
                label=None if g is not None else f"model, Shore {result.shore:.4g}")
    if labels:
        _label_trials(ax, labels)
    ax.set_xlabel("inflation pressure P (MPa)")
    ax.set_ylabel("tube outer diameter (mm)")
    shore_txt = "known" if result.shore is None else f"{result.shore:.4g}"
    ax.set_title(f"{result.method} ({result.model}): Shore {shore_txt}, ID "
                 f"{result.tube_id_mm:.4g} mm, avg error {result.average_error_pct:.2f}%",
                 fontsize=SMALL + 1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL, loc="upper left")
    finish(ax.figure, created)
    return ax


def _label_trials(ax: Any, labels: list[tuple[float, dict[str, float]]]) -> None:
    """Write each trial's Shore A at its curve's end, spread apart, in a margin on the right."""
    ax.autoscale_view()
    lo, hi = ax.get_ylim()
    x_lo, x_hi = ax.get_xlim()
    height_pt = ax.figure.get_figheight() * 72.0 * ax.get_position().height
    gap = (hi - lo) * SMALL * 1.25 / max(height_pt, 1.0)   # one text line, in data units
    for x_end, ends in labels:
        items = sorted(ends.items(), key=lambda kv: kv[1])
        ys = [y for _, y in items]
        for i in range(1, len(ys)):          # push up, then shift the stack back into view
            ys[i] = max(ys[i], ys[i - 1] + gap)
        over = ys[-1] - (hi - 0.5 * gap) if ys else 0.0
        if over > 0:
            ys = [y - over for y in ys]
        for (text, y_end), y in zip(items, ys, strict=True):
            ax.annotate(text, (x_end, y_end), xytext=(x_end + 0.03 * (x_hi - x_lo), y),
                        textcoords="data", fontsize=SMALL, color="0.4", va="center",
                        arrowprops={"arrowstyle": "-", "color": "0.75", "lw": 0.6})
    ax.set_xlim(x_lo, x_hi + 0.13 * (x_hi - x_lo))      # room for the labels
    ax.text(0.99, 0.01, "grey: trials (Shore A)", transform=ax.transAxes, ha="right",
            va="bottom", fontsize=SMALL, color="0.4")


def plot_table1(
    stage: CalibrationStage, table1: Mapping[str, Any], fig: Any | None = None
) -> Any:
    """Table 1 and Fig 5b of the reproduction: ANSYS vs our diameters, Shore from the test.

    Left: per Table 1 Shore column, the paper's ANSYS diameters (markers) and ours (lines) at
    the fitted tube ID. Right: the bisection and bounded fits to the test column, the paper's
    62.5 Hs column and the test points. ``table1`` holds ``pressure_mpa``,
    ``simulated_outer_diameter_mm`` (four columns) and ``test_outer_diameter_mm`` (MPa, mm).
    Returns the Figure.

    Parameters
    ----------
    stage : CalibrationStage
        The calibration stage of :func:`exofric.reproduction.reproduce` (diameters in mm).
    table1 : mapping
        The paper's Table 1 (:func:`exofric.paper.table1`; pressures in MPa, diameters in mm).
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric import paper
    >>> fig = plot_table1(fast_result.calibration, paper.table1(), Figure())
    >>> len(fig.axes), fig.axes[1].get_title()
    (2, 'Shore from the test column (Fig 5b)')
    """
    fig, created = new_figure(fig, (10.4, 4.8))
    a1, a2 = fig.subplots(1, 2)
    for i, col in enumerate(stage.columns):
        c = f"C{i}"
        a1.plot(col["pressure_mpa"], col["paper_outer_diameter_mm"], "o", color=c,
                label=f"paper ANSYS {col['shore']:g} Hs")
        a1.plot(col["pressure_mpa"], col["our_outer_diameter_mm"], "-", color=c,
                label=f"exofric FE {col['shore']:g} Hs")
    a1.set_title(f"Table 1 columns; tube ID fitted = {stage.tube_id_mm:.4f} mm",
                 fontsize=SMALL + 1)
    for res, lab, sty in ((stage.bisection, "bisection", "-"), (stage.bounded, "bounded", "--")):
        a2.plot(res.data.pressure_mpa, res.simulated_mm, sty,
                label=f"exofric {lab}: Shore {res.shore:.2f} ({res.average_error_pct:.2f}%)")
    a2.plot(table1["pressure_mpa"], table1["simulated_outer_diameter_mm"][3], "s", mfc="none",
            color="0.4", label="paper ANSYS 62.5 Hs (0.46%)")
    a2.plot(table1["pressure_mpa"], table1["test_outer_diameter_mm"], "o", color="tab:red",
            label="test (Table 1)")
    a2.set_title("Shore from the test column (Fig 5b)", fontsize=SMALL + 1)
    for ax in (a1, a2):
        ax.set_xlabel("pressure P (MPa)")
        ax.set_ylabel("tube outer diameter (mm)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=SMALL, loc="upper left")
    finish(fig, created)
    return fig
