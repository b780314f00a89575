"""Ring tensile test figure: force (N) against pin displacement (mm)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from exofric.plots._common import SMALL, finish, new_axes

if TYPE_CHECKING:
    from exofric.simulate import RingResult

__all__ = ["plot_ring_test"]


def plot_ring_test(
    result: RingResult,
    ax: Any | None = None,
    measured: tuple[Sequence[float], Sequence[float]] | None = None,
) -> Any:
    """Force of one pin (N) against pin displacement (mm): FE, optionally beside a test.

    One line for the FE (markers on the computed displacements, from 0), and measured points
    (red squares) when given. Returns the Axes.

    Parameters
    ----------
    result : RingResult
        From :func:`exofric.simulate.ring_test` (mm, N).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).
    measured : (sequence of float, sequence of float), optional
        Measured pin displacements (mm) and forces (N), e.g. from
        :func:`exofric.io.read_ring_test`.

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import ring_test
    >>> r = ring_test(8.3, 4.97, 5.0, 3.0, [0.2, 0.4], MooneyRivlin.from_shore(62.5),
    ...               mesh=MeshSpec(1, 8))
    >>> ax = plot_ring_test(r, Figure().subplots(), measured=([0.2, 0.4], [0.1, 0.3]))
    >>> len(ax.lines), ax.get_xlabel()
    (2, 'pin displacement (mm)')
    """
    import numpy as np

    ax, created = new_axes(ax, (5.6, 4.4))
    d = np.asarray(result.displacement_mm, dtype=float)
    f = np.asarray(result.force_n, dtype=float)
    if d[0] > 0.0:  # the test starts at zero force with the pins touching
        d, f = np.concatenate([[0.0], d]), np.concatenate([[0.0], f])
    ax.plot(d, f, "o-", ms=4, label=f"FE (exofric, {result.section})")
    if measured is not None:
        ax.plot(list(measured[0]), list(measured[1]), "s", ms=6, mfc="none", mew=1.5,
                color="tab:red", label="measured", zorder=4)
    g = result.geometry
    ax.set_title(f"ring {g['ring_od_mm']:g}/{g['ring_id_mm']:g} mm x {g['width_mm']:g} mm "
                 f"wide, pins {g['pin_mm']:g} mm", fontsize=SMALL + 2)
    ax.set_xlabel("pin displacement (mm)")
    ax.set_ylabel("force (N)")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=min(0.0, float(np.min(f))))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL + 1, loc="upper left")
    finish(ax.figure, created)
    return ax
