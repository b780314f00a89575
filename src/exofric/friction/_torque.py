"""Joint torque from friction: T = F R (paper Secs. 3.2 and 4), checked against a requirement.

Units: friction F in N, lever arm R in m, torque T in Nm, wrap angle in degrees. The paper's
examples: 180.49 N x 0.10 m = 18.05 Nm (base group at 0.6 MPa) and 300 N x 0.10 m = 30 Nm
(test 3), against the knee's 0-40 Nm (paper ref [32]).

Capstan transmission (optional; issue 15). In the exosuit (paper Fig 2) the wire leaves the
friction block and wraps the knee arc before it reaches its anchor on the joint at radius R.
If it slides over that arc (coefficient mu_arc, wrap angle theta), the arc is a capstan.
Derivation (Euler-Eytelwein): on an element d theta of the wrap the wire's tension T presses
it onto the arc with T d theta, so friction mu_arc T d theta acts on it against its sliding;
equilibrium along the wire gives dT/d theta = mu_arc T, measured in the direction of sliding.
Tension therefore grows exponentially toward the end the wire slides to:

    T_load / T_hold = exp(mu_arc theta)   (T_load: the end the wire slides toward)

The end at the block carries the block's friction F (the wire beyond the block is free, so
the friction is the tension it leaves the block with); the end at the anchor carries the
force that makes the joint torque, T_joint = R x (anchor tension). Which end is the loaded
one is set by the direction of motion, which ``direction`` makes explicit:

* ``"locking"`` (default): the joint drives the wire -- the knee flexes and pulls the wire
  over the arc and through the block, which resists. The wire slides toward the anchor, so
  the anchor is the loaded end: T = F R exp(+mu_arc theta). The arc adds friction; the torque
  that the brace resists with (and the joint must overcome) exceeds F R.
* ``"buffering"``: the wire slides over the arc away from the joint, toward the block -- the
  block side's tension F pulls it back while the joint yields (pays wire out). The anchor is
  the holding end: T = F R exp(-mu_arc theta). The arc absorbs part of F before the joint.

For a wire that does not slide over the arc (stuck by static friction), the anchor tension
may lie anywhere between the two: the two directions bound the transmitted torque. With
``wrap_deg = 0`` or ``mu_arc = 0`` both give T = F R, the paper's relation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError, check_finite, check_positive, check_range

__all__ = ["TorqueCheck", "capstan_factor", "torque"]

Direction = Literal["locking", "buffering"]
#: Largest wrap angle (deg) accepted by :func:`torque`: two full turns.
WRAP_MAX_DEG = 720.0


def capstan_factor(wrap_deg: float, mu_arc: float, direction: str = "locking") -> float:
    """Anchor-to-block tension ratio over the knee arc: exp(+-mu_arc theta) (unitless).

    Euler-Eytelwein (see the module docstring): ``"locking"`` (the joint pulls the wire over
    the arc toward itself) gives exp(+mu_arc theta), ``"buffering"`` (the wire slides over
    the arc back toward the block) exp(-mu_arc theta); theta = ``wrap_deg`` in radians.

    Parameters
    ----------
    wrap_deg : float
        Wrap angle of the wire on the arc in degrees, 0-720.
    mu_arc : float
        Friction coefficient of the wire on the arc (unitless, 0-2; warned above 1.5).
    direction : {"locking", "buffering"}
        Direction of the wire's sliding over the arc (see above).

    Returns
    -------
    float
        T_anchor / F (unitless): 1 for no wrap or no friction.

    Raises
    ------
    InputError
        A bad angle, coefficient or direction (the message names it).

    Examples
    --------
    >>> round(capstan_factor(180.0, 0.1), 6), round(capstan_factor(180.0, 0.1, "buffering"), 6)
    (1.369108, 0.730403)
    """
    from exofric.simulate import check_friction

    theta = math.radians(check_range("wrap_deg", wrap_deg, 0.0, WRAP_MAX_DEG, unit="deg"))
    mu = check_friction("mu_arc", mu_arc)
    if direction not in ("locking", "buffering"):
        raise InputError(f"direction must be 'locking' or 'buffering', got {direction!r}",
                         param="direction")
    sign = 1.0 if direction == "locking" else -1.0
    return math.exp(sign * mu * theta)


@checked_init
@dataclass(frozen=True)
class TorqueCheck(DisplayMixin):
    """Joint torque T = F R and whether it lies within a requirement [min, max] Nm.

    Built by :func:`torque`.

    Attributes
    ----------
    friction_n : float
        Friction force F in N (at the block).
    arm_radius_m : float
        Lever arm R in m.
    torque_nm : float
        T = F R x ``capstan`` in Nm.
    required_min_nm, required_max_nm : float
        The required torque range in Nm (knee: 0-40 Nm).
    wrap_deg : float
        Wrap angle of the wire over the knee arc in degrees (0: none).
    mu_arc : float
        Friction coefficient of the wire on the arc (unitless).
    direction : {"locking", "buffering"}
        Direction of motion that set the sign of the capstan exponent.
    capstan : float
        The capstan factor exp(+-mu_arc theta) (unitless; 1 without a wrap).

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
    wrap_deg: float = 0.0
    mu_arc: float = 0.0
    direction: str = "locking"
    capstan: float = 1.0

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
        """JSON-ready dict (N, m, Nm, %, deg)."""
        return {
            "friction_n": self.friction_n,
            "arm_radius_m": self.arm_radius_m,
            "torque_nm": self.torque_nm,
            "required_min_nm": self.required_min_nm,
            "required_max_nm": self.required_max_nm,
            "meets_max": self.meets_max,
            "coverage_pct": self.coverage_pct,
            "wrap_deg": self.wrap_deg,
            "mu_arc": self.mu_arc,
            "direction": self.direction,
            "capstan_factor": self.capstan,
            "torque_no_wrap_nm": self.friction_n * self.arm_radius_m,
        }


def torque(
    friction_n: float,
    arm_radius_m: float = 0.10,
    required_nm: tuple[float, float] = (0.0, 40.0),
    *,
    wrap_deg: float = 0.0,
    mu_arc: float = 0.0,
    direction: Direction = "locking",
) -> TorqueCheck:
    """Torque T = F R exp(+-mu_arc theta) (Nm) from friction F (N), checked against a range.

    Without a wrap (the defaults) T = F R, the paper's relation. With the wire wrapping the
    knee arc by ``wrap_deg`` at coefficient ``mu_arc``, the capstan factor of
    :func:`capstan_factor` multiplies it, its sign set by ``direction`` (derivation in the
    module docstring).

    Parameters
    ----------
    friction_n : float
        Friction force in N at the block (usually at the maximum pressure).
    arm_radius_m : float
        Lever arm R in m (paper: 0.10 m, Fig 2b).
    required_nm : (min, max)
        Required torque range in Nm (knee: 0-40 Nm, paper ref [32]).
    wrap_deg : float
        Wrap angle of the wire over the knee arc in degrees (0-720; default 0: none).
    mu_arc : float
        Friction coefficient of the wire on the arc (unitless, 0-2; default 0).
    direction : {"locking", "buffering"}
        ``"locking"``: the joint pulls the wire over the arc (T = F R exp(+mu_arc theta));
        ``"buffering"``: the wire slides back over the arc toward the block
        (T = F R exp(-mu_arc theta)).

    Returns
    -------
    TorqueCheck

    Examples
    --------
    >>> t = torque(300.0)          # the paper's test 3: 300 N x 0.10 m
    >>> t.torque_nm, t.meets_max, t.coverage_pct
    (30.0, False, 75.0)
    >>> t = torque(180.49, 0.1, wrap_deg=90.0, mu_arc=0.15)         # locking: the arc adds
    >>> round(t.torque_nm, 3), round(t.capstan, 4)
    (22.844, 1.2657)
    """
    f = check_finite("friction_n", friction_n)
    r = check_positive("arm_radius_m (lever arm)", arm_radius_m, "m")
    lo = check_finite("required torque min (Nm)", required_nm[0])
    hi = check_finite("required torque max (Nm)", required_nm[1])
    if hi < lo:
        raise InputError(f"required torque range must have min <= max Nm, got [{lo:g}, {hi:g}]")
    k = capstan_factor(wrap_deg, mu_arc, direction)
    return TorqueCheck(f, r, float(f * r) if k == 1.0 else float(f * r * k), lo, hi,
                       float(wrap_deg), float(mu_arc), str(direction), k)
