"""Paper numbers beside ours: :class:`Comparison` rows and the paper's self-consistency checks.

* :class:`Comparison` -- one printed number of the paper beside exofric's value, with the
  difference (in the row's unit) and, where it means something, the difference in %
  (:attr:`Comparison.difference_kind` says which difference a row shows: none for p-values
  and fitted polynomial coefficients, percentage points for quantities already in %);
  ``synthetic`` flags rows built on the virtual rig's output (the paper's raw friction curves
  are not published).
* :func:`printed_decimals` -- the decimals with which a paper value was printed;
  :attr:`Comparison.decimals` the decimals a row is shown with (the paper's).
* :func:`paper_checks` -- printed numbers against the same quantity recomputed from the
  paper's own equations and numbers (no FE, no rig).

Every stage of ``exofric reproduce`` (:mod:`exofric.reproduction`) reports its checks as
:class:`Comparison` rows. Pure computation: no printing, no files.

Units: per row (mm, N, MPa, s, Nm, or '' for unitless); differences in %.

Examples
--------
>>> Comparison("gamma (Eq 7)", "", 0.7168, 0.7168).difference
0.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from exofric import paper
from exofric._validate import checked_init
from exofric.errors import InputError
from exofric.friction import CubicFit, FrictionModel, pressure_for_friction, torque

__all__ = ["Comparison", "DIFFERENCE_KINDS", "printed_decimals", "paper_checks"]

#: How a :class:`Comparison` row shows ours - paper: ``"relative"`` (in the row's unit and in %
#: of the paper value), ``"points"`` (in the row's unit only: the row is already in %, so the
#: difference is in percentage points), ``"absolute"`` (in the unit only: the values differ in
#: sign or the paper value is 0, so a ratio means nothing), ``"none"`` (no difference: a value
#: is missing, or the quantity is a p-value or a fitted polynomial coefficient). ``"auto"``
#: (the default of :class:`Comparison`) picks one from the row.
DIFFERENCE_KINDS = ("auto", "relative", "points", "absolute", "none")

#: Quantities for which ours - paper means nothing (lower-case substrings of the quantity):
#: p-values (of synthetic data, or of unpublished curves) and fitted polynomial coefficients
#: (ill-conditioned: they trade off against each other; compare the curves).
_NO_DIFFERENCE = ("p-value", "coefficient")

#: Most significant figures a row is shown with, whatever the paper value's float repr says.
_MAX_SIGNIFICANT = 5


def printed_decimals(value: float) -> int:
    """Decimals with which a paper value was printed (from its shortest repr), e.g. 4.0033 -> 4.

    Parameters
    ----------
    value : float
        A number as the paper prints it (any unit); its shortest ``repr`` is read.

    Returns
    -------
    int
        Digits after the decimal point (0 for an integer value).

    Examples
    --------
    >>> printed_decimals(0.00575), printed_decimals(62.5), printed_decimals(268.55)
    (5, 1, 2)
    """
    text = repr(float(value))
    if "e" in text or "E" in text:
        mant, exp = text.lower().split("e")
        dec = len(mant.split(".")[1].rstrip("0")) if "." in mant else 0
        return max(0, dec - int(exp))
    return len(text.split(".")[1].rstrip("0")) if "." in text else 0


@checked_init
@dataclass(frozen=True)
class Comparison:
    """One paper number beside ours.

    Attributes
    ----------
    quantity : str
        What is compared (with the paper's table/figure/equation).
    unit : str
        Unit of both values ('' for unitless).
    paper_value, our_value : float or None
        None when the paper prints no value (e.g. the tube ID) or we have none.
    note : str
        Why they differ, or what the row means.
    synthetic : bool
        True when our value comes from synthetic (virtual-rig) data.
    kind : str
        Which difference the row shows, one of :data:`DIFFERENCE_KINDS`; ``"auto"`` (default)
        resolves it from the row (see :attr:`difference_kind`).

    Examples
    --------
    >>> c = Comparison("N at 0.6 MPa", "N", 268.55, 240.1)
    >>> round(c.difference, 2), round(c.difference_pct, 2), c.difference_kind, c.decimals
    (-28.45, -10.59, 'relative', 2)
    >>> Comparison("PI settling-time reduction", "%", 26.0, 32.67).difference_kind
    'points'
    >>> Comparison("test 6: ANOVA p-value", "", 0.0164, 0.94).difference_pct is None
    True
    """

    quantity: str
    unit: str
    paper_value: float | None
    our_value: float | None
    note: str = ""
    synthetic: bool = False
    kind: str = "auto"

    def __post_init__(self) -> None:
        if self.kind not in DIFFERENCE_KINDS:
            raise InputError(f"kind must be one of {', '.join(DIFFERENCE_KINDS)}, got "
                             f"{self.kind!r}")

    @property
    def difference_kind(self) -> str:
        """Which difference the row shows: ``"relative"``, ``"points"``, ``"absolute"``, ``"none"``.

        ``kind`` unless it is ``"auto"``; then: ``"none"`` when a value is missing or the
        quantity is a p-value or a fitted coefficient, ``"points"`` when the unit is ``%``,
        ``"absolute"`` when the paper value is 0 or the two differ in sign, else
        ``"relative"``.
        """
        if self.paper_value is None or self.our_value is None:
            return "none"
        if self.kind != "auto":
            return self.kind
        q = self.quantity.lower()
        if any(word in q for word in _NO_DIFFERENCE):
            return "none"
        if self.unit.strip() == "%":
            return "points"
        p, o = float(self.paper_value), float(self.our_value)
        if p == 0.0 or (o != 0.0 and (p > 0) != (o > 0)):
            return "absolute"
        return "relative"

    @property
    def difference(self) -> float | None:
        """ours - paper (in ``unit``), None if either is missing."""
        if self.paper_value is None or self.our_value is None:
            return None
        return float(self.our_value - self.paper_value)

    @property
    def difference_pct(self) -> float | None:
        """100 (ours - paper) / |paper| (%); None unless :attr:`difference_kind` is relative."""
        d = self.difference
        if d is None or self.paper_value == 0 or self.difference_kind != "relative":
            return None
        return float(100.0 * d / abs(float(self.paper_value)))  # type: ignore[arg-type]

    @property
    def decimals(self) -> int | None:
        """Decimals to show our value and the difference with: the paper's printed decimals.

        From :func:`printed_decimals` of the paper value, at most 5 significant figures of it
        (a value the paper's equations give, e.g. Eq 8 at 0.4 MPa, has a long repr); None
        without a paper value.
        """
        if self.paper_value is None:
            return None
        p = float(self.paper_value)
        dec = printed_decimals(p)
        if p != 0.0 and math.isfinite(p):
            dec = min(dec, max(0, _MAX_SIGNIFICANT - 1 - math.floor(math.log10(abs(p)))))
        return dec

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready row: values in ``unit``, ``difference_pct`` in %, how to show them."""
        return {
            "quantity": self.quantity,
            "unit": self.unit,
            "paper_value": self.paper_value,
            "our_value": self.our_value,
            "difference": self.difference,
            "difference_pct": self.difference_pct,
            "difference_kind": self.difference_kind,
            "decimals": self.decimals,
            "note": self.note,
            "synthetic": self.synthetic,
        }


def paper_checks() -> tuple[Comparison, ...]:
    """Printed numbers of the paper against the same quantity recomputed from its other numbers.

    ``paper_value`` is as printed, ``our_value`` what the paper's own equations or numbers
    give (see ``docs/paper-notes*.md``). Units per row.

    Examples
    --------
    >>> rows = {c.quantity.split(":")[0]: c for c in paper_checks()}
    >>> round(rows["Sec 5 pressure for 54.40 N"].our_value, 4)
    0.2926
    """
    sc = paper.scalar
    eq8 = CubicFit(paper.eq8(), 0.2, 0.6)
    g = sc("gamma")
    p_eq8 = eq8.inverse(sc("target_friction_n"))
    red_pi = 100.0 * (sc("settling_pi_s") - sc("settling_pi_model_s")) / sc("settling_pi_s")
    red_pid = 100.0 * (sc("settling_pid_s") - sc("settling_pid_model_s")) / sc("settling_pid_s")
    t = torque(sc("test3_max_friction_n"), sc("arm_radius_m"),
               (sc("knee_torque_min_nm"), sc("knee_torque_max_nm")))
    return (
        Comparison("Sec 5 pressure for 54.40 N: Eq 9 inverted", "MPa", sc("target_pressure_mpa"),
                   pressure_for_friction(sc("target_friction_n"), eq8, FrictionModel(g)),
                   f"0.26 is Eq 8 inverted without gamma ({p_eq8:.4f} MPa)"),
        Comparison("Sec 5 friction at the printed 0.26 MPa (Eq 9)", "N", sc("target_friction_n"),
                   g * eq8(sc("target_pressure_mpa")), "Eq 9 evaluated at 0.26 MPa"),
        Comparison("Sec 3.2/3.4 model at 0.6 MPa: gamma x 268.55 N vs measured", "N",
                   sc("base_friction_at_0_6_mpa_n"), g * sc("base_squeeze_force_at_0_6_mpa_n"),
                   "the only published matched pair; its error is not the 10.68% of Sec 3.5"),
        Comparison("Eq 8 at 0.6 MPa vs the base group's N (Fig 7)", "N",
                   sc("base_squeeze_force_at_0_6_mpa_n"), eq8(0.6),
                   "Eq 8 is the test-5 structure, not the base group"),
        Comparison("Sec 5 PI settling-time reduction (5.73 - 4.20)/5.73", "%",
                   sc("settling_reduction_pi_pct"), red_pi, "printed truncated, 27% rounded"),
        Comparison("Sec 5 PID settling-time reduction (6.17 - 4.39)/6.17", "%",
                   sc("settling_reduction_pid_pct"), red_pid, "printed rounded"),
        Comparison("Sec 4 test 3 torque against the knee's 40 Nm", "Nm",
                   sc("knee_torque_max_nm"), t.torque_nm,
                   f"'enough to meet 0-40 Nm' covers {t.coverage_pct:.0f}% of the range"),
    )
