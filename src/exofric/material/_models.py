"""Silicone material model: Shore A hardness to Mooney-Rivlin constants.

The paper (Ma et al. 2021, Eqs 2-6) builds the air tube's Mooney-Rivlin model
from its Shore A hardness:

* Eq 3: ``E0 = (2.15 S + 15.75) / (100 - S)`` MPa (Gent's 1958 relation, rounded),
* Eq 4: ``G = E0 / 3 = 2 (C10 + C01)``,
* Eq 5: ``C01 / C10 = 0.05``,
* Eq 6: ``d = (1 - 2 nu) / (C10 + C01)`` with ``nu = 0.498``.

The strain energy (Eq 2, ANSYS convention) is
``U = C10 (I1b - 3) + C01 (I2b - 3) + (J - 1)^2 / d``, so the bulk modulus is
``K = 2 / d`` and the small-strain shear modulus ``mu = 2 (C10 + C01)``.

Units: moduli and C10, C01 in MPa; d in 1/MPa.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from statistics import NormalDist
from typing import TYPE_CHECKING

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import (
    InputError,
    check_finite,
    check_positive,
    check_range,
    warn_implausible,
)

if TYPE_CHECKING:
    from exofric.material._hyperelastic import HyperelasticModel

__all__ = [
    "CORRELATIONS",
    "Correlation",
    "MooneyRivlin",
    "MaterialRangeWarning",
    "shore_to_modulus",
]


class MaterialRangeWarning(UserWarning):
    """A correlation is used outside the hardness range it was published for.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     _ = shore_to_modulus(95.0)
    >>> caught[0].category.__name__
    'MaterialRangeWarning'
    """


def _paper(s: float) -> float:
    return (2.15 * s + 15.75) / (100.0 - s)


def _gent(s: float) -> float:
    return 0.0981 * (56.0 + 7.62336 * s) / (0.137505 * (254.0 - 2.54 * s))


_STANDARD_NORMAL = NormalDist()


def _erfinv(x: float) -> float:
    """Inverse error function of a float, by the standard library (no SciPy at import).

    ``erfinv(x) = Phi^-1((1 + x) / 2) / sqrt(2)`` (``statistics.NormalDist.inv_cdf``, Wichura's
    AS241) as the start, from the exact ``q = 1 - |x|`` when ``|x| >= 0.5``, then one Newton
    step on ``erf`` (``erfc`` when ``|x| >= 0.5``) recovers the digits that forming
    ``(1 + x) / 2`` loses for small ``|x|``. Agrees with ``scipy.special.erfinv`` to 2e-15
    relative on (-1, 1) (observed 5e-16, tests/test_material_erfinv.py); ``+-inf`` at ``+-1``,
    NaN outside.
    """
    if not -1.0 < x < 1.0:
        return math.copysign(math.inf, x) if abs(x) == 1.0 else math.nan
    if x == 0.0:
        return x
    a = abs(x)
    q = 1.0 - a  # exact for a >= 0.5 (Sterbenz)
    if a < 0.5:
        y = _STANDARD_NORMAL.inv_cdf(0.5 + 0.5 * a) / math.sqrt(2.0)
        r = math.erf(y) - a
    else:
        y = -_STANDARD_NORMAL.inv_cdf(0.5 * q) / math.sqrt(2.0)
        r = q - math.erfc(y)
    y -= r * math.exp(y * y) * (math.sqrt(math.pi) / 2.0)
    return math.copysign(y, x)


def _qi(s: float) -> float:
    # S = 100 erf(3.186e-4 sqrt(E[Pa]))  ->  E = (erfinv(S/100) / 3.186e-4)^2 Pa
    return (_erfinv(s / 100.0) / 3.186e-4) ** 2 * 1e-6


def _astm_log10(s: float) -> float:
    return 10.0 ** (0.0235 * s - 0.6403)


@checked_init
@dataclass(frozen=True)
class Correlation:
    """A published Shore A -> Young's modulus correlation.

    Attributes
    ----------
    name : str
        Key used by the API and the CLI (``--correlation``).
    func : callable
        Shore A hardness -> E0 in MPa.
    valid : tuple of float
        Hardness range (Shore A) in which exofric uses it without a warning.
    reference : str
        Where it comes from.

    Examples
    --------
    >>> c = CORRELATIONS["paper"]
    >>> c.valid, round(c.func(62.5), 4)
    ((20.0, 80.0), 4.0033)
    """

    name: str
    func: Callable[[float], float]
    valid: tuple[float, float]
    reference: str


#: The Shore A -> Young's modulus correlations by name (``'paper'``: the paper's Eq 3, ``'gent'``,
#: ...); each maps a hardness (Shore A) to E (MPa) over its stated range.
CORRELATIONS: dict[str, Correlation] = {
    c.name: c
    for c in (
        Correlation(
            "paper",
            _paper,
            (20.0, 80.0),
            "Ma et al. 2021, Eq 3: E0 = (2.15 S + 15.75)/(100 - S) MPa; Gent's relation "
            "with its constants rounded.",
        ),
        Correlation(
            "gent",
            _gent,
            (20.0, 80.0),
            "Gent, A.N. (1958) Trans. IRI 34, 46: E = 0.0981(56 + 7.62336 S)/"
            "(0.137505(254 - 2.54 S)) MPa.",
        ),
        Correlation(
            "qi",
            _qi,
            (20.0, 80.0),
            "Qi, Joyce & Boyce (2003) Rubber Chem. Technol. 76, 419: "
            "S = 100 erf(3.186e-4 sqrt(E)), E in Pa (neo-Hookean initial modulus).",
        ),
        Correlation(
            "astm-log10",
            _astm_log10,
            (20.0, 80.0),
            "Log-linear ASTM D2240/BS 903 fit: log10(E[MPa]) = 0.0235 S - 0.6403. The log is "
            "base 10; some sources misquote it with the natural log, which gives ~3x lower E.",
        ),
    )
}


def shore_to_modulus(shore: float, correlation: str = "paper") -> float:
    """Young's modulus E0 (MPa) of a rubber from its Shore A hardness.

    Parameters
    ----------
    shore : float
        Shore A hardness, in (0, 100).
    correlation : {'paper', 'gent', 'qi', 'astm-log10'}
        Which published correlation to use (see :data:`CORRELATIONS`). All four
        are empirical; exofric warns (:class:`MaterialRangeWarning`) outside
        20-80 Shore A, a conservative range common to all four, where the
        published fits are backed by data.

    Returns
    -------
    float
        E0 in MPa.

    Examples
    --------
    >>> round(shore_to_modulus(62.5), 5)
    4.00333
    """
    if not isinstance(correlation, str) or correlation not in CORRELATIONS:
        raise InputError(
            f"correlation must be one of {', '.join(CORRELATIONS)}, got {correlation!r}"
        )
    s = check_range("shore", shore, 0.0, 100.0, lo_open=True, hi_open=True)
    corr = CORRELATIONS[correlation]
    lo, hi = corr.valid
    if not lo <= s <= hi:
        warnings.warn(
            f"shore {s:g} is outside the {lo:g}-{hi:g} Shore A range of the "
            f"'{correlation}' correlation; E0 is an extrapolation",
            MaterialRangeWarning,
            stacklevel=2,
        )
    return float(corr.func(s))


@checked_init
@dataclass(frozen=True)
class MooneyRivlin:
    """Two-parameter Mooney-Rivlin material (paper Eq 2, ANSYS convention).

    ``U = C10 (I1b - 3) + C01 (I2b - 3) + (J - 1)^2 / d``.

    Attributes
    ----------
    c10_mpa, c01_mpa : float
        Material constants C10, C01 in MPa (``c10_mpa + c01_mpa > 0``); the same names as the
        ``to_dict()`` keys (``.c10`` and ``.c01`` remain as read-only aliases).
    d_per_mpa : float
        Incompressibility parameter d in 1/MPa (``d > 0``; bulk modulus ``2/d``; ``.d`` is a
        read-only alias). The implied
        small-strain Poisson ratio must be > 0 (``d < 3 / (2 (c10 + c01))``, else
        :class:`~exofric.errors.InputError`); below ``defaults.PLAUSIBLE_POISSON_MIN`` (0.45)
        a :class:`~exofric.errors.PlausibilityWarning` says the rubber is not nearly
        incompressible.
    shore : float or None
        The Shore A hardness it was built from, if any.
    correlation : str or None
        The Shore -> E0 correlation used, if any.

    Examples
    --------
    >>> m = MooneyRivlin.from_shore(62.5)
    >>> round(m.c10_mpa, 5), round(m.d_per_mpa, 6)
    (0.63545, 0.005995)
    """

    c10_mpa: float
    c01_mpa: float
    d_per_mpa: float
    shore: float | None = None
    correlation: str | None = None

    @property
    def c10(self) -> float:
        """C10 in MPa (alias of ``c10_mpa``)."""
        return self.c10_mpa

    @property
    def c01(self) -> float:
        """C01 in MPa (alias of ``c01_mpa``)."""
        return self.c01_mpa

    @property
    def d(self) -> float:
        """d in 1/MPa (alias of ``d_per_mpa``)."""
        return self.d_per_mpa

    def __post_init__(self) -> None:
        # Bounds far outside any rubber (silicones: C10 ~ 0.01-10 MPa, d ~ 1e-4-1e-1 1/MPa) but
        # inside what the FE solver can take: C10, C01 within +-1e4 MPa, 1e-12 <= d <= 1e4 1/MPa
        # (bulk/shear modulus ratio up to ~1e12; 1e300 reaches the solver as inf/NaN).
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): C10, C01, d and Shore stored as
        # float whatever number type is given (JSON-ready, one repr).
        for name, v in (("c10", self.c10_mpa), ("c01", self.c01_mpa)):
            if isinstance(v, (str, bytes, bool)) or v is None:
                raise InputError(f"{name} must be a number in MPa, got {v!r}")
            object.__setattr__(self, f"{name}_mpa", check_range(name, v, -1e4, 1e4, unit="MPa"))
        if isinstance(self.d_per_mpa, (str, bytes, bool)) or self.d_per_mpa is None:
            raise InputError(f"d must be a number in 1/MPa, got {self.d_per_mpa!r}")
        check_positive("d", self.d_per_mpa, "1/MPa")
        object.__setattr__(self, "d_per_mpa", check_range("d", self.d_per_mpa, 1e-12, 1e4,
                                                          unit="1/MPa"))
        if self.shore is not None:
            if isinstance(self.shore, (str, bytes, bool)):
                raise InputError(f"shore must be a number or None, got {self.shore!r}")
            object.__setattr__(self, "shore", check_finite("shore", self.shore))
        if self.correlation is not None and not isinstance(self.correlation, str):
            raise InputError(f"correlation must be a string or None, got {self.correlation!r}")
        if self.c10_mpa + self.c01_mpa <= 0.0:
            raise InputError(
                "c10 + c01 must be > 0 MPa (shear modulus 2(c10+c01)), got "
                f"{self.c10_mpa + self.c01_mpa:g}"
            )
        # the implied small-strain Poisson ratio: <= 0 is refused (as from_shore refuses it),
        # below defaults.PLAUSIBLE_POISSON_MIN warns (a rubber is nearly incompressible)
        mu = 2.0 * (self.c10_mpa + self.c01_mpa)
        nu = self.poisson
        if nu <= 0.0:
            raise InputError(f"d must be < 3 / (2 (c10 + c01)) = {3.0 / mu:.4g} 1/MPa (implied "
                             f"Poisson ratio > 0), got {self.d_per_mpa:g} (Poisson ratio {nu:.3f})",
                             param="d")
        if nu < defaults.PLAUSIBLE_POISSON_MIN:
            warn_implausible(f"d = {self.d_per_mpa:g} 1/MPa implies a Poisson ratio of {nu:.3f}; a "
                             f"silicone is nearly incompressible (0.49-0.4999, the paper 0.498):"
                             f" is d in 1/MPa?")

    @classmethod
    def from_shore(
        cls,
        shore: float,
        correlation: str = "paper",
        c01_ratio: float = 0.05,
        poisson: float = defaults.POISSON,
        c10_divisor: float | None = None,
    ) -> MooneyRivlin:
        """Build the material from Shore A hardness by the paper's Eqs 3-6.

        Parameters
        ----------
        shore : float
            Shore A hardness in (0, 100).
        correlation : str
            Shore -> E0 correlation (default ``'paper'``, Eq 3).
        c01_ratio : float
            C01 / C10 (Eq 5; default 0.05), in [0, 1].
        poisson : float
            Poisson's ratio nu in (0, 0.5) (Eq 6; default 0.498).
        c10_divisor : float, optional
            ``C10 = (G/2) / c10_divisor``; default ``1 + c01_ratio`` (Eq 4 exactly). The
            paper's printed Table 2 corresponds to 1.005 (a slip for 1.05, see the notes).

        Returns
        -------
        MooneyRivlin
            ``G = E0/3 = 2(C10 + C01)`` (Eq 4), ``d = (1 - 2 nu)/(C10 + C01)`` (Eq 6).
        """
        ratio = check_range("c01_ratio", c01_ratio, 0.0, 1.0)
        nu = check_range("poisson", poisson, 0.0, 0.5, lo_open=True, hi_open=True)
        e0 = shore_to_modulus(shore, correlation)
        g = e0 / 3.0
        div = 1.0 + ratio if c10_divisor is None else check_positive("c10_divisor", c10_divisor)
        c10 = g / 2.0 / div
        c01 = ratio * c10
        d = (1.0 - 2.0 * nu) / (c10 + c01)
        return cls(c10_mpa=c10, c01_mpa=c01, d_per_mpa=d, shore=float(shore),
                   correlation=correlation)

    @property
    def shear_modulus(self) -> float:
        """Small-strain shear modulus ``mu = 2 (C10 + C01)`` in MPa."""
        return 2.0 * (self.c10_mpa + self.c01_mpa)

    @property
    def bulk_modulus(self) -> float:
        """Bulk modulus ``K = 2 / d`` in MPa."""
        return 2.0 / self.d_per_mpa

    @property
    def youngs_modulus(self) -> float:
        """Small-strain Young's modulus ``E = 9 K mu / (3 K + mu)`` in MPa."""
        k, mu = self.bulk_modulus, self.shear_modulus
        return 9.0 * k * mu / (3.0 * k + mu)

    @property
    def poisson(self) -> float:
        """Small-strain Poisson's ratio ``(3K - 2mu) / (2(3K + mu))``."""
        k, mu = self.bulk_modulus, self.shear_modulus
        return (3.0 * k - 2.0 * mu) / (2.0 * (3.0 * k + mu))

    def with_bulk_factor(self, factor: float) -> MooneyRivlin:
        """Same shear behaviour, bulk modulus multiplied by ``factor`` (d divided).

        Parameters
        ----------
        factor : float
            Bulk-modulus multiplier (unitless), > 0.

        Returns
        -------
        MooneyRivlin
        """
        f = check_positive("bulk factor", factor)
        return MooneyRivlin(self.c10_mpa, self.c01_mpa, self.d_per_mpa / f, self.shore,
                            self.correlation)

    def to_model(self) -> HyperelasticModel:
        """The same material as a :class:`HyperelasticModel` (``mooney-rivlin``).

        Gives the homogeneous stresses, the strain energy and the stability check of the
        common model interface; the FE solver keeps taking this class.

        Returns
        -------
        HyperelasticModel
            ``params = (c10_mpa, c01_mpa)``, same ``d_per_mpa``.
        """
        from exofric.material._hyperelastic import HyperelasticModel

        return HyperelasticModel("mooney-rivlin", (self.c10_mpa, self.c01_mpa), self.d_per_mpa)

    def check_fe_stability(self, stretch_max: float | None = None) -> None:
        """Refuse constants that are Drucker-unstable where the FE solvers deform a tube.

        :meth:`HyperelasticModel.check_fe_stability` of :meth:`to_model`, the error about
        ``c10`` and ``c01`` (MPa). Constants from :meth:`from_shore` (C10, C01 > 0) always
        pass.

        Parameters
        ----------
        stretch_max : float, optional
            Largest principal stretch checked (unitless, > 1); default
            ``defaults.MR_STRETCH_LIMIT`` (2.5).

        Raises
        ------
        InputError
            ``param="c10"``: the constants and, per path, the unstable stretches.

        Examples
        --------
        >>> MooneyRivlin(0.5, -0.3, 0.005).check_fe_stability()
        Traceback (most recent call last):
        ...
        exofric.errors.InputError: c10, c01: mooney-rivlin (C10 = 0.5 MPa, C01 = -0.3 MPa) is \
Drucker-unstable (dP/dl <= 0) within the stretches the FE reaches (principal stretches \
0.4-2.5): uniaxial at stretch 0.4-0.744; equibiaxial at stretch 1.13-1.58. Give parameters \
stable there (HyperelasticModel.stability shows where)
        """
        from exofric.material._hyperelastic import _check_fe_stability

        if self.c10_mpa >= 0.0 and self.c01_mpa >= 0.0:
            return  # W convex in (I1, I2) with positive weights: stable at every stretch
        _check_fe_stability(self.to_model(), stretch_max, "c10, c01")

    def to_dict(self) -> dict[str, float | str | None]:
        """JSON-ready dict with unit-suffixed keys (MPa, 1/MPa)."""
        return {
            "shore": self.shore,
            "correlation": self.correlation,
            "e0_mpa": 3.0 * self.shear_modulus,  # Eq 4: E0 = 3 G
            "g_mpa": self.shear_modulus,
            "c10_mpa": self.c10_mpa,
            "c01_mpa": self.c01_mpa,
            "d_per_mpa": self.d_per_mpa,
            "k_mpa": self.bulk_modulus,
        }
