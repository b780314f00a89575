"""Figures for the friction model: gamma fit with residuals, predictions, cubic fit, torque.

Presentation only: each function takes computed results (read through their attributes) and
draws on a given Axes/Figure or a new one, which it returns (write it with
:func:`exofric.plots.save`). Units: MPa, N, %, Nm.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import finish, new_axes, new_figure

if TYPE_CHECKING:
    from exofric.friction import GammaFit, Prediction

__all__ = ["plot_gamma_fit", "plot_predictions", "plot_cubic_fit", "plot_torque"]


def plot_gamma_fit(fit: GammaFit, title: str = "", *, fig: Any | None = None) -> Any:
    """Measured vs fitted friction (left), residuals in N (middle) and in % (right).

    Parameters
    ----------
    fit : GammaFit
        Result of :func:`exofric.friction.fit_gamma`.
    title : str
        Figure title (e.g. ``"SYNTHETIC rig data"``).
    fig : matplotlib Figure, optional
        Empty figure to draw the three Axes on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.friction import fit_gamma
    >>> fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 190.0], [0.2, 0.4, 0.6],
    ...                 [100.0, 200.0, 268.55])
    >>> fig = plot_gamma_fit(fit, "three points", fig=Figure())
    >>> [ax.get_ylabel() for ax in fig.axes][:2]
    ['friction F (N)', 'residual F^ - F (N)']
    """
    fig, created = new_figure(fig, (13, 4))
    a1, a2, a3 = fig.subplots(1, 3)
    p = np.asarray(fit.pressure_mpa)
    a1.plot(p, fit.friction_n, "o", color="tab:red", label="measured F")
    lab = f"gamma N (gamma = {fit.gamma:.4f})"
    if fit.kind == "affine":
        lab = f"gamma N + F0 (gamma = {fit.gamma:.4f}, F0 = {fit.model.f0_n:.2f} N)"
    o = np.argsort(p)
    a1.plot(p[o], np.asarray(fit.predicted_friction_n)[o], "-", color="k", label=lab)
    a1.set_ylabel("friction F (N)")
    a1.legend(fontsize=8)
    lo, hi = fit.gamma_ci95
    a1.set_title(f"95% CI [{lo:.4f}, {hi:.4f}] ({fit.ci_method})", fontsize=9)
    a2.plot(p, fit.residual_n, "o", color="tab:blue")
    a2.set_ylabel("residual F^ - F (N)")
    a2.set_title(f"n = {fit.n_points} points", fontsize=9)
    a3.plot(p, fit.point_relative_error_pct, "s", color="tab:orange")
    a3.set_ylabel("relative error (F^ - F)/F (%)")
    a3.set_title(f"mean |rel. error| = {fit.relative_error_pct:.2f}%", fontsize=9)
    for ax in (a1, a2, a3):
        ax.set_xlabel("pressure P (MPa)")
        ax.grid(alpha=0.3)
    for ax in (a2, a3):
        ax.axhline(0.0, color="0.5", lw=0.8)
    if title:
        fig.suptitle(title)
    finish(fig, created)
    return fig


def plot_predictions(
    preds: Sequence[Prediction], title: str = "", *, fig: Any | None = None
) -> Any:
    """Per structure: predicted (black) vs tested (red) friction and the relative error curve.

    One row of two Axes per prediction on ``fig`` (an empty Figure; default a new one).
    Returns the Figure.

    Parameters
    ----------
    preds : sequence of Prediction
        E.g. ``predict(...).predictions`` (:func:`exofric.friction.predict`; MPa, N, %).
    title : str
        Figure title (none when empty).
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from matplotlib.figure import Figure
    >>> from exofric.friction import paper_structures, predict
    >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
    >>> r = predict(paper_structures()[:2], 0.7, None, [0.3, 0.6], squeeze_fn=fake)
    >>> fig = plot_predictions(r.predictions, "stand-in squeeze", fig=Figure())
    >>> len(fig.axes), fig.axes[2].get_title()
    (4, 'test 2: deviation 9.1%')
    """
    k = max(len(preds), 1)
    fig, created = new_figure(fig, (10, 3.2 * k))
    axes = fig.subplots(k, 2, squeeze=False)
    for (a1, a2), pr in zip(axes, preds, strict=False):
        a1.plot(pr.pressure_mpa, pr.predicted_friction_n, "-", color="k", label="predicted")
        if pr.measured is not None:
            a1.plot(pr.measured.pressure_mpa, pr.measured.friction_n, "o-", color="tab:red",
                    label="tested")
            a2.plot(pr.measured.pressure_mpa, pr.relative_error_pct, "o-", color="tab:blue")
            m = pr.max_relative_error_pct
            a2.set_title(f"max relative error {m:.2f}%" if m is not None else "", fontsize=9)
        else:
            a2.text(0.5, 0.5, "no measured curve", ha="center", va="center",
                    transform=a2.transAxes)
        dev = pr.deviation
        flag = "" if dev.in_validated_region else " (outside validated region)"
        a1.set_title(f"{pr.structure.name}: deviation {dev.deviation_pct:.1f}%{flag}", fontsize=9)
        a1.set_xlabel("pressure P (MPa)")
        a1.set_ylabel("friction F (N)")
        a1.legend(fontsize=8)
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
    ax, created = new_axes(ax, (6.4, 4.2))
    pp = np.linspace(ours.p_min_mpa, ours.p_max_mpa, 101)
    ax.plot(pressure_mpa, squeeze_force_n, "o", label="exofric FE, test 5")
    ax.plot(pp, ours(pp), "-", label=f"exofric cubic (R^2 = {ours.r2:.5f})")
    ax.plot(pp, paper_eq8(pp), "k--", label="paper Eq 8")
    for key, lab, col in (("eq9_mpa", "Eq 9 inverse", "k"),
                          ("paper_printed_mpa", "paper's printed 0.26", "tab:red"),
                          ("our_exact_curve_mpa", "ours (FE + our gamma)", "tab:blue")):
        ax.axvline(inverse_mpa[key], color=col, ls=":", lw=1,
                   label=f"{target_n:g} N: {lab} {inverse_mpa[key]:.4f} MPa")
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("squeezing force N (N)")
    ax.set_title("Fig 11: cubic fit for test 5", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
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
    ax, created = new_axes(ax, (6.4, 4.0))
    x = np.arange(len(names))
    ax.bar(x, list(torque_nm), color="tab:blue", label="exofric (predicted)")
    if reference is not None:
        ax.plot(list(reference[0]), list(reference[1]), "*", ms=12, color="tab:red",
                label=reference[2])
    if limit_nm is not None:
        ax.axhline(limit_nm, color="k", ls="--", label=limit_label)
        ax.set_ylim(0.0, 1.3 * max([limit_nm, *torque_nm]))   # room for the legend
    ax.set_xticks(x, list(names), rotation=30)
    ax.set_ylabel(f"torque T = F R at {pressure_mpa:g} MPa (Nm)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    finish(ax.figure, created)
    return ax
