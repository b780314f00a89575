"""Dimensionless form of the squeeze problem and a physical applicability measure.

Units: sizes mm, pressure and shear modulus MPa, force N; every group is unitless.

The plane-strain squeeze of a hyperelastic tube (Mooney-Rivlin with fixed C01/C10 and
Poisson's ratio, small-strain shear modulus G = 2 (C10 + C01)) between a rigid wire and a
rigid hole has, without gravity, no length scale of its own: every length can be scaled by
one factor (the contact penalty, a stiffness per area per gap, by its inverse) and the
displacement field scales with it (see ``tests/test_clearance.py``). Its inputs therefore
reduce to the groups

========================  =========================  =====================================
group                     definition                 physical meaning
========================  =========================  =====================================
``pressure_ratio``        P / G                      how hard the air inflates the wall
``clearance_ratio``       c / d1, c = D - d1 - d2    how far the tube must bulge to touch
``wall_ratio``            t / d1, t = (d1 - ID) / 2  bending stiffness of the wall
``wire_ratio``            d2 / d1                    how sharply the wire indents the tube
========================  =========================  =====================================

and the response, the squeeze force N over the tube length L, to the **squeeze number**
``N / (P L d2)``: the force on the wire per unit length in units of the pressure acting
over the wire's diameter, an effective contact width in wire diameters (0 before contact,
about 2 for the base group at 0.6 MPa, below 3.5 over the benchmark sweep). It was chosen over
``N / (L d1 G)`` because it stays O(1) at every pressure and size, so a surrogate fitted to it
(:mod:`exofric.design._surrogate`) has an error that is uniform in relative terms, whereas
``N / (L d1 G)`` grows from 0 by two orders of magnitude over 0.05-0.6 MPa (both groups
are exact for similar designs: N per length scales with the size at equal P/G).

The **applicability distance** (:func:`applicability`) is the normalised Euclidean distance
in the three geometric groups and in ln G, from the design to the nearest calibration
design (default: the paper's base group, on which gamma was fitted). Each group is divided
by its entry of :data:`GROUP_SCALES`: the change of that group alone that moves the base
group's squeeze curve N(P) by 10 % of N(0.6 MPa) on average over 0.05-0.6 MPa (central
differences of exofric's FE, recomputed by ``tests/test_surrogate.py``). A distance of 1
thus means: to first order, the squeeze mechanics of the design differ from the calibrated
ones by about as much as gamma's own calibration error on the base group (10.68 %, paper
Sec. 3.5), so gamma, an effective coefficient fitted on one contact regime, is being applied
to another. Physically the distance is dominated by the clearance: c/d1 sets the pressure at
which the tube first touches the wire, and N(P) is shifted by that onset.

The threshold :data:`APPLICABILITY_THRESHOLD` = 1 lies in the gap the paper's own data leave:
its accepted tests 2-5 (errors -25 to +12 %) are at distances 0.06-0.55, its failures, tests
7 and 6 (errors -92 and +189 %), at 1.6 and 4.1. The paper's deviation metric
(:func:`exofric.friction.deviation`, reported beside) does not separate them: test 4
(accepted) is at 13.7 %, test 2 at 9.1 % but at 31 % by the paper's own reading of Table 3.
``benchmarks/bench_surrogate.py`` checks the linearisation on a 256-design FE sweep (the
measured change of N(P) against the distance).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from exofric._validate import checked_init
from exofric.errors import InputError, check_positive
from exofric.friction import deviation
from exofric.geometry import BASE, Structure

__all__ = ["GROUPS", "GROUP_SCALES", "APPLICABILITY_THRESHOLD", "Applicability",
           "dimensionless_groups", "squeeze_number", "applicability", "sweep_groups"]

#: The geometric groups of a design (unitless), in this order.
GROUPS = ("clearance_ratio", "wall_ratio", "wire_ratio")

#: Scale of each group in the applicability distance: the change of that group alone that
#: moves the base group's squeeze curve (default mesh, Shore 62.5, no gravity) by 10 % of
#: N(0.6 MPa) on average over 0.05-0.6 MPa (central differences of exofric's FE; see the
#: module docstring). ``log_shear_modulus`` is the change of ln G.
GROUP_SCALES: Mapping[str, float] = {
    "clearance_ratio": 0.037, "wall_ratio": 0.028, "wire_ratio": 0.40,
    "log_shear_modulus": 0.25,
}

#: Applicability distance above which a prediction is flagged as an extrapolation (unitless):
#: between the paper's accepted tests 2-5 (at most 0.55) and its failed tests 7 and 6 (1.6,
#: 4.1); 1 ~ a 10 % change of N(P), gamma's own calibration error (10.68 %).
APPLICABILITY_THRESHOLD = 1.0


def dimensionless_groups(structure: Structure, shear_modulus_mpa: float) -> dict[str, float]:
    """The geometric groups of a structure and its shear modulus (unitless; G in MPa).

    Parameters
    ----------
    structure : Structure
        Hole D, tube OD d1 and ID, wire d2 (mm).
    shear_modulus_mpa : float
        Small-strain shear modulus G of the tube (MPa), e.g.
        :attr:`exofric.material.MooneyRivlin.shear_modulus`.

    Returns
    -------
    dict
        ``clearance_ratio`` c/d1, ``wall_ratio`` t/d1, ``wire_ratio`` d2/d1 (unitless) and
        ``shear_modulus_mpa`` (MPa; P/G is the pressure group).

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> g = dimensionless_groups(BASE, 1.33)
    >>> round(g["clearance_ratio"], 4), round(g["wall_ratio"], 4), round(g["wire_ratio"], 4)
    (0.012, 0.2006, 0.1928)
    >>> h = dimensionless_groups(BASE.scaled(1.5), 1.33)     # similar designs, same groups
    >>> all(abs(g[k] - h[k]) < 1e-12 for k in g)
    True
    """
    g = check_positive("shear_modulus_mpa", shear_modulus_mpa, "MPa")
    d1 = structure.tube_od_mm
    return {"clearance_ratio": structure.clearance_mm / d1, "wall_ratio": structure.wall_mm / d1,
            "wire_ratio": structure.wire_mm / d1, "shear_modulus_mpa": g}


def squeeze_number(squeeze_force_n: Any, pressure_mpa: Any, length_mm: Any,
                   wire_mm: Any) -> np.ndarray:
    """The response group N / (P L d2) (unitless; N in N, P in MPa, L and d2 in mm).

    Parameters
    ----------
    squeeze_force_n : array_like
        Squeeze force N over the tube length (N).
    pressure_mpa : array_like
        Pressure P (MPa), > 0.
    length_mm, wire_mm : array_like
        Tube length L and wire diameter d2 (mm).

    Returns
    -------
    ndarray
        N / (P L d2), broadcast over the inputs.

    Examples
    --------
    >>> float(squeeze_number(240.0, 0.6, 116.0, 1.6).round(3))
    2.155
    """
    p = np.asarray(pressure_mpa, dtype=float)
    if np.any(~(p > 0)):
        raise InputError("pressure_mpa must be > 0 MPa for the squeeze number N/(P L d2)")
    return np.asarray(squeeze_force_n, dtype=float) / (p * np.asarray(length_mm, float)
                                                       * np.asarray(wire_mm, float))


def sweep_groups(frame: pd.DataFrame) -> pd.DataFrame:
    """The groups of every row of a sweep (:func:`exofric.design.run_sweep` ``.frame``).

    Parameters
    ----------
    frame : DataFrame
        Sweep rows with the design sizes (mm), ``c10_mpa``/``c01_mpa`` (MPa),
        ``pressure_mpa`` (MPa) and ``squeeze_force_n`` (N).

    Returns
    -------
    DataFrame
        ``frame``'s rows with ``shear_modulus_mpa`` (MPa), ``pressure_ratio`` P/G,
        ``clearance_ratio``, ``wall_ratio``, ``wire_ratio`` and ``squeeze_number``
        N/(P L d2) (unitless) added.

    Examples
    --------
    >>> f = pd.DataFrame({"hole_mm": [10.0], "tube_od_mm": [8.3], "tube_id_mm": [4.97],
    ...     "wire_mm": [1.6], "length_mm": [116.0], "c10_mpa": [0.635], "c01_mpa": [0.032],
    ...     "pressure_mpa": [0.6], "squeeze_force_n": [240.0]})
    >>> g = sweep_groups(f)
    >>> round(float(g["pressure_ratio"][0]), 3), round(float(g["squeeze_number"][0]), 3)
    (0.45, 2.155)
    """
    f = frame.copy()
    f["shear_modulus_mpa"] = 2.0 * (f["c10_mpa"].to_numpy(float) + f["c01_mpa"].to_numpy(float))
    f["pressure_ratio"] = f["pressure_mpa"].to_numpy(float) / f["shear_modulus_mpa"]
    _add_geometric_groups(f)
    f["squeeze_number"] = squeeze_number(f["squeeze_force_n"], f["pressure_mpa"],
                                         f["length_mm"], f["wire_mm"])
    return f


def _add_geometric_groups(f: pd.DataFrame) -> None:
    """Add the columns of :data:`GROUPS` (unitless) to a table of designs, in place, from its
    ``hole_mm``, ``tube_od_mm``, ``tube_id_mm`` and ``wire_mm`` (mm): the definitions of
    :func:`dimensionless_groups`, one row per design or per sweep row."""
    d1 = f["tube_od_mm"].to_numpy(float)
    f["clearance_ratio"] = (f["hole_mm"].to_numpy(float) - d1 - f["wire_mm"].to_numpy(float)) / d1
    f["wall_ratio"] = 0.5 * (d1 - f["tube_id_mm"].to_numpy(float)) / d1
    f["wire_ratio"] = f["wire_mm"].to_numpy(float) / d1


@checked_init
@dataclass(frozen=True)
class Applicability:
    """How far a design is from the calibration designs, in the dimensionless groups.

    Attributes
    ----------
    distance : float
        Normalised Euclidean distance in the groups to the nearest calibration design
        (unitless; 1 ~ a 10 % change of the squeeze curve, see the module docstring).
    nearest : int
        Index of that calibration design.
    contributions : dict
        Signed normalised difference per group (``clearance_ratio``, ``wall_ratio``,
        ``wire_ratio``, ``log_shear_modulus``) to the nearest calibration design.
    threshold : float
        Distance above which the design is outside the applicability domain.
    deviation_pct : float
        The paper's deviation metric (max/min ratio of the D, d1, d2 scale factors, %) from
        :func:`exofric.friction.deviation` against the nearest calibration design.
    paper_deviation_pct : float
        The largest |scale factor - 1| (%), the paper's reading of its Table 3.

    Examples
    --------
    >>> from exofric.geometry import Structure
    >>> a = applicability(Structure(10.0, 8.3, 4.97, 1.1), 1.33)      # Table 3, test 7
    >>> round(a.distance, 1), a.inside, max(a.contributions, key=a.contributions.get)
    (1.6, False, 'clearance_ratio')
    """

    distance: float
    nearest: int
    contributions: dict[str, float]
    threshold: float
    deviation_pct: float
    paper_deviation_pct: float

    @property
    def inside(self) -> bool:
        """True when the distance is at most the threshold."""
        return bool(self.distance <= self.threshold)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unitless distance, deviations in %)."""
        return {"applicability_distance": self.distance, "nearest_calibration": self.nearest,
                "contributions": dict(self.contributions), "threshold": self.threshold,
                "inside_applicability_domain": self.inside,
                "deviation_pct": self.deviation_pct,
                "paper_deviation_pct": self.paper_deviation_pct}


def _coords(structure: Structure, g_mpa: float) -> np.ndarray:
    grp = dimensionless_groups(structure, g_mpa)
    return np.array([grp[k] / GROUP_SCALES[k] for k in GROUPS]
                    + [np.log(g_mpa) / GROUP_SCALES["log_shear_modulus"]])


def applicability(
    structure: Structure,
    shear_modulus_mpa: float,
    calibration: Sequence[tuple[Structure, float]] | None = None,
    threshold: float = APPLICABILITY_THRESHOLD,
) -> Applicability:
    """Distance of a design from the calibration designs in the dimensionless groups.

    Parameters
    ----------
    structure : Structure
        The design (mm).
    shear_modulus_mpa : float
        Its tube's shear modulus G (MPa).
    calibration : sequence of (Structure, float), optional
        The designs gamma was calibrated on, each with its G (MPa). Default: the paper's
        base group with Shore 62.5 (paper correlation, G = 1.334 MPa).
    threshold : float
        Distance above which the design is outside the domain (default
        :data:`APPLICABILITY_THRESHOLD`).

    Returns
    -------
    Applicability

    Examples
    --------
    >>> from exofric.friction import paper_structures
    >>> [round(applicability(s, 1.334).distance, 2) for s in paper_structures()]
    [0.0, 0.55, 0.06, 0.33, 0.27, 4.08, 1.64]
    """
    thr = check_positive("threshold", threshold)
    if calibration is None:
        from exofric.material import MooneyRivlin

        calibration = [(BASE, MooneyRivlin.from_shore(62.5).shear_modulus)]
    if not calibration:
        raise InputError("calibration must list at least one (structure, G) pair")
    x = _coords(structure, check_positive("shear_modulus_mpa", shear_modulus_mpa, "MPa"))
    cal = np.array([_coords(s, check_positive("calibration G", g, "MPa"))
                    for s, g in calibration])
    diff = x[None, :] - cal
    dist = np.sqrt((diff ** 2).sum(axis=1))
    i = int(np.argmin(dist))
    dev = deviation(structure, calibration[i][0])
    names = (*GROUPS, "log_shear_modulus")
    return Applicability(float(dist[i]), i, {k: float(v) for k, v in zip(names, diff[i],
                                                                           strict=True)},
                         thr, dev.deviation_pct, dev.paper_deviation_pct)
