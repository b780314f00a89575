"""The design map: torque reachable at the pressure limit over two design dimensions.

Units on the axes: mm (or Shore A); colour: torque T(pmax) in Nm. Every design is drawn: where
other dimensions vary too (e.g. the hole D), one panel per combination of them. Squares reach
the target, circles do not; a black edge is inside the validated region, a red edge outside;
grey crosses are impossible designs; a star at a marker's corner marks the best-ranked
design (its number stays readable). A legend says so.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from exofric.plots._common import SMALL

if TYPE_CHECKING:
    import pandas as pd

    from exofric.design import DesignSearch

__all__ = ["plot_design_map", "map_axes"]

_AXIS_ORDER = ("tube_od_mm", "wire_mm", "hole_mm", "tube_id_mm", "shore", "length_mm")
_LABELS = {"tube_od_mm": "tube OD d1 (mm)", "wire_mm": "wire d2 (mm)",
           "hole_mm": "hole D (mm)", "tube_id_mm": "tube ID (mm)",
           "shore": "hardness (Shore A)", "length_mm": "tube length L (mm)"}
_SHORT = {"tube_od_mm": "d1 (mm)", "wire_mm": "d2 (mm)", "hole_mm": "D (mm)",
          "tube_id_mm": "ID (mm)", "shore": "Shore A", "length_mm": "L (mm)"}


def map_axes(table: pd.DataFrame) -> tuple[str, str]:
    """The two design columns to plot: varying ones first, d1 and d2 preferred.

    Parameters
    ----------
    table : DataFrame
        Designs with the columns ``tube_od_mm``, ``wire_mm``, ``hole_mm``, ``tube_id_mm``
        (mm), ``shore`` (Shore A) and ``length_mm`` (mm), e.g. ``DesignSearch.table``.

    Returns
    -------
    (str, str)
        The x and y column names: the first two that vary, in the order tube OD, wire, hole,
        tube ID, hardness, length (then constant ones in that order).

    Examples
    --------
    >>> import pandas as pd
    >>> t = pd.DataFrame({"tube_od_mm": [8.3, 8.3], "wire_mm": [1.6, 1.6],
    ...                   "hole_mm": [10.0, 11.0], "tube_id_mm": [4.97, 4.97],
    ...                   "shore": [62.5, 55.0], "length_mm": [116.0, 116.0]})
    >>> map_axes(t)
    ('hole_mm', 'shore')
    """
    varying = [c for c in _AXIS_ORDER if table[c].nunique() > 1]
    rest = [c for c in _AXIS_ORDER if c not in varying]
    x, y = (varying + rest)[:2]
    return x, y


def plot_design_map(
    search: DesignSearch,
    ax: Any | None = None,
    *,
    skipped: pd.DataFrame | None = None,
    x: str | None = None,
    y: str | None = None,
) -> Any:
    """Draw the design map on ``ax`` (default a new figure) and return its (first) Axes.

    Every design of ``search.table`` is one marker, coloured by its torque at pmax (Nm, the
    number inside): a square when it reaches the target, a circle when not; black edge inside
    the validated region, red outside. When dimensions other than ``x`` and ``y`` vary, one
    panel per combination of them (a given ``ax`` is split into those panels); a legend
    explains the markers.

    Parameters
    ----------
    search : DesignSearch
        Ranked designs (torques in Nm at ``search.pmax_mpa`` MPa).
    ax : matplotlib Axes, optional
        Where to draw (a colour bar is added beside it; split into panels if needed).
    skipped : DataFrame, optional
        Impossible designs (rows with the design columns), drawn as grey crosses.
    x, y : str, optional
        Design columns for the axes (default :func:`map_axes`).

    Returns
    -------
    matplotlib Axes
        The first panel (all panels are in its figure).

    Examples
    --------
    >>> from exofric.design import search_designs, sweep
    >>> from exofric.plots import save
    >>> frame = sweep({"pressures_mpa": [0.3, 0.6], "solver": {"n_radial": 1, "n_circ": 12},
    ...                "grid": {"wire_mm": [1.1, 1.6]}}, tmp_dir / "sweep", serial=True)
    >>> s = search_designs(frame, 12.0, 0.1, 0.6)            # 12 Nm on a 0.1 m arm
    >>> save(plot_design_map(s), tmp_dir / "design-map.png").name
    'design-map.png'
    """
    import numpy as np

    t = search.table
    dx, dy = map_axes(t)
    x, y = x or dx, y or dy
    facet_cols, combos = _facets(t, x, y)
    n = len(combos)
    ncol = min(n, 3)
    nrow = -(-n // ncol)
    fig, axes, created = _panels(ax, n, nrow, ncol)
    lo, hi = float(t["torque_at_pmax_nm"].min()), float(t["torque_at_pmax_nm"].max())
    reach = t["reaches_target"].to_numpy(bool) if "reaches_target" in t else \
        (t["torque_at_pmax_nm"] >= search.target_torque_nm).to_numpy(bool)
    t = t.assign(_reach=reach)
    sc = None
    for a, combo in zip(axes, combos, strict=True):
        pairs: list[tuple[str, Any]] = list(zip(facet_cols, combo, strict=True))
        sel = np.ones(len(t), bool)
        for c, w in pairs:
            sel &= (t[c] == w).to_numpy()
        sc = _draw_panel(a, t[sel], x, y, lo, hi, pairs, search.best, skipped) or sc
    for i, a in enumerate(axes):
        if i // ncol == nrow - 1 or i + ncol >= n:   # the lowest panel of its column
            a.set_xlabel(_LABELS.get(x, x))
            a.tick_params(labelbottom=True)         # shared x hides them above a gap
        if i % ncol == 0:
            a.set_ylabel(_LABELS.get(y, y))
            a.tick_params(labelleft=True)
    if sc is not None:
        fig.colorbar(sc, ax=axes, label=f"torque at {search.pmax_mpa:g} MPa (Nm)", shrink=0.9)
    handles = _legend_handles(search, skipped)
    head = (f"Target {search.target_torque_nm:g} Nm, R = {search.arm_radius_m:g} m, gamma = "
            f"{search.gamma:g}, pmax = {search.pmax_mpa:g} MPa; numbers: torque (Nm); "
            f"{len(t)} designs")
    if created:
        fig.suptitle(head, fontsize=SMALL + 1)
        fig.legend(handles=handles, fontsize=SMALL, loc="outside lower center", ncol=2,
                   frameon=False)
    else:
        axes[0].set_title(head if n == 1 else axes[0].get_title(), fontsize=SMALL)
        axes[-1].legend(handles=handles, fontsize=SMALL - 1, loc="best")
    return axes[0]


def _facets(t: pd.DataFrame, x: str, y: str) -> tuple[list[str], list[tuple[Any, ...]]]:
    """The dimensions other than x and y that vary within a cell, and their combinations (one
    panel each; a tube ID scaled with d1 adds none)."""
    facet_cols: list[str] = []
    for c in _AXIS_ORDER:
        if c not in (x, y) and t.groupby([x, y, *facet_cols])[c].nunique().max() > 1:
            facet_cols.append(c)
    combos = (list(t.groupby(facet_cols, sort=True).groups) if facet_cols else [()])
    return facet_cols, [c if isinstance(c, tuple) else (c,) for c in combos]


def _panels(ax: Any | None, n: int, nrow: int, ncol: int) -> tuple[Any, list[Any], bool]:
    """(figure, the n panel Axes, whether the figure is new): a new figure, or the caller's
    Axes split into the panels."""
    import numpy as np

    if ax is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(min(10.4, 1.0 + 3.3 * ncol) if n > 1 else 6.4,
                                  1.6 + 3.0 * nrow if n > 1 else 5.2),
                         layout="constrained")
        axes = list(np.atleast_1d(fig.subplots(nrow, ncol, squeeze=False,
                                               sharex=True, sharey=True).ravel()))
        created = True
    else:
        fig = ax.figure
        created = False
        if n == 1:
            axes = [ax]
        else:  # split the caller's Axes into the panels
            gs = ax.get_subplotspec().subgridspec(nrow, ncol)
            ax.remove()
            axes = [fig.add_subplot(gs[i // ncol, i % ncol]) for i in range(nrow * ncol)]
    for extra in axes[n:]:
        extra.remove()
    return fig, axes[:n], created


def _draw_panel(a: Any, sub: pd.DataFrame, x: str, y: str, lo: float, hi: float,
                pairs: list[tuple[str, Any]], best: Any, skipped: pd.DataFrame | None) -> Any:
    """One panel: the designs (torque in Nm as colour and number; square if it reaches the
    target; edge by the validated region), impossible ones, the best; its scatter or None."""
    import numpy as np

    sc = None
    for reached, marker in ((True, "s"), (False, "o")):
        part = sub[sub["_reach"] == reached]
        if not len(part):
            continue
        sc = a.scatter(part[x], part[y], c=part["torque_at_pmax_nm"], cmap="viridis",
                       vmin=lo, vmax=hi, s=330 if reached else 260, marker=marker,
                       edgecolors=["black" if v else "red"
                                   for v in part["in_validated_region"].to_numpy(bool)],
                       linewidths=1.8, zorder=3)
    for _, r in sub.iterrows():
        a.annotate(f"{r['torque_at_pmax_nm']:.0f}", (r[x], r[y]), ha="center", va="center",
                   fontsize=SMALL - 1, zorder=4,
                   color="white" if r["torque_at_pmax_nm"] < 0.5 * (lo + hi) else "black")
    if skipped is not None and len(skipped):
        ok = np.ones(len(skipped), bool)
        for c, w in pairs:
            ok &= (skipped[c] == w).to_numpy()
        sk = skipped[ok]
        if len(sk):
            a.scatter(sk[x], sk[y], marker="x", s=50, color="0.5", zorder=2)
    if best is not None and all(best[c] == w for c, w in pairs):
        from matplotlib.transforms import offset_copy

        # at the marker's upper right corner, so that the design's number stays readable
        corner = offset_copy(a.transData, fig=a.figure, x=10, y=10, units="points")
        a.scatter([best[x]], [best[y]], marker="*", s=170, color="orange", edgecolors="k",
                  zorder=5, transform=corner)
    if pairs:
        a.set_title(", ".join(f"{_SHORT.get(c, c)} = {w:g}" for c, w in pairs),
                    fontsize=SMALL + 1)
    a.margins(0.25)
    a.grid(alpha=0.3)
    return sc


def _legend_handles(search: DesignSearch, skipped: pd.DataFrame | None) -> list[Any]:
    """The legend's entries: what the marker shapes, edges, crosses and the star mean."""
    from matplotlib.lines import Line2D

    tgt = f"{search.target_torque_nm:g} Nm"
    handles = [
        Line2D([], [], marker="s", ls="none", ms=11, mfc="0.8", mec="k", mew=1.5,
               label=f"square: reaches {tgt} by {search.pmax_mpa:g} MPa"),
        Line2D([], [], marker="o", ls="none", ms=10, mfc="0.8", mec="k", mew=1.5,
               label=f"circle: does not reach {tgt}"),
        Line2D([], [], marker="s", ls="none", ms=11, mfc="none", mec="k", mew=1.5,
               label="black edge: inside the validated region"),
        Line2D([], [], marker="s", ls="none", ms=11, mfc="none", mec="red", mew=1.5,
               label="red edge: outside (> 20 % deviation or other hardness)"),
    ]
    if skipped is not None and len(skipped):
        handles.append(Line2D([], [], marker="x", ls="none", color="0.5",
                              label="impossible design"))
    best = search.best
    if best is not None:
        handles.append(Line2D([], [], marker="*", ls="none", ms=13, mfc="orange", mec="k",
                              label=f"best ({search.objective}): {best['name']}"))
    return handles
