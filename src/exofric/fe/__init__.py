"""exofric's finite-element solver: plane-strain hyperelasticity with rigid contact.

Modules: ``mesh`` (graded polar quad9/quad4 meshes), ``elements`` (shape functions,
quadrature), ``hyperelastic`` (vectorised mixed u/p Mooney-Rivlin), ``loads``
(follower pressure as a cavity-area potential), ``solver`` (sparse assembly,
Newton with line search, load stepping with cutback).
"""
