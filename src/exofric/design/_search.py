"""Design search: which structures of a swept space reach a target joint torque, and how easily.

Units: pressure MPa, squeezing force N and friction N (totals over the tube length),
torque Nm, lever arm m, sizes mm, deviation %.

For each solved design of a sweep (rows of :func:`exofric.design.run_sweep`), the squeeze
curve N(P) (with N(0) = 0 prepended when the sweep starts above 0 MPa: no contact force
before inflation) gives

* the torque at the allowed maximum pressure, T(pmax) = R (gamma N(pmax) + F0), with N
  interpolated by monotone cubic (PCHIP) interpolation between the swept pressures;
* the least pressure reaching the target torque, P* = N^-1((T*/R - F0) / gamma): the first
  root of the same interpolant (NaN when not reached by pmax);
* the margins pmax - P* (MPa) and T(pmax) - T* (Nm).

Designs reaching the target are ranked by least P* (``objective="pressure"``) or by largest
torque margin (``objective="margin"``). Each is marked ``in_validated_region`` when its
geometric deviation from the base is within the paper's 20 % and its hardness is the base's:
outside it, gamma is an extrapolation (paper Sec. 4: errors up to 189 %).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_finite, check_positive, check_range
from exofric.friction import FrictionModel, SqueezeCurve

__all__ = ["DesignSearch", "design_metrics", "search_designs", "DEFAULT_SPACE", "OBJECTIVES"]

#: What :func:`search_designs` ranks by: ``"pressure"`` (the lowest pressure, MPa, that reaches
#: the target torque) or ``"margin"`` (the largest torque margin, Nm, at the pressure limit).
OBJECTIVES = ("pressure", "margin")

#: Design space used by ``exofric design`` without a CONFIG: d1 and d2 around the base
#: group (D = 10 mm, ID scaled with d1) at the paper's 116 mm tube length and at 300 mm (the
#: knee's default 40 Nm at R = 0.1 m needs ~400 N of friction: the 116 mm base tube gives
#: 17 Nm at 0.6 MPa), the paper's 0.05-0.6 MPa, default mesh.
DEFAULT_SPACE: Mapping[str, Any] = {
    "name": "default-design-space",
    "pressures_mpa": [round(0.05 * i, 2) for i in range(1, 13)],
    "grid": {"hole_mm": [10.0], "tube_od_mm": [7.3, 7.8, 8.3, 8.8],
             "wire_mm": [1.1, 1.35, 1.6], "length_mm": [116.0, 300.0]},
}

_CANDIDATE_COLS = (
    "name", "family", "key", "hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm", "length_mm",
    "shore", "required_pressure_mpa", "pressure_margin_mpa", "torque_at_pmax_nm",
    "torque_margin_nm", "max_torque_nm", "max_pressure_mpa", "contact_onset_pressure_mpa",
    "deviation_pct", "in_validated_region", "note",
)


@checked_init
@dataclass(frozen=True)
class DesignSearch(DisplayMixin):
    """Designs of a sweep ranked against a target torque (Nm) at a pressure limit (MPa).

    Attributes
    ----------
    target_torque_nm : float
        Required joint torque T* (Nm).
    arm_radius_m : float
        Lever arm R (m).
    pmax_mpa : float
        Highest allowed pressure (MPa).
    gamma : float
        Friction coefficient of F = gamma N + F0 (unitless).
    f0_n : float
        Friction offset F0 (N).
    objective : str
        Ranking: ``'pressure'`` (least pressure reaching T*) or ``'margin'`` (largest
        torque margin).
    validated_only : bool
        Whether :attr:`ranked` keeps only designs inside the validated region.
    table : DataFrame
        One row per solved design (columns of :data:`_CANDIDATE_COLS` plus
        ``reaches_target``), reaching designs first in objective order.

    Examples
    --------
    >>> p = [0.2, 0.4, 0.6]
    >>> rows = pd.DataFrame({"key": ["a"] * 3 + ["b"] * 3, "design_index": [0] * 3 + [1] * 3,
    ...     "name": ["a"] * 3 + ["b"] * 3, "family": "", "status": "ok",
    ...     "pressure_mpa": p + p, "squeeze_force_n": [200.0, 400.0, 600.0, 50, 100, 150],
    ...     "hole_mm": 10.0, "tube_od_mm": 8.3, "tube_id_mm": 4.97, "wire_mm": 1.6,
    ...     "length_mm": 116.0, "shore": 62.5, "deviation_pct": 0.0,
    ...     "in_validated_region": True, "contact_onset_pressure_mpa": 0.0})
    >>> s = search_designs(rows, 40.0, 0.1, 0.6, gamma=1.0)    # 40 Nm at 0.1 m: F = 400 N
    >>> list(s.ranked["name"]), list(s.closest["name"]), round(s.best["torque_margin_nm"], 6)
    (['a'], ['b'], 20.0)
    """

    target_torque_nm: float
    arm_radius_m: float
    pmax_mpa: float
    gamma: float
    f0_n: float
    objective: str
    validated_only: bool
    table: pd.DataFrame = field(repr=False)

    @property
    def ranked(self) -> pd.DataFrame:
        """Designs reaching the target (only validated ones if ``validated_only``), ranked."""
        t = self.table[self.table["reaches_target"]]
        return t[t["in_validated_region"]] if self.validated_only else t

    @property
    def closest(self) -> pd.DataFrame:
        """Designs not reaching the target, largest torque at pmax first."""
        t = self.table[~self.table["reaches_target"]]
        return t.sort_values("torque_at_pmax_nm", ascending=False, kind="stable")

    @property
    def best(self) -> dict[str, Any] | None:
        """The best-ranked design (dict of :data:`_CANDIDATE_COLS`), None if none reaches."""
        r = self.ranked
        return _record(r.iloc[0]) if len(r) else None

    @property
    def best_validated(self) -> dict[str, Any] | None:
        """The best design inside the validated region, None if none reaches."""
        r = self.ranked[self.ranked["in_validated_region"]]
        return _record(r.iloc[0]) if len(r) else None

    def to_dict(self, top: int = 10) -> dict[str, Any]:
        """JSON-ready summary: the ``top`` ranked ``candidates`` and the ``closest`` designs
        that do not reach the target (MPa, Nm, mm, %).

        Parameters
        ----------
        top : int
            How many ranked candidates and closest non-reaching designs to list.

        Returns
        -------
        dict
            The search settings, counts (``evaluated``, ``reaching``, ...), ``best``,
            ``best_validated``, ``candidates`` and ``closest``.
        """
        reach = self.table[self.table["reaches_target"]]
        return {
            "target_torque_nm": self.target_torque_nm, "arm_radius_m": self.arm_radius_m,
            "pmax_mpa": self.pmax_mpa, "gamma": self.gamma, "f0_n": self.f0_n,
            "objective": self.objective, "validated_only": self.validated_only,
            "evaluated": int(len(self.table)), "reaching": int(len(reach)),
            "reaching_validated": int(reach["in_validated_region"].sum()),
            "outside_validated": int((~self.table["in_validated_region"]).sum()),
            "best": self.best, "best_validated": self.best_validated,
            "candidates": [_record(r) for _, r in self.ranked.head(top).iterrows()],
            "closest": [_record(r) for _, r in self.closest.head(top).iterrows()],
        }

    def to_frame(self) -> pd.DataFrame:
        """The ranked table as a DataFrame (a copy of :attr:`table`): one row per solved design.

        Reaching designs first in objective order. Columns: the design (``name``, ``key``,
        ``hole_mm``, ``tube_od_mm``, ``tube_id_mm``, ``wire_mm``, ``length_mm``, ``shore``),
        ``required_pressure_mpa`` (NaN when not reached), ``pressure_margin_mpa``,
        ``torque_at_pmax_nm``, ``torque_margin_nm``, ``max_torque_nm``, ``max_pressure_mpa``,
        ``contact_onset_pressure_mpa``, ``deviation_pct``, ``in_validated_region``,
        ``reaches_target`` and ``note``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> p = [0.2, 0.4, 0.6]
        >>> rows = pd.DataFrame({"key": ["a"] * 3, "design_index": 0, "name": "a",
        ...     "family": "", "status": "ok", "pressure_mpa": p,
        ...     "squeeze_force_n": [200.0, 400.0, 600.0], "hole_mm": 10.0, "tube_od_mm": 8.3,
        ...     "tube_id_mm": 4.97, "wire_mm": 1.6, "length_mm": 116.0, "shore": 62.5,
        ...     "deviation_pct": 0.0, "in_validated_region": True,
        ...     "contact_onset_pressure_mpa": 0.0})
        >>> s = search_designs(rows, 40.0, 0.1, 0.6, gamma=1.0)
        >>> s.to_frame()[["name", "required_pressure_mpa"]].round(6).values.tolist()
        [['a', 0.4]]
        """
        return self.table.copy()

    def plot(self, ax: Any | None = None, *, skipped: pd.DataFrame | None = None) -> Any:
        """Draw the design map: torque at pmax (Nm) over two design dimensions (mm).

        :func:`exofric.plots.plot_design_map` (best design starred, designs outside the
        validated region edged red); write it with :func:`exofric.plots.save`.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).
        skipped : DataFrame, optional
            Impossible designs of the sweep (``status == "skipped"`` rows), grey crosses.

        Returns
        -------
        matplotlib Axes

        Examples
        --------
        >>> p = [0.2, 0.4, 0.6]
        >>> rows = pd.DataFrame({"key": ["a"] * 3, "design_index": 0, "name": "a",
        ...     "family": "", "status": "ok", "pressure_mpa": p,
        ...     "squeeze_force_n": [200.0, 400.0, 600.0], "hole_mm": 10.0, "tube_od_mm": 8.3,
        ...     "tube_id_mm": 4.97, "wire_mm": 1.6, "length_mm": 116.0, "shore": 62.5,
        ...     "deviation_pct": 0.0, "in_validated_region": True,
        ...     "contact_onset_pressure_mpa": 0.0})
        >>> search_designs(rows, 40.0, 0.1, 0.6, gamma=1.0).plot().get_xlabel()
        'tube OD d1 (mm)'
        """
        from exofric.plots import plot_design_map

        return plot_design_map(self, ax, skipped=skipped)


def _record(row: pd.Series) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for c in _CANDIDATE_COLS:
        v = row[c]
        if isinstance(v, np.bool_ | bool):
            out[c] = bool(v)
        elif isinstance(v, float | np.floating):
            out[c] = None if not np.isfinite(v) else float(v)
        else:
            out[c] = v
    return out


def _one(p: np.ndarray, n: np.ndarray, pmax: float, target_n: float) -> tuple[float, float]:
    """(N at pmax (N), least pressure (MPa) where N reaches target_n, NaN beyond pmax).

    Both come from one :class:`~exofric.friction.SqueezeCurve` (monotone PCHIP of N(P), with
    (0 MPa, 0 N) prepended when the sweep starts above 0 MPa): the force at pmax is its value
    and the least pressure its first crossing of the target (:meth:`SqueezeCurve.pressure`).
    A target at or below the first node's force needs the curve's first pressure.
    """
    curve = SqueezeCurve(p, n).with_origin()
    n_pmax = float(curve(pmax, edge_tol_mpa=1e-12))       # pmax <= last pressure + 1e-12
    n_first, n_top = curve.force_range_n
    if target_n > n_top:
        return n_pmax, np.nan
    p_req = curve.pressure_mpa[0] if target_n <= n_first else curve.pressure(target_n)
    return n_pmax, (p_req if p_req <= pmax + 1e-12 else np.nan)


def design_metrics(
    frame: pd.DataFrame,
    target_torque_nm: float,
    arm_radius_m: float,
    pmax_mpa: float,
    gamma: float,
    f0_n: float = 0.0,
) -> pd.DataFrame:
    """Per-design torque at pmax, least pressure for the target and margins (unranked).

    Parameters
    ----------
    frame : DataFrame
        Sweep rows (one per design and pressure; ``status``, ``key``, ``pressure_mpa`` in MPa,
        ``squeeze_force_n`` in N, design columns in mm).
    target_torque_nm, arm_radius_m, pmax_mpa, gamma, f0_n : float
        Target T* (Nm), lever arm R (m), pressure limit (MPa), F = gamma N + F0 (F0 in N).

    Returns
    -------
    DataFrame
        One row per solved design with :data:`_CANDIDATE_COLS` and ``reaches_target``.

    Examples
    --------
    See :func:`search_designs`, which ranks this table.
    """
    model = FrictionModel(gamma, f0_n)
    target_n = float(model.squeeze(target_torque_nm / arm_radius_m))
    ok = frame[frame["status"] == "ok"].sort_values(["design_index", "pressure_mpa"])
    if ok.empty:
        raise InputError("the sweep has no solved design to search (all skipped or failed)")
    pmax_avail = float(ok.groupby("key")["pressure_mpa"].max().min())
    if pmax_mpa > pmax_avail + 1e-12:
        raise InputError(f"pmax_mpa {pmax_mpa:g} MPa is above the sweep's largest pressure "
                         f"{pmax_avail:g} MPa; allowed range (0, {pmax_avail:g}] MPa")
    rows = []
    for key, g in ok.groupby("key", sort=False):
        p = g["pressure_mpa"].to_numpy(float)
        n = g["squeeze_force_n"].to_numpy(float)
        n_pmax, p_req = _one(p, n, pmax_mpa, target_n)
        first = g.iloc[0]
        t_pmax = float(model.friction(n_pmax)) * arm_radius_m
        rows.append({
            **{c: first[c] for c in ("name", "family", "hole_mm", "tube_od_mm", "tube_id_mm",
                                     "wire_mm", "length_mm", "shore", "deviation_pct",
                                     "in_validated_region", "contact_onset_pressure_mpa",
                                     "design_index")},
            "key": key, "required_pressure_mpa": p_req,
            "pressure_margin_mpa": pmax_mpa - p_req, "torque_at_pmax_nm": t_pmax,
            "torque_margin_nm": t_pmax - target_torque_nm,
            "max_torque_nm": float(model.friction(float(n[-1]))) * arm_radius_m,
            "max_pressure_mpa": float(p[-1]), "reaches_target": bool(np.isfinite(p_req)),
            "note": "" if np.all(np.diff(n) >= 0) else "N(P) not monotone: first crossing",
        })
    out = pd.DataFrame(rows)
    out["in_validated_region"] = out["in_validated_region"].astype(bool)
    return out


def search_designs(
    frame: pd.DataFrame,
    target_torque_nm: float,
    arm_radius_m: float,
    pmax_mpa: float,
    *,
    gamma: float | None = None,
    f0_n: float | None = None,
    objective: str = "pressure",
    validated_only: bool = False,
) -> DesignSearch:
    """Rank the designs of a sweep that reach ``target_torque_nm`` by ``pmax_mpa``.

    Parameters
    ----------
    frame : DataFrame
        Rows of a sweep (:func:`exofric.design.run_sweep` ``.frame``).
    target_torque_nm : float
        Required joint torque T* (Nm), e.g. 40 for the knee (paper ref [32]).
    arm_radius_m : float
        Lever arm R (m), paper 0.10.
    pmax_mpa : float
        Highest allowed pressure (MPa), at most the sweep's largest pressure.
    gamma, f0_n : float, optional
        Friction model F = gamma N + F0 (default: the sweep's, from ``frame``).
    objective : {'pressure', 'margin'}
        Rank by least pressure reaching T*, or by largest torque margin T(pmax) - T* (Nm).
    validated_only : bool
        Rank only designs inside the validated deviation region.

    Returns
    -------
    DesignSearch

    Examples
    --------
    >>> import pandas as pd
    >>> p = [0.2, 0.4, 0.6]
    >>> rows = pd.DataFrame({"key": ["a"] * 3, "design_index": 0, "name": "a", "family": "",
    ...     "status": "ok", "pressure_mpa": p, "squeeze_force_n": [200.0, 400.0, 600.0],
    ...     "hole_mm": 10.0, "tube_od_mm": 8.3, "tube_id_mm": 4.97, "wire_mm": 1.6,
    ...     "length_mm": 116.0, "shore": 62.5, "deviation_pct": 0.0,
    ...     "in_validated_region": True, "contact_onset_pressure_mpa": 0.0})
    >>> s = search_designs(rows, 40.0, 0.1, 0.6, gamma=1.0)   # N = 1000 P reaches 400 N
    >>> round(s.best["required_pressure_mpa"], 6)
    0.4
    """
    t = check_positive("target_torque_nm", target_torque_nm, "Nm")
    r = check_positive("arm_radius_m (lever arm)", arm_radius_m, "m")
    pmax = check_range("pmax_mpa", pmax_mpa, 0.0, 2.0, lo_open=True, unit="MPa")
    if objective not in OBJECTIVES:
        raise InputError(f"objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}")

    def _from_frame(col: str, default: float) -> float:
        vals = frame[col].dropna().unique() if col in frame else np.array([])
        return float(vals[0]) if len(vals) else default

    g = check_positive("gamma", gamma if gamma is not None else _from_frame("gamma", D.PAPER_GAMMA))
    f0 = check_finite("f0_n (N)", f0_n if f0_n is not None else _from_frame("f0_n", 0.0))
    m = design_metrics(frame, t, r, pmax, g, f0)
    if objective == "pressure":
        order = ["reaches_target", "required_pressure_mpa", "torque_margin_nm"]
        asc = [False, True, False]
    else:
        order = ["reaches_target", "torque_margin_nm", "required_pressure_mpa"]
        asc = [False, False, True]
    m = m.sort_values(order + ["design_index"], ascending=asc + [True], kind="stable")
    return DesignSearch(t, r, pmax, g, f0, objective, validated_only, m.reset_index(drop=True))
