"""exofric's finite-element solver: plane-strain hyperelasticity with rigid contact.

Discretisation and solver only; the problems users ask for (inflate, squeeze) and their results
are in :mod:`exofric.simulate`.

* :class:`MeshSpec`, :func:`polar_mesh` -- graded polar quad9/quad4 meshes of the tube section.
* :class:`InflationProblem`, :class:`SqueezeProblem` -- the two boundary-value problems (mixed
  u/p Mooney-Rivlin, follower pressure as a cavity-area potential, rigid circles as penalty
  contact, optionally with Coulomb friction: :func:`evaluate_friction`, per interface
  ``mu_wall`` / ``mu_wire``).
* :class:`PlaneStrainMaterial` -- a :class:`~exofric.material.MooneyRivlin` or any
  :class:`~exofric.material.HyperelasticModel` (neo-Hookean, Mooney-Rivlin, Yeoh, Ogden) as the
  body's kernel.
* :class:`NewtonSettings`, :func:`solve_path` -- Newton with line search along a load path,
  with cutback.

Units: mm, N, MPa; forces per unit depth in N/mm.

Examples
--------
>>> from exofric.fe import MeshSpec
>>> MeshSpec(2, 24, grading=6.0).n_circ
24
"""

from exofric.fe._assembly import Assembler
from exofric.fe._contact import (
    ContactState,
    FrictionState,
    RigidCircle,
    active_set_direction,
    evaluate_contact,
    evaluate_friction,
    nodal_weights,
    polar_angle,
)
from exofric.fe._elements import (
    ReferenceData,
    lagrange_1d,
    pressure_basis,
    reference_data,
    shape_2d,
)
from exofric.fe._hyperelastic import (
    HyperelasticBody,
    PlaneStrainMaterial,
    isochoric_derivatives,
    mooney_rivlin_plane_strain,
    ogden_plane_strain,
    stress_from_derivatives,
    von_mises,
    yeoh_plane_strain,
)
from exofric.fe._inflation import ENDS, InflationProblem, MeshSpec, PressurizedTube, check_ends
from exofric.fe._loads import area_hessian, enclosed_area
from exofric.fe._mesh import TubeMesh, graded_angles, polar_mesh, two_sided_angles
from exofric.fe._ring import (
    RING_MESH,
    RING_PENALTY,
    RING_SECTIONS,
    PlaneStressBody,
    RingProblem,
)
from exofric.fe._solver import NewtonSettings, PathPoint, Problem, solve_path
from exofric.fe._squeeze import (
    GRAVITY_MM_S2,
    GRAVITY_OPTIONS,
    MU_MAX,
    MU_WARN,
    SqueezeProblem,
    half_boundaries,
    patch_edge,
    wall_arc,
    wire_halfwidth,
)
from exofric.fe._stats import SolverStats, StatsCollector, collect_stats

__all__ = [
    "ENDS",
    "GRAVITY_MM_S2",
    "GRAVITY_OPTIONS",
    "MU_MAX",
    "MU_WARN",
    "Assembler",
    "active_set_direction",
    "ContactState",
    "HyperelasticBody",
    "InflationProblem",
    "MeshSpec",
    "NewtonSettings",
    "PathPoint",
    "PlaneStrainMaterial",
    "PressurizedTube",
    "Problem",
    "PlaneStressBody",
    "RING_MESH",
    "RING_PENALTY",
    "RING_SECTIONS",
    "RingProblem",
    "ReferenceData",
    "RigidCircle",
    "SolverStats",
    "SqueezeProblem",
    "StatsCollector",
    "TubeMesh",
    "area_hessian",
    "check_ends",
    "collect_stats",
    "enclosed_area",
    "evaluate_contact",
    "evaluate_friction",
    "FrictionState",
    "polar_angle",
    "graded_angles",
    "lagrange_1d",
    "isochoric_derivatives",
    "stress_from_derivatives",
    "mooney_rivlin_plane_strain",
    "nodal_weights",
    "ogden_plane_strain",
    "polar_mesh",
    "pressure_basis",
    "reference_data",
    "shape_2d",
    "solve_path",
    "von_mises",
    "half_boundaries",
    "patch_edge",
    "two_sided_angles",
    "wall_arc",
    "wire_halfwidth",
    "yeoh_plane_strain",
]

# every public function checks its arguments' kinds (InputError naming the parameter)
from exofric._lazy import export_checked  # noqa: E402

export_checked(__name__)
