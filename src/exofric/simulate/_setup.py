"""What a squeeze solve depends on, but the pressures: :class:`SqueezeSetup`, validated once.

The structure, the material, the tube's ends, the friction of the section's contacts, the
accuracy (or an explicit mesh), gravity, the wire's angle and the solver's numerical
parameters travel together from the CLI or the Python API to the contact kernel as one frozen
object, checked in one place, and come back on the result (``SqueezeResult.setup``): before,
``mu_wall`` changed names five times between the CLI and the kernel and was checked twice.
Units: mm, MPa, N/mm^3, t/mm^3, deg.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric import defaults
from exofric._validate import checked_init
from exofric.errors import InputError, check_positive
from exofric.fe import GRAVITY_OPTIONS, MeshSpec, NewtonSettings, check_ends
from exofric.geometry import Structure
from exofric.material import HyperelasticModel, MooneyRivlin
from exofric.simulate._common import FEMaterial, check_friction, fe_material_of, resolve_accuracy

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from exofric.simulate._squeeze_result import SqueezeResult

__all__ = ["SqueezeSetup"]


@checked_init
@dataclass(frozen=True)
class SqueezeSetup:
    """A squeeze problem but its pressures: structure, material, ends, friction, accuracy, ...

    The parameters are those of :func:`~exofric.simulate.squeeze` (which builds one); they are
    validated when the setup is made, so an invalid one cannot exist. :meth:`solve` runs it.

    Parameters
    ----------
    structure : Structure
        Hole, tube and wire (mm) and tube length (mm).
    material : MooneyRivlin or HyperelasticModel
        Tube material.
    ends : {'plane-strain', 'closed', 'open'}
        The tube's axial condition.
    mu_wall, mu_wire : float
        Coulomb coefficients of the tube on the hole wall and on the wire (unitless, [0, 2]).
    friction_penalty : float or None
        Tangential penalty (N/mm^3); None: the default fraction of ``penalty``.
    accuracy : {'draft', 'standard', 'fine'} or None
        Named accuracy level (None: the default, unless ``mesh`` is given).
    mesh : MeshSpec or None
        An explicit mesh instead of a level (no error estimate).
    gravity : {'none', 'toward-wall', 'toward-wire'}
        The tube's weight.
    wire_angle_deg : float
        Angle of the wire centre from the top of the hole (deg, |a| < 90).
    full_model : bool
        Solve the full section also at angle 0.
    penalty : float
        Contact penalty (N/mm^3, > 0).
    density : float
        Tube density (t/mm^3, > 0).
    settings : NewtonSettings or None
        Newton settings (None: :data:`exofric.defaults.SQUEEZE_NEWTON`).
    onset_tol_mpa : float
        Tolerance of the bracketed contact onset (MPa, > 0).
    regulariser, rotation_regulariser : float
        Relative stiffness of the floating-mode and rotation springs (unitless, > 0).
    keep_fields : bool
        Keep displacements and stresses for plots and export.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> s = SqueezeSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wall=0.3)
    >>> s.mu, s.levels()[0]
    ((0.3, 0.0), 'standard')
    >>> SqueezeSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=-1.0)
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: mu_wire must be >= 0 (unitless friction coefficient), got -1
    """

    structure: Structure
    material: MooneyRivlin | HyperelasticModel
    ends: str = "plane-strain"
    mu_wall: float = 0.0
    mu_wire: float = 0.0
    friction_penalty: float | None = None
    accuracy: str | None = None
    mesh: MeshSpec | None = None
    gravity: str = defaults.GRAVITY
    wire_angle_deg: float = 0.0
    full_model: bool = False
    penalty: float = defaults.CONTACT_PENALTY_N_PER_MM3
    density: float = defaults.SILICONE_DENSITY_T_PER_MM3
    settings: NewtonSettings | None = None
    onset_tol_mpa: float = 2e-4
    regulariser: float = defaults.REGULARISER_SPRING_REL
    rotation_regulariser: float = defaults.ROTATION_SPRING_REL
    keep_fields: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.structure, Structure):
            raise InputError(f"structure must be a Structure, got {type(self.structure).__name__}",
                             param="structure")
        fe_material_of(self.material)
        check_positive("penalty", self.penalty, "N/mm^3")
        check_positive("density", self.density, "t/mm^3")
        check_positive("onset_tol_mpa", self.onset_tol_mpa, "MPa")
        check_positive("regulariser", self.regulariser)
        check_positive("rotation_regulariser", self.rotation_regulariser)
        check_friction("mu_wall", self.mu_wall)
        check_friction("mu_wire", self.mu_wire)
        check_ends(self.ends)
        if self.friction_penalty is not None:
            check_positive("friction_penalty", self.friction_penalty, "N/mm^3")
        angle = self.angle_deg
        if (angle != 0.0 or self.full_model) and self.gravity != "none":
            # toward the wall the weight holds the tube at the bottom until the wire pushes it
            # along the wall; that slide, resisted only by the weight (~1e-4 N/mm per mm
            # against the contact's 1e5), defeats load control on coarse meshes.
            raise InputError(f"an off-centre wire (wire_angle_deg = {angle:g}) needs gravity "
                             f"'none', got {self.gravity!r}", param="wire_angle_deg")
        if self.gravity not in GRAVITY_OPTIONS:
            raise InputError(f"gravity must be one of {', '.join(GRAVITY_OPTIONS)}, got "
                             f"{self.gravity!r}", param="gravity")
        self.levels()

    @property
    def angle_deg(self) -> float:
        """The wire angle as a float in (-90, 90) deg (InputError otherwise)."""
        try:
            angle = float(self.wire_angle_deg)
        except (TypeError, ValueError):
            raise InputError(f"wire_angle_deg must be a number in (-90, 90) deg, got "
                             f"{self.wire_angle_deg!r}", param="wire_angle_deg") from None
        if not (np.isfinite(angle) and abs(angle) < 90.0):
            raise InputError(f"wire_angle_deg must be a number in (-90, 90) deg, got {angle:g}",
                             param="wire_angle_deg")
        return angle

    @property
    def mu(self) -> tuple[float, float]:
        """(mu_wall, mu_wire) as floats (unitless)."""
        return float(self.mu_wall), float(self.mu_wire)

    @property
    def fe_material(self) -> FEMaterial:
        """The FE's view of the material (:func:`fe_material_of`)."""
        return fe_material_of(self.material)

    @property
    def newton(self) -> NewtonSettings:
        """The Newton settings (the default ones unless given)."""
        return self.settings or NewtonSettings(**defaults.SQUEEZE_NEWTON)

    @property
    def full(self) -> bool | None:
        """True to force the full section, None to let the angle decide."""
        return True if self.full_model else None

    def levels(self) -> tuple[str, MeshSpec, MeshSpec | None]:
        """(accuracy name, mesh solved, nested coarse mesh of the estimate or None).

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> name, m, c = SqueezeSetup(BASE, MooneyRivlin.from_shore(62.5)).levels()
        >>> name, m.n_circ, c.n_circ
        ('standard', 32, 16)
        """
        return resolve_accuracy(self.accuracy, self.mesh, defaults.SQUEEZE_ACCURACY)

    def solve(self, pressures_mpa: ArrayLike) -> SqueezeResult:
        """Solve the squeeze at the given pressures (MPa): :func:`~exofric.simulate.squeeze`.

        Parameters
        ----------
        pressures_mpa : array_like
            Strictly increasing pressures (MPa), in [0, 2].

        Returns
        -------
        SqueezeResult
            With this setup as its ``setup``.

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> s = SqueezeSetup(BASE, MooneyRivlin.from_shore(62.5), keep_fields=False)
        >>> round(float(s.solve([0.6]).squeeze_force_n[0]))
        241
        """
        from exofric.simulate._squeeze import solve_setup

        return solve_setup(self, pressures_mpa)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (mm, MPa, N/mm^3, t/mm^3, deg).

        Examples
        --------
        >>> from exofric.geometry import BASE
        >>> SqueezeSetup(BASE, MooneyRivlin.from_shore(62.5)).to_dict()["ends"]
        'plane-strain'
        """
        return {
            "structure": self.structure.to_dict(), "material": self.material.to_dict(),
            "ends": self.ends, "mu_wall": float(self.mu_wall), "mu_wire": float(self.mu_wire),
            "friction_penalty_n_per_mm3": (None if self.friction_penalty is None
                                           else float(self.friction_penalty)),
            "accuracy": self.accuracy,
            "mesh": None if self.mesh is None else self.mesh.to_dict(),
            "gravity": self.gravity, "wire_angle_deg": self.angle_deg,
            "full_model": bool(self.full_model), "penalty_n_per_mm3": float(self.penalty),
            "density_t_per_mm3": float(self.density), "onset_tol_mpa": float(self.onset_tol_mpa),
            "regulariser": float(self.regulariser),
            "rotation_regulariser": float(self.rotation_regulariser),
            "keep_fields": bool(self.keep_fields),
        }
