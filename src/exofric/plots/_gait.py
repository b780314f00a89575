"""Gait figures: the knee lock stride after stride (demand vs delivered torque, pressure,
valve, knee angle), and several controllers on one stride.

Presentation only: results are read through their attributes (time s, torque Nm, pressure
MPa, angle rad); each function draws on a given Figure or a new one, which it returns.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, new_figure

if TYPE_CHECKING:
    from exofric.control import GaitResult

__all__ = ["plot_gait", "plot_gait_compare"]


def plot_gait(result: GaitResult, fig: Any | None = None, *, strides: int | None = 3) -> Any:
    """Four rows over the last ``strides`` strides: torque, pressure, valve, knee angle.

    Row 1: demanded (black, dashed) and delivered joint torque (Nm; negative = extension);
    row 2: tube pressure and the pressure command (MPa); row 3: valve opening (-1 vent ..
    1 fill; empty without a valve model); row 4: knee flexion (deg). Stance is shaded.

    Parameters
    ----------
    result : GaitResult
        From :func:`exofric.control.simulate_gait`.
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).
    strides : int or None
        How many of the last strides to show (None: all).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import numpy as np
    >>> from matplotlib.figure import Figure
    >>> from exofric.control import GaitSetup, simulate_gait
    >>> t = np.linspace(0.0, 1.0, 200, endpoint=False)
    >>> class Walk:
    ...     time_s = t
    ...     knee_angle_rad = 0.5 * (1 - np.cos(2 * np.pi * t))
    ...     knee_moment_nm = -40.0 * np.sin(2 * np.pi * t)
    >>> fig = plot_gait(simulate_gait(Walk(), GaitSetup(strides=2), controller="ff"), Figure())
    >>> len(fig.axes), fig.axes[-1].get_xlabel()
    (4, 'time (s)')
    """
    fig, created = new_figure(fig, (8.0, 8.0))
    axes = fig.subplots(4, 1, sharex=True)
    n_str = len(result.strides)
    n = result.time_s.size // n_str
    k0 = 0 if strides is None else max(0, n_str - strides)
    sl = slice(k0 * n, n_str * n)
    t = result.time_s[sl]
    stance = round(n * _stance(result))
    for ax in axes:
        for j in range(k0, n_str):
            ax.axvspan(result.time_s[j * n], result.time_s[j * n + stance - 1], color="0.93",
                       lw=0)
    a = axes[0]
    a.plot(t, result.demand_nm[sl], "k--", lw=1.2, label="demand")
    a.plot(t, result.torque_nm[sl], color="tab:blue", lw=1.2, label="delivered")
    a.axhline(0.0, color="0.6", lw=0.6)
    a.set_ylabel("knee torque (Nm)")
    a.legend(loc="lower right", fontsize=SMALL)
    last = result.strides[-1]
    a.set_title(f"{result.controller}: stride {n_str} RMS error {last.rms_error_nm:.2f} Nm "
                f"({last.rms_error_pct:.0f} % of peak), engage {last.engage_latency_ms:.0f} ms, "
                f"release {last.release_latency_ms:.0f} ms", fontsize=SMALL)
    b = axes[1]
    b.plot(t, result.command_mpa[sl], color="tab:orange", lw=1.0, label="command")
    b.plot(t, result.pressure_mpa[sl], color="tab:red", lw=1.4, label="tube pressure")
    b.set_ylabel("pressure (MPa)")
    b.legend(loc="upper right", fontsize=SMALL)
    c = axes[2]
    c.plot(t, result.valve_opening[sl], color="tab:green", lw=1.0)
    c.set_ylim(-1.05, 1.05)
    c.set_ylabel("valve opening\n(-1 vent, 1 fill)")
    d = axes[3]
    d.plot(t, np.degrees(result.knee_angle_rad[sl]), color="tab:purple", lw=1.2)
    d.set_ylabel("knee flexion (deg)")
    d.set_xlabel("time (s)")
    d.text(0.01, 0.92, "shaded: stance", transform=d.transAxes, fontsize=SMALL, va="top")
    finish(fig, created)
    return fig


def _stance(result: GaitResult) -> float:
    s = result.setup.stance_fraction
    return float(s) if s is not None else float(getattr(result, "stance_fraction", 0.6))


def plot_gait_compare(results: Sequence[GaitResult], fig: Any | None = None) -> Any:
    """The last stride of several controllers: delivered torque against the demand (Nm) and
    the tube pressure (MPa), over the first half of the stride.

    Parameters
    ----------
    results : sequence of GaitResult
        From :func:`exofric.control.compare_gait` (``.results``).
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import numpy as np
    >>> from matplotlib.figure import Figure
    >>> from exofric.control import GaitSetup, compare_gait
    >>> t = np.linspace(0.0, 1.0, 200, endpoint=False)
    >>> class Walk:
    ...     time_s = t
    ...     knee_angle_rad = 0.5 * (1 - np.cos(2 * np.pi * t))
    ...     knee_moment_nm = -40.0 * np.sin(2 * np.pi * t)
    >>> c = compare_gait(Walk(), GaitSetup(strides=1), controllers=("ff", "preview"))
    >>> len(plot_gait_compare(c.results, Figure()).axes)
    2
    """
    fig, created = new_figure(fig, (8.0, 6.0))
    a, b = fig.subplots(2, 1, sharex=True)
    r0 = results[0]
    n = r0.time_s.size // len(r0.strides)
    half = n // 2
    t = r0.time_s[:half]
    a.plot(t, r0.demand_nm[-n:][:half], "k--", lw=1.4, label="demand")
    for r in results:
        m = r.strides[-1]
        a.plot(t, r.torque_nm[-n:][:half], lw=1.1,
               label=f"{r.controller} ({m.rms_error_nm:.2f} Nm RMS)")
        b.plot(t, r.pressure_mpa[-n:][:half], lw=1.1, label=r.controller)
    a.axhline(0.0, color="0.6", lw=0.6)
    a.set_ylabel("knee torque (Nm)")
    a.legend(fontsize=SMALL, loc="lower right")
    a.set_title(f"last stride ({len(r0.strides)}), first half", fontsize=SMALL)
    b.set_ylabel("tube pressure (MPa)")
    b.set_xlabel("time in the stride (s)")
    b.legend(fontsize=SMALL, loc="upper right")
    finish(fig, created)
    return fig
