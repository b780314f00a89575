"""Hyperelastic models beside Mooney-Rivlin: neo-Hookean, Yeoh, Ogden (N = 1-3).

Every model is nearly incompressible with the same volumetric term and bulk convention as
:class:`~exofric.material.MooneyRivlin` (paper Eq 2, ANSYS): ``W = W_iso(Ib1, Ib2) + (J - 1)^2
/ d``, bulk modulus ``K = 2 / d``. The isochoric parts (MPa; bars: isochoric invariants and
stretches ``lb_i = J^(-1/3) l_i``):

* neo-Hookean: ``C10 (Ib1 - 3)``; shear modulus ``mu = 2 C10``;
* Mooney-Rivlin: ``C10 (Ib1 - 3) + C01 (Ib2 - 3)``; ``mu = 2 (C10 + C01)``;
* Yeoh: ``C10 (Ib1 - 3) + C20 (Ib1 - 3)^2 + C30 (Ib1 - 3)^3``; ``mu = 2 C10``;
* Ogden (ABAQUS convention): ``sum_i 2 mu_i / alpha_i^2 (lb1^a_i + lb2^a_i + lb3^a_i - 3)``;
  ``mu = sum_i mu_i``.

The homogeneous responses are those of the incompressible limit (``J = 1``; ``d`` plays no
part): with ``t_i = l_i dW/dl_i`` and the stress-free lateral direction ``k``, the Cauchy
stress in the loaded direction is ``sigma = t_1 - t_k`` and the nominal (engineering) stress
``P = sigma / l``, for

* uniaxial tension/compression: stretches ``(l, l^-1/2, l^-1/2)``, ``k = 2``;
* equibiaxial: ``(l, l, l^-2)``, ``k = 3``;
* planar (pure shear): ``(l, 1, 1/l)``, ``k = 3``.

Units: stresses and moduli in MPa, d in 1/MPa, stretches and Ogden exponents unitless.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import InputError, check_range, warn_implausible

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import ArrayLike, NDArray

    from exofric.material._models import MooneyRivlin

__all__ = [
    "HYPERELASTIC_MODELS",
    "MODES",
    "HyperelasticModel",
    "StabilityCheck",
    "material_model",
]

#: The homogeneous test modes, in the order every result lists them.
MODES: tuple[str, ...] = ("uniaxial", "biaxial", "planar")
#: Stress measures of the data: nominal (force per undeformed area) or Cauchy (true).
STRESS_KINDS: tuple[str, ...] = ("engineering", "true")


def _ogden_names(n: int) -> tuple[str, ...]:
    return tuple(x for i in range(1, n + 1) for x in (f"mu{i}_mpa", f"alpha{i}"))


#: Model name -> its parameter names (unit suffix ``_mpa`` = MPa; the rest unitless).
HYPERELASTIC_MODELS: dict[str, tuple[str, ...]] = {
    "neo-hookean": ("c10_mpa",),
    "mooney-rivlin": ("c10_mpa", "c01_mpa"),
    "yeoh": ("c10_mpa", "c20_mpa", "c30_mpa"),
    "ogden1": _ogden_names(1),
    "ogden2": _ogden_names(2),
    "ogden3": _ogden_names(3),
}

#: Default Poisson ratio behind the default d (the paper's, Eq 6).
_POISSON = defaults.POISSON


def _mode_stretches(mode: str, lam: Any) -> tuple[Any, Any, Any]:
    if mode == "uniaxial":
        lat = lam ** -0.5
        return lam, lat, lat
    if mode == "biaxial":
        return lam, lam, lam ** -2.0
    return lam, lam * 0.0 + 1.0, 1.0 / lam


def _shear_modulus(name: str, p: tuple[float, ...]) -> float:
    if name == "mooney-rivlin":
        return 2.0 * (p[0] + p[1])
    if name.startswith("ogden"):
        return float(sum(p[0::2]))
    return 2.0 * p[0]


def _principal_t(name: str, p: Sequence[float] | NDArray[np.float64], l1: Any, l2: Any,
                 l3: Any) -> tuple[Any, Any, Any]:
    """``t_i = l_i dW_iso/dl_i`` at ``J = 1`` (MPa); complex-safe for the complex step."""
    if name.startswith("ogden"):
        out = []
        for li in (l1, l2, l3):
            out.append(sum(2.0 * m / a * li ** a for m, a in zip(p[0::2], p[1::2],
                                                                strict=True)))
        return out[0], out[1], out[2]
    i1 = l1 * l1 + l2 * l2 + l3 * l3
    c01 = 0.0
    if name == "yeoh":
        w1 = p[0] + 2.0 * p[1] * (i1 - 3.0) + 3.0 * p[2] * (i1 - 3.0) ** 2
    else:
        w1 = p[0]
        if name == "mooney-rivlin":
            c01 = p[1]
    t1, t2, t3 = (2.0 * li * li * (w1 + c01 * (i1 - li * li)) for li in (l1, l2, l3))
    return t1, t2, t3



def _isochoric_stress(name: str, params: Sequence[float] | NDArray[np.float64], mode: str,
                      lam: Any, kind: str) -> Any:
    """Stress (MPa) along a homogeneous incompressible path, no checks (complex-safe)."""
    l1, l2, l3 = _mode_stretches(mode, lam)
    t1, t2, t3 = _principal_t(name, params, l1, l2, l3)
    sigma = t1 - (t2 if mode == "uniaxial" else t3)
    return sigma if kind == "true" else sigma / lam

def _check_mode(mode: str) -> str:
    if not isinstance(mode, str) or mode not in MODES:
        raise InputError(f"mode must be one of {', '.join(MODES)}, got {mode!r}", param="mode")
    return mode


def _check_kind(kind: str) -> str:
    if not isinstance(kind, str) or kind not in STRESS_KINDS:
        raise InputError(f"kind must be one of {', '.join(STRESS_KINDS)}, got {kind!r}",
                         param="kind")
    return kind


def _stretch_array(stretch: ArrayLike) -> NDArray[np.float64]:
    import numpy as np

    try:
        a = np.asarray(stretch, dtype=float)
    except (TypeError, ValueError):
        raise InputError("stretch must be numbers (unitless), got "
                         f"{stretch!r}", param="stretch") from None
    if not np.all(np.isfinite(a)) or np.any(a <= 0.0):
        bad = a[~(np.isfinite(a) & (a > 0.0))].ravel()[0]
        raise InputError(f"stretch must be finite and > 0 (unitless), got {bad:g}",
                         param="stretch")
    return a


@checked_init
@dataclass(frozen=True)
class StabilityCheck:
    """Drucker stability of a model along the three homogeneous paths, over a stretch range.

    The criterion is the tangent of the nominal stress along each path: ``dP/dl > 0`` for
    uniaxial, equibiaxial and planar deformation (the check ABAQUS makes for its
    hyperelastic fits), evaluated on ``n_points`` stretches spaced evenly over
    ``[stretch_min, stretch_max]`` for every path. It is necessary, not sufficient, for the
    general Drucker condition ``dP : dF > 0`` (which also asks it of mixed paths).

    Attributes
    ----------
    stable : bool
        True when ``dP/dl > 0`` on all three paths over the whole range.
    stretch_min, stretch_max : float
        The stretch range checked (unitless).
    unstable_from : dict of str to float or None
        Per path (``uniaxial``, ``biaxial``, ``planar``): the stretch (unitless) nearest
        1 where ``dP/dl <= 0``, or None where stable.
    n_points : int
        Stretches checked per path.
    modes : tuple of str
        The paths checked (default all three; a fit checks the modes it had data of, with
        ``unstable_from`` None for the others).

    Examples
    --------
    >>> check = material_model("neo-hookean", [0.2]).stability(0.5, 3.0)
    >>> check.stable, check.unstable_from["planar"]
    (True, None)
    """

    stable: bool
    stretch_min: float
    stretch_max: float
    unstable_from: dict[str, float | None]
    n_points: int = 401
    modes: tuple[str, ...] = MODES

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``stable``, the range checked, per path the first unstable stretch.

        Returns
        -------
        dict
            ``criterion`` names the test made.
        """
        names = {"uniaxial": "uniaxial", "biaxial": "equibiaxial", "planar": "planar"}
        paths = [names[m] for m in self.modes]
        listed = paths[0] if len(paths) == 1 else ", ".join(paths[:-1]) + " and " + paths[-1]
        return {
            "stable": self.stable,
            "criterion": f"dP/dl > 0 along {listed} path{'s' if len(paths) > 1 else ''}",
            "modes": list(self.modes),
            "stretch_min": self.stretch_min,
            "stretch_max": self.stretch_max,
            "unstable_from": dict(self.unstable_from),
        }


@checked_init
@dataclass(frozen=True)
class HyperelasticModel:
    """A nearly incompressible hyperelastic material: model name, parameters and ``d``.

    Build it with :func:`material_model` (checks the name and the parameter count) or
    :meth:`MooneyRivlin.to_model`. ``W = W_iso + (J - 1)^2 / d`` (the volumetric term and
    bulk convention of :class:`~exofric.material.MooneyRivlin`); see the module docstring
    for each ``W_iso``.

    Attributes
    ----------
    name : str
        One of :data:`HYPERELASTIC_MODELS`: ``neo-hookean``, ``mooney-rivlin``, ``yeoh``,
        ``ogden1``, ``ogden2``, ``ogden3``.
    params : tuple of float
        The parameters in the order of :attr:`param_names`: C's and Ogden ``mu_i`` in MPa,
        Ogden ``alpha_i`` unitless (Ogden: ``mu1, alpha1, mu2, alpha2, ...``).
    d_per_mpa : float
        Incompressibility parameter d in 1/MPa (bulk modulus ``2/d``), > 0; 0 (the default)
        selects ``2 (1 - 2 nu) / mu`` with the paper's nu = 0.498 (Eq 6).

    Examples
    --------
    >>> m = material_model("yeoh", [0.19, -0.0019, 4.1e-5])
    >>> round(m.shear_modulus_mpa, 3), m.param_names
    (0.38, ('c10_mpa', 'c20_mpa', 'c30_mpa'))
    """

    name: str
    params: tuple[float, ...]
    d_per_mpa: float = field(default=0.0)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or self.name not in HYPERELASTIC_MODELS:
            raise InputError(f"model must be one of {', '.join(HYPERELASTIC_MODELS)}, got "
                             f"{self.name!r}", param="model")
        names = HYPERELASTIC_MODELS[self.name]
        try:
            vals = tuple(float(v) for v in self.params)
        except (TypeError, ValueError):
            raise InputError(f"params of {self.name} must be {len(names)} numbers "
                             f"({', '.join(names)}), got {self.params!r}",
                             param="params") from None
        if len(vals) != len(names):
            raise InputError(f"params: {self.name} takes {len(names)} parameter"
                             f"{'s' if len(names) > 1 else ''} ({', '.join(names)}), got "
                             f"{len(vals)}", param="params")
        for n, v in zip(names, vals, strict=True):
            check_range(n, v, -1e4, 1e4, unit="MPa" if n.endswith("_mpa") else "")
        if self.name.startswith("ogden") and any(v == 0.0 for v in vals[1::2]):
            raise InputError("alpha: an Ogden exponent must be nonzero, got 0", param="params")
        mu = _shear_modulus(self.name, vals)
        if not mu > 0.0:
            raise InputError(f"params: the shear modulus of {self.name} must be > 0 MPa, got "
                             f"{mu:g}", param="params")
        if isinstance(self.d_per_mpa, (str, bytes, bool)) or self.d_per_mpa is None:
            raise InputError(f"d must be a number in 1/MPa, got {self.d_per_mpa!r}", param="d")
        # 0 (the default) selects the paper's Poisson ratio (Eq 6)
        d = check_range("d", 2.0 * (1.0 - 2.0 * _POISSON) / mu if self.d_per_mpa == 0.0
                        else self.d_per_mpa, 1e-12, 1e4, unit="1/MPa")
        # A value type: its constructor stores the normalised parameters (a tuple of float,
        # hashable; the default d resolved) whatever sequence it is given, and a frozen
        # dataclass sets a field only through object.__setattr__ (as its generated __init__).
        object.__setattr__(self, "params", vals)
        object.__setattr__(self, "d_per_mpa", d)
        nu = self.poisson
        if nu <= 0.0:
            raise InputError(f"d must be < 3 / mu = {3.0 / mu:.4g} 1/MPa (implied Poisson ratio "
                             f"> 0), got {d:g}", param="d")
        if nu < defaults.PLAUSIBLE_POISSON_MIN:
            warn_implausible(f"d = {d:g} 1/MPa implies a Poisson ratio of {nu:.3f}; a rubber "
                             "is nearly incompressible: is d in 1/MPa?")

    # --- parameters ---------------------------------------------------------------------

    @property
    def param_names(self) -> tuple[str, ...]:
        """Parameter names in order, with their unit suffix (``_mpa``: MPa; else unitless)."""
        return HYPERELASTIC_MODELS[self.name]

    @property
    def shear_modulus_mpa(self) -> float:
        """Initial (small-strain) shear modulus mu in MPa."""
        return _shear_modulus(self.name, self.params)

    @property
    def bulk_modulus_mpa(self) -> float:
        """Bulk modulus ``K = 2 / d`` in MPa."""
        return 2.0 / self.d_per_mpa

    @property
    def poisson(self) -> float:
        """Small-strain Poisson's ratio ``(3K - 2mu) / (2(3K + mu))`` (unitless)."""
        k, mu = self.bulk_modulus_mpa, self.shear_modulus_mpa
        return (3.0 * k - 2.0 * mu) / (2.0 * (3.0 * k + mu))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``model``, ``params`` by name (unit suffix), moduli, ``d_per_mpa``.

        Returns
        -------
        dict
            Keys end in their unit (``_mpa``, ``_per_mpa``).
        """
        return {
            "model": self.name,
            "params": dict(zip(self.param_names, self.params, strict=True)),
            "shear_modulus_mpa": self.shear_modulus_mpa,
            "d_per_mpa": self.d_per_mpa,
            "bulk_modulus_mpa": self.bulk_modulus_mpa,
        }

    def to_mooney_rivlin(self) -> MooneyRivlin:
        """The same material as a :class:`MooneyRivlin` (what the FE solver takes).

        Only a neo-Hookean (``C01 = 0``) or Mooney-Rivlin model has one; others raise
        :class:`~exofric.errors.InputError`.

        Returns
        -------
        MooneyRivlin
            Same C10, C01 (MPa) and d (1/MPa).
        """
        from exofric.material._models import MooneyRivlin

        if self.name not in ("neo-hookean", "mooney-rivlin"):
            raise InputError(f"model {self.name} has no Mooney-Rivlin form (only neo-hookean "
                             "and mooney-rivlin)", param="model")
        c01 = self.params[1] if self.name == "mooney-rivlin" else 0.0
        return MooneyRivlin(self.params[0], c01, self.d_per_mpa)

    # --- energy and stresses ---------------------------------------------------------------

    def _stress(self, mode: str, lam: Any, kind: str) -> Any:
        return _isochoric_stress(self.name, self.params, mode, lam, kind)

    @staticmethod
    def trial_stress_mpa(name: str, params: Sequence[float] | NDArray[np.float64], mode: str,
                         stretch: ArrayLike, kind: str = "engineering") -> NDArray[np.float64]:
        """:meth:`stress_mpa` of model ``name`` with ``params``, the parameters unchecked.

        For an optimiser's trial points, which need not make a valid material (a negative
        modulus): no model is built, nothing is checked (the stretches included: > 0 as for
        :meth:`stress_mpa`) and no warning is given.

        Parameters
        ----------
        name : str
            A key of :data:`HYPERELASTIC_MODELS`.
        params : sequence of float
            The parameters in the order of its names (MPa or unitless).
        mode : {'uniaxial', 'biaxial', 'planar'}
            The path.
        stretch : array_like of float
            Stretch of the loaded direction (unitless).
        kind : {'engineering', 'true'}
            Nominal or Cauchy stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa, the shape of ``stretch``.

        Examples
        --------
        >>> HyperelasticModel.trial_stress_mpa("neo-hookean", (0.5,), "uniaxial", [2.0])
        array([1.75])
        """
        import numpy as np

        lam = np.asarray(stretch, dtype=float)
        return np.asarray(_isochoric_stress(name, params, mode, lam, kind), dtype=float)

    @staticmethod
    def trial_shear_modulus_mpa(name: str,
                                params: Sequence[float] | NDArray[np.float64]) -> float:
        """:attr:`shear_modulus_mpa` of model ``name`` with ``params``, unchecked (see above).

        Parameters
        ----------
        name : str
            A key of :data:`HYPERELASTIC_MODELS`.
        params : sequence of float
            The parameters in the order of its names (MPa or unitless).

        Returns
        -------
        float
            mu in MPa (linear in the parameters of every model).

        Examples
        --------
        >>> HyperelasticModel.trial_shear_modulus_mpa("mooney-rivlin", (0.3, 0.1))
        0.8
        """
        return float(_shear_modulus(name, tuple(float(v) for v in params)))

    def stress_mpa(self, mode: str, stretch: ArrayLike,
                   kind: str = "engineering") -> NDArray[np.float64]:
        """Stress (MPa) in the loaded direction of a homogeneous incompressible test.

        Parameters
        ----------
        mode : {'uniaxial', 'biaxial', 'planar'}
            Uniaxial, equibiaxial or planar (pure shear) deformation.
        stretch : array_like of float
            Stretch ``l`` of the loaded direction (unitless), > 0.
        kind : {'engineering', 'true'}
            Nominal stress (force per undeformed area) or Cauchy (true) stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa, same shape as ``stretch``.
        """
        import numpy as np

        lam = _stretch_array(stretch)
        return np.asarray(self._stress(_check_mode(mode), lam, _check_kind(kind)), dtype=float)

    def uniaxial_stress_mpa(self, stretch: ArrayLike,
                            kind: str = "engineering") -> NDArray[np.float64]:
        """Uniaxial stress (MPa): stretches ``(l, l^-1/2, l^-1/2)``.

        Parameters
        ----------
        stretch : array_like of float
            Stretch of the loaded direction (unitless), > 0.
        kind : {'engineering', 'true'}
            Nominal or Cauchy stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa.
        """
        return self.stress_mpa("uniaxial", stretch, kind)

    def biaxial_stress_mpa(self, stretch: ArrayLike,
                           kind: str = "engineering") -> NDArray[np.float64]:
        """Equibiaxial stress (MPa): stretches ``(l, l, l^-2)``.

        Parameters
        ----------
        stretch : array_like of float
            In-plane stretch (unitless), > 0.
        kind : {'engineering', 'true'}
            Nominal or Cauchy stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa.
        """
        return self.stress_mpa("biaxial", stretch, kind)

    def planar_stress_mpa(self, stretch: ArrayLike,
                          kind: str = "engineering") -> NDArray[np.float64]:
        """Planar (pure shear) stress (MPa): stretches ``(l, 1, 1/l)``.

        Parameters
        ----------
        stretch : array_like of float
            Stretch of the loaded direction (unitless), > 0.
        kind : {'engineering', 'true'}
            Nominal or Cauchy stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa.
        """
        return self.stress_mpa("planar", stretch, kind)

    def tangent_mpa(self, mode: str, stretch: ArrayLike) -> NDArray[np.float64]:
        """Tangent ``dP/dl`` (MPa) of the nominal stress along a homogeneous path.

        By the complex step ``Im P(l + i h) / h`` (``h = 1e-30``): exact to rounding.

        Parameters
        ----------
        mode : {'uniaxial', 'biaxial', 'planar'}
            The path.
        stretch : array_like of float
            Stretch (unitless), > 0.

        Returns
        -------
        numpy.ndarray
            dP/dl in MPa.
        """
        import numpy as np

        lam = _stretch_array(stretch)
        h = 1e-30
        z = self._stress(_check_mode(mode), lam + 1j * h, "engineering")
        return np.asarray(np.imag(z) / h, dtype=float)

    def strain_energy_mpa(self, l1: ArrayLike, l2: ArrayLike,
                          l3: ArrayLike) -> NDArray[np.float64]:
        """Strain energy density W (MPa = mJ/mm^3) at principal stretches, volumetric term included.

        ``W = W_iso(lb1, lb2, lb3) + (J - 1)^2 / d`` with ``J = l1 l2 l3`` and the isochoric
        stretches ``lb_i = J^(-1/3) l_i``.

        Parameters
        ----------
        l1, l2, l3 : array_like of float
            Principal stretches (unitless), > 0.

        Returns
        -------
        numpy.ndarray
            W in MPa.
        """
        import numpy as np

        a, b, c = (_stretch_array(x) for x in (l1, l2, l3))
        j = a * b * c
        a, b, c = (x * j ** (-1.0 / 3.0) for x in (a, b, c))
        p = self.params
        if self.name.startswith("ogden"):
            w = sum(2.0 * m / al ** 2 * (a ** al + b ** al + c ** al - 3.0)
                    for m, al in zip(p[0::2], p[1::2], strict=True))
        else:
            i1 = a * a + b * b + c * c - 3.0
            if self.name == "yeoh":
                w = p[0] * i1 + p[1] * i1 ** 2 + p[2] * i1 ** 3
            else:
                w = p[0] * i1
                if self.name == "mooney-rivlin":
                    i2 = (a * b) ** 2 + (b * c) ** 2 + (c * a) ** 2 - 3.0
                    w = w + p[1] * i2
        return np.asarray(w + (j - 1.0) ** 2 / self.d_per_mpa, dtype=float)

    def stability(self, stretch_min: float, stretch_max: float,
                  n_points: int = 401, modes: tuple[str, ...] = MODES) -> StabilityCheck:
        """Drucker stability (``dP/dl > 0``) along the homogeneous paths over a stretch range.

        Parameters
        ----------
        stretch_min, stretch_max : float
            Range of stretches checked (unitless), ``0 < stretch_min < stretch_max``.
        n_points : int
            Stretches checked per path, evenly spaced (>= 2).
        modes : tuple of str
            The paths checked (default all three: uniaxial, biaxial, planar).

        Returns
        -------
        StabilityCheck
            ``stable`` and, per path, the first unstable stretch counted from 1.
        """
        import numpy as np

        lo = check_range("stretch_min", stretch_min, 0.0, 1e3, lo_open=True)
        hi = check_range("stretch_max", stretch_max, lo, 1e3, lo_open=True)
        n = int(check_range("n_points", n_points, 2, 1e6))
        lam = np.linspace(lo, hi, n)
        order = np.argsort(np.abs(np.log(lam)))  # nearest l = 1 first
        checked = tuple(_check_mode(m) for m in modes)
        first: dict[str, float | None] = dict.fromkeys(MODES)
        for mode in checked:
            bad = ~(self.tangent_mpa(mode, lam) > 0.0)
            hits = order[bad[order]]
            first[mode] = float(lam[hits[0]]) if hits.size else None
        return StabilityCheck(all(v is None for v in first.values()), lo, hi, first, n, checked)

    def check_fe_stability(self, stretch_max: float | None = None) -> None:
        """Refuse parameters that are Drucker-unstable where the FE solvers deform a tube.

        The FE problems (squeeze, inflation, ring test, pull-out) need positive small-strain
        moduli (``mu > 0``, ``K > 0``: checked when the model is made) and a material that
        stays stable at large strain: where ``dP/dl <= 0`` Newton fails deep in the solve.
        Checked: ``dP/dl > 0`` along the uniaxial, equibiaxial and planar paths at every state
        whose principal stretches lie in ``[1 / stretch_max, stretch_max]`` (uniaxial and
        planar ``l`` over that range, equibiaxial ``l`` over its square root), 801 stretches
        per path, cached per parameter set; an instability up to twice ``stretch_max`` is a
        :class:`~exofric.errors.PlausibilityWarning`.

        Parameters
        ----------
        stretch_max : float, optional
            Largest principal stretch checked (unitless, > 1); default
            ``defaults.MR_STRETCH_LIMIT`` (2.5: the range the FE results are validated for).

        Raises
        ------
        InputError
            ``param="params"``: the model, its parameters and, per path, the unstable
            stretches.

        Examples
        --------
        >>> material_model("yeoh", [0.19, -0.0019, 4.1e-5]).check_fe_stability()  # stable
        >>> material_model("mooney-rivlin", [-0.1, 0.4]).check_fe_stability()
        Traceback (most recent call last):
        ...
        exofric.errors.InputError: params: mooney-rivlin (C10 = -0.1 MPa, C01 = 0.4 MPa) is \
Drucker-unstable (dP/dl <= 0) within the stretches the FE reaches (principal stretches \
0.4-2.5): uniaxial at stretch 1.71-2.5. Give parameters stable there \
(HyperelasticModel.stability shows where)
        """
        _check_fe_stability(self, stretch_max)

    def section_instability(self, stretch: float) -> tuple[str, float] | None:
        """Whether a solve that stopped at largest principal stretch ``stretch`` stopped on
        the material's own Drucker instability (issue 38).

        Compared: ``stretch`` and the smallest stretch > 1 from which the planar or uniaxial
        path is Drucker-unstable (``dP/dl <= 0``; the paths a plane section's state lies
        near); the material is blamed from 90 % of that stretch on (the failed step may have
        crossed it).

        Parameters
        ----------
        stretch : float
            Largest principal stretch of the last converged state (unitless).

        Returns
        -------
        tuple of (str, float) or None
            The words naming the stretch, the model, its parameters and the unstable stretch,
            and that stretch (unitless); None when the material does not explain it.

        Examples
        --------
        >>> soft = material_model("ogden1", [0.6, 0.55])
        >>> soft.section_instability(2.0) is None
        True
        >>> print(soft.section_instability(3.2)[0])
        largest principal stretch 3.2: ogden1 (mu1 = 0.6 MPa, alpha1 = 0.55) is \
Drucker-unstable (dP/dl <= 0) from planar stretch 3.08, a material instability no finer mesh \
cures
        """
        return _section_instability(self, float(stretch))


def _shown(name: str, value: float) -> str:
    """A parameter as a message shows it: ``C10 = 0.5 MPa``, ``alpha1 = 2`` (not the Python
    name, which the CLI would take for its option)."""
    if name.endswith("_mpa"):
        label = name[:-4]
        return f"{label.upper() if label.startswith('c') else label} = {value:.4g} MPa"
    return f"{name} = {value:.4g}"


#: The paths of the FE check, as messages name them.
_PATH_NAMES = {"uniaxial": "uniaxial", "biaxial": "equibiaxial", "planar": "planar"}


def _fe_ranges(stretch_max: float) -> dict[str, tuple[float, float]]:
    """Per path, the stretches (unitless) at which every principal stretch lies in
    ``[1 / stretch_max, stretch_max]``: equibiaxial ``(l, l, l^-2)`` only to
    ``stretch_max^(1/2)``."""
    s = float(stretch_max)
    return {"uniaxial": (1.0 / s, s), "biaxial": (s ** -0.5, s ** 0.5), "planar": (1.0 / s, s)}


@functools.lru_cache(maxsize=64)
def _fe_unstable(name: str, params: tuple[float, ...],
                 stretch_max: float) -> dict[str, list[tuple[float, float]]]:
    """Per path, the stretch intervals (unitless) of the FE's range where ``dP/dl <= 0``
    (on 801 stretches evenly spaced in ln l per path, 1 included)."""
    import numpy as np

    out: dict[str, list[tuple[float, float]]] = {}
    for mode, (lo, hi) in _fe_ranges(stretch_max).items():
        lam = np.unique(np.concatenate([np.geomspace(lo, hi, 801), [1.0]]))
        z = _isochoric_stress(name, params, mode, lam + 1j * 1e-30, "engineering")
        bad = ~(np.imag(z) / 1e-30 > 0.0)
        if not bad.any():
            continue
        idx = np.flatnonzero(bad)
        runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
        out[mode] = [(float(lam[r[0]]), float(lam[r[-1]])) for r in runs]
    return out


def _check_fe_stability(model: HyperelasticModel, stretch_max: float | None,
                        subject: str = "params") -> None:
    """:meth:`HyperelasticModel.check_fe_stability`; ``subject`` opens the message and is
    the error's parameter (its first name)."""
    smax = float(defaults.MR_STRETCH_LIMIT if stretch_max is None
                 else check_range("stretch_max", stretch_max, 1.0, 1e3, lo_open=True))
    params = tuple(model.params)
    bad = _fe_unstable(model.name, params, smax)
    values = ", ".join(_shown(n, v) for n, v in zip(model.param_names, params, strict=True))
    if bad:
        where = "; ".join(f"{_PATH_NAMES[m]} at stretch "
                          + " and ".join(f"{a:.3g}-{b:.3g}" for a, b in runs)
                          for m, runs in bad.items())
        raise InputError(f"{subject}: {model.name} ({values}) is Drucker-unstable (dP/dl <= 0) "
                         f"within the stretches the FE reaches (principal stretches "
                         f"{1.0 / smax:.3g}-{smax:.3g}): {where}. Give parameters stable there "
                         "(HyperelasticModel.stability shows where)",
                         param=subject.split(",")[0])
    wide = 2.0 * smax
    later = _fe_unstable(model.name, params, wide)
    if later:
        # per run, its stretch nearest 1; the nearest of all
        near = [(b if b < 1.0 else a, m) for m, runs in later.items() for a, b in runs]
        lam, mode = min(near, key=lambda t: abs(math.log(t[0])))
        warn_implausible(f"{model.name} ({values}) is Drucker-unstable from {_PATH_NAMES[mode]} "
                         f"stretch {lam:.3g}, beyond the {1.0 / smax:.3g}-{smax:.3g} the FE "
                         "results are validated for: a solve that stretches the tube that far "
                         "fails to converge")


#: The homogeneous paths an FE section's state lies near: an in-plane stretch l with the
#: out-of-plane stretch near 1 (planar: plane strain, the squeeze and the inflation) or free
#: (uniaxial: plane stress, the ring). Equibiaxial (l, l, 1/l^2) needs an out-of-plane
#: stretch no section reaches, so its onset is not compared with a section's stretch.
_SECTION_PATHS = ("planar", "uniaxial")

#: A solve that stopped with its largest stretch this close below the onset (the failing step
#: may have crossed it: a squeeze's last steps grow the stretch by up to 30 %) is the material's.
_ONSET_MARGIN = 0.9


@functools.lru_cache(maxsize=64)
def _tension_onset(name: str, params: tuple[float, ...],
                   stretch_max: float = 10.0) -> tuple[float, str] | None:
    """The smallest stretch > 1 (unitless) at which the planar or uniaxial path turns
    Drucker-unstable (``dP/dl <= 0``, complex-step derivative on 2001 stretches evenly spaced
    in ln l up to ``stretch_max``), with its path; None if both are stable there."""
    import numpy as np

    lam = np.geomspace(1.0, stretch_max, 2001)
    best: tuple[float, str] | None = None
    for mode in _SECTION_PATHS:
        z = _isochoric_stress(name, params, mode, lam + 1j * 1e-30, "engineering")
        bad = np.flatnonzero(~(np.imag(z) / 1e-30 > 0.0))
        if bad.size and (best is None or lam[bad[0]] < best[0]):
            best = (float(lam[bad[0]]), mode)
    return best


def _section_instability(model: HyperelasticModel, stretch: float) -> tuple[str, float] | None:
    """Why a solve stopped at largest principal stretch ``stretch`` (unitless), if it is the
    material's: (words naming the stretch, the model, its parameters and the unstable
    stretch; the onset stretch), or None when ``stretch`` is below ``_ONSET_MARGIN`` x the
    planar/uniaxial Drucker onset (or there is none up to stretch 10)."""
    onset = _tension_onset(model.name, tuple(float(v) for v in model.params))
    if onset is None or not stretch >= _ONSET_MARGIN * onset[0]:
        return None
    values = ", ".join(_shown(n, v) for n, v in zip(model.param_names, model.params,
                                                     strict=True))
    return (f"largest principal stretch {stretch:.3g}: {model.name} ({values}) is "
            f"Drucker-unstable (dP/dl <= 0) from {onset[1]} stretch {onset[0]:.3g}, a material "
            "instability no finer mesh cures", onset[0])


def material_model(name: str, params: ArrayLike, d: float | None = None,
                   poisson: float = _POISSON) -> HyperelasticModel:
    """A hyperelastic model by name, with its parameters checked.

    Parameters
    ----------
    name : str
        ``neo-hookean``, ``mooney-rivlin``, ``yeoh``, ``ogden1``, ``ogden2``, ``ogden3``, or
        ``ogden`` (N from the parameter count: 2, 4 or 6). Case and ``_`` for ``-`` are
        forgiven.
    params : array_like of float
        In the order of :data:`HYPERELASTIC_MODELS`: C10, C01, C20, C30 and Ogden ``mu_i`` in
        MPa; Ogden ``alpha_i`` unitless, given as pairs ``mu1, alpha1, mu2, alpha2, ...``.
    d : float, optional
        Incompressibility parameter d in 1/MPa (``K = 2/d``). Default: from ``poisson``,
        ``d = 2 (1 - 2 nu) / mu`` (the paper's Eq 6 with its shear modulus mu).
    poisson : float
        Small-strain Poisson ratio nu in (0, 0.5) behind the default d (0.498, the paper's).

    Returns
    -------
    HyperelasticModel

    Raises
    ------
    InputError
        Unknown name (the message lists the known ones) or wrong parameter count (the message
        names the model and the count it takes).

    Examples
    --------
    >>> m = material_model("ogden", [0.63, 1.3, 0.0012, 5.0, -0.01, -2.0])
    >>> m.name, round(m.shear_modulus_mpa, 4)
    ('ogden3', 0.6212)
    >>> material_model("yeo", [1.0])
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: model must be one of neo-hookean, mooney-rivlin, yeoh, ogden1, \
ogden2, ogden3 (or ogden), got 'yeo'
    """
    import numpy as np

    key = name.strip().lower().replace("_", "-") if isinstance(name, str) else name
    if isinstance(key, str):
        key = {"neohookean": "neo-hookean", "mooneyrivlin": "mooney-rivlin"}.get(key, key)
    if key == "ogden":
        try:
            n = len(params)  # type: ignore[arg-type]
        except TypeError:
            n = -1
        if n not in (2, 4, 6):
            raise InputError(f"params: ogden takes 2, 4 or 6 parameters (pairs mu_i in MPa, "
                             f"alpha_i), got {n if n >= 0 else params!r}", param="params")
        key = f"ogden{n // 2}"
    if not isinstance(key, str) or key not in HYPERELASTIC_MODELS:
        raise InputError(f"model must be one of {', '.join(HYPERELASTIC_MODELS)} (or ogden), "
                         f"got {name!r}", param="model")
    try:
        vals = tuple(float(v) for v in np.ravel(np.asarray(params, dtype=float)))
    except (TypeError, ValueError):
        raise InputError(f"params of {key} must be numbers, got {params!r}",
                         param="params") from None
    if d is None:
        nu = check_range("poisson", poisson, 0.0, 0.5, lo_open=True, hi_open=True)
        names = HYPERELASTIC_MODELS[key]
        if len(vals) != len(names):
            raise InputError(f"params: {key} takes {len(names)} parameter"
                             f"{'s' if len(names) > 1 else ''} ({', '.join(names)}), got "
                             f"{len(vals)}", param="params")
        mu = _shear_modulus(key, vals)
        if not (math.isfinite(mu) and mu > 0.0):
            raise InputError(f"params: the shear modulus of {key} must be > 0 MPa, got "
                             f"{mu:g}", param="params")
        d = 2.0 * (1.0 - 2.0 * nu) / mu
    elif isinstance(d, (str, bytes, bool)):
        raise InputError(f"d must be a number in 1/MPa, got {d!r}", param="d")
    else:
        d = check_range("d", d, 0.0, 1e4, lo_open=True, unit="1/MPa")
    return HyperelasticModel(key, vals, float(d))

