"""Paper numbers beside ours: :class:`Comparison` rows and the paper's self-consistency checks.

* :class:`Comparison` -- one printed number of the paper beside exofric's value, with the
  difference (in the row's unit) and the difference in %; ``synthetic`` flags rows built on
  the virtual rig's output (the paper's raw friction curves are not published).
* :func:`printed_decimals` -- the decimals with which a paper value was printed.
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

from dataclasses import dataclass
from typing import Any

from exofric import paper
from exofric.friction import CubicFit, FrictionModel, pressure_for_friction, torque

__all__ = ["Comparison", "printed_decimals", "paper_checks"]


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

    Examples
    --------
    >>> c = Comparison("N at 0.6 MPa", "N", 268.55, 240.1)
    >>> round(c.difference, 2), round(c.difference_pct, 2)
    (-28.45, -10.59)
    """

    quantity: str
    unit: str
    paper_value: float | None
    our_value: float | None
    note: str = ""
    synthetic: bool = False

    @property
    def difference(self) -> float | None:
        """ours - paper (in ``unit``), None if either is missing."""
        if self.paper_value is None or self.our_value is None:
            return None
        return float(self.our_value - self.paper_value)

    @property
    def difference_pct(self) -> float | None:
        """100 (ours - paper) / |paper| (%), None if undefined."""
        d = self.difference
        if d is None or self.paper_value == 0:
            return None
        return float(100.0 * d / abs(float(self.paper_value)))  # type: ignore[arg-type]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready row: values in ``unit``, ``difference_pct`` in %."""
        return {
            "quantity": self.quantity,
            "unit": self.unit,
            "paper_value": self.paper_value,
            "our_value": self.our_value,
            "difference": self.difference,
            "difference_pct": self.difference_pct,
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
