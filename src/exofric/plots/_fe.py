"""Figures (matplotlib, Agg): deformed sections coloured by stress, curves.

Presentation only: every function takes computed results and draws them.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["section_polygons", "draw_section", "plot_inflation", "plot_squeeze", "save"]

# boundary walk of a quad9 element (a = 3 j + i) and of a quad4 (a = 2 j + i)
_Q9_RING = [0, 1, 2, 5, 8, 7, 6, 3]
_Q4_RING = [0, 1, 3, 2]


def _plt() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def section_polygons(
    nodes: np.ndarray, elements: np.ndarray, mirror: Sequence[str] = ()
) -> np.ndarray:
    """Element outlines (e, k, 2) in mm; ``mirror`` adds copies reflected in 'x' and/or 'y'."""
    ring = _Q9_RING if elements.shape[1] == 9 else _Q4_RING
    polys = nodes[elements[:, ring]]
    out = [polys]
    if "x" in mirror:  # reflect across the y axis (x -> -x)
        out += [p * np.array([-1.0, 1.0]) for p in list(out)]
    if "y" in mirror:
        out += [p * np.array([1.0, -1.0]) for p in list(out)]
    return np.concatenate(out)


def draw_section(
    ax: Any,
    nodes: np.ndarray,
    elements: np.ndarray,
    values: np.ndarray | None,
    mirror: Sequence[str] = (),
    cmap: str = "viridis",
    vmax: float | None = None,
    edgecolor: str = "k",
    label: str = "von Mises stress (MPa)",
) -> Any:
    """Draw a (deformed) section on ``ax``; colour by element ``values`` if given."""
    from matplotlib.collections import PolyCollection

    polys = section_polygons(nodes, elements, mirror)
    reps = len(polys) // len(elements)
    if values is None:
        pc = PolyCollection(list(polys), facecolors="none", edgecolors=edgecolor, linewidths=0.3)
    else:
        pc = PolyCollection(
            list(polys), array=np.tile(values, reps), cmap=cmap, edgecolors="k", linewidths=0.15
        )
        if vmax is not None:
            pc.set_clim(0.0, vmax)
    ax.add_collection(pc)
    ax.set_aspect("equal")
    ax.autoscale_view()
    return pc


def save(fig: Any, path: str | Path) -> Path:
    """Save and close a figure; return the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p, dpi=130, bbox_inches="tight")
    _plt().close(fig)
    return p


def plot_inflation(result: Any, path: str | Path) -> Path:
    """Undeformed and deformed tube sections coloured by von Mises stress, and OD(P)."""
    plt = _plt()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.8))
    draw_section(a1, result.nodes, result.elements, None, mirror=("x", "y"), edgecolor="0.6")
    vmax = float(max(v.max() for v in result.von_mises_mpa))
    pc = None
    for u, vm in zip(result.displacements[-1:], result.von_mises_mpa[-1:], strict=True):
        pc = draw_section(a1, result.nodes + u, result.elements, vm, mirror=("x", "y"), vmax=vmax)
    if pc is not None:
        fig.colorbar(pc, ax=a1, label="von Mises stress (MPa)")
    a1.set_title(f"Section at {result.pressure_mpa[-1]:g} MPa (grey: undeformed)")
    a1.set_xlabel("x (mm)")
    a1.set_ylabel("y (mm)")
    a2.plot(result.pressure_mpa, result.outer_diameter_mm, "o-", label="FE (exofric)")
    a2.plot(
        result.pressure_mpa,
        result.analytic_outer_diameter_mm(),
        "k--",
        label="incompressible closed form",
    )
    a2.set_xlabel("pressure (MPa)")
    a2.set_ylabel("outer diameter (mm)")
    a2.grid(alpha=0.3)
    a2.legend()
    return save(fig, path)


def plot_squeeze(
    result: Any, path: str | Path, show_pressures: Sequence[float] = (0.2, 0.4, 0.6)
) -> Path:
    """Deformed sections with stress, the hole and the wire (Fig 6), and N(P) (Fig 7)."""
    from matplotlib.patches import Circle

    plt = _plt()
    p = np.asarray(result.pressure_mpa)
    idx = sorted({int(np.argmin(np.abs(p - q))) for q in show_pressures})
    fig, axes = plt.subplots(1, len(idx) + 1, figsize=(4.2 * (len(idx) + 1), 4.4))
    s = result.structure
    vmax = float(max(result.von_mises_mpa[i].max() for i in idx)) if result.von_mises_mpa else None
    pc = None
    for ax, i in zip(axes[:-1], idx, strict=True):
        pc = draw_section(
            ax,
            result.nodes + result.displacements[i],
            result.elements,
            result.von_mises_mpa[i],
            mirror=("x",),
            vmax=vmax,
        )
        ax.add_patch(Circle((0, 0), 0.5 * s.hole_mm, fill=False, color="0.3", lw=1.2))
        ax.add_patch(Circle(s.wire_center_mm, 0.5 * s.wire_mm, color="0.55"))
        ax.set_xlim(-0.55 * s.hole_mm, 0.55 * s.hole_mm)
        ax.set_ylim(-0.55 * s.hole_mm, 0.55 * s.hole_mm)
        ax.set_title(f"P = {p[i]:g} MPa, N = {result.squeeze_force_n[i]:.1f} N")
        ax.set_xlabel("x (mm)")
    if pc is not None:
        fig.colorbar(pc, ax=list(axes[:-1]), label="von Mises stress (MPa)", shrink=0.8)
    ax = axes[-1]
    ax.plot(p, result.squeeze_force_n, "o-", label="exofric FE")
    if result.contact_onset_pressure_mpa is not None:
        ax.axvline(result.contact_onset_pressure_mpa, color="0.6", ls=":", label="contact onset")
    ax.set_xlabel("pressure (MPa)")
    ax.set_ylabel(f"squeezing force N (N, L = {s.length_mm:g} mm)")
    ax.grid(alpha=0.3)
    ax.legend()
    return save(fig, path)
