"""Issue 18: gravity as an option, a regulariser without bias, the bracketed contact onset,
one mesh default, and error estimates that bound the discretisation error.

References are independent of the squeeze solver: the onset against the free inflation's 1D
boundary-value problem (``compressible_inflation``, scipy ``solve_bvp``), equilibrium by the
balance of vertical forces, the weight by hand, and the error estimates against much finer
meshes (the FElupe comparison is ``tests/test_squeeze_reference.py``). Units: mm, N, MPa.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from exofric import defaults
from exofric.errors import InputError
from exofric.fe import MeshSpec
from exofric.friction import paper_structures
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import compressible_inflation, inflate, squeeze

MAT = MooneyRivlin.from_shore(62.5)
P12 = np.round(np.arange(0.05, 0.601, 0.05), 2)
STRUCTURES = {s.name: s for s in paper_structures()}


def _free_onset_mpa(s) -> float:
    """Without weight or friction the squeeze begins when the free tube spans wall to wire.

    The tube touches the wall at one point with no force, so it inflates freely (the 1D
    plane-strain solution); it touches the wire when its outer diameter reaches D - d2.
    """
    def f(p: float) -> float:
        od = compressible_inflation(s.tube_od_mm, s.tube_id_mm, MAT, [p]).outer_diameter_mm
        return float(od[0]) - (s.hole_mm - s.wire_mm)

    return float(brentq(f, 1e-6, 0.6, xtol=1e-7))


@pytest.mark.parametrize("name", ["test 1", "test 2", "test 3", "test 5", "test 7"])
def test_onset_is_where_the_free_tube_spans_wall_to_wire(name):
    s = STRUCTURES[name]
    r = squeeze(s, MAT, P12, accuracy="draft", keep_fields=False)
    # The issue asks for the onset to 1e-3 MPa; it is bracketed to 2e-4 MPa and the FE free
    # inflation is within 3e-5 of the 1D solution in diameter (~1e-4 MPa here). Measured:
    # within 1e-5 MPa on all five structures.
    assert r.contact_onset_pressure_mpa == pytest.approx(_free_onset_mpa(s), abs=1e-3)
    onset = r.contact_onset_pressure_mpa
    assert np.all(r.squeeze_force_n[r.pressure_mpa < onset] == 0.0)
    assert np.all(r.squeeze_force_n[r.pressure_mpa > onset + 1e-3] > 0.0)


def test_weight_delays_the_onset_and_a_touching_tube_starts_at_zero():
    s = STRUCTURES["test 5"]
    none = squeeze(s, MAT, [0.1, 0.2], accuracy="draft", keep_fields=False)
    wall = squeeze(s, MAT, [0.1, 0.2], accuracy="draft", gravity="toward-wall",
                   keep_fields=False)
    # the weight squashes the tube on the wall: it reaches the wire later (measured +3e-4 MPa)
    assert wall.contact_onset_pressure_mpa > none.contact_onset_pressure_mpa
    # test 4 has zero clearance (D = d1 + d2): the squeeze begins at P = 0
    t4 = squeeze(STRUCTURES["test 4"], MAT, [0.05], accuracy="draft", keep_fields=False)
    assert t4.contact_onset_pressure_mpa == 0.0


def test_reported_n_does_not_depend_on_the_regulariser():
    # gravity "none": the floating-mode spring (x 0.01, x 1, x 100 of its default stiffness)
    # carries no force at the reported states, so N agrees to 1e-6 N/mm (the bound);
    # the remaining difference is Newton's tolerance (~1e-10 N/mm).
    runs = [squeeze(BASE, MAT, P12, mesh=MeshSpec(2, 24), regulariser=k, keep_fields=False)
            for k in (0.01, 1.0, 100.0)]
    for r in runs[1:]:
        np.testing.assert_allclose(r.squeeze_force_n_per_mm, runs[0].squeeze_force_n_per_mm,
                                   rtol=0, atol=1e-6)


@pytest.mark.parametrize("gravity", ["none", "toward-wall", "toward-wire"])
def test_vertical_equilibrium_for_each_orientation(gravity):
    r = squeeze(BASE, MAT, np.concatenate([[0.0], P12]), mesh=MeshSpec(2, 24), gravity=gravity,
                keep_fields=False)
    # weight by hand: rho g pi (R^2 - r^2) = 1.1e-9 t/mm^3 x 9810 mm/s^2 x ring area; quad9
    # arcs approximate the circles to ~3e-6 in area on this mesh, hence 1e-4
    w = 1.1e-9 * 9810 * np.pi * (4.15**2 - 2.485**2)
    sign = {"none": 0.0, "toward-wall": 1.0, "toward-wire": -1.0}[gravity]
    assert r.weight_n_per_mm == pytest.approx(abs(sign) * w, rel=1e-4)
    # the pressure has no net force: wall (up) - wire (down) = weight (down, toward the wall)
    # or -weight (up, toward the wire); Newton's tolerance makes it ~1e-10 N/mm
    resid = r.wall_force_n_per_mm - r.squeeze_force_n_per_mm - sign * w
    assert np.max(np.abs(resid)) < 1e-6
    if gravity == "toward-wire":  # hanging on the wire at P = 0: it carries the weight
        assert r.squeeze_force_n_per_mm[0] == pytest.approx(w, rel=1e-4)
    else:
        assert r.squeeze_force_n_per_mm[0] == 0.0


def test_gravity_changes_low_forces_by_about_the_weight():
    # Near onset the weight is a large share of N (the test-5 case): with the tube
    # resting on the wall N is smaller than without gravity, by less than the weight itself
    # (part of the weight goes into squashing the tube on the wall, not into N).
    s = STRUCTURES["test 5"]
    kw = {"mesh": MeshSpec(2, 24), "keep_fields": False}
    none = squeeze(s, MAT, [0.15, 0.6], **kw).squeeze_force_n_per_mm
    wall = squeeze(s, MAT, [0.15, 0.6], gravity="toward-wall", **kw)
    diff = none - wall.squeeze_force_n_per_mm
    assert np.all(diff > 0) and np.all(diff < wall.weight_n_per_mm)


def test_one_mesh_default_and_option_errors():
    # MeshSpec(4, 48) grades toward the wire like the CLI and the accuracy levels
    assert MeshSpec(4, 48).grading == defaults.SQUEEZE_MESH["grading"]
    assert MeshSpec().grading == defaults.SQUEEZE_ACCURACY["standard"]["grading"]
    with pytest.raises(InputError, match="accuracy or mesh"):
        squeeze(BASE, MAT, [0.3], accuracy="fine", mesh=MeshSpec(2, 24))
    with pytest.raises(InputError, match="accuracy must be one of"):
        squeeze(BASE, MAT, [0.3], accuracy="best")
    with pytest.raises(InputError, match="gravity must be one of"):
        squeeze(BASE, MAT, [0.3], gravity="down")
    with pytest.raises(InputError, match="cannot be coarsened"):
        MeshSpec(3, 25).coarsened(2, 2)


def test_nested_coarse_mesh_keeps_every_other_boundary():
    from exofric.fe import graded_angles

    fine = MeshSpec(3, 32, grading=6.0)
    coarse = fine.coarsened(1, 2)
    a = graded_angles(-np.pi / 2, np.pi / 2, 32, fine.grading, np.pi / 2)
    b = graded_angles(-np.pi / 2, np.pi / 2, 16, coarse.grading, np.pi / 2)
    np.testing.assert_allclose(a[::2], b, atol=1e-14)  # nested up to round-off


@pytest.mark.slow
def test_draft_estimate_bounds_the_error_against_a_fine_mesh():
    # draft (2 x 24, estimate from 2 x 12) against 4 x 96 (within ~0.1% of a 6 x 192 mesh from
    # 0.1 MPa on this structure): wherever N >= 1% of N(0.6), the estimate bounds the actual
    # error once the reference's own uncertainty (0.1%) is added.
    s = STRUCTURES["test 1"]
    r = squeeze(s, MAT, P12, accuracy="draft", keep_fields=False)
    ref = squeeze(s, MAT, P12, mesh=MeshSpec(4, 96), keep_fields=False).squeeze_force_n_per_mm
    m = ref >= 0.01 * ref[-1]
    err = 100 * np.abs(r.squeeze_force_n_per_mm[m] / ref[m] - 1)
    assert np.all(err <= r.estimate.pct[m] + 0.1), (err, r.estimate.pct[m])
    assert r.estimate.mesh is not None and r.estimate.mesh.n_circ == 12


def test_inflation_error_estimate_bounds_the_error_against_the_1d_solution():
    p = [0.1, 0.3, 0.6]
    ref = compressible_inflation(8.3, 4.97, MAT, p).outer_diameter_mm
    for level in ("draft", "standard", "fine"):
        r = inflate(8.3, 4.97, MAT, p, accuracy=level, keep_fields=False)
        err = np.abs(r.outer_diameter_mm - ref)
        # the 1D solution is solved to 1e-8 mm; measured err/estimate <= 0.7 on all levels
        assert np.all(err <= r.outer_diameter_error_estimate_mm + 1e-7), (level, err)
    d = r.to_dict()
    assert d["accuracy"] == "fine" and len(d["outer_diameter_error_estimate_mm"]) == 3


def test_cli_json_carries_the_estimate_and_the_mesh(cli):
    r = cli(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
             "--shore", "62.5", "--pressures", "0.2,0.6", "--accuracy", "draft", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["accuracy"] == "draft" and d["gravity"] == "none"
    assert len(d["n_error_estimate_pct"]) == 2 and d["mesh"]["n_circ"] == 24
    assert d["estimate_mesh"]["n_circ"] == 12
    bad = cli(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire",
               "1.6", "--shore", "62.5", "--gravity", "sideways"])
    assert bad.code == 2 and "--gravity" in bad.err and bad.err.count("\n") == 1
