"""Calibration figures: Fig 5b (diameter against pressure with the trials), Table 1, and the
joint material calibration (data against model per test, misfit profile).

Presentation only: results are read through their attributes (MPa, mm, %); each function
draws on a given Axes/Figure or a new one, which it returns.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, new_axes, new_figure

if TYPE_CHECKING:
    from exofric.calibration import CalibrationResult, MaterialCalibration
    from exofric.reproduction import CalibrationStage

__all__ = ["plot_calibration", "plot_material_calibration", "plot_table1"]


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


_MODE_COLOURS = {"uniaxial": "tab:blue", "biaxial": "tab:orange", "planar": "tab:green"}


def plot_material_calibration(result: MaterialCalibration, fig: Any | None = None) -> Any:
    """Joint material calibration: data against model for each test, and the misfit profile.

    One panel per kind of test: inflation (outer diameter in mm against pressure in MPa; the
    FE model at the data's pressures, joined from the undeformed OD), tensile (nominal stress
    in MPa against stretch, every mode given; the model's closed-form curve), ring (force in N
    against pin displacement in mm; the FE model at the data's displacements). The last panel
    is the misfit profile along the worst-determined direction: delta chi^2 (unitless; 1 = one
    standard deviation) against the step in relative parameters (%). A flat profile is a
    direction the data do not see. Returns the Figure.

    Parameters
    ----------
    result : MaterialCalibration
        From :func:`exofric.calibration.calibrate_material` (mm, N, MPa).
    fig : matplotlib Figure, optional
        An empty figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.calibration import calibrate_material
    >>> lam = np.linspace(1.1, 2.5, 6)
    >>> r = calibrate_material("neo-hookean", tensile=(lam, 0.41 * (lam - lam**-2)))
    >>> fig = plot_material_calibration(r, Figure())
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['stretch (unitless)', 'step along the worst direction (% of each parameter)']
    """
    ds = result.datasets
    kinds = [k for k in ("inflation", "tensile", "ring")
             if (k == "tensile" and any(m in ds for m in _MODE_COLOURS)) or k in ds]
    prof = result.identifiability.profile
    n = len(kinds) + (prof is not None)
    ncol = 1 if n == 1 else 2
    nrow = (n + ncol - 1) // ncol
    fig, created = new_figure(fig, (5.2 * ncol, 3.9 * nrow))
    grid = fig.subplots(nrow, ncol, squeeze=False)
    axes = list(grid.ravel())
    if len(axes) > n:  # a free slot: the fitted values as text
        _summary(axes[n], result)
        for extra in axes[n + 1:]:
            extra.remove()
    for ax, kind in zip(axes, kinds, strict=False):
        if kind == "inflation":
            d = ds["inflation"]
            od = result.tube_od_mm if result.tube_od_mm is not None else float(d.measured[0])
            p = np.concatenate([[0.0], d.x]) if d.x[0] > 0 else d.x
            f = np.concatenate([[od], d.fitted]) if d.x[0] > 0 else d.fitted
            ax.plot(d.x, d.measured, "o", color="tab:red", mfc="none", label="measured")
            ax.plot(p, f, "-", color="k", lw=1.6,
                    label=f"model (FE, {result.ends}): RMS {d.rms:.2g} mm")
            ax.set_xlabel("inflation pressure P (MPa)")
            ax.set_ylabel("tube outer diameter (mm)")
            ax.set_title("inflation", fontsize=SMALL + 1)
        elif kind == "tensile":
            for mode, c in _MODE_COLOURS.items():
                if mode not in ds:
                    continue
                d = ds[mode]
                lam = np.linspace(min(1.0, float(d.x.min())), max(1.0, float(d.x.max())), 200)
                ax.plot(d.x, d.measured, "o", color=c, mfc="none", ms=5, label=f"{mode} data")
                ax.plot(lam, result.model.stress_mpa(mode, lam), "-", color=c, lw=1.6,
                        label=f"model: RMS {d.rms:.3g} MPa")
            ax.set_xlabel("stretch (unitless)")
            ax.set_ylabel("nominal stress P (MPa)")
            ax.set_title("tensile", fontsize=SMALL + 1)
        else:
            d = ds["ring"]
            x = np.concatenate([[0.0], d.x]) if d.x[0] > 0 else d.x
            f = np.concatenate([[0.0], d.fitted]) if d.x[0] > 0 else d.fitted
            ax.plot(d.x, d.measured, "o", color="tab:purple", mfc="none", label="measured")
            ax.plot(x, f, "-", color="k", lw=1.6, label=f"model (FE): RMS {d.rms:.3g} N")
            ax.set_xlabel("pin displacement (mm)")
            ax.set_ylabel("force on one pin (N)")
            ax.set_title("ring test", fontsize=SMALL + 1)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=SMALL, loc="upper left")
    if prof is not None:
        ax = axes[len(kinds)]
        ok = np.isfinite(prof.delta_chi2)
        ax.plot(100 * prof.step_rel[ok], prof.delta_chi2[ok], "o-", color="k", ms=4)
        ax.axhline(1.0, color="tab:red", lw=0.8, ls="--", label="delta chi^2 = 1 (1 sd)")
        if np.isfinite(prof.sd_rel):
            for sgn in (-1, 1):
                ax.axvline(100 * sgn * prof.sd_rel, color="0.6", lw=0.8, ls=":")
        ax.set_xlabel("step along the worst direction (% of each parameter)")
        ax.set_ylabel("misfit change delta chi^2 (unitless)")
        direction = ", ".join(f"{c:+.2f} {nm}" for nm, c in zip(prof.names, prof.direction,
                                                                strict=True))
        ax.set_title(f"profile: {direction}", fontsize=SMALL)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=SMALL, loc="upper center")
    ident = result.identifiability
    id_txt = "" if result.tube_id_mm is None else f", tube ID {result.tube_id_mm:.4g} mm"
    verdict = "identifiable" if ident.identifiable else "NOT identifiable"
    fig.suptitle(f"{result.model.name}: mu = {result.model.shear_modulus_mpa:.4g} +- "
                 f"{result.shear_modulus_stderr_mpa:.2g} MPa{id_txt}; {verdict} (cond "
                 f"{ident.condition_number:.3g})", fontsize=SMALL + 1)
    finish(fig, created)
    return fig


def _summary(ax: Any, result: MaterialCalibration) -> None:
    """The fitted parameters +- standard errors, correlation and misfit, as text in ``ax``."""
    ax.set_axis_off()
    se = dict(zip(result.names, result.stderr, strict=True))
    lines = [f"{result.model.name} ({result.ends}); standard errors from {result.stderr_from}"]
    for n, v in zip(result.model.param_names, result.model.params, strict=True):
        unit = " MPa" if n.endswith("_mpa") else ""
        lines.append(f"  {n} = {v:.5g} +- {se[n]:.2g}{unit}")
    lines.append(f"  mu = {result.model.shear_modulus_mpa:.5g} +- "
                 f"{result.shear_modulus_stderr_mpa:.2g} MPa")
    if result.tube_id_mm is not None:
        tid = (f"{result.tube_id_mm:.4f} +- {result.tube_id_stderr_mm:.4f} mm"
               if result.tube_id_stderr_mm is not None else f"{result.tube_id_mm:.4f} mm (given)")
        lines.append(f"  tube ID = {tid}")
    ident = result.identifiability
    if ident.max_correlation_pair:
        a, b = ident.max_correlation_pair
        lines.append(f"largest correlation: {a}, {b}: {ident.max_correlation:+.4f}")
    lines.append(f"condition number {ident.condition_number:.3g}; worst direction known to "
                 f"+-{100 * ident.worst_sd_rel:.2g} %")
    for k, d in result.datasets.items():
        lines.append(f"{k}: {d.n_points} point{'s' if d.n_points > 1 else ''}, RMS "
                     f"{d.rms:.3g} {d.unit} ({d.rms_pct:.2g} %)")
    ax.text(0.0, 1.0, "\n".join(lines), transform=ax.transAxes, va="top", ha="left",
            fontsize=SMALL, family="monospace")
