"""Joint torque from friction: T = F R (paper Secs. 3.2 and 4), checked against a requirement.

Units: friction F in N, lever arm R in m, torque T in Nm. The paper's examples: 180.49 N x
0.10 m = 18.05 Nm (base group at 0.6 MPa) and 300 N x 0.10 m = 30 Nm (test 3), against the
knee's 0-40 Nm (paper ref [32]).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from exofric.errors import InputError, check_finite, check_positive

__all__ = ["TorqueCheck", "torque"]


@dataclass(frozen=True)
class TorqueCheck:
    """Joint torque T = F R and whether it lies within a requirement [min, max] Nm.

    Built by :func:`torque`.

    Attributes
    ----------
    friction_n : float
        Friction force F in N.
    arm_radius_m : float
        Lever arm R in m.
    torque_nm : float
        T = F R in Nm.
    required_min_nm, required_max_nm : float
        The required torque range in Nm (knee: 0-40 Nm).

    Examples
    --------
    >>> t = TorqueCheck(180.49, 0.10, 18.049, 0.0, 40.0)     # base group at 0.6 MPa
    >>> t.meets_max, round(t.coverage_pct, 2)
    (False, 45.12)
    """

    friction_n: float
    arm_radius_m: float
    torque_nm: float
    required_min_nm: float
    required_max_nm: float

    @property
    def meets_max(self) -> bool:
        """True when T reaches the top of the required range (can hold the joint)."""
        return self.torque_nm >= self.required_max_nm

    @property
    def coverage_pct(self) -> float:
        """Share of the required range [min, max] that T covers, in %, clipped to [0, 100]."""
        span = self.required_max_nm - self.required_min_nm
        if span <= 0:
            return 100.0 if self.meets_max else 0.0
        frac = (self.torque_nm - self.required_min_nm) / span
        return float(100.0 * min(max(frac, 0.0), 1.0))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (N, m, Nm, %)."""
        return {
            "friction_n": self.friction_n,
            "arm_radius_m": self.arm_radius_m,
            "torque_nm": self.torque_nm,
            "required_min_nm": self.required_min_nm,
            "required_max_nm": self.required_max_nm,
            "meets_max": self.meets_max,
            "coverage_pct": self.coverage_pct,
        }


def torque(
    friction_n: float,
    arm_radius_m: float = 0.10,
    required_nm: tuple[float, float] = (0.0, 40.0),
) -> TorqueCheck:
    """Torque T = F R (Nm) from friction F (N) and arm radius R (m), checked against a range.

    Parameters
    ----------
    friction_n : float
        Friction force in N (usually at the maximum pressure).
    arm_radius_m : float
        Lever arm R in m (paper: 0.10 m, Fig 2b).
    required_nm : (min, max)
        Required torque range in Nm (knee: 0-40 Nm, paper ref [32]).

    Examples
    --------
    >>> t = torque(300.0)          # the paper's test 3: 300 N x 0.10 m
    >>> t.torque_nm, t.meets_max, t.coverage_pct
    (30.0, False, 75.0)
    """
    f = check_finite("friction_n", friction_n)
    r = check_positive("arm_radius_m (lever arm)", arm_radius_m, "m")
    lo = check_finite("required torque min (Nm)", required_nm[0])
    hi = check_finite("required torque max (Nm)", required_nm[1])
    if hi < lo:
        raise InputError(f"required torque range must have min <= max Nm, got [{lo:g}, {hi:g}]")
    return TorqueCheck(f, r, float(f * r), lo, hi)
