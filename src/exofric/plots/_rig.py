"""Figures for raw rig logs: what :func:`exofric.friction.reduce_log` found and averaged.

Presentation only: the function reads the reduction's attributes (time series, plateaus, pulls,
skipped pulls) and draws on a given Figure or a new one, which it returns. Units: s, MPa, N, mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from exofric.plots._common import new_figure

if TYPE_CHECKING:
    from exofric.friction import RigReduction

__all__ = ["plot_reduction"]

_UP, _DOWN = "#9ecae1", "#fdd0a2"            # plateau shading by branch
_FWD, _BWD = "#c7e9c0", "#dadaeb"            # pull shading by direction
_WIN = {"forward": "#31a354", "backward": "#756bb1"}


def plot_reduction(red: RigReduction, title: str = "", *, fig: Any | None = None) -> Any:
    """The raw log with plateaus, pulls, steady (kinetic) windows and static peaks marked.

    Panels share the time axis (s): pressure (MPa) with the detected plateaus shaded by branch
    (up, down); force (N) with each pull shaded by direction, its steady window darker, the
    window's mean (tared force plus tare) as a red bar, the breakaway peak as a triangle and the
    skipped pulls hatched; displacement (mm) when the log has it.

    Parameters
    ----------
    red : RigReduction
        Result of :func:`exofric.friction.reduce_log`.
    title : str
        Figure title (default: the log's source name).
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.friction import reduce_log, simulate_raw_log
    >>> red = reduce_log(simulate_raw_log([0.2, 0.6], [80.0, 240.0], 0.5, seed=4).to_frame())
    >>> fig = plot_reduction(red, fig=Figure())
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['pressure (MPa)', 'force (N)', 'displacement (mm)']
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    has_x = red.displacement_mm is not None
    fig, _ = new_figure(fig, (12.0, 8.0 if has_x else 6.5))
    ratios = [1.0, 1.6, 0.8] if has_x else [1.0, 1.6]
    axes = fig.subplots(len(ratios), 1, sharex=True, gridspec_kw={"height_ratios": ratios})
    ap, af = axes[0], axes[1]
    t = red.time_s
    lw = 0.6 if t.size < 20000 else 0.4
    ap.plot(t, red.pressure_mpa, color="k", lw=lw)
    for pl in red.plateaus:
        ap.axvspan(pl["t_start_s"], pl["t_end_s"], color=_UP if pl["branch"] == "up" else _DOWN,
                   alpha=0.6, lw=0)
    ap.set_ylabel("pressure (MPa)")
    af.plot(t, red.force_n, color="k", lw=lw)
    ms = 4.0 if len(red.pulls) <= 60 else 2.5
    for r in red.pulls:
        af.axvspan(r["t_start_s"], r["t_end_s"], color=_FWD if r["direction"] == "forward"
                   else _BWD, lw=0)
        af.axvspan(r["t_kinetic_start_s"], r["t_kinetic_end_s"], color=_WIN[r["direction"]],
                   alpha=0.35, lw=0)
        level = r["force_kinetic_n"] + r["tare_n"]
        af.plot([r["t_kinetic_start_s"], r["t_kinetic_end_s"]], [level, level], color="tab:red",
                lw=1.6, solid_capstyle="butt")
        sign = 1.0 if r["direction"] == "forward" else -1.0
        peak = sign * r["static_n"] + r["bias_n"] + r["tare_n"]
        af.plot([r["t_static_s"]], [peak], marker="v" if sign > 0 else "^", ms=ms,
                color="tab:red", ls="none")
    for sk in red.skipped:
        af.axvspan(sk["t_start_s"], sk["t_end_s"], facecolor="none", edgecolor="tab:red",
                   hatch="///", lw=0.5)
    af.set_ylabel("force (N)")
    if has_x:
        ax = axes[2]
        ax.plot(t, red.displacement_mm, color="k", lw=lw)
        ax.set_ylabel("displacement (mm)")
    axes[-1].set_xlabel("time (s)")
    handles = [
        Patch(color=_UP, alpha=0.6, label="plateau, up branch"),
        Patch(color=_DOWN, alpha=0.6, label="plateau, down branch"),
        Patch(color=_FWD, label="pull forward"),
        Patch(color=_BWD, label="pull backward"),
        Patch(color=_WIN["forward"], alpha=0.35, label="steady (kinetic) window"),
        Line2D([], [], color="tab:red", lw=1.6, label="kinetic mean"),
        Line2D([], [], color="tab:red", marker="v", ls="none", ms=4, label="static peak"),
        Patch(facecolor="none", edgecolor="tab:red", hatch="///", label="skipped pull"),
    ]
    fig.legend(handles=handles, loc="upper center", ncol=4, fontsize=8, frameon=False,
               bbox_to_anchor=(0.5, 0.995))
    n = len(red.pulls)
    head = title or red.source or "raw rig log"
    fig.suptitle(f"{head}: {len(red.plateaus)} plateaus, {n} pulls used, {len(red.skipped)} "
                 f"skipped (pulls found in the {red.pull_detection})", y=0.93, fontsize=10)
    for a in axes:
        a.grid(alpha=0.3, lw=0.5)
        a.margins(x=0.005)
    fig.subplots_adjust(top=0.89, hspace=0.08, left=0.07, right=0.99, bottom=0.07)
    return fig

