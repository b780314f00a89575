"""What a pull-out depends on, but the pressure and the path: :class:`PulloutSetup`.

The structure, the material, the three interfaces' friction (and the static coefficient), the
cable's EA, the tube's end fittings, the squeeze's accuracy and the numerics of the section and
the shear lag travel together from the CLI, the knee's stiffness and the calibration from pulls
to the solvers as one frozen object, checked once (issue 32: ``pullout`` had 20 parameters,
``joint_stiffness`` 17, ``section_pullout`` 14). Units: mm, N, MPa, N/mm^3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import InputError, check_positive, check_range, warn_implausible
from exofric.geometry import Structure
from exofric.material import HyperelasticModel, MooneyRivlin
from exofric.simulate._common import check_friction, fe_material_of

if TYPE_CHECKING:
    from exofric.simulate._pullout import PulloutResult, SectionPullout
    from exofric.simulate._squeeze_result import SqueezeResult

__all__ = ["PULLOUT_ENDS", "PulloutNumerics", "PulloutSetup", "check_pullout_friction"]

#: the tube's end fittings: held axially, or free to slide on the wall
PULLOUT_ENDS = ("fixed", "free")


def _count(name: str, value: Any, low: int, high: int) -> int:
    """``value`` as an int in [low, high] (InputError naming ``name`` otherwise)."""
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise InputError(f"{name} must be an integer in [{low}, {high}], got {value!r}",
                         param=name)
    return int(value)


@checked_init
@dataclass(frozen=True)
class PulloutNumerics:
    """Numerical parameters of the section solve and the shear lag (defaults: converged).

    Parameters
    ----------
    n_steps : int
        Section load steps to 3x the estimated slip displacement ([2, 10000]; more are added
        until full sliding).
    stick_penalty : float
        Stick penalty of the section's augmented Lagrangian (N/mm^3, > 0).
    creep_tol_mm : float
        Largest elastic slip of a sticking node (mm, > 0).
    n_z : int
        Cable elements along the tube length ([2, 100000]).
    n_path : int
        Path steps per pulled-end amplitude ([2, 100000]).
    line_stick_rel : float
        Stick spring of the wire-wall line contact relative to the section's initial
        stiffness (unitless, > 0; the rigid limit as it grows).
    held_zone : {'vector', 'scalar'}
        Model of the zones next to held end faces (``ends="fixed"``): the 3-D incremental
        problem about the squeeze (``'vector'``; Mooney-Rivlin and neo-Hookean tubes, others
        use the scalar one) or the axial field alone with a rod modulus 3 G (``'scalar'``).

    Examples
    --------
    >>> PulloutNumerics(n_z=20, n_path=20).n_steps
    40
    >>> PulloutNumerics(n_path=1)
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: n_path must be an integer in [2, 100000], got 1
    >>> PulloutNumerics(held_zone="bonded")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: held_zone must be 'vector' or 'scalar', got 'bonded'
    """

    n_steps: int = defaults.PULLOUT_SECTION_STEPS
    stick_penalty: float = defaults.PULLOUT_STICK_PENALTY_N_PER_MM3
    creep_tol_mm: float = defaults.PULLOUT_CREEP_TOL_MM
    n_z: int = defaults.PULLOUT_Z_ELEMENTS
    n_path: int = defaults.PULLOUT_PATH_STEPS
    line_stick_rel: float = defaults.PULLOUT_LINE_STICK_REL
    held_zone: str = defaults.PULLOUT_HELD_ZONE

    def __post_init__(self) -> None:
        _count("n_steps", self.n_steps, 2, 10_000)
        _count("n_z", self.n_z, 2, 100_000)
        _count("n_path", self.n_path, 2, 100_000)
        check_positive("stick_penalty", self.stick_penalty, "N/mm^3")
        check_positive("creep_tol_mm", self.creep_tol_mm, "mm")
        check_positive("line_stick_rel", self.line_stick_rel)
        if self.held_zone not in ("vector", "scalar"):
            raise InputError(f"held_zone must be 'vector' or 'scalar', got {self.held_zone!r}",
                             param="held_zone")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unit-suffixed keys)."""
        return {"n_steps": self.n_steps, "stick_penalty_n_per_mm3": float(self.stick_penalty),
                "creep_tol_mm": float(self.creep_tol_mm), "n_z": self.n_z,
                "n_path": self.n_path, "line_stick_rel": float(self.line_stick_rel),
                "held_zone": self.held_zone}


def check_pullout_friction(mu_wire: float, mu_wall: float, mu_wire_wall: float, ends: str,
                           mu_static: float | None = None) -> tuple[float, float, float, float]:
    """(mu_wire, mu_wall, mu_wire_wall, mu_static) of a pull, checked (unitless).

    Parameters
    ----------
    mu_wire, mu_wall, mu_wire_wall : float
        Kinetic Coulomb coefficients tube-wire, tube-wall, wire-wall (unitless, [0, 2]).
    ends : {'fixed', 'free'}
        The tube's end fittings.
    mu_static : float or None
        Static coefficient of the wire's interfaces (unitless, >= ``mu_wire``; None: mu_wire).

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> check_pullout_friction(0.3, 0.5, 0.2, "fixed", 0.36)
    (0.3, 0.5, 0.2, 0.36)
    """
    mw = check_friction("mu_wire", mu_wire)
    mh = check_friction("mu_wall", mu_wall)
    mww = check_friction("mu_wire_wall", mu_wire_wall)
    if ends not in PULLOUT_ENDS:
        raise InputError(f"ends must be one of {', '.join(PULLOUT_ENDS)}, got {ends!r}",
                         param="ends")
    if mu_static is None:
        return mw, mh, mww, mw
    ms = check_friction("mu_static", mu_static)
    if ms < mw:
        raise InputError(f"mu_static must be >= the kinetic mu_wire ({mw:g}), got {ms:g}",
                         param="mu_static")
    return mw, mh, mww, ms


@checked_init
@dataclass(frozen=True)
class PulloutSetup:
    """A pull-out problem but its pressure and path: structure, material, friction, cable, ends.

    Validated when made (an invalid setup cannot exist); :meth:`section` and :meth:`pull` run
    it (they are :func:`~exofric.simulate.section_pullout` and
    :func:`~exofric.simulate.pullout`), and :func:`exofric.friction.joint_stiffness` takes one.

    Parameters
    ----------
    structure : Structure
        Hole, tube and wire (mm) and tube length (mm).
    material : MooneyRivlin or HyperelasticModel
        Tube material.
    mu_wire, mu_wall, mu_wire_wall : float
        Kinetic Coulomb coefficients (unitless, [0, 2]) tube-wire, tube-wall, wire-wall.
    mu_static : float, optional
        Static coefficient of the wire's interfaces (unitless, >= ``mu_wire``); every slider
        of the section law holds ``mu_static / mu_wire`` x its kinetic capacity until it
        slides. Default: ``mu_wire`` (no static peak).
    cable_ea_n : float
        Cable axial stiffness EA (N, in (0, 1e10]), default :data:`exofric.defaults.CABLE_EA_N`.
    ends : {'fixed', 'free'}
        Tube held axially by its end fittings (the zones next to them solved in 3-D; a tube
        that slides on the wall is held by them until the wire slides), or free to slide on
        the wall once the wall arc slides.
    accuracy : {'draft', 'standard', 'fine'} or None
        The squeeze's accuracy level (None: the default unless ``mesh`` is given).
    mesh : MeshSpec or None
        An explicit squeeze mesh instead of a level.
    numerics : PulloutNumerics
        Steps, penalties and elements of the section and the shear lag.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> s = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...                  mu_wire_wall=0.2, mu_static=0.36)
    >>> s.static_ratio
    1.2
    >>> PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
    ...              mu_wire_wall=0.2, mu_static=0.1)
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: mu_static must be >= the kinetic mu_wire (0.3), got 0.1
    """

    structure: Structure
    material: MooneyRivlin | HyperelasticModel
    mu_wire: float
    mu_wall: float
    mu_wire_wall: float
    mu_static: float | None = None
    cable_ea_n: float = defaults.CABLE_EA_N
    ends: str = "fixed"
    accuracy: str | None = None
    mesh: Any = None
    numerics: PulloutNumerics = field(default_factory=PulloutNumerics)

    def __post_init__(self) -> None:
        if not isinstance(self.structure, Structure):
            raise InputError(f"structure must be a Structure, got {type(self.structure).__name__}",
                             param="structure")
        fe_material_of(self.material)
        check_pullout_friction(self.mu_wire, self.mu_wall, self.mu_wire_wall, self.ends,
                               self.mu_static)
        # a steel cable of 1.6 mm is ~1.3e5 N; 1e10 N is a rigid cable for any tube (EA / L
        # >= 1e7 N/mm against the tube's ~15 N/mm) and keeps the shear lag's round-off bounded
        check_range("cable_ea_n", self.cable_ea_n, 0.0, 1e10, lo_open=True, unit="N")
        if not isinstance(self.numerics, PulloutNumerics):
            raise InputError("numerics must be a PulloutNumerics, got "
                             f"{type(self.numerics).__name__}", param="numerics")

    @property
    def friction(self) -> tuple[float, float, float, float]:
        """(mu_wire, mu_wall, mu_wire_wall, mu_static) as floats (unitless)."""
        return check_pullout_friction(self.mu_wire, self.mu_wall, self.mu_wire_wall, self.ends,
                                      self.mu_static)

    @property
    def static_ratio(self) -> float:
        """mu_static / mu_wire (unitless; 1 without a static peak or without wire friction)."""
        mw, _, _, ms = self.friction
        return ms / mw if mw > 0 else 1.0

    def with_friction(self, **coefficients: float | None) -> PulloutSetup:
        """A copy with other coefficients, validated.

        Parameters
        ----------
        **coefficients : float or None
            Any of ``mu_wire``, ``mu_wall``, ``mu_wire_wall`` (unitless, [0, 2]) and
            ``mu_static`` (unitless, >= ``mu_wire``; None: no static peak).

        Returns
        -------
        PulloutSetup

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> s = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
        ...                  mu_wire_wall=0.2)
        >>> s.with_friction(mu_wire=0.4).friction
        (0.4, 0.5, 0.2, 0.4)
        """
        unknown = set(coefficients) - {"mu_wire", "mu_wall", "mu_wire_wall", "mu_static"}
        if unknown:
            raise InputError(f"with_friction: unknown coefficient(s) {sorted(unknown)}",
                             param="coefficients")
        return replace(self, **coefficients)  # type: ignore[arg-type]

    def travel_mm(self, displacement_mm: float) -> float:
        """The pulled end's amplitude (mm), checked against the tube length: in (0, L].

        The one check of a pull's travel (:func:`pullout`, :meth:`pull`,
        :func:`exofric.friction.joint_stiffness`), before any solve; above 10 mm a
        :class:`~exofric.errors.PlausibilityWarning` (the squeeze state is held, which assumes
        the travel is small against the length).

        Parameters
        ----------
        displacement_mm : float
            Amplitude of the pulled end (mm).

        Returns
        -------
        float
            The amplitude (mm).

        Raises
        ------
        InputError
            Not a finite number in (0, L] (``param="displacement_mm"``).

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> s = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
        ...                  mu_wire_wall=0.2)
        >>> s.travel_mm(3)
        3.0
        >>> s.travel_mm(200.0)
        Traceback (most recent call last):
        ...
        exofric.errors.InputError: displacement_mm must be in (0, 116] mm (the tube length), \
got 200.0
        """
        length_mm = self.structure.length_mm
        try:
            dmax = float(displacement_mm)
        except (TypeError, ValueError):
            dmax = float("nan")
        if not (math.isfinite(dmax) and 0.0 < dmax <= length_mm):
            raise InputError(f"displacement_mm must be in (0, {length_mm:g}] mm (the tube "
                             f"length), got {displacement_mm!r}", param="displacement_mm")
        if dmax > 10.0:
            warn_implausible(f"displacement_mm = {dmax:g} mm: the squeeze state is held, which "
                             "assumes the wire's travel is small against the tube's length")
        return dmax

    def section(self, pressure_mpa: float, *, squeeze_result: SqueezeResult | None = None,
                squeeze_index: int = -1) -> SectionPullout:
        """The per-unit-length pull at ``pressure_mpa``: :func:`section_pullout`.

        Parameters
        ----------
        pressure_mpa : float
            Pressure (MPa).
        squeeze_result : SqueezeResult, optional
            A solved squeeze (fields kept) to start from.
        squeeze_index : int
            Index of the pressure in ``squeeze_result``.

        Returns
        -------
        SectionPullout
        """
        from exofric.simulate._pullout import section_pullout

        return section_pullout(self, pressure_mpa, squeeze_result=squeeze_result,
                               squeeze_index=squeeze_index)

    def pull(self, pressure_mpa: float, *, displacement_mm: float = 1.0, cycles: int = 1,
             first_loading: bool = False, squeeze_result: SqueezeResult | None = None,
             squeeze_index: int = -1) -> PulloutResult:
        """The whole length pulled at ``pressure_mpa``: :func:`pullout` (mm, N).

        Parameters
        ----------
        pressure_mpa : float
            Pressure (MPa).
        displacement_mm : float
            Amplitude of the pulled end (mm), in (0, L].
        cycles : int
            Back-and-forth cycles ([0, 100]).
        first_loading : bool
            Only the first leg, finely stepped past the breakaway.
        squeeze_result : SqueezeResult, optional
            A solved squeeze (fields kept) to start from.
        squeeze_index : int
            Index of the pressure in ``squeeze_result``.

        Returns
        -------
        PulloutResult
        """
        from exofric.simulate._pullout import pullout

        return pullout(self, pressure_mpa, displacement_mm=displacement_mm, cycles=cycles,
                       first_loading=first_loading, squeeze_result=squeeze_result,
                       squeeze_index=squeeze_index)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (mm, N, unitless coefficients).

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
        ...              mu_wire_wall=0.2).to_dict()["mu_static"]
        0.3
        """
        mw, mh, mww, ms = self.friction
        return {"structure": self.structure.to_dict(), "material": self.material.to_dict(),
                "mu_wire": mw, "mu_wall": mh, "mu_wire_wall": mww, "mu_static": ms,
                "cable_ea_n": float(self.cable_ea_n), "ends": self.ends,
                "accuracy": self.accuracy,
                "mesh": None if self.mesh is None else self.mesh.to_dict(),
                "numerics": self.numerics.to_dict()}
