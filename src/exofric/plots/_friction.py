"""Figures for the friction model: gamma fit with residuals, predictions, cubic fit, torque.

Presentation only: each function takes computed results (read through their attributes) and
draws on a given Axes/Figure or a new one, which it returns (write it with
:func:`exofric.plots.save`). Units: MPa, N, %, Nm.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, is_synthetic, new_axes, new_figure

if TYPE_CHECKING:
    from exofric.friction import GammaFit, Prediction

__all__ = ["plot_gamma_fit", "plot_predictions", "plot_cubic_fit", "plot_torque"]


def plot_gamma_fit(
    fit: GammaFit,
    title: str = "",
    *,
    fig: Any | None = None,
    data_label: str | None = None,
    paper_point: tuple[float, float, str] | None = None,
) -> Any:
    """Data vs fitted friction (left), residuals in N (middle) and in % (right).

    Parameters
    ----------
    fit : GammaFit
        Result of :func:`exofric.friction.fit_gamma`.
    title : str
        Figure title (e.g. ``"SYNTHETIC rig data"``).
    fig : matplotlib Figure, optional
        Empty figure to draw the three Axes on (default a new one).
    data_label : str, optional
        What the friction points are, for the legend (``"<data_label> F"``): e.g.
        ``"measured"`` or ``"synthetic (virtual rig)"``. Default: the latter when ``title``
        says SYNTHETIC, else ``"measured"``.
    paper_point : (float, float, str), optional
        A published point to show on the left panel: pressure (MPa), friction (N) and its
        label, e.g. the paper's 180.49 N at 0.6 MPa (``exofric.paper.scalar(
        "base_friction_at_0_6_mpa_n")``); a black star.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.friction import fit_gamma
    >>> fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
    ...                 [100.0, 200.0, 268.55])
    >>> fig = plot_gamma_fit(fit, "SYNTHETIC", fig=Figure(), paper_point=(0.6, 180.49, "paper"))
    >>> [ax.get_ylabel() for ax in fig.axes][:2]
    ['friction F (N)', 'residual F^ - F (N)']
    >>> [t.get_text() for t in fig.axes[0].get_legend().get_texts()][::2]
    ['synthetic (virtual rig) F', 'paper']
    """
    fig, created = new_figure(fig, (10.5, 3.7))
    a1, a2, a3 = fig.subplots(1, 3)
    if data_label is None:
        data_label = "synthetic (virtual rig)" if is_synthetic(title) else "measured"
    p = np.asarray(fit.pressure_mpa)
    a1.plot(p, fit.friction_n, "o", color="tab:red", label=f"{data_label} F")
    lab = f"gamma N, gamma = {fit.gamma:.4f}"
    if fit.kind == "affine":
        lab = f"gamma N + F0, gamma = {fit.gamma:.4f},\nF0 = {fit.model.f0_n:.2f} N"
    o = np.argsort(p)
    a1.plot(p[o], np.asarray(fit.predicted_friction_n)[o], "-", color="k", label=lab)
    if paper_point is not None:
        a1.plot([paper_point[0]], [paper_point[1]], "*", ms=13, color="k", mfc="gold",
                zorder=4, label=paper_point[2])
    a1.set_ylabel("friction F (N)")
    y0, y1 = a1.get_ylim()
    a1.set_ylim(y0, y1 + 0.45 * (y1 - y0))          # headroom: the legend sits above the data
    a1.legend(fontsize=SMALL, loc="upper left")
    lo, hi = fit.gamma_ci95
    a1.set_title(f"95% CI [{lo:.4f}, {hi:.4f}]\n({fit.ci_method})", fontsize=SMALL + 1)
    a2.plot(p, fit.residual_n, "o", color="tab:blue")
    a2.set_ylabel("residual F^ - F (N)")
    a2.set_title(f"n = {fit.n_points} points", fontsize=SMALL + 1)
    a3.plot(p, fit.point_relative_error_pct, "s", color="tab:orange")
    a3.set_ylabel("relative error (F^ - F)/F (%)")
    a3.set_title(f"mean |rel. error| = {fit.relative_error_pct:.2f}%", fontsize=SMALL + 1)
    for ax in (a1, a2, a3):
        ax.set_xlabel("pressure P (MPa)")
        ax.grid(alpha=0.3)
    for ax in (a2, a3):
        ax.axhline(0.0, color="0.5", lw=0.8)
    if title:
        fig.suptitle(title)
    finish(fig, created)
    return fig


def _one_panel(preds: Sequence[Prediction], fig: Any,
               bands: Mapping[str, tuple[Sequence[float], Sequence[float]]] | None = None) -> Any:
    """All predicted curves on one Axes (no measured curves to compare with): each labelled
    with its geometric deviation from the base group; dashed (and said so in the title) only
    when some curve is outside the validated region; tolerance bands shaded (issue 34)."""
    ax = fig.subplots()
    marks = "osD^vP*Xh<>"
    any_outside = False
    for i, pr in enumerate(preds):
        dev = pr.deviation
        ok = dev.in_validated_region
        any_outside |= not ok
        name = pr.structure.name or f"structure {i + 1}"
        if bands and pr.structure.name in bands:
            lo, hi = bands[pr.structure.name]
            ax.fill_between(pr.pressure_mpa, lo, hi, color=f"C{i % 10}", alpha=0.18, lw=0,
                            label=f"{name}: 5-95 % band of the tolerances")
        ax.plot(pr.pressure_mpa, pr.predicted_friction_n, "-" if ok else "--",
                marker=marks[i % len(marks)], ms=4, color=f"C{i % 10}",
                label=f"{name} (deviation {dev.deviation_pct:.1f} %"
                      + (")" if ok else ", outside)"))
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("predicted friction F (N)")
    ax.set_title("predicted friction; deviation: of the geometry from the base group"
                 + ("\n(dashed: outside the validated region)" if any_outside else ""),
                 fontsize=SMALL + 1)
    ax.grid(alpha=0.3)
    entries = len(ax.get_legend_handles_labels()[0])
    y0, y1 = ax.get_ylim()
    ax.set_ylim(y0, y1 + 0.07 * entries * (y1 - y0))   # headroom: the legend sits above the data
    ax.legend(fontsize=SMALL, loc="upper left")
    return ax


def plot_predictions(
    preds: Sequence[Prediction],
    title: str = "",
    *,
    fig: Any | None = None,
    paper_max_error_pct: Mapping[str, float] | None = None,
    data_label: str | None = None,
    bands: Mapping[str, tuple[Sequence[float], Sequence[float]]] | None = None,
) -> Any:
    """Per structure: predicted vs tested friction and the relative error curve (Figs 8-10).

    One row of two Axes per prediction on ``fig`` (an empty Figure; default a new one): left,
    the tested points (large red circles, dashed) under the predicted curve (black line with
    small white squares), so both stay visible where they agree; right, the relative error
    and, when given, the paper's printed maximum error (red dashed line). When no prediction
    has a measured curve, one Axes compares all predicted curves instead. Returns the Figure.

    Parameters
    ----------
    preds : sequence of Prediction
        E.g. ``predict(...).predictions`` (:func:`exofric.friction.predict`; MPa, N, %).
    title : str
        Figure title (none when empty).
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).
    paper_max_error_pct : mapping of str to float, optional
        The paper's printed maximum relative error (%) per structure name (e.g.
        ``{"test 2": -12.0}`` from ``exofric.paper.load()["max_relative_error"]``).
    data_label : str, optional
        Legend label of the tested points; default ``"synthetic 'tested' (virtual rig)"``
        when ``title`` says SYNTHETIC, else ``"tested"``.
    bands : mapping of str to (sequence, sequence), optional
        Per structure name, the 5 % and 95 % friction (N) at its pressures, shaded around the
        predicted curve (``exofric predict --tolerance``).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from matplotlib.figure import Figure
    >>> from exofric.friction import MeasuredCurve, paper_structures, predict
    >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
    >>> r = predict(paper_structures()[:2], 0.7, None, [0.3, 0.6], squeeze_fn=fake)
    >>> fig = plot_predictions(r.predictions, "stand-in squeeze", fig=Figure())
    >>> len(fig.axes), len(fig.axes[0].lines)          # no measured curves: one panel
    (1, 2)
    >>> meas = {"test 2": MeasuredCurve.of([0.3, 0.6], [80.0, 170.0])}
    >>> r = predict(paper_structures()[1:2], 0.7, None, [0.3, 0.6], squeeze_fn=fake,
    ...             measured=meas, base=paper_structures()[0])
    >>> fig = plot_predictions(r.predictions, fig=Figure(), paper_max_error_pct={"test 2": -12.0})
    >>> len(fig.axes), fig.axes[0].get_title(), fig.axes[1].get_legend().get_texts()[1].get_text()
    (2, 'test 2: deviation 9.1%', "paper's printed max -12.00%")
    """
    fig, created = new_figure(fig, (6.4, 4.4) if not any(p.measured is not None for p in preds)
                              else (10.0, 3.4 * max(len(preds), 1) + 0.4))
    if not any(p.measured is not None for p in preds):
        _one_panel(preds, fig, bands)
        if title:
            fig.suptitle(title)
        finish(fig, created)
        return fig
    if data_label is None:
        data_label = "synthetic 'tested' (virtual rig)" if is_synthetic(title) else "tested"
    paper_err = dict(paper_max_error_pct or {})
    axes = fig.subplots(len(preds), 2, squeeze=False)
    for (a1, a2), pr in zip(axes, preds, strict=False):
        if pr.measured is not None:
            a1.plot(pr.measured.pressure_mpa, pr.measured.friction_n, "o--", ms=8, lw=1.2,
                    color="tab:red", alpha=0.8, label=data_label, zorder=2)
        a1.plot(pr.pressure_mpa, pr.predicted_friction_n, "-", color="k", lw=1.4, marker="s",
                ms=3.5, mfc="white", mew=1.0, label="predicted (exofric)", zorder=3)
        if bands and pr.structure.name in bands:
            lo, hi = bands[pr.structure.name]
            a1.fill_between(pr.pressure_mpa, lo, hi, color="0.6", alpha=0.3, lw=0,
                            label="predicted 5-95 % band", zorder=1)
        if pr.measured is not None:
            a2.plot(pr.measured.pressure_mpa, pr.relative_error_pct, "o-", color="tab:blue",
                    label="exofric: (F^ - F)/F")
            m = pr.max_relative_error_pct
            a2.set_title(f"max relative error {m:.2f}%" if m is not None else "",
                         fontsize=SMALL + 1)
        else:
            a2.text(0.5, 0.5, "no measured curve", ha="center", va="center",
                    transform=a2.transAxes)
        pe = paper_err.get(pr.structure.name)
        if pe is not None:
            a2.axhline(pe, color="tab:red", ls="--", lw=1.2, label=f"paper's printed max {pe:.2f}%")
        if a2.get_legend_handles_labels()[0]:
            a2.legend(fontsize=SMALL, loc="best")
        dev = pr.deviation
        flag = "" if dev.in_validated_region else " (outside validated region)"
        a1.set_title(f"{pr.structure.name}: deviation {dev.deviation_pct:.1f}%{flag}",
                     fontsize=SMALL + 1)
        a1.set_xlabel("pressure P (MPa)")
        a1.set_ylabel("friction F (N)")
        a1.legend(fontsize=SMALL, loc="upper left")
        a1.grid(alpha=0.3)
        a2.axhline(0.0, color="0.5", lw=0.8)
        a2.set_xlabel("pressure P (MPa)")
        a2.set_ylabel("relative error (%)")
        a2.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    finish(fig, created)
    return fig


def plot_cubic_fit(
    pressure_mpa: Sequence[float],
    squeeze_force_n: Sequence[float],
    ours: Any,
    paper_eq8: Any,
    inverse_mpa: Mapping[str, float],
    target_n: float,
    ax: Any | None = None,
) -> Any:
    """FE N(P) points, our cubic and the paper's Eq 8, and the pressures for a target (Fig 11).

    Parameters
    ----------
    pressure_mpa, squeeze_force_n : sequence of float
        FE points (MPa, N).
    ours, paper_eq8 : CubicFit
        Cubics N(P) (callable on MPa, with ``p_min_mpa``, ``p_max_mpa``; ``ours.r2``).
    inverse_mpa : mapping
        Pressures (MPa) for ``target_n``: keys ``eq9_mpa``, ``paper_printed_mpa``,
        ``our_exact_curve_mpa`` (each a dotted vertical line).
    target_n : float
        Target friction (N), for the labels.
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric import paper
    >>> from exofric.friction import CubicFit
    >>> p = np.linspace(0.2, 0.6, 5)
    >>> eq8 = CubicFit(paper.eq8(), 0.2, 0.6)
    >>> ours = CubicFit.fit(p, eq8(p))
    >>> inv = {"eq9_mpa": 0.2926, "paper_printed_mpa": 0.26, "our_exact_curve_mpa": 0.2926}
    >>> ax = plot_cubic_fit(p, eq8(p), ours, eq8, inv, 54.40, Figure().subplots())
    >>> len(ax.lines)          # FE points, two cubics, three pressures
    6
    """
    ax, created = new_axes(ax, (7.2, 5.4))
    pp = np.linspace(ours.p_min_mpa, ours.p_max_mpa, 101)
    ax.plot(pressure_mpa, squeeze_force_n, "o", label="exofric FE, test 5")
    ax.plot(pp, ours(pp), "-", label=f"exofric cubic (R^2 = {ours.r2:.5f})")
    ax.plot(pp, paper_eq8(pp), "k--", label="paper Eq 8")
    # the paper printed 0.26 MPa: shown as printed (:g), the computed ones to 4 decimals
    for key, lab, col, fmt in (("eq9_mpa", "Eq 9 inverse", "k", ".4f"),
                               ("paper_printed_mpa", "paper's printed value", "tab:red", "g"),
                               ("our_exact_curve_mpa", "exofric FE + our gamma", "tab:blue",
                                ".4f")):
        ax.axvline(inverse_mpa[key], color=col, ls=":", lw=1.2,
                   label=f"P for {target_n:g} N, {lab}: {inverse_mpa[key]:{fmt}} MPa")
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("squeezing force N (N)")
    ax.set_title("Fig 11: cubic fit for test 5", fontsize=SMALL + 1)
    ax.grid(alpha=0.3)
    # below the Axes: the vertical lines cross every height, so no corner inside is free
    ax.legend(fontsize=SMALL, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
              frameon=False)
    finish(ax.figure, created)
    return ax


def plot_torque(
    names: Sequence[str],
    torque_nm: Sequence[float],
    ax: Any | None = None,
    *,
    reference: tuple[Sequence[float], Sequence[float], str] | None = None,
    limit_nm: float | None = None,
    limit_label: str = "required torque (max)",
    pressure_mpa: float = 0.6,
) -> Any:
    """Bar chart of the torque T = F R (Nm) per structure at ``pressure_mpa`` (MPa).

    ``reference`` = (bar positions, torques in Nm, label) adds red stars (e.g. the paper's
    measured values); ``limit_nm`` a dashed horizontal line. Returns the Axes.

    Parameters
    ----------
    names : sequence of str
        Bar labels (structure names).
    torque_nm : sequence of float
        Torque per structure in Nm.
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).
    reference : (sequence of float, sequence of float, str) or None
        Bar positions (0-based), torques in Nm and a legend label for comparison stars.
    limit_nm : float or None
        Required torque in Nm, drawn as a dashed line.
    limit_label : str
        Legend label of that line.
    pressure_mpa : float
        Pressure in MPa at which the torques hold (for the axis label).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> ax = plot_torque(["test 1", "test 3"], [18.05, 30.0], Figure().subplots(),
    ...                  reference=([1], [30.0], "paper"), limit_nm=40.0)
    >>> len(ax.patches), ax.get_ylabel()
    (2, 'torque T = F R at 0.6 MPa (Nm)')
    """
    ax, created = new_axes(ax, (7.2, 4.4))
    x = np.arange(len(names))
    ax.bar(x, list(torque_nm), color="tab:blue", label="exofric (predicted)")
    if reference is not None:
        ax.plot(list(reference[0]), list(reference[1]), "*", ms=12, color="tab:red",
                label=reference[2])
    if limit_nm is not None:
        ax.axhline(limit_nm, color="k", ls="--", label=limit_label)
        ax.set_ylim(0.0, 1.12 * max([limit_nm, *torque_nm]))
    ax.set_xticks(x, list(names), rotation=30)
    ax.set_ylabel(f"torque T = F R at {pressure_mpa:g} MPa (Nm)")
    ax.grid(alpha=0.3, axis="y")
    # above the Axes, never on the bars or the limit line
    ax.legend(fontsize=SMALL, loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=2,
              frameon=False, borderaxespad=0.0)
    finish(ax.figure, created)
    return ax
