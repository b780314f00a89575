"""Friction prediction for other structures and its applicability (paper Sec. 4, Table 3).

For each structure, the squeeze simulation gives N(P) (N, total over the tube length) and the
model gives F = gamma N + F0 (N). With a measured curve, the relative error per pressure is
(F_pred - F_meas) / F_meas in % (predicted at the measured pressures themselves: they are
added to the simulated pressures) and the maximum relative error is the signed value of
largest magnitude (Figs 8-10). With the base group measured too, each test's errors are
compared with the base group's by one-way ANOVA (Table 4).

Applicability. With scale factors s_D, s_d1, s_d2 (structure / base diameters):

* ``deviation_pct`` (exofric's metric) = 100 (max s / min s - 1): how far the structure is
  from a proportional scaling of the base (0 for any pure scaling). Table 3 gives
  9.1, 1.7, 13.7, 10.8, 23.0, 45.5 % for tests 2-7, ordered like the paper's findings.
* ``paper_deviation_pct`` = 100 max |s - 1| (matches the printed column for tests 4-7);
  ``tube_ref_deviation_pct`` = 100 max |s - s_d1| (matches tests 2-5 and 7). The paper
  does not define its column; see docs/paper-notes.md.
* ``clearance_change_pct`` = 100 (c / d1 - c_b / d1_b), c = D - d1 - d2 (mm): the gap that
  decides when contact starts, which the paper ignores (percentage points of the tube OD).

A prediction with ``deviation_pct`` above the threshold (20 %, where the paper found the
model valid) emits :class:`ApplicabilityWarning`.

Table 3 prints no tube inner diameters: :func:`paper_structures` takes the base ID scaled
with d1, ID_i = ID_base d1_i / d1_base (the same wall-to-diameter ratio), and L = 116 mm.

Two laws. ``gamma`` (a float or :class:`FrictionModel`) is the paper's F = gamma N + F0;
an :class:`~exofric.friction.InterfaceFrictionModel` is the interface-resolved law
F = mu_tube S_wire + mu_wall N + F0 (issue 15), which needs each squeeze result's
``wire_pressure_integral_n_per_mm`` (S_wire = that x L). Any other
:class:`~exofric.friction.FrictionLaw` plugs in the same way: predict gives it the columns it
names in ``inputs``. ``compare`` evaluates a law of another name beside the first: each
:class:`Prediction` then lists both (:class:`LawPrediction`) with their errors against the
measured curve, side by side.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_positive, check_pressures, check_series
from exofric.friction._fit import relative_errors
from exofric.friction._interfaces import WIRE_KEY, _get
from exofric.friction._law import FrictionLaw, curve_column
from exofric.friction._model import FrictionModel
from exofric.friction._stats import AnovaResult, anova_vs_base
from exofric.friction._torque import TorqueCheck, torque
from exofric.geometry import BASE, Structure

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "ApplicabilityWarning",
    "Deviation",
    "deviation",
    "LawPrediction",
    "MeasuredCurve",
    "Prediction",
    "PredictionSet",
    "predict",
    "paper_structures",
    "structures_from_dict",
]

#: Deviation (%) up to which the paper found the model valid (Sec. 4).
VALIDATED_DEVIATION_PCT = 20.0


class ApplicabilityWarning(UserWarning):
    """A friction prediction is made outside the geometric deviation the paper validated.

    Emitted by :func:`predict` for each structure whose ``deviation_pct`` exceeds the
    threshold (20 % by default); the prediction is still made.

    Examples
    --------
    >>> import warnings
    >>> from types import SimpleNamespace
    >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     _ = predict(paper_structures()[5:6], 0.7, None, [0.6], squeeze_fn=fake,
    ...                 base=paper_structures()[0])                      # test 6 vs base
    >>> [w.category.__name__ for w in caught]
    ['ApplicabilityWarning']
    """


@checked_init
@dataclass(frozen=True)
class Deviation:
    """Geometric deviation of a structure from the base group (see module docstring).

    Built by :func:`deviation`; s_D, s_d1, s_d2 are the structure / base ratios of the hole,
    tube OD and wire diameters.

    Attributes
    ----------
    scale_hole, scale_tube, scale_wire : float
        Scale factors s_D, s_d1, s_d2 (unitless).
    deviation_pct : float
        exofric's metric 100 (max s / min s - 1) in % (0 for a proportional scaling).
    paper_deviation_pct : float
        100 max |s - 1| in % (the paper's printed column for tests 4-7).
    tube_ref_deviation_pct : float
        100 max |s - s_d1| in % (the printed column for tests 2-5 and 7).
    size_change_pct : float
        Geometric-mean size change 100 (exp(mean ln s) - 1) in %.
    clearance_mm, base_clearance_mm : float
        Clearance c = D - d1 - d2 of the structure and of the base, in mm.
    clearance_change_pct : float
        100 (c / d1 - c_b / d1_b): change of the clearance relative to the tube OD, in
        percentage points.
    threshold_pct : float
        Deviation in % up to which the structure counts as in the validated region.

    Examples
    --------
    >>> from exofric.geometry import Structure
    >>> d = deviation(Structure(11.0, 9.2, 5.5, 1.6))      # Table 3, test 5
    >>> round(d.scale_hole, 3), round(d.deviation_pct, 1), d.in_validated_region
    (1.1, 10.8, True)
    """

    scale_hole: float
    scale_tube: float
    scale_wire: float
    deviation_pct: float
    paper_deviation_pct: float
    tube_ref_deviation_pct: float
    size_change_pct: float
    clearance_mm: float
    base_clearance_mm: float
    clearance_change_pct: float
    threshold_pct: float

    @property
    def in_validated_region(self) -> bool:
        """True when ``deviation_pct`` <= ``threshold_pct``."""
        return self.deviation_pct <= self.threshold_pct + 1e-9

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (scale factors unitless, % and mm)."""
        return {
            "scale_hole": self.scale_hole,
            "scale_tube": self.scale_tube,
            "scale_wire": self.scale_wire,
            "deviation_pct": self.deviation_pct,
            "paper_deviation_pct": self.paper_deviation_pct,
            "tube_ref_deviation_pct": self.tube_ref_deviation_pct,
            "size_change_pct": self.size_change_pct,
            "clearance_mm": self.clearance_mm,
            "base_clearance_mm": self.base_clearance_mm,
            "clearance_change_pct": self.clearance_change_pct,
            "threshold_pct": self.threshold_pct,
            "in_validated_region": self.in_validated_region,
        }


def deviation(
    structure: Structure, base: Structure = BASE, threshold_pct: float = VALIDATED_DEVIATION_PCT
) -> Deviation:
    """Deviation metrics of ``structure`` from ``base`` (diameters in mm, results in %).

    Parameters
    ----------
    structure : Structure
        The structure to assess (hole, tube OD and wire diameters in mm).
    base : Structure
        The base group it is compared with (default :data:`~exofric.geometry.BASE`).
    threshold_pct : float
        Deviation in % (> 0) up to which the model counts as validated (default 20 %).

    Returns
    -------
    Deviation

    Examples
    --------
    >>> from exofric.geometry import Structure
    >>> d = deviation(Structure(12.3, 9.2, 5.5, 1.6))     # Table 3, test 6
    >>> round(d.deviation_pct, 1), round(d.paper_deviation_pct, 1), d.in_validated_region
    (23.0, 23.0, False)
    """
    thr = check_positive("threshold_pct", threshold_pct, "%")
    s = np.array([structure.hole_mm / base.hole_mm, structure.tube_od_mm / base.tube_od_mm,
                  structure.wire_mm / base.wire_mm])
    c, cb = structure.clearance_mm, base.clearance_mm
    return Deviation(
        scale_hole=float(s[0]),
        scale_tube=float(s[1]),
        scale_wire=float(s[2]),
        deviation_pct=float(100.0 * (s.max() / s.min() - 1.0)),
        paper_deviation_pct=float(100.0 * np.max(np.abs(s - 1.0))),
        tube_ref_deviation_pct=float(100.0 * np.max(np.abs(s - s[1]))),
        size_change_pct=float(100.0 * (np.exp(np.mean(np.log(s))) - 1.0)),
        clearance_mm=float(c),
        base_clearance_mm=float(cb),
        clearance_change_pct=float(100.0 * (c / structure.tube_od_mm - cb / base.tube_od_mm)),
        threshold_pct=thr,
    )


def paper_structures(base: Structure = BASE) -> tuple[Structure, ...]:
    """The seven Table 3 structures (mm), named ``"test 1"`` ... ``"test 7"``.

    Tube IDs are not printed: ID_i = base.tube_id_mm x d1_i / base.tube_od_mm; L = base length.

    Parameters
    ----------
    base : Structure
        Supplies the tube ID to scale (mm) and the length L (mm); default
        :data:`~exofric.geometry.BASE`.

    Returns
    -------
    tuple of Structure

    Examples
    --------
    >>> s = paper_structures()
    >>> len(s), s[1].hole_mm, round(s[1].tube_id_mm, 4)
    (7, 7.5, 3.7125)
    """
    from exofric import paper

    out = []
    for row in paper.table3():
        d1 = float(row["tube_od_mm"])
        out.append(Structure(float(row["hole_mm"]), d1, base.tube_id_mm * d1 / base.tube_od_mm,
                             float(row["wire_mm"]), base.length_mm, f"test {row['test']}"))
    return tuple(out)


_KEYS = {"name", "hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm", "length_mm"}


def structures_from_dict(
    data: Mapping[str, Any], base: Structure = BASE
) -> tuple[tuple[Structure, ...], Structure]:
    """Structures from a parsed structures file (see ``examples/structures-paper.toml``).

    ``data`` has a list ``structure`` of tables with ``hole_mm``, ``tube_od_mm``, ``wire_mm``
    and optional ``name``, ``tube_id_mm`` (default: base ID scaled with d1), ``length_mm``
    (default: the base length); an optional ``base`` table (same keys, ``tube_id_mm``
    required) replaces :data:`~exofric.geometry.BASE`. Returns (structures, base).

    Parameters
    ----------
    data : mapping
        The parsed file (e.g. from :mod:`tomllib`); sizes in mm.
    base : Structure
        The base used when ``data`` has no ``base`` table (default
        :data:`~exofric.geometry.BASE`).

    Returns
    -------
    (tuple of Structure, Structure)
        The structures, in file order, and the base.

    Raises
    ------
    InputError
        Missing or unknown keys, non-numeric sizes, an empty list or duplicate names.

    Examples
    --------
    >>> structs, base = structures_from_dict(
    ...     {"structure": [{"name": "small", "hole_mm": 7.5, "tube_od_mm": 6.2,
    ...                     "wire_mm": 1.1}]})
    >>> s = structs[0]
    >>> s.name, round(s.tube_id_mm, 4), s.length_mm, base.name
    ('small', 3.7125, 116.0, 'base (test 1)')
    """
    if "base" in data:
        b = data["base"]
        if not isinstance(b, Mapping):
            raise InputError("structures file: 'base' must be a table")
        base = _structure(b, None, "base", base)
    rows = data.get("structure")
    if not isinstance(rows, list) or not rows:
        raise InputError("structures file: needs a non-empty [[structure]] list")
    out = tuple(_structure(r, base, f"structure {i + 1}", base) for i, r in enumerate(rows))
    names = [s.name for s in out]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise InputError(f"structures file: duplicate structure name {sorted(dup)[0]!r}")
    return out, base


def _structure(row: Any, scale_from: Structure | None, where: str, base: Structure) -> Structure:
    if not isinstance(row, Mapping):
        raise InputError(f"structures file: {where} must be a table")
    extra = set(row) - _KEYS
    if extra:
        raise InputError(f"structures file: {where} has unknown key {sorted(extra)[0]!r} "
                         f"(allowed: {', '.join(sorted(_KEYS))})")
    for key in ("hole_mm", "tube_od_mm", "wire_mm") + (("tube_id_mm",) if not scale_from else ()):
        if key not in row:
            raise InputError(f"structures file: {where} is missing {key!r}")
    try:
        d1 = float(row["tube_od_mm"])
        tid = (float(row["tube_id_mm"]) if "tube_id_mm" in row
               else base.tube_id_mm * d1 / base.tube_od_mm)
        return Structure(float(row["hole_mm"]), d1, tid, float(row["wire_mm"]),
                         float(row.get("length_mm", base.length_mm)),
                         str(row.get("name", where)))
    except (TypeError, ValueError) as exc:
        if isinstance(exc, InputError):
            raise InputError(f"structures file: {where}: {exc}") from None
        raise InputError(f"structures file: {where}: sizes must be numbers in mm") from None


@checked_init
@dataclass(frozen=True)
class MeasuredCurve:
    """A measured friction curve: pressures (MPa) and friction forces (N).

    Build it with :meth:`of`, which validates and sorts the points.

    Attributes
    ----------
    pressure_mpa : tuple of float
        Pressures in MPa, >= 0, non-decreasing (a pressure repeats for replicate pulls; each
        replicate is one error in the ANOVA).
    friction_n : tuple of float
        Measured friction forces in N, one per pressure.

    Examples
    --------
    >>> MeasuredCurve((0.3, 0.6), (70.0, 180.0)).friction_n
    (70.0, 180.0)
    """

    pressure_mpa: tuple[float, ...]
    friction_n: tuple[float, ...]

    @classmethod
    def of(cls, pressure_mpa: ArrayLike, friction_n: ArrayLike) -> MeasuredCurve:
        """Validated curve (finite, equal lengths; replicates allowed), sorted by pressure.

        Parameters
        ----------
        pressure_mpa : array_like
            Pressures in MPa, >= 0, any order; a repeated pressure is a replicate.
        friction_n : array_like
            Friction forces in N, one per pressure.

        Returns
        -------
        MeasuredCurve

        Raises
        ------
        InputError
            NaN/inf, negative pressures or unequal lengths.

        Examples
        --------
        >>> MeasuredCurve.of([0.6, 0.3], [180.0, 70.0]).pressure_mpa
        (0.3, 0.6)
        """
        p, f = check_series("pressure_mpa", pressure_mpa, "friction_n", friction_n,
                            x_unit="MPa", y_unit="N", increasing=False, min_points=1,
                            x_min=0.0, where="measured curve")
        o = np.argsort(p, kind="stable")
        return cls(tuple(p[o].tolist()), tuple(f[o].tolist()))


#: Any friction law (kept name; the laws' protocol is :class:`~exofric.friction.FrictionLaw`).
AnyLaw = FrictionLaw


def structure_label(structure: Structure) -> str:
    """A structure's label in tables: its ``name``, else its diameters (mm).

    Examples
    --------
    >>> structure_label(Structure(10.0, 8.3, 4.97, 1.6))
    'D 10 / d1 8.3 / ID 4.97 / d2 1.6 mm'
    >>> structure_label(Structure(10.0, 8.3, 4.97, 1.6, name="base"))
    'base'
    """
    return structure.name or (f"D {structure.hole_mm:g} / d1 {structure.tube_od_mm:g} / "
                              f"ID {structure.tube_id_mm:g} / d2 {structure.wire_mm:g} mm")


def _law_name(model: FrictionLaw) -> str:
    return model.name


def _law_params(model: FrictionLaw) -> dict[str, Any]:
    """The law's coefficients (its ``to_dict()`` without the ``law`` label)."""
    return {k: v for k, v in model.to_dict().items() if k != "law"}


@checked_init
@dataclass(frozen=True)
class LawPrediction:
    """One law's predicted friction for one structure, and its errors (N, %).

    Attributes
    ----------
    law : str
        Which law (its ``name``): ``"gamma"`` for F = gamma N + F0, ``"interfaces"`` for
        F = mu_tube S_wire + mu_wall N + F0, or another :class:`FrictionLaw`'s.
    model : FrictionLaw
        Its coefficients (unitless) and F0 (N).
    predicted_friction_n : tuple of float
        Friction in N at the prediction's pressures.
    relative_error_pct : tuple of float
        Signed relative error in % at each measured point (empty without a measurement).

    Examples
    --------
    >>> lp = LawPrediction("gamma", FrictionModel(0.5), (60.0, 120.0), (9.09, -4.0))
    >>> round(lp.max_relative_error_pct, 2), round(lp.mean_abs_relative_error_pct, 3)
    (9.09, 6.545)
    """

    law: str
    model: AnyLaw
    predicted_friction_n: tuple[float, ...]
    relative_error_pct: tuple[float, ...] = ()

    @property
    def max_relative_error_pct(self) -> float | None:
        """Signed relative error of largest magnitude (%), None without a measurement."""
        e = np.asarray(self.relative_error_pct, dtype=float)
        e = e[np.isfinite(e)]
        return float(e[np.argmax(np.abs(e))]) if e.size else None

    @property
    def mean_abs_relative_error_pct(self) -> float | None:
        """Mean |relative error| (%), None without a measurement."""
        e = np.asarray(self.relative_error_pct, dtype=float)
        e = e[np.isfinite(e)]
        return float(np.mean(np.abs(e))) if e.size else None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: law, coefficients (unitless), F (N), errors (%)."""
        return {
            "law": self.law,
            **_law_params(self.model),
            "predicted_friction_n": list(self.predicted_friction_n),
            "relative_error_pct": list(self.relative_error_pct),
            "max_relative_error_pct": self.max_relative_error_pct,
            "mean_abs_relative_error_pct": self.mean_abs_relative_error_pct,
        }


@checked_init
@dataclass(frozen=True)
class Prediction(DisplayMixin):
    """Predicted friction for one structure (MPa, N, %, Nm).

    One entry of :attr:`PredictionSet.predictions`, built by :func:`predict`.

    Attributes
    ----------
    structure : Structure
        The structure (sizes in mm).
    model : FrictionLaw
        The law used: gamma (unitless), or mu_tube and mu_wall (unitless), or another
        :class:`FrictionLaw`; and F0 (N).
    pressure_mpa : tuple of float
        Pressures of the predicted curve in MPa (the requested ones plus any measured ones).
    squeeze_force_n : tuple of float
        Simulated squeezing force N(P) in N (total over the tube length).
    predicted_friction_n : tuple of float
        F = gamma N + F0 in N.
    contact_onset_pressure_mpa : float or None
        Pressure in MPa at which the tube first touches the wire, if the squeeze reported it.
    deviation : Deviation
        Geometric deviation from the base (metrics in % and mm).
    torque : TorqueCheck
        Torque T = F R in Nm at the highest pressure, against the required range.
    measured : MeasuredCurve or None
        The measured curve (MPa, N), if one was given.
    relative_error_pct : tuple of float
        Signed relative error in % at each measured pressure (empty without a measurement).
    wire_pressure_integral_n : tuple of float
        S_wire in N per pressure (the tube-wire contact pressure integrated over the arc and
        the length), when the squeeze reported it; else empty.
    laws : tuple of LawPrediction
        Every law evaluated, the one used first (two with ``compare``); empty when built by
        hand.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
    >>> meas = {"test 1": MeasuredCurve.of([0.3, 0.6], [55.0, 125.0])}
    >>> pr = predict(paper_structures()[:1], 0.5, None, [0.3, 0.6], squeeze_fn=fake,
    ...              measured=meas).predictions[0]
    >>> pr.predicted_friction_n, round(pr.max_relative_error_pct, 2), pr.torque.torque_nm
    ((60.0, 120.0), 9.09, 12.0)
    """

    structure: Structure
    model: AnyLaw
    pressure_mpa: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    predicted_friction_n: tuple[float, ...]
    contact_onset_pressure_mpa: float | None
    deviation: Deviation
    torque: TorqueCheck
    measured: MeasuredCurve | None = None
    relative_error_pct: tuple[float, ...] = ()
    wire_pressure_integral_n: tuple[float, ...] = ()
    laws: tuple[LawPrediction, ...] = ()

    @property
    def law(self) -> str:
        """The law used (its name): ``"gamma"``, ``"interfaces"`` or another law's."""
        return _law_name(self.model)

    @property
    def max_relative_error_pct(self) -> float | None:
        """Signed relative error of largest magnitude (%), None without a measured curve."""
        e = np.asarray(self.relative_error_pct, dtype=float)
        e = e[np.isfinite(e)]
        return float(e[np.argmax(np.abs(e))]) if e.size else None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: curves (MPa, N), errors (%), deviation (%), torque (Nm)."""
        params = _law_params(self.model)
        d: dict[str, Any] = {
            "name": self.structure.name,
            "structure": self.structure.to_dict(),
            "gamma": params.pop("gamma", None),
            "f0_n": self.model.f0_n,
            "pressure_mpa": list(self.pressure_mpa),
            "squeeze_force_n": list(self.squeeze_force_n),
            "predicted_friction_n": list(self.predicted_friction_n),
            "contact_onset_pressure_mpa": self.contact_onset_pressure_mpa,
            "deviation_pct": self.deviation.deviation_pct,
            "paper_deviation_pct": self.deviation.paper_deviation_pct,
            "in_validated_region": self.deviation.in_validated_region,
            "deviation": self.deviation.to_dict(),
            "max_friction_n": self.torque.friction_n,
            "max_torque_nm": self.torque.torque_nm,
            "meets_torque_requirement": self.torque.meets_max,
            "law": self.law,
        }
        params.pop("f0_n", None)
        d.update(params)                   # the law's other coefficients (mu_tube, mu_wall)
        if self.wire_pressure_integral_n:
            d["wire_pressure_integral_n"] = list(self.wire_pressure_integral_n)
        if self.measured is not None:
            d["measured_pressure_mpa"] = list(self.measured.pressure_mpa)
            d["measured_friction_n"] = list(self.measured.friction_n)
            d["relative_error_pct"] = list(self.relative_error_pct)
            d["max_relative_error_pct"] = self.max_relative_error_pct
        if len(self.laws) > 1:
            d["law_comparison"] = {lp.law: lp.to_dict() for lp in self.laws}
        return d

    def to_frame(self) -> pd.DataFrame:
        """The predicted curve as a DataFrame: one row per pressure (MPa, N, %).

        Columns: ``structure`` (its name, else its diameters: :func:`structure_label`),
        ``pressure_mpa``, ``squeeze_force_n``,
        ``predicted_friction_n``, and with a measured curve ``measured_friction_n`` and
        ``relative_error_pct`` (means over replicates; NaN at pressures without a
        measurement; the measured pressures are among the predicted ones) and ``n_measured``.
        With S_wire known, ``wire_pressure_integral_n``; with two laws compared, per law
        ``<law>_friction_n`` and, when measured, ``<law>_relative_error_pct`` (law ``gamma``
        or ``interfaces``).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from types import SimpleNamespace
        >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
        >>> r = predict(paper_structures()[:1], 0.5, None, [0.3, 0.6], squeeze_fn=fake)
        >>> r.predictions[0].to_frame()["predicted_friction_n"].tolist()
        [60.0, 120.0]
        """
        import pandas as pd

        p = np.asarray(self.pressure_mpa, dtype=float)
        cols: dict[str, Any] = {
            "structure": [structure_label(self.structure)] * p.size,
            "pressure_mpa": p,
            "squeeze_force_n": np.asarray(self.squeeze_force_n, dtype=float),
            "predicted_friction_n": np.asarray(self.predicted_friction_n, dtype=float),
        }
        if self.wire_pressure_integral_n:
            cols["wire_pressure_integral_n"] = np.asarray(self.wire_pressure_integral_n,
                                                          dtype=float)
        compare = len(self.laws) > 1
        if compare:
            for lp in self.laws:
                cols[f"{lp.law}_friction_n"] = np.asarray(lp.predicted_friction_n, dtype=float)
        if self.measured is not None:
            at = np.searchsorted(p, np.asarray(self.measured.pressure_mpa, dtype=float))
            count = np.bincount(at, minlength=p.size).astype(float)

            def per_pressure(values: Any) -> Any:
                with np.errstate(invalid="ignore", divide="ignore"):
                    v = np.bincount(at, weights=values, minlength=p.size) / count
                return np.where(count > 0, v, np.nan)

            cols["measured_friction_n"] = per_pressure(self.measured.friction_n)
            cols["relative_error_pct"] = per_pressure(self.relative_error_pct)
            cols["n_measured"] = count.astype(int)
            if compare:
                for lp in self.laws:
                    cols[f"{lp.law}_relative_error_pct"] = per_pressure(lp.relative_error_pct)
        return pd.DataFrame(cols)


@checked_init
@dataclass(frozen=True)
class PredictionSet(DisplayMixin):
    """Predictions for several structures, plus the ANOVA vs the base group when measured.

    Returned by :func:`predict`.

    Attributes
    ----------
    predictions : tuple of Prediction
        One per structure, in the order given.
    base : Structure
        The base group of the deviation metrics (mm).
    anova : tuple of AnovaResult
        Each measured test structure's errors against the base group's (Table 4); empty
        unless the base group and at least one other structure were measured.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
    >>> r = predict(paper_structures()[:2], 0.5, None, [0.3, 0.6], squeeze_fn=fake)
    >>> [p.structure.name for p in r.predictions], r.anova
    (['test 1', 'test 2'], ())
    """

    predictions: tuple[Prediction, ...]
    base: Structure
    anova: tuple[AnovaResult, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict with ``structures`` (list) and ``anova`` (list).

        Also ``law`` (``"gamma"`` or ``"interfaces"``; ``gamma`` is None for the latter, which
        adds ``mu_tube`` and ``mu_wall``) and, with two laws compared, ``law_comparison``:
        per law the mean and largest |relative error| (%) over every measured point.
        """
        first = self.predictions[0] if self.predictions else None
        model = None if first is None else first.model
        params = {} if model is None else _law_params(model)
        d: dict[str, Any] = {
            "gamma": params.pop("gamma", None),
            "base": self.base.to_dict(),
            "structures": [p.to_dict() for p in self.predictions],
            "anova": [a.to_dict() for a in self.anova],
            "law": "gamma" if model is None else _law_name(model),
        }
        params.pop("f0_n", None)
        d.update(params)                   # the law's other coefficients (mu_tube, mu_wall)
        if first is not None and len(first.laws) > 1:
            summary: dict[str, Any] = {}
            for i, lp in enumerate(first.laws):
                e = np.concatenate([np.asarray(p.laws[i].relative_error_pct, dtype=float)
                                    for p in self.predictions] + [np.empty(0)])
                e = e[np.isfinite(e)]
                summary[lp.law] = {
                    **_law_params(lp.model),
                    "n_measured": int(e.size),
                    "mean_abs_relative_error_pct": float(np.mean(np.abs(e))) if e.size
                    else None,
                    "max_abs_relative_error_pct": float(np.max(np.abs(e))) if e.size else None,
                }
            d["law_comparison"] = summary
        return d

    def to_frame(self) -> pd.DataFrame:
        """All predicted curves as one DataFrame: one row per structure and pressure.

        The rows of each :meth:`Prediction.to_frame`, stacked in structure order (columns
        ``structure``, ``pressure_mpa``, ``squeeze_force_n``, ``predicted_friction_n``, and
        ``measured_friction_n``, ``relative_error_pct`` when any curve was measured).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from types import SimpleNamespace
        >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
        >>> r = predict(paper_structures()[:2], 0.5, None, [0.3, 0.6], squeeze_fn=fake)
        >>> r.to_frame().groupby("structure").size().tolist()
        [2, 2]
        """
        import pandas as pd

        frames = [p.to_frame() for p in self.predictions]
        if not frames:
            return pd.DataFrame(columns=["structure", "pressure_mpa", "squeeze_force_n",
                                         "predicted_friction_n"])
        return pd.concat(frames, ignore_index=True)

    def plot(self, fig: Any | None = None, *, title: str = "") -> Any:
        """Draw predicted (black) vs tested (red) friction and the relative error, per structure.

        One row of two Axes per structure (:func:`exofric.plots.plot_predictions`); write the
        figure with :func:`exofric.plots.save`.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on (default a new one).
        title : str
            Figure title.

        Returns
        -------
        matplotlib Figure

        Examples
        --------
        >>> from types import SimpleNamespace
        >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
        >>> r = predict(paper_structures()[:2], 0.5, None, [0.3, 0.6], squeeze_fn=fake)
        >>> len(r.plot().axes)          # no measured curves: one panel of all predictions
        1
        """
        from exofric.plots import plot_predictions

        return plot_predictions(self.predictions, title, fig=fig)


SqueezeFn = Callable[[Structure, Any, np.ndarray], Any]


def _same_geometry(a: Structure, b: Structure) -> bool:
    return all(math.isclose(x, y, rel_tol=1e-9) for x, y in
               ((a.hole_mm, b.hole_mm), (a.tube_od_mm, b.tube_od_mm), (a.wire_mm, b.wire_mm)))


def _wire_integral(res: Any, structure: Structure) -> NDArray[np.float64]:
    """S_wire (N) per pressure of a squeeze result, or InputError naming the missing key.

    The result gives it per mm of tube (``wire_pressure_integral_n_per_mm``, N/mm): times its
    ``length_mm`` (default the structure's).
    """
    per_mm = _get(res, WIRE_KEY)
    if per_mm is None:
        raise InputError(
            f"{structure.name}: the squeeze result has no {WIRE_KEY!r} (the tube-wire contact "
            "pressure integral the interface law needs); make it with `exofric squeeze ... "
            "--json` from a version with contact outputs", param=WIRE_KEY)
    length = getattr(res, "length_mm", None) or structure.length_mm
    return np.asarray(per_mm, dtype=float).ravel() * float(length)


def _as_law(name: str, value: Any) -> FrictionLaw:
    if isinstance(value, FrictionLaw):
        return value
    try:
        g = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a gamma (number), a FrictionModel, an "
                         f"InterfaceFrictionModel or another FrictionLaw, got "
                         f"{type(value).__name__}", param=name) from None
    return FrictionModel(g)


#: The columns predict gives a law besides the pressure: N from the squeeze, S_wire from its
#: per-mm tube-wire integral (any other input is read off the squeeze result by its name).
_SQUEEZE_COLUMN = "squeeze_force_n"
_WIRE_COLUMN = "wire_pressure_integral_n"


def _law_inputs(res: Any, s: Structure, p: NDArray[np.float64], n: NDArray[np.float64],
                laws: Sequence[FrictionLaw]) -> dict[str, NDArray[np.float64]]:
    """The columns (MPa, N) the laws read, from one squeeze result at pressures ``p``.

    S_wire is taken whenever the result has it (it is reported), else only when a law needs
    it (InputError naming the missing key); any other input by its name on the result.
    """
    cols = {"pressure_mpa": p, _SQUEEZE_COLUMN: n}
    needed = {k for law in laws for k in law.inputs} - set(cols)
    maybe = _get(res, WIRE_KEY)
    if _WIRE_COLUMN in needed or (maybe is not None and np.size(maybe) == p.size):
        cols[_WIRE_COLUMN] = _wire_integral(res, s)
        if cols[_WIRE_COLUMN].shape != p.shape:
            raise InputError(f"{s.name}: squeeze returned {cols[_WIRE_COLUMN].size} {WIRE_KEY} "
                             f"values for {p.size} pressures")
    for key in sorted(needed - set(cols)):
        law = next(law.name for law in laws if key in law.inputs)
        cols[key] = curve_column(res, key, law, size=p.size, where=s.name)
    return cols


def _law_friction(model: FrictionLaw, cols: Mapping[str, NDArray[np.float64]]
                  ) -> NDArray[np.float64]:
    return np.asarray(model.friction_of(cols), dtype=float)


def _errors_at(f: NDArray[np.float64], at: NDArray[np.intp] | None,
               meas: MeasuredCurve | None) -> tuple[float, ...]:
    """Relative errors (%) of predicted F (N) at the measured points (empty without them)."""
    if at is None or meas is None:
        return ()
    return tuple(relative_errors(f[at], meas.friction_n).tolist())


def predict(
    structures: Sequence[Structure],
    gamma: float | FrictionLaw,
    material: Any,
    pressures_mpa: ArrayLike,
    *,
    squeeze_fn: SqueezeFn | None = None,
    measured: Mapping[str, MeasuredCurve] | None = None,
    base: Structure | None = None,
    threshold_pct: float = VALIDATED_DEVIATION_PCT,
    arm_radius_m: float = 0.10,
    required_torque_nm: tuple[float, float] = (0.0, 40.0),
    alpha: float = 0.05,
    compare: float | FrictionLaw | None = None,
) -> PredictionSet:
    """Predict F = gamma N(P) + F0 for each structure and compare with measured curves.

    Or, given an :class:`~exofric.friction.InterfaceFrictionModel`, the interface-resolved
    F = mu_tube S_wire(P) + mu_wall N(P) + F0.

    Parameters
    ----------
    structures : sequence of Structure
        Structures (mm); names must be unique (they key ``measured``).
    gamma : float or FrictionLaw
        The law used: an equivalent coefficient (unitless), a full gamma model with offset F0
        (N), the interface law (mu_tube, mu_wall unitless; F0 in N), which needs the
        squeeze results' ``wire_pressure_integral_n_per_mm``, or any other
        :class:`~exofric.friction.FrictionLaw` (its other inputs are read off the squeeze
        results by name).
    material : MooneyRivlin
        Tube material passed to the squeeze simulation.
    pressures_mpa : array_like
        Strictly increasing pressures (MPa) for the predicted curves.
    squeeze_fn : callable, optional
        ``squeeze(structure, material, pressures_mpa)`` returning an object with arrays
        ``pressure_mpa`` and ``squeeze_force_n`` (total N), optionally
        ``contact_onset_pressure_mpa``, and for the interface law
        ``wire_pressure_integral_n_per_mm`` (N/mm; times ``length_mm``, or the structure's
        length, for S_wire in N); default :func:`exofric.simulate.squeeze`.
    measured : mapping name -> MeasuredCurve, optional
        Measured friction per structure name; the measured pressures are simulated too.
    base : Structure, optional
        Reference for the deviation metrics (and the ANOVA base group when measured); default
        the first structure. The result's ``base`` (and ``to_dict()["base"]``) says which.
    threshold_pct : float
        Deviation (%) above which :class:`ApplicabilityWarning` is emitted.
    arm_radius_m, required_torque_nm : float, (float, float)
        Lever arm (m) and required torque range (Nm) for the torque check at max pressure.
    alpha : float
        ANOVA significance level.
    compare : float or FrictionLaw, optional
        A second law (of another name) evaluated beside the first (e.g. the interface law
        beside gamma): each prediction's ``laws`` then holds both, with their errors against
        the measured curve.

    Returns
    -------
    PredictionSet

    Warns
    -----
    ApplicabilityWarning
        For each structure with ``deviation_pct`` above ``threshold_pct``.

    Examples
    --------
    A stand-in squeeze N(P) = 400 P keeps the example fast; the default runs the FE.

    >>> from types import SimpleNamespace
    >>> fake = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p)
    >>> r = predict(paper_structures()[:2], 0.7, None, [0.2, 0.4, 0.6], squeeze_fn=fake)
    >>> [round(f, 6) for f in r.predictions[1].predicted_friction_n]
    [56.0, 112.0, 168.0]
    >>> round(r.predictions[1].deviation.deviation_pct, 1)
    9.1

    The interface law beside gamma (the stand-in adds S_wire = 1.1 N per mm of tube):

    >>> from exofric.friction import InterfaceFrictionModel
    >>> fake2 = lambda s, m, p: SimpleNamespace(pressure_mpa=p, squeeze_force_n=400 * p,
    ...     wire_pressure_integral_n_per_mm=440 * p / 116.0, length_mm=116.0)
    >>> r = predict(paper_structures()[:1], InterfaceFrictionModel(0.5, 0.15), None, [0.6],
    ...             squeeze_fn=fake2, compare=0.7)
    >>> [round(f, 6) for f in r.predictions[0].predicted_friction_n], r.to_dict()["law"]
    ([168.0], 'interfaces')
    >>> [lp.law for lp in r.predictions[0].laws]
    ['interfaces', 'gamma']
    """
    model = _as_law("gamma", gamma)
    other = None if compare is None else _as_law("compare", compare)
    if other is not None and _law_name(other) == _law_name(model):
        raise InputError(f"compare must be the other law than {_law_name(model)!r} (got the "
                         "same law twice)", param="compare")
    laws_used = (model,) if other is None else (model, other)
    grid = check_pressures("pressures_mpa", np.asarray(pressures_mpa, dtype=float).ravel())
    if not structures:
        raise InputError("predict needs at least one structure")
    if base is None:
        base = structures[0]
    names = [s.name for s in structures]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise InputError(f"structure names must be unique, {sorted(dup)[0]!r} repeats")
    measured = dict(measured or {})
    unknown = set(measured) - set(names)
    if unknown:
        raise InputError(f"measured curve {sorted(unknown)[0]!r} matches no structure "
                         f"(names: {', '.join(names)})")
    if squeeze_fn is None:
        from functools import partial

        from exofric.simulate import squeeze as _squeeze

        squeeze_fn = partial(_squeeze, keep_fields=False)
    preds = []
    for s in structures:
        meas = measured.get(s.name)
        p_eval = grid if meas is None else np.union1d(grid, np.asarray(meas.pressure_mpa))
        res = squeeze_fn(s, material, p_eval)
        p_out = np.asarray(res.pressure_mpa, dtype=float).ravel()
        n_out = np.asarray(res.squeeze_force_n, dtype=float).ravel()
        if p_out.shape != p_eval.shape or n_out.shape != p_eval.shape:
            raise InputError(f"{s.name}: squeeze returned {n_out.size} forces for "
                             f"{p_eval.size} pressures")
        cols = _law_inputs(res, s, p_out, n_out, laws_used)
        s_out = cols.get(_WIRE_COLUMN)
        f_out = _law_friction(model, cols)
        dev = deviation(s, base, threshold_pct)
        if not dev.in_validated_region:
            warnings.warn(
                f"{s.name}: deviation {dev.deviation_pct:.1f}% from the base exceeds "
                f"{threshold_pct:g}%, outside the region where the paper validated the model",
                ApplicabilityWarning, stacklevel=2,
            )
        at = None if meas is None else np.searchsorted(p_out, np.asarray(meas.pressure_mpa))
        rel = _errors_at(f_out, at, meas)
        laws = [LawPrediction(_law_name(model), model, tuple(f_out.tolist()), rel)]
        if other is not None:
            f_other = _law_friction(other, cols)
            laws.append(LawPrediction(_law_name(other), other, tuple(f_other.tolist()),
                                      _errors_at(f_other, at, meas)))
        onset = getattr(res, "contact_onset_pressure_mpa", None)
        preds.append(Prediction(
            structure=s, model=model, pressure_mpa=tuple(p_out.tolist()),
            squeeze_force_n=tuple(n_out.tolist()), predicted_friction_n=tuple(f_out.tolist()),
            contact_onset_pressure_mpa=None if onset is None else float(onset),
            deviation=dev,
            torque=torque(float(f_out[-1]), arm_radius_m, required_torque_nm),
            measured=meas, relative_error_pct=rel,
            wire_pressure_integral_n=() if s_out is None else tuple(s_out.tolist()),
            laws=tuple(laws),
        ))
    anova: tuple[AnovaResult, ...] = ()
    base_pred = next((p for p in preds if p.measured is not None
                      and _same_geometry(p.structure, base)), None)
    if base_pred is not None:
        others = {p.structure.name: p.relative_error_pct for p in preds
                  if p.measured is not None and p is not base_pred}
        if others and np.isfinite(base_pred.relative_error_pct).sum() >= 2:
            anova = anova_vs_base(base_pred.relative_error_pct, others, alpha=alpha)
    return PredictionSet(tuple(preds), base, anova)
