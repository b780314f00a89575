"""Cross-checks of exofric's FE results against independent FElupe models.

FElupe (GPL-3) is a test/benchmark extra only; the models live in
``benchmarks/felupe_models.py``. These tests skip only if FElupe itself cannot be
imported (``make test`` installs it). Units: mm, N, MPa.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("felupe", reason="FElupe (GPL-3 test extra) is not installed")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import felupe as fem  # noqa: E402
from felupe_models import (  # noqa: E402
    EXOFRIC_TO_VTK_QUAD9,
    SqueezeSetup,
    felupe_inflate,
    felupe_squeeze_model,
    mooney_rivlin_iso_stress,
)

from exofric.fe import polar_mesh  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import (
    compressible_inflation,  # noqa: E402
    inflate,  # noqa: E402
)

MAT = MooneyRivlin.from_shore(62.5)
OD, ID = 8.3, 4.97

# FElupe reference for the squeeze: half tube 4 x 40 quad9 graded 10:1 toward the wire.
# Mesh study (benchmarks/README.md), N(0.6 MPa) in N/mm: 2.07396 / 2.07292 / 2.07282 /
# 2.07328 on 2x20 / 4x40 / 6x60 / 8x80 (N(0.3): 0.41115 / 0.41258 / 0.41220 / 0.41212),
# so 4 x 40 is within 0.03% (0.6) and 0.11% (0.3) of the finest. Penalty 3e3 / 1e4 / 3e4
# gives 2.072883 / 2.072917 / 2.072927 (error ~ 1/penalty: 2e-5 at 3e3, used here for speed).
REFERENCE = SqueezeSetup(n_radial=4, n_circ=40, grading=10.0, penalty=3e3)


def _mr_energy(F: np.ndarray, c10: float, c01: float) -> np.ndarray:
    Fm = np.moveaxis(F, (0, 1), (-2, -1))
    J = np.linalg.det(Fm)
    C = np.einsum("ki...,kj...->ij...", F, F)
    i1 = np.einsum("ii...->...", C)
    i2 = 0.5 * (i1**2 - np.einsum("ij...,ji...->...", C, C))
    return c10 * (J ** (-2 / 3) * i1 - 3) + c01 * (J ** (-4 / 3) * i2 - 3)


def test_mooney_rivlin_stress_and_tangent_are_derivatives() -> None:
    """P = dW/dF and A = dP/dF of the hand-written law, by central differences."""
    rng = np.random.default_rng(1)
    F = np.eye(3)[..., None, None] + 0.2 * rng.standard_normal((3, 3, 2, 3))
    c10, c01, h = 0.6, 0.1, 1e-6
    P = mooney_rivlin_iso_stress(F, c10, c01)
    A = mooney_rivlin_iso_stress(F, c10, c01, tangent=True)
    Pn, An = np.zeros_like(P), np.zeros_like(A)
    for i in range(3):
        for j in range(3):
            dF = np.zeros_like(F)
            dF[i, j] = h
            Pn[i, j] = (_mr_energy(F + dF, c10, c01) - _mr_energy(F - dF, c10, c01)) / (2 * h)
            An[:, :, i, j] = (
                mooney_rivlin_iso_stress(F + dF, c10, c01)
                - mooney_rivlin_iso_stress(F - dF, c10, c01)
            ) / (2 * h)
    # central differences, h = 1e-6: truncation ~h^2 |W'''| ~ 1e-12, round-off
    # ~eps |W| / h ~ 1e-10; 1e-7 absolute (entries are O(1) MPa) leaves a wide margin
    # yet catches any wrong term (those are O(0.1)).
    np.testing.assert_allclose(P, Pn, atol=1e-7)
    np.testing.assert_allclose(A, An, atol=1e-7)


def test_exofric_quad9_order_maps_to_felupe() -> None:
    """exofric's a = 3 j + i order, permuted, gives valid FElupe quad9 cells."""
    m = polar_mesh(0.5 * ID, 0.5 * OD, 2, 6)
    mesh = fem.Mesh(m.nodes, m.elements[:, EXOFRIC_TO_VTK_QUAD9], "quad9")
    region = fem.RegionBiQuadraticQuad(mesh)
    assert np.all(region.dV > 0)
    exact = 0.25 * np.pi * ((0.5 * OD) ** 2 - (0.5 * ID) ** 2)
    # quadratic arcs of 15 deg miss the circle by O(theta^4) ~ 1e-5 of the area; a wrong
    # node order gives negative or O(1)-wrong volumes
    assert region.dV.sum() == pytest.approx(exact, rel=5e-5)


def test_felupe_inflation_matches_1d_reference() -> None:
    """The FElupe model itself reproduces the compressible 1D solution (0.01%)."""
    p = np.array([0.1, 0.3, 0.6])
    m = polar_mesh(0.5 * ID, 0.5 * OD, 2, 6)
    fr = felupe_inflate(m.nodes, m.elements, MAT, p)
    ref = compressible_inflation(OD, ID, MAT, p).outer_diameter_mm
    # 2 x 6 quad9 mesh: discretisation error ~2e-5 (same as exofric's on this mesh);
    # 1e-4 is the accuracy the inflation benchmark requires of the mesh
    np.testing.assert_allclose(fr.outer_diameter_mm, ref, rtol=1e-4)


def test_inflation_matches_felupe_on_the_same_mesh() -> None:
    """exofric's free inflation = FElupe's on exofric's own mesh, 0.1..0.6 MPa."""
    p = np.linspace(0.1, 0.6, 6)
    res = inflate(OD, ID, MAT, p, keep_fields=False)
    fr = felupe_inflate(res.nodes, res.elements, MAT, p)
    # Same mesh, same Q9 displacement; the pressure spaces differ (exofric: condensed
    # {1, xi, eta}; FElupe: discontinuous bilinear p and J). Every element of this polar
    # mesh is mirror-symmetric about its mid-angle and the solution is axisymmetric, so
    # the odd-in-eta pressure modes vanish and both spaces reduce to {1, xi}: the two
    # discrete problems coincide and only the Newton tolerances separate them
    # (measured 5e-10). 1e-6 is far tighter than the 0.05% first asked for, and still
    # leaves three decades for solver tolerances.
    np.testing.assert_allclose(res.outer_diameter_mm, fr.outer_diameter_mm, rtol=1e-6)
    np.testing.assert_allclose(res.inner_diameter_mm, fr.inner_diameter_mm, rtol=1e-6)


def test_felupe_squeeze_equilibrium_and_onset() -> None:
    """FElupe squeeze on a coarse mesh: contact forces balance the self-weight."""
    r = felupe_squeeze_model([0.05, 0.3], SqueezeSetup(n_radial=2, n_circ=20))
    # wall force - wire force = weight (N/mm): Newton stops at a relative residual of
    # 1.5e-8 of the reaction forces (O(1) N/mm), so 1e-6 N/mm is a strict bound
    np.testing.assert_allclose(r.equilibrium_n_per_mm, 0.0, atol=1e-6)
    # weight of the discretised tube: quadratic arcs miss the annulus area by ~1e-5
    assert r.weight_n_per_mm == pytest.approx(1.1e-9 * 9810 * np.pi * (4.15**2 - 2.485**2),
                                              rel=1e-4)
    # free OD at 0.05 MPa is 8.392 mm < 8.4 mm: the 0.1 mm clearance is still open
    assert r.squeeze_force_n_per_mm[0] == 0.0
    assert r.squeeze_force_n_per_mm[1] > 0.1
    assert np.all(r.max_penetration_mm < 1e-4)


@pytest.fixture(scope="module")
def felupe_reference() -> np.ndarray:
    """FElupe N (N/mm, full model) at 0.3 and 0.6 MPa on the reference mesh."""
    return felupe_squeeze_model([0.3, 0.6], REFERENCE).squeeze_force_n_per_mm


@pytest.mark.slow
def test_felupe_squeeze_reference_is_mesh_converged(felupe_reference: np.ndarray) -> None:
    """Halving the FElupe element size changes N(0.6 MPa) by < 0.1%."""
    coarse = felupe_squeeze_model(
        [0.3, 0.6], SqueezeSetup(n_radial=2, n_circ=20, penalty=3e3)
    ).squeeze_force_n_per_mm
    # measured: 0.35% at 0.3 MPa and 0.05% at 0.6 MPa between 2 x 20 and 4 x 40; with
    # the observed convergence the 4 x 40 reference is then well inside the 0.5% check
    change = np.abs(coarse / felupe_reference - 1.0)
    assert change[0] < 5e-3 and change[1] < 1e-3, change


@pytest.mark.slow
def test_squeeze_matches_felupe(felupe_reference: np.ndarray) -> None:
    """exofric's squeeze force at 0.3 and 0.6 MPa = FElupe's within 0.5%."""
    from exofric.geometry import BASE
    from exofric.simulate import squeeze

    res = squeeze(BASE, MAT, np.linspace(0.05, 0.6, 12))
    got = np.interp([0.3, 0.6], res.pressure_mpa, res.squeeze_force_n_per_mm)
    # 0.5% (the acceptance): both are converged to ~0.05% in mesh and ~1e-5 in
    # penalty, but they differ in contact discretisation (exofric: tributary-weighted
    # node penalty; FElupe: uniform node penalty) and in the pressure space.
    np.testing.assert_allclose(got, felupe_reference, rtol=5e-3)
