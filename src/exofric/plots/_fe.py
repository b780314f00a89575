"""FE figures: deformed sections coloured by stress, N(P) and OD(P) curves (Figs 6-7).

Presentation only: every function takes computed results (read through their attributes)
and draws them on a given Axes/Figure or a new one, which it returns. Units: mm, N, MPa.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, new_axes, new_figure

if TYPE_CHECKING:
    from exofric.simulate import InflationResult, SqueezeResult

__all__ = ["section_polygons", "draw_section", "plot_inflation", "plot_inflation_curve",
           "plot_squeeze", "plot_squeeze_force", "plot_squeeze_curves"]

# boundary walk of a quad9 element (a = 3 j + i) and of a quad4 (a = 2 j + i)
_Q9_RING = [0, 1, 2, 5, 8, 7, 6, 3]
_Q4_RING = [0, 1, 3, 2]


def section_polygons(
    nodes: np.ndarray, elements: np.ndarray, mirror: Sequence[str] = ()
) -> np.ndarray:
    """Element outlines (e, k, 2) in mm; ``mirror`` adds copies reflected in 'x' and/or 'y'.

    Parameters
    ----------
    nodes : ndarray, shape (n, 2)
        Node coordinates in mm (deformed: nodes + displacements).
    elements : ndarray, shape (e, 9) or (e, 4)
        Node indices of each quad9 (or quad4) element, in the FE's tensor-product order.
    mirror : sequence of {'x', 'y'}
        Add copies reflected across the y axis ('x': x -> -x) and/or the x axis ('y'),
        e.g. ``("x", "y")`` for the full section of a quarter model.

    Returns
    -------
    ndarray, shape (e * copies, k, 2)
        Closed boundary polygons (k = 8 for quad9, 4 for quad4) in mm.

    Examples
    --------
    >>> nodes = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    >>> section_polygons(nodes, np.array([[0, 1, 2, 3]]), mirror=("x",)).shape
    (2, 4, 2)
    """
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
    """Draw a (deformed) section (mm) on ``ax``; colour by element ``values`` if given.

    Returns the ``PolyCollection`` (for a colour bar).

    Parameters
    ----------
    ax : matplotlib Axes
        Where to draw (its aspect is set equal and its limits fitted).
    nodes : ndarray, shape (n, 2)
        Node coordinates in mm.
    elements : ndarray, shape (e, 9) or (e, 4)
        Node indices per element (see :func:`section_polygons`).
    values : ndarray, shape (e,), or None
        One colour value per element (e.g. von Mises stress in MPa); None draws outlines.
    mirror : sequence of {'x', 'y'}
        Reflected copies to add (see :func:`section_polygons`).
    cmap : str
        Colour map name for ``values``.
    vmax : float or None
        Top of the colour scale (bottom 0), in the unit of ``values``; default their maximum.
    edgecolor : str
        Outline colour when ``values`` is None.
    label : str
        Label of the collection (used by a colour bar or legend).

    Returns
    -------
    matplotlib.collections.PolyCollection

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> ax = Figure().subplots()
    >>> nodes = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    >>> pc = draw_section(ax, nodes, np.array([[0, 1, 2, 3]]), np.array([0.4]), mirror=("x",))
    >>> len(pc.get_paths()), pc.get_label()
    (2, 'von Mises stress (MPa)')
    """
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
    pc.set_label(label)
    ax.add_collection(pc)
    ax.set_aspect("equal")
    ax.autoscale_view()
    return pc


def plot_inflation_curve(
    result: InflationResult,
    ax: Any | None = None,
    *,
    measured: tuple[Sequence[float], Sequence[float], str] | None = None,
) -> Any:
    """Outer diameter (mm) against pressure (MPa): FE beside the incompressible closed form.

    Two lines: FE (markers) and the closed form (dashed), and optionally measured diameters
    (red squares). Returns the Axes.

    Parameters
    ----------
    result : InflationResult
        From :func:`exofric.simulate.inflate` (pressures in MPa, diameters in mm).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).
    measured : (sequence of float, sequence of float, str), optional
        Measured outer diameters to compare with: pressures (MPa), diameters (mm) and a
        legend label, e.g. Table 1's test column for the paper's 8.3 mm tube
        (``exofric.paper.table1()``).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import inflate
    >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.1, 0.2],
    ...             mesh=MeshSpec(1, 12, grading=6.0))
    >>> ax = plot_inflation_curve(r, Figure().subplots(),
    ...                           measured=([0.1, 0.2], [8.53, 8.78], "test (Table 1)"))
    >>> len(ax.lines), ax.get_ylabel()
    (3, 'outer diameter (mm)')
    """
    ax, created = new_axes(ax, (5.6, 4.4))
    ends = getattr(result, "ends", "plane-strain")
    fe_label, ref_label = ("FE (exofric)", "incompressible closed form") \
        if ends == "plane-strain" else (f"FE (exofric), {ends} ends",
                                        f"incompressible thick tube, {ends} ends")
    ax.plot(result.pressure_mpa, result.outer_diameter_mm, "o-", label=fe_label)
    ax.plot(result.pressure_mpa, result.analytic_outer_diameter_mm(), "k--",
            label=ref_label)
    if measured is not None:
        ax.plot(list(measured[0]), list(measured[1]), "s", ms=7, mfc="none", mew=1.5,
                color="tab:red", label=measured[2], zorder=4)
    ax.set_xlabel("pressure (MPa)")
    ax.set_ylabel("outer diameter (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL + 1, loc="upper left")
    finish(ax.figure, created)
    return ax


def plot_tube_ends(results: Sequence[InflationResult], fig: Any | None = None) -> Any:
    """Outer diameter and axial stretch against pressure for tubes with different ends.

    Two Axes on ``fig`` (an empty Figure; default a new one): the outer diameter (mm) and the
    axial stretch (unitless) of each result (markers: FE), each beside its incompressible
    reference (dashed: the plane-strain closed form or the semi-analytic closed/open-end
    thick tube). Returns the Figure.

    Parameters
    ----------
    results : sequence of InflationResult
        From :func:`exofric.simulate.inflate` with different ``ends`` (MPa, mm); the legend
        names each by its ends.
    fig : matplotlib Figure, optional
        An empty Figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import inflate
    >>> m = MooneyRivlin.from_shore(62.5)
    >>> rs = [inflate(8.3, 4.97, m, [0.1, 0.2], mesh=MeshSpec(1, 4), ends=e)
    ...       for e in ("plane-strain", "closed")]
    >>> f = plot_tube_ends(rs, Figure())
    >>> len(f.axes), f.axes[1].get_ylabel()
    (2, 'axial stretch (-)')
    """
    fig, created = new_figure(fig, (9.0, 3.8))
    ax_od, ax_l = fig.subplots(1, 2)
    for k, r in enumerate(results):
        c = f"C{k}"
        ends = getattr(r, "ends", "plane-strain")
        lz = np.ones_like(r.pressure_mpa) if r.axial_stretch is None else r.axial_stretch
        ax_od.plot(r.pressure_mpa, r.outer_diameter_mm, "o", color=c, label=f"FE, {ends}")
        ax_od.plot(r.pressure_mpa, r.analytic_outer_diameter_mm(), "--", color=c, lw=1.2,
                   label=f"reference, {ends}")
        ax_l.plot(r.pressure_mpa, lz, "o-", color=c, label=ends)
    ax_od.set_xlabel("pressure (MPa)")
    ax_od.set_ylabel("outer diameter (mm)")
    ax_od.legend(fontsize=SMALL, loc="upper left")
    ax_l.axhline(1.0, color="0.6", lw=0.8)
    ax_l.set_xlabel("pressure (MPa)")
    ax_l.set_ylabel("axial stretch (-)")
    ax_l.legend(fontsize=SMALL, loc="best")
    for a in (ax_od, ax_l):
        a.grid(alpha=0.3)
    ax_od.set_title("dashed: incompressible references", fontsize=SMALL + 1)
    finish(fig, created)
    return fig


def plot_inflation(
    result: InflationResult,
    fig: Any | None = None,
    *,
    measured: tuple[Sequence[float], Sequence[float], str] | None = None,
) -> Any:
    """Undeformed and deformed tube sections coloured by von Mises stress, and OD(P).

    Draws two Axes on ``fig`` (an empty Figure; default a new one) and returns the Figure.
    Without stored fields (``keep_fields=False``) the section panel shows the undeformed mesh.

    Parameters
    ----------
    result : InflationResult
        From :func:`exofric.simulate.inflate` (mm, MPa); the section is drawn at its last
        pressure.
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).
    measured : (sequence of float, sequence of float, str), optional
        Measured outer diameters for the OD(P) panel (MPa, mm, label); see
        :func:`plot_inflation_curve`.

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import inflate
    >>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.1, 0.2],
    ...             mesh=MeshSpec(1, 12, grading=6.0))
    >>> fig = plot_inflation(r, Figure())
    >>> len(fig.axes), fig.axes[0].get_title()          # section, OD(P), colour bar
    (3, 'Section at 0.2 MPa (grey: undeformed)')
    """
    fig, created = new_figure(fig, (10.0, 4.4))
    a1, a2 = fig.subplots(1, 2)
    draw_section(a1, result.nodes, result.elements, None, mirror=("x", "y"), edgecolor="0.6")
    if result.displacements:
        vmax = float(max(v.max() for v in result.von_mises_mpa))
        pc = draw_section(a1, result.nodes + result.displacements[-1], result.elements,
                          result.von_mises_mpa[-1], mirror=("x", "y"), vmax=vmax)
        fig.colorbar(pc, ax=a1, label="von Mises stress (MPa)")
    a1.set_title(f"Section at {result.pressure_mpa[-1]:g} MPa (grey: undeformed)",
                 fontsize=SMALL + 2)
    a1.set_xlabel("x (mm)")
    a1.set_ylabel("y (mm)")
    plot_inflation_curve(result, a2, measured=measured)
    finish(fig, created)
    return fig


def plot_squeeze_force(
    result: SqueezeResult,
    ax: Any | None = None,
    *,
    reference: tuple[float, float, str] | None = None,
    title: str = "",
    label: str = "exofric FE",
) -> Any:
    """Squeezing force N (N, total over the tube length) against pressure (MPa) (Fig 7).

    One line, a dotted vertical line at the contact onset (if reached), and an optional
    ``reference`` point ``(pressure MPa, force N, label)`` drawn as a red star.
    Returns the Axes.

    Parameters
    ----------
    result : SqueezeResult
        From :func:`exofric.simulate.squeeze` (pressures in MPa, forces in N).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).
    reference : (float, float, str) or None
        A point to compare with: pressure in MPa, force in N, legend label.
    title : str
        Axes title (none when empty).
    label : str
        Legend label of the FE curve.

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6],
    ...             mesh=MeshSpec(1, 12, grading=6.0), keep_fields=False)
    >>> ax = plot_squeeze_force(r, Figure().subplots(), reference=(0.6, 240.0, "paper"))
    >>> len(ax.lines), ax.get_ylabel()        # FE, reference star, contact onset
    (3, 'squeezing force N (N, L = 116 mm)')
    """
    ax, created = new_axes(ax, (6.4, 4.2))
    ax.plot(result.pressure_mpa, result.squeeze_force_n, "o-", label=label)
    estimate = getattr(result, "estimate", None)  # ErrorEstimate (absent on other N(P) results)
    if estimate is not None and estimate.n_per_mm is not None:
        # the two-mesh discretisation error estimate, as a band (N)
        half = np.asarray(estimate.n_per_mm) * result.structure.length_mm
        ax.fill_between(result.pressure_mpa, result.squeeze_force_n - half,
                        result.squeeze_force_n + half, color="tab:blue", alpha=0.25, lw=0,
                        label=f"estimated discretisation error ({estimate.accuracy})")
    if reference is not None:
        ax.plot([reference[0]], [reference[1]], "*", ms=12, color="tab:red", label=reference[2])
    if result.contact_onset_pressure_mpa is not None:
        ax.axvline(result.contact_onset_pressure_mpa, color="0.6", ls=":", label="contact onset")
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel(f"squeezing force N (N, L = {result.structure.length_mm:g} mm)")
    if title:
        ax.set_title(title, fontsize=SMALL + 1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL, loc="lower right")  # N(P) rises to the upper right
    finish(ax.figure, created)
    return ax


def plot_squeeze_curves(
    results: Sequence[SqueezeResult], ax: Any | None = None, *, title: str = ""
) -> Any:
    """N(P) (N against MPa) of several structures, one line each, labelled by name.

    Parameters
    ----------
    results : sequence of SqueezeResult
        From :func:`exofric.simulate.squeeze` (pressures in MPa, forces in N).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure).
    title : str
        Axes title (none when empty).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6],
    ...             mesh=MeshSpec(1, 12, grading=6.0), keep_fields=False)
    >>> ax = plot_squeeze_curves([r], Figure().subplots(), title="base group")
    >>> [t.get_text() for t in ax.get_legend().get_texts()]
    ['base (test 1)']
    """
    ax, created = new_axes(ax, (6.4, 4.2))
    for res in results:
        ax.plot(res.pressure_mpa, res.squeeze_force_n, "o-", ms=3, label=res.structure.name)
    ax.set_xlabel("pressure P (MPa)")
    ax.set_ylabel("squeezing force N (N)")
    if title:
        ax.set_title(title, fontsize=SMALL + 1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL)
    finish(ax.figure, created)
    return ax


def plot_squeeze(
    result: SqueezeResult,
    fig: Any | None = None,
    *,
    show_pressures: Sequence[float] = (0.2, 0.4, 0.6),
) -> Any:
    """Deformed sections with stress, the hole and the wire (Fig 6), and N(P) (Fig 7).

    One section per pressure of ``show_pressures`` (MPa; the nearest computed ones; hole D as
    a circle, the wire as a grey disc) and the N(P) panel of :func:`plot_squeeze_force`, on
    ``fig`` (an empty Figure; default a new one): one section beside N(P), or two and more in
    a row above it, sized for a page column (about 10 in wide).
    Without stored fields (``keep_fields=False``) only the N(P) panel is drawn.
    Returns the Figure.

    Parameters
    ----------
    result : SqueezeResult
        From :func:`exofric.simulate.squeeze` (mm, MPa, N), with fields for the sections.
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).
    show_pressures : sequence of float
        Pressures in MPa whose sections to draw (the nearest computed ones, each once).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.3, 0.6],
    ...             mesh=MeshSpec(1, 12, grading=6.0))
    >>> fig = plot_squeeze(r, Figure(), show_pressures=(0.6,))
    >>> len(fig.axes), fig.axes[0].get_title()[:10]     # section, N(P), colour bar
    (3, 'P = 0.6 MP')
    """
    from matplotlib.patches import Circle

    p = np.asarray(result.pressure_mpa)
    idx = sorted({int(np.argmin(np.abs(p - q))) for q in show_pressures})
    if not result.displacements:
        idx = []
    # sized for a ~1100 px page column (<= 1400 px at 130 dpi, text >= 9 pt): one or no
    # section beside N(P); two or more sections in a row above a centred N(P) panel
    s = result.structure
    if len(idx) >= 2:
        fig, created = new_figure(fig, (10.4, 7.6))
        if created:
            fig.set_layout_engine("constrained")
        top, bottom = fig.subfigures(2, 1, height_ratios=[1.15, 1.0])
        sections = list(np.atleast_1d(top.subplots(1, len(idx))))
        ax_n = bottom.add_subplot(bottom.add_gridspec(1, 6)[0, 1:5])
        bar_owner = top
    else:
        fig, created = new_figure(fig, (10.0, 4.4) if idx else (6.4, 4.4))
        if created and idx:
            fig.set_layout_engine("constrained")
        row = list(np.atleast_1d(fig.subplots(1, len(idx) + 1)))
        sections, ax_n = row[:-1], row[-1]
        bar_owner = fig
    pc = None
    # a full model (off-centre wire) is drawn as it is; the half model is mirrored about x = 0
    full = str(getattr(result, "symmetry", "")).startswith("full")
    angle = np.radians(float(getattr(result, "wire_angle_deg", 0.0)))
    r_wire = float(np.hypot(*s.wire_center_mm))
    wire_xy = (r_wire * np.sin(angle), r_wire * np.cos(angle))
    if idx:
        vmax = float(max(result.von_mises_mpa[i].max() for i in idx))
        for k, (ax, i) in enumerate(zip(sections, idx, strict=True)):
            pc = draw_section(ax, result.nodes + result.displacements[i], result.elements,
                              result.von_mises_mpa[i], mirror=() if full else ("x",),
                              vmax=vmax)
            ax.add_patch(Circle((0, 0), 0.5 * s.hole_mm, fill=False, color="0.3", lw=1.2))
            ax.add_patch(Circle(wire_xy, 0.5 * s.wire_mm, color="0.55"))
            ax.set_xlim(-0.55 * s.hole_mm, 0.55 * s.hole_mm)
            ax.set_ylim(-0.55 * s.hole_mm, 0.55 * s.hole_mm)
            ax.set_title(f"P = {p[i]:g} MPa, N = {result.squeeze_force_n[i]:.1f} N",
                         fontsize=SMALL + 1)
            ax.set_xlabel("x (mm)")
            if k == 0:
                ax.set_ylabel("y (mm)")
    if pc is not None:
        bar_owner.colorbar(pc, ax=sections, label="von Mises stress (MPa)", shrink=0.9)
    plot_squeeze_force(result, ax_n)
    if created and pc is None:
        fig.tight_layout()
    return fig


def plot_contact_pressure(result: SqueezeResult, ax: Any | None = None, *,
                          index: int = -1) -> Any:
    """Contact pressure (and friction traction) along the wire's and the wall's contact arcs.

    True normal pressure (MPa, solid, markers at the contact nodes) against the arc position
    (mm) from each arc's centre, for the wire (dark) and the hole wall (light); with friction
    the signed friction traction is dashed and sticking nodes are filled. The title gives the
    pressure and the integrals S_wire and S_wall (N/mm).

    Parameters
    ----------
    result : SqueezeResult
        From :func:`exofric.simulate.squeeze` (its ``contact`` profiles).
    ax : matplotlib Axes, optional
        Where to draw (default a new figure, 6.4 x 4.2 in).
    index : int
        Which pressure of ``result.pressure_mpa`` (default the last).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.fe import MeshSpec
    >>> from exofric.geometry import BASE
    >>> from exofric.material import MooneyRivlin
    >>> from exofric.simulate import squeeze
    >>> r = squeeze(BASE, MooneyRivlin.from_shore(62.5), [0.6], mesh=MeshSpec(2, 12))
    >>> plot_contact_pressure(r, Figure().add_subplot()).get_xlabel()
    'arc position from the contact centre (mm)'
    """
    ax, created = new_axes(ax, (6.4, 4.2))
    p = float(result.pressure_mpa[index])
    prof = result.contact.profiles[index] if result.contact.profiles else {}
    fric = result.mu_wall > 0.0 or result.mu_wire > 0.0
    for name, color in (("wire", "#1f4e79"), ("wall", "#e08a2c")):
        arc = prof.get(name)
        if not arc or not arc["arc_mm"]:
            continue
        s = np.asarray(arc["arc_mm"])
        stick = np.asarray(arc["stick"], dtype=bool)
        ax.plot(s, arc["pressure_mpa"], "-", color=color, lw=1.8,
                label=f"{name}: pressure")
        ax.plot(s[~stick], np.asarray(arc["pressure_mpa"])[~stick], "o", mfc="white",
                color=color, ms=4)
        ax.plot(s[stick], np.asarray(arc["pressure_mpa"])[stick], "o", color=color, ms=4)
        if fric:
            ax.plot(s, arc["shear_mpa"], "--", color=color, lw=1.2,
                    label=f"{name}: friction traction")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("arc position from the contact centre (mm)")
    ax.set_ylabel("contact traction (MPa)")
    sw = result.contact.wire_pressure_integral_n_per_mm
    sl = result.contact.wall_pressure_integral_n_per_mm
    title = f"P = {p:g} MPa"
    if sw is not None and sl is not None:
        title += f": S_wire {sw[index]:.3f}, S_wall {sl[index]:.3f} N/mm"
    if fric:
        title += f" (mu wall {result.mu_wall:g}, wire {result.mu_wire:g}; filled: stick)"
    ax.set_title(title, fontsize=SMALL)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=SMALL, loc="upper right")
    finish(ax.figure, created)
    return ax
