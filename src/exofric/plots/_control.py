"""Control figures: one closed-loop trajectory, and the Fig 12 cases side by side.

Presentation only: results are read through their attributes (time s, friction N,
pressure MPa); each function draws on a given Axes/Figure or a new one, which it returns.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from exofric.plots._common import finish, new_axes, new_figure

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
    ax.legend(fontsize=8)
    finish(ax.figure, created)
    return ax


def _fmt(v: float | None) -> str:
    return "-" if v is None else f"{v:.2f} s"


def plot_control_cases(
    cases: Sequence[CaseResult],
    fig: Any | None = None,
    *,
    title: str = "",
    pressure: bool = True,
) -> Any:
    """Step responses of control cases, one column per controller (paper Fig 12c-e).

    Top row: friction (N) against time (s), red without and blue with the model feedforward,
    the target (black) and its settling band (grey); the legend gives each settling time and
    the title the paper's. Bottom row (``pressure=True``): tube pressure (MPa) and the
    controller's command (dotted).

    Parameters
    ----------
    cases : sequence of CaseResult
        From :func:`exofric.reproduction.run_case` or ``compare(...).cases``.
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).
    title : str
        Figure title.
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
    """
    kinds = list(dict.fromkeys(c.controller for c in cases)) or ["pid"]
    n = len(kinds)
    fig, created = new_figure(fig, (4.2 * n, 6.0) if pressure else (4.0 * n, 3.8))
    axes = fig.subplots(2 if pressure else 1, n, squeeze=False, sharex=True, sharey="row")
    for j, kind in enumerate(kinds):
        ax = axes[0][j]
        mine = [c for c in cases if c.controller == kind]
        for c in mine:
            s = c.simulation
            lab = "with model" if c.feedforward else "without model"
            col = "tab:blue" if c.feedforward else "tab:red"
            ts = c.metrics.settling_time_s
            ax.plot(s.time_s, s.friction_n, color=col,
                    label=f"{lab}: " + ("not settled" if ts is None else f"{ts:.2f} s"))
            if pressure:
                axp = axes[1][j]
                axp.plot(s.time_s, s.pressure_mpa, color=col)
                axp.plot(s.time_s, s.command_mpa, color=col, ls=":", lw=0.8)
        if mine:
            tgt, band = mine[0].metrics.reference, mine[0].metrics.band
            ax.axhline(tgt, color="k", lw=1)
            ax.axhspan(tgt * (1 - band), tgt * (1 + band), color="0.88")
        ref = {c.feedforward: c.paper_settling_time_s for c in mine}
        ptxt = ", ".join(f"{'with' if ff else 'without'} {_fmt(v)}"
                         for ff, v in sorted(ref.items()))
        ax.set_title(f"{kind.upper()}" + (f" (paper: {ptxt})" if ptxt else ""), fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
        if pressure:
            axes[1][j].set_xlabel("time (s)")
            axes[1][j].grid(alpha=0.3)
        else:
            ax.set_xlabel("time (s)")
    axes[0][0].set_ylabel("friction F (N)")
    if pressure:
        axes[1][0].set_ylabel("pressure (MPa); command dotted")
    if title:
        fig.suptitle(title)
    finish(fig, created)
    return fig
