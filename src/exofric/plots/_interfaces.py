"""Figure of the interface-resolved friction fit (issue 15): both laws per structure.

Presentation only: reads an :class:`~exofric.friction.InterfaceFit` through its attributes.
Units: MPa, N, %.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, is_synthetic, new_figure

if TYPE_CHECKING:
    from exofric.friction import InterfaceFit

__all__ = ["plot_interface_fit"]


def plot_interface_fit(
    fit: InterfaceFit,
    title: str = "",
    *,
    fig: Any | None = None,
    data_label: str | None = None,
) -> Any:
    """Friction per structure: data, the interface law and the pooled gamma (left); errors (right).

    Left: measured friction (markers, one colour per structure) against pressure, the fitted
    interface law F = mu_tube S + mu_wall N (+ F0) (solid) and the single pooled gamma fit
    F = gamma N (dashed). Right: the relative error (F^ - F)/F in % of each law per point
    (filled: interface law; open: pooled gamma).

    Parameters
    ----------
    fit : InterfaceFit
        Result of :func:`exofric.friction.fit_interfaces`.
    title : str
        Figure title (e.g. ``"SYNTHETIC rig data"``).
    fig : matplotlib Figure, optional
        Empty figure to draw the two Axes on (default a new one).
    data_label : str, optional
        What the points are, for the legend; default ``"synthetic"`` when ``title`` says
        SYNTHETIC, else ``"measured"``.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.friction import InterfaceCurves, InterfaceTest, fit_interfaces
    >>> c = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
    >>> d = InterfaceCurves([0.2, 0.6], [30.0, 360.0], [20.0, 240.0], "b")
    >>> fit = fit_interfaces([InterfaceTest(c, [0.2, 0.6], [15.0, 180.0]),
    ...                       InterfaceTest(d, [0.2, 0.6], [19.0, 228.0])])
    >>> fig = plot_interface_fit(fit, "SYNTHETIC", fig=Figure())
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['friction F (N)', 'relative error (F^ - F)/F (%)']
    """
    fig, created = new_figure(fig, (10.5, 4.2))
    a1, a2 = fig.subplots(1, 2)
    if data_label is None:
        data_label = "synthetic" if is_synthetic(title) else "measured"
    names = np.asarray(fit.structure, dtype=object)
    p = np.asarray(fit.pressure_mpa)
    f = np.asarray(fit.friction_n)
    fi = np.asarray(fit.predicted_friction_n)
    fg = np.asarray(fit.gamma_predicted_friction_n)
    ei = np.asarray(fit.point_relative_error_pct)
    with np.errstate(divide="ignore", invalid="ignore"):
        eg = np.where(f != 0, 100.0 * (fg - f) / f, np.nan)
    marks = "osD^vP*Xh<>"
    for i, s in enumerate(fit.structures):
        m = names == s
        c = f"C{i % 10}"
        o = np.argsort(p[m], kind="stable")
        a1.plot(p[m], f[m], marks[i % len(marks)], color=c, ms=5, alpha=0.8,
                label=f"{s}: {data_label}")
        a1.plot(p[m][o], fi[m][o], "-", color=c, lw=1.6)
        a1.plot(p[m][o], fg[m][o], "--", color=c, lw=1.2)
        a2.plot(p[m], ei[m], marks[i % len(marks)], color=c, ms=5, label=f"{s}: interfaces")
        a2.plot(p[m], eg[m], marks[i % len(marks)], color=c, ms=6, mfc="none",
                label=f"{s}: gamma")
    a1.plot([], [], "-", color="k", label="interface law (solid)")
    a1.plot([], [], "--", color="k", label=f"pooled gamma = {fit.gamma_pooled:.4f} (dashed)")
    a1.set_xlabel("pressure P (MPa)")
    a1.set_ylabel("friction F (N)")
    y0, y1 = a1.get_ylim()
    a1.set_ylim(y0, y1 + 0.5 * (y1 - y0))           # headroom: the legend sits above the data
    a1.legend(fontsize=SMALL, loc="upper left")
    lo_t, hi_t = fit.mu_tube_ci
    lo_w, hi_w = fit.mu_wall_ci
    ident = "identifiable" if fit.identifiable else "NOT identifiable"
    a1.set_title(f"mu_tube = {fit.mu_tube:.4f} [{lo_t:.4f}, {hi_t:.4f}], mu_wall = "
                 f"{fit.mu_wall:.4f} [{lo_w:.4f}, {hi_w:.4f}]\n95 % CI ({fit.ci_method}); "
                 f"kappa = {fit.condition_number:.3g}, {ident}", fontsize=SMALL + 1)
    a2.axhline(0.0, color="0.5", lw=0.8)
    a2.set_xlabel("pressure P (MPa)")
    a2.set_ylabel("relative error (F^ - F)/F (%)")
    a2.set_title(f"mean |rel. error|: interfaces {fit.relative_error_pct:.2f} %, gamma "
                 f"{fit.gamma_relative_error_pct:.2f} %\n(filled: interfaces, open: gamma)",
                 fontsize=SMALL + 1)
    a2.legend(fontsize=SMALL, loc="best", ncol=2)
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    finish(fig, created)
    return fig
