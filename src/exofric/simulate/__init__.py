"""The FE problems users ask for, their results, and the closed-form references they are checked by.

* :func:`inflate` -> :class:`InflationResult` -- free inflation of the tube (quarter model).
* :func:`squeeze` -> :class:`SqueezeResult` (its groups :class:`ContactOutputs`,
  :class:`ErrorEstimate`) -- the tube-wire-hole squeeze N(P) (half model,
  paper §3.4, Figs 6-7).
* :class:`SqueezeSetup` -- everything a squeeze depends on but the pressures (structure,
  material, ends, friction, accuracy, gravity, ...), validated once; ``setup.solve(P)`` is
  :func:`squeeze`, and every :class:`SqueezeResult` carries its ``setup``.
* :func:`incompressible_inflation`, :func:`compressible_inflation` -- exact and 1D-BVP
  references for the free inflation; :func:`tube_inflation` -> :class:`TubeInflationCurve` --
  the incompressible thick tube with closed or open ends (generalised plane strain).
* :func:`check_stretch`, :class:`StretchWarning` -- the paper's validated stretch range.
* :class:`PulloutSetup` (with :class:`PulloutNumerics`) -- a pull-out but its pressure and
  path; :func:`section_pullout` -> :class:`SectionPullout` (per unit length) and
  :func:`pullout` -> :class:`PulloutResult` (the whole length) -- the wire pulled through
  the inflated tube.
* :func:`squeeze_with_clearance` -> :class:`ClearanceSqueeze` -- N(P) with the clearance
  distributed along the tube (:class:`ClearanceDistribution`);
  :func:`squeeze_tolerances` -> :class:`ToleranceResult` -- percentile bands of N(P) under size
  and hardness tolerances (quasi-Monte Carlo) and a sensitivity ranking.

Units: mm, N, MPa, s; forces per unit depth in N/mm, totals = per depth x tube length.

Examples
--------
>>> from exofric.simulate import inflate
>>> from exofric.material import MooneyRivlin
>>> r = inflate(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.2])
>>> round(float(r.outer_diameter_mm[0]), 2)
8.75
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.simulate._analytic import (
        InflationCurve,
        TubeInflationCurve,
        compressible_inflation,
        incompressible_inflation,
        incompressible_limit_pressure,
        incompressible_pressure,
        tube_inflation,
    )
    from exofric.simulate._clearance import (
        ClearanceDistribution,
        ClearanceSqueeze,
        squeeze_with_clearance,
    )
    from exofric.simulate._common import check_friction
    from exofric.simulate._inflate import InflationResult, inflate
    from exofric.simulate._pullout import PulloutResult, SectionPullout, pullout, section_pullout
    from exofric.simulate._pullout_setup import (
        PulloutNumerics,
        PulloutSetup,
        check_pullout_friction,
    )
    from exofric.simulate._ring import RingResult, ring_test
    from exofric.simulate._setup import SqueezeSetup
    from exofric.simulate._squeeze import squeeze
    from exofric.simulate._squeeze_result import ContactOutputs, ErrorEstimate, SqueezeResult
    from exofric.simulate._stretch import StretchWarning, check_stretch
    from exofric.simulate._tolerance import TOLERANCE_NAMES, ToleranceResult, squeeze_tolerances


# Lazy facade (PEP 562): ``squeeze`` does not load the inflation and its closed-form references;
# each name is loaded from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
