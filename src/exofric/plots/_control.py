"""Control figures: one closed-loop trajectory, and the Fig 12 cases side by side.

Presentation only: results are read through their attributes (time s, friction N,
pressure MPa); each function draws on a given Axes/Figure or a new one, which it returns.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from exofric.plots._common import SMALL, finish, new_axes, new_figure

if TYPE_CHECKING:
    from exofric.control import SimulationResult
    from exofric.reproduction import CaseResult

__all__ = ["plot_simulation", "plot_control_cases"]


def plot_simulation(sim: SimulationResult, ax: Any | None = None) -> Any:
    """Friction (N) and its set-point against time (s) for one closed-loop simulation.

    Two lines: the true friction (solid) and the set-point (black, dashed). Returns the Axes.

    Parameters
    ----------
    sim : SimulationResult
        From :func:`exofric.control.simulate` (time in s, friction in N).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.control import Controller, PIDGains, PlantParams, simulate
    >>> sim = simulate(Controller(PIDGains(0.002, 0.003)), PlantParams(),
    ...                lambda p: 200.0 * p, 40.0, duration_s=2.0)
    >>> ax = plot_simulation(sim, Figure().subplots())
    >>> len(ax.lines), ax.get_xlabel()
    (2, 'time (s)')
    """
    ax, created = new_axes(ax, (6.4, 4.0))
    ax.plot(sim.time_s, sim.friction_n, color="tab:blue", label="friction")
    ax.plot(sim.time_s, sim.setpoint_n, "k--", lw=1, label="set-point")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("friction F (N)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL)
    finish(ax.figure, created)
    return ax


def _fmt(v: float | None) -> str:
    return "-" if v is None else f"{v:.2f} s"


def _settle(v: float | None, ff: bool) -> str:
    if v is None:
        return "never settles" if not ff else "never"
    return f"{v:.2f} s"


def plot_control_cases(
    cases: Sequence[CaseResult],
    fig: Any | None = None,
    *,
    title: str | None = None,
    pressure: bool = True,
) -> Any:
    """Step responses of control cases, one column per controller (paper Fig 12c-e).

    The one Fig 12 design (``exofric control compare --plot``, the report, ``.plot()``):
    top row, friction (N) against time (s), red without and blue with the model feedforward,
    the target (black) and its settling band (grey); each column's title gives exofric's
    settling times ("PD, exofric: without model never settles, with 4.08 s") and, below, the
    paper's ("paper: without 5.73 s, with 4.20 s"). Bottom row
    (``pressure=True``): tube pressure (MPa) and the controller's command (dotted). One legend
    for the whole figure sits above the Axes, so it never covers a curve.

    Parameters
    ----------
    cases : sequence of CaseResult
        From :func:`exofric.reproduction.run_case` or ``compare(...).cases``.
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).
    title : str, optional
        Figure title (above the legend); default ``"target <reference> N"``, as the CLI's;
        ``""`` for none.
    pressure : bool
        Add the pressure row.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.reproduction import ControlSetup, run_case
    >>> setup = ControlSetup.default()
    >>> cases = [run_case(setup, "pi", feedforward=ff) for ff in (False, True)]
    >>> fig = plot_control_cases(cases, Figure())
    >>> len(fig.axes), len(fig.axes[0].lines)     # friction and pressure rows; 2 runs + target
    (2, 3)
    >>> print(fig.axes[0].get_title())
    PI, exofric: without model 6.06 s, with 4.08 s
    paper: without 5.73 s, with 4.20 s
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    kinds = list(dict.fromkeys(c.controller for c in cases)) or ["pid"]
    n = len(kinds)
    width = max(4.6, 3.5 * n)
    fig, created = new_figure(fig, (width, 6.4) if pressure else (width, 4.2))
    axes = fig.subplots(2 if pressure else 1, n, squeeze=False, sharex=True, sharey="row")
    band_pct = None
    for j, kind in enumerate(kinds):
        ax = axes[0][j]
        mine = [c for c in cases if c.controller == kind]
        for c in mine:
            s = c.simulation
            col = "tab:blue" if c.feedforward else "tab:red"
            ax.plot(s.time_s, s.friction_n, color=col, lw=1.6)
            if pressure:
                axp = axes[1][j]
                axp.plot(s.time_s, s.pressure_mpa, color=col, lw=1.6)
                axp.plot(s.time_s, s.command_mpa, color=col, ls=":", lw=1.0)
        if mine:
            tgt, band = mine[0].metrics.reference, mine[0].metrics.band
            band_pct = 100.0 * band
            ax.axhline(tgt, color="k", lw=1)
            ax.axhspan(tgt * (1 - band), tgt * (1 + band), color="0.85")
        ours = {c.feedforward: c.metrics.settling_time_s for c in mine}
        ref = {c.feedforward: c.paper_settling_time_s for c in mine}
        otxt = ", ".join(f"{'with' if ff else 'without model'} {_settle(v, ff)}"
                         for ff, v in sorted(ours.items()))
        ptxt = ", ".join(f"{'with' if ff else 'without'} {_fmt(v)}"
                         for ff, v in sorted(ref.items()) if v is not None)
        head = f"{kind.upper()}, exofric: {otxt}" if otxt else kind.upper()
        ax.set_title(head + (f"\npaper: {ptxt}" if ptxt else ""), fontsize=SMALL)
        ax.grid(alpha=0.3)
        if pressure:
            axes[1][j].set_xlabel("time (s)")
            axes[1][j].grid(alpha=0.3)
        else:
            ax.set_xlabel("time (s)")
    axes[0][0].set_ylabel("friction F (N)")
    if pressure:
        axes[1][0].set_ylabel("pressure (MPa)")
    ffs = {c.feedforward for c in cases}
    handles: list[Any] = []
    if False in ffs:
        handles += [Line2D([], [], color="tab:red", lw=1.6, label="without model")]
    if True in ffs:
        handles += [Line2D([], [], color="tab:blue", lw=1.6, label="with model")]
    handles += [Line2D([], [], color="k", lw=1, label="target")]
    if band_pct is not None:
        handles += [Patch(color="0.85", label=f"settling band \u00b1{band_pct:g} %")]
    if pressure:
        handles += [Line2D([], [], color="0.3", ls=":", lw=1.0, label="command (pressure row)")]
    if title is None:
        title = f"target {cases[0].metrics.reference:g} N" if cases else ""
    ncol = min(len(handles), 3)
    leg: dict[str, Any] = {"handles": handles, "ncol": ncol, "fontsize": SMALL, "frameon": False,
                           "title": title or None, "title_fontsize": SMALL + 3}
    if created:
        fig.set_layout_engine("constrained")
        fig.legend(loc="outside upper center", **leg)
    else:  # a caller's figure: make room above the Axes, in figure coordinates
        fig.subplots_adjust(top=0.74 if pressure else 0.62, hspace=0.25)
        fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.995), **leg)
    return fig
