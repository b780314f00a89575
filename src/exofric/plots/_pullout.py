"""Pull-out of the wire (section q(delta), whole length F(delta)) and the joint's K(P)."""

from __future__ import annotations

from typing import Any

from exofric.plots._common import finish, new_axes

__all__ = ["plot_joint_stiffness", "plot_pullout"]


def plot_pullout(result: Any, ax: Any | None = None) -> Any:
    """Force against wire displacement: q (N/mm) of a section, or F (N) at the pulled end.

    Parameters
    ----------
    result : SectionPullout or PulloutResult
        From :func:`exofric.simulate.section_pullout` / :func:`exofric.simulate.pullout`.
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> r = SimpleNamespace(displacement_mm=np.array([0, 1.0]), force_n=np.array([0, 2.0]),
    ...                     static_force_n=2.0, sliding_force_n=2.0)
    >>> plot_pullout(r).get_xlabel()
    'wire displacement (mm)'
    """
    ax, created = new_axes(ax, (5.5, 4.0))
    if hasattr(result, "force_n"):
        ax.plot(result.displacement_mm, result.force_n, "-", lw=1.5, label="F at the pulled end")
        ax.axhline(result.sliding_force_n, ls=":", color="0.4", label="whole length sliding")
        ax.set_ylabel("pull force F (N)")
    else:
        ax.plot(result.displacement_mm, result.force_n_per_mm, "-o", ms=2, lw=1.5,
                label="q (tube + wire-wall)")
        ax.plot(result.displacement_mm, result.tube_force_n_per_mm, "--", lw=1,
                label="tube-wire arc")
        ax.axhline(result.sliding_force_n_per_mm, ls=":", color="0.4", label="sliding plateau")
        ax.set_ylabel("force per length q (N/mm)")
    ax.set_xlabel("wire displacement (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    finish(ax.figure, created)
    return ax


def plot_joint_stiffness(result: Any, ax: Any | None = None) -> Any:
    """K(P) (Nm/rad, left axis) and T_break(P) (Nm, right axis) against pressure (MPa).

    Parameters
    ----------
    result : JointStiffness
        From :func:`exofric.friction.joint_stiffness`.
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).

    Returns
    -------
    matplotlib Axes
        The left (stiffness) axes.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> r = SimpleNamespace(pressure_mpa=np.array([0.3, 0.6]),
    ...                     stiffness_nm_per_rad=np.array([10.0, 30.0]),
    ...                     breakaway_torque_nm=np.array([5.0, 12.0]))
    >>> plot_joint_stiffness(r).get_xlabel()
    'pressure P (MPa)'
    """
    ax, created = new_axes(ax, (5.5, 4.0))
    ax.plot(result.pressure_mpa, result.stiffness_nm_per_rad, "-o", color="C0")
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("joint stiffness K (Nm/rad)", color="C0")
    ax2 = ax.twinx()
    ax2.plot(result.pressure_mpa, result.breakaway_torque_nm, "-s", color="C3")
    ax2.set_ylabel("breakaway torque T_break (Nm)", color="C3")
    ax.grid(alpha=0.3)
    finish(ax.figure, created)
    return ax
