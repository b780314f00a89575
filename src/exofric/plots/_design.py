"""The design map: torque reachable at the pressure limit over two design dimensions.

Units on the axes: mm (or Shore A); colour: torque T(pmax) in Nm. Where other dimensions
vary too, each cell shows the design of largest torque over them (a red edge when that
design is outside the validated region); grey crosses mark cells with only impossible
designs; the star is the best-ranked design.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from exofric.plots._common import new_axes

if TYPE_CHECKING:
    import pandas as pd

    from exofric.design import DesignSearch

__all__ = ["plot_design_map", "map_axes"]

_AXIS_ORDER = ("tube_od_mm", "wire_mm", "hole_mm", "tube_id_mm", "shore", "length_mm")
_LABELS = {"tube_od_mm": "tube OD d1 (mm)", "wire_mm": "wire d2 (mm)",
           "hole_mm": "hole D (mm)", "tube_id_mm": "tube ID (mm)",
           "shore": "hardness (Shore A)", "length_mm": "tube length L (mm)"}


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
    """Draw the design map on ``ax`` (default a new figure) and return the Axes.

    Parameters
    ----------
    search : DesignSearch
        Ranked designs (torques in Nm at ``search.pmax_mpa`` MPa).
    ax : matplotlib Axes, optional
        Where to draw (a colour bar is added beside it).
    skipped : DataFrame, optional
        Impossible designs (rows with the design columns), drawn as grey crosses.
    x, y : str, optional
        Design columns for the axes (default :func:`map_axes`).

    Returns
    -------
    matplotlib Axes

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
    import pandas as pd  # lazy: importing exofric.plots must not load pandas

    ax, created = new_axes(ax, (6.4, 5.2))
    fig = ax.figure
    if created:
        fig.set_layout_engine("constrained")
    t = search.table
    dx, dy = map_axes(t)
    x, y = x or dx, y or dy
    # one cell per (x, y): the design of largest torque there (and its validity)
    top = t.loc[t.groupby([x, y])["torque_at_pmax_nm"].idxmax()]
    cell = pd.DataFrame({x: top[x].to_numpy(), y: top[y].to_numpy(),
                         "torque": top["torque_at_pmax_nm"].to_numpy(),
                         "valid": top["in_validated_region"].to_numpy(bool)})
    sc = ax.scatter(cell[x], cell[y], c=cell["torque"], cmap="viridis", s=260, marker="s",
                    edgecolors=["black" if v else "red" for v in cell["valid"]], linewidths=1.5)
    fig.colorbar(sc, ax=ax, label=f"max torque at {search.pmax_mpa:g} MPa (Nm)")
    for _, r in cell.iterrows():
        ax.annotate(f"{r['torque']:.0f}", (r[x], r[y]), ha="center", va="center", fontsize=7,
                    color="white" if r["torque"] < cell["torque"].median() else "black")
    out_valid = cell[~cell["valid"]]
    if len(out_valid):
        ax.scatter([], [], marker="s", facecolors="none", edgecolors="red",
                   label="outside validated region (> 20 % deviation or other hardness)")
    if skipped is not None and len(skipped):
        taken = set(zip(cell[x], cell[y], strict=True))
        sk = skipped[[(a, b) not in taken for a, b in zip(skipped[x], skipped[y], strict=True)]]
        if len(sk):
            ax.scatter(sk[x], sk[y], marker="x", color="0.5", label="impossible design")
    best = search.best
    if best is not None:
        ax.scatter([best[x]], [best[y]], marker="*", s=300, color="orange", edgecolors="k",
                   zorder=5, label=f"best ({search.objective}): {best['name']}")
    ax.set_xlabel(_LABELS.get(x, x))
    ax.set_ylabel(_LABELS.get(y, y))
    ax.set_title(f"Target {search.target_torque_nm:g} Nm, R = {search.arm_radius_m:g} m, "
                 f"gamma = {search.gamma:g}, pmax = {search.pmax_mpa:g} MPa", fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        if created:
            fig.legend(fontsize=7, loc="outside lower center", ncol=1, frameon=False)
        else:
            ax.legend(fontsize=7)
    return ax
