"""Structured polar meshes of the tube cross-section (an annulus or a sector of it).

Elements are 9-node quadratic quadrilaterals (``quad9``) whose nodes lie exactly on
circles and radial lines, so the geometry is quadratic where the elements are;
``quad4`` (corner nodes only) is available for locking studies. Circumferential
spacing can be graded toward one angle (the wire contact patch in the squeeze
problem).

Local node numbering of an element: ``a = 3 j + i`` with ``i`` the radial index
(0 inner, 2 outer) and ``j`` the angular index (0 at the lower angle), both in
{0, 1, 2}; for ``quad4`` the corners in the same tensor order (i, j in {0, 1}).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exofric._validate import checked_init
from exofric.errors import InputError, check_positive

__all__ = ["TubeMesh", "polar_mesh", "graded_angles", "two_sided_angles"]


@checked_init
@dataclass(frozen=True)
class TubeMesh:
    """A structured polar mesh of a tube (coordinates in mm, centre at the origin).

    Attributes
    ----------
    nodes : ndarray (n, 2)
        Undeformed node coordinates (mm).
    elements : ndarray (e, 9) or (e, 4)
        Node indices per element (see the module docstring for the ordering).
    kind : {'quad9', 'quad4'}
        Element type.
    grid : ndarray (nr_nodes, nt_nodes)
        Node index at radial line ``i`` and angular line ``j`` of the structured grid.
    angles : ndarray (nt_nodes,)
        Angle (rad) of each angular grid line.
    radii : ndarray (nr_nodes,)
        Radius (mm) of each radial grid line.
    full_circle : bool
        True when the mesh closes on itself (no symmetry planes).

    Examples
    --------
    >>> m = polar_mesh(2.485, 4.15, 2, 4)
    >>> m.n_nodes, m.order, m.boundary_edges("inner").shape
    (45, 2, (4, 3))
    """

    nodes: np.ndarray
    elements: np.ndarray
    kind: str
    grid: np.ndarray
    angles: np.ndarray
    radii: np.ndarray
    full_circle: bool

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return int(self.nodes.shape[0])

    @property
    def order(self) -> int:
        """Geometric/interpolation order: 2 for quad9, 1 for quad4."""
        return 2 if self.kind == "quad9" else 1

    @property
    def inner_nodes(self) -> np.ndarray:
        """Nodes of the inner (cavity) surface, by increasing angle."""
        return self.grid[0]

    @property
    def outer_nodes(self) -> np.ndarray:
        """Nodes of the outer surface, by increasing angle."""
        return self.grid[-1]

    def boundary_edges(self, side: str) -> np.ndarray:
        """Edges of the ``'inner'`` or ``'outer'`` surface as node tuples, by increasing angle.

        Each row has ``order + 1`` nodes (3 for quad9, 2 for quad4).

        Parameters
        ----------
        side : {'inner', 'outer'}
            Which surface (anything but ``'inner'`` means the outer one).

        Returns
        -------
        ndarray (m, order + 1)
            Node indices of each edge.
        """
        line = self.grid[0] if side == "inner" else self.grid[-1]
        k = self.order
        starts = np.arange(0, line.size - 1, k)
        return np.stack([line[starts + m] for m in range(k + 1)], axis=1)

    def to_dict(self) -> dict[str, object]:
        """Small JSON-ready summary (sizes only)."""
        return {
            "kind": self.kind,
            "n_nodes": self.n_nodes,
            "n_elements": int(len(self.elements)),
            "angle_range_deg": [
                float(np.degrees(self.angles[0])),
                float(np.degrees(self.angles[-1])),
            ],
        }


def graded_angles(
    theta0: float, theta1: float, n: int, grading: float = 1.0, toward: float | None = None
) -> np.ndarray:
    """Element boundary angles on [theta0, theta1] (n elements), graded toward ``toward``.

    ``grading`` is the ratio of the largest to the smallest element (1 = uniform);
    sizes vary geometrically away from ``toward`` (an angle inside the range, by
    default ``theta1``).

    Parameters
    ----------
    theta0, theta1 : float
        Range of angles (rad), ``theta0 < theta1``.
    n : int
        Number of elements, >= 1.
    grading : float
        Largest / smallest element size (unitless), >= 1.
    toward : float, optional
        Angle (rad) where the elements are smallest (default ``theta1``).

    Returns
    -------
    ndarray (n + 1,)
        Element boundary angles (rad), increasing.

    Examples
    --------
    >>> graded_angles(0.0, 1.0, 3, grading=4.0).round(4).tolist()
    [0.0, 0.5714, 0.8571, 1.0]
    """
    if n < 1:
        raise InputError(f"number of circumferential elements must be >= 1, got {n}")
    g = check_positive("grading", grading)
    if g < 1.0:
        raise InputError(f"grading must be >= 1 (largest/smallest element), got {g:g}")
    t = theta1 if toward is None else float(toward)
    if not theta0 <= t <= theta1:
        raise InputError(f"grading angle must lie in the mesh's angle range, got {t:g} rad")
    if g == 1.0:
        return np.linspace(theta0, theta1, n + 1)

    def one_side(length: float, m: int) -> np.ndarray:
        # m elements, geometric growth from the graded end, ratio max/min = g
        if m == 1:
            return np.array([0.0, length])
        q = g ** (1.0 / (m - 1))
        sizes = q ** np.arange(m)
        return np.concatenate([[0.0], np.cumsum(sizes) / sizes.sum() * length])

    if t == theta1:
        return theta1 - one_side(theta1 - theta0, n)[::-1]
    if t == theta0:
        return theta0 + one_side(theta1 - theta0, n)
    n_lo = max(1, round(n * (t - theta0) / (theta1 - theta0)))
    n_hi = max(1, n - n_lo)
    lo = t - one_side(t - theta0, n_lo)[::-1]
    hi = t + one_side(theta1 - t, n_hi)
    return np.concatenate([lo, hi[1:]])


def two_sided_angles(
    theta0: float, theta1: float, split: float, n: int, n0: int, grading0: float,
    grading1: float,
) -> np.ndarray:
    """Element boundary angles refined toward both ends of [theta0, theta1] (rad).

    ``n0`` of the ``n`` elements cover [theta0, split], graded toward ``theta0`` (largest /
    smallest ``grading0``); the other ``n - n0`` cover [split, theta1], graded toward
    ``theta1`` (``grading1``). Each part is geometric, so merging neighbours pairwise in
    each part gives a nested mesh of the same kind (``MeshSpec.coarsened``).

    Parameters
    ----------
    theta0, theta1, split : float
        Range of angles and the angle between the two parts (rad), theta0 < split < theta1.
    n, n0 : int
        Elements in all (>= 2) and in the first part (1 <= n0 < n).
    grading0, grading1 : float
        Largest / smallest element of each part (unitless, >= 1).

    Returns
    -------
    ndarray (n + 1,)
        Element boundary angles (rad), increasing.

    Examples
    --------
    >>> two_sided_angles(0.0, 2.0, 1.0, 4, 2, 2.0, 2.0).round(4).tolist()
    [0.0, 0.3333, 1.0, 1.6667, 2.0]
    """
    if not (theta0 < split < theta1 and 1 <= n0 < n):
        raise InputError(f"two-sided grading needs theta0 < split < theta1 and 1 <= n0 < n, "
                         f"got split {split:g} rad in [{theta0:g}, {theta1:g}], n0 = {n0}, "
                         f"n = {n}")
    lo = graded_angles(theta0, split, n0, grading0, theta0)
    hi = graded_angles(split, theta1, n - n0, grading1, theta1)
    return np.concatenate([lo, hi[1:]])


def polar_mesh(
    inner_radius_mm: float,
    outer_radius_mm: float,
    n_radial: int,
    n_circ: int,
    *,
    theta0: float = 0.0,
    theta1: float = 0.5 * np.pi,
    grading: float = 1.0,
    grade_toward: float | None = None,
    radial_ratio: float = 1.0,
    kind: str = "quad9",
    center: tuple[float, float] = (0.0, 0.0),
    boundaries: np.ndarray | None = None,
) -> TubeMesh:
    """Structured polar mesh of the sector ``theta0..theta1`` of an annulus.

    Parameters
    ----------
    inner_radius_mm, outer_radius_mm : float
        Undeformed radii (mm), 0 < inner < outer.
    n_radial, n_circ : int
        Element counts through the wall and around the sector.
    theta0, theta1 : float
        Sector limits (rad); ``theta1 - theta0 = 2 pi`` gives a closed ring.
    grading, grade_toward : float
        Circumferential grading (largest/smallest element) toward an angle (rad).
    radial_ratio : float
        Ratio of outermost to innermost element thickness (1 = uniform).
    kind : {'quad9', 'quad4'}
        Element type.
    center : (float, float)
        Centre of the annulus (mm).
    boundaries : ndarray (n_circ + 1,), optional
        Explicit element boundary angles (rad, increasing, from ``theta0`` to ``theta1``),
        e.g. from :func:`two_sided_angles`; ``grading`` and ``grade_toward`` are then unused.

    Returns
    -------
    TubeMesh

    Examples
    --------
    >>> m = polar_mesh(2.485, 4.15, 2, 4)
    >>> m.nodes.shape, m.elements.shape
    ((45, 2), (8, 9))
    """
    a = check_positive("inner radius", inner_radius_mm, "mm")
    b = check_positive("outer radius", outer_radius_mm, "mm")
    if a >= b:
        raise InputError(f"inner radius must be < outer radius ({b:g} mm), got {a:g}")
    if n_radial < 1 or n_circ < 1:
        raise InputError(f"mesh counts must be >= 1, got n_radial={n_radial}, n_circ={n_circ}")
    if kind not in ("quad9", "quad4"):
        raise InputError(f"element kind must be 'quad9' or 'quad4', got {kind!r}")
    k = 2 if kind == "quad9" else 1
    full = bool(np.isclose(theta1 - theta0, 2 * np.pi))
    # radial element boundaries (geometric thickness ratio), then mid-nodes
    if radial_ratio == 1.0 or n_radial == 1:
        rb = np.linspace(a, b, n_radial + 1)
    else:
        q = radial_ratio ** (1.0 / (n_radial - 1))
        sz = q ** np.arange(n_radial)
        rb = a + np.concatenate([[0.0], np.cumsum(sz)]) / sz.sum() * (b - a)
    if boundaries is None:
        tb = graded_angles(theta0, theta1, n_circ, grading, grade_toward)
    else:
        tb = np.asarray(boundaries, dtype=float)
        if tb.shape != (n_circ + 1,) or np.any(np.diff(tb) <= 0.0):
            raise InputError(f"boundaries must be {n_circ + 1} increasing angles (rad)")
    if k == 2:
        radii = np.empty(2 * n_radial + 1)
        radii[0::2], radii[1::2] = rb, 0.5 * (rb[:-1] + rb[1:])
        angles = np.empty(2 * n_circ + 1)
        angles[0::2], angles[1::2] = tb, 0.5 * (tb[:-1] + tb[1:])
    else:
        radii, angles = rb, tb
    nr, nt = radii.size, angles.size
    nt_unique = nt - 1 if full else nt
    grid: np.ndarray = np.arange(nr * nt_unique).reshape(nr, nt_unique)
    if full:
        grid = np.concatenate([grid, grid[:, :1]], axis=1)  # last angle line = first
    R, T = np.meshgrid(radii, angles[:nt_unique], indexing="ij")
    nodes = np.stack(
        [center[0] + (R * np.cos(T)).ravel(), center[1] + (R * np.sin(T)).ravel()], axis=1
    )
    eg, jg = np.meshgrid(np.arange(n_radial) * k, np.arange(n_circ) * k, indexing="ij")
    ei, ej = eg.ravel(), jg.ravel()
    loc = [(i, j) for j in range(k + 1) for i in range(k + 1)]  # a = (k+1) j + i
    elements = np.stack([grid[ei + i, ej + j] for (i, j) in loc], axis=1)
    return TubeMesh(nodes, elements, kind, grid, angles, radii, full)
