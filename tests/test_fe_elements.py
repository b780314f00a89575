"""Our quad9 isoparametric mapping and quadrature against scikit-fem's (independent code).

scikit-fem builds the same curved mesh from the element vertices (MeshQuad2 with its edge and
interior nodes moved onto the same polar positions as ours); element areas and second moments
of area from its quadrature must match ours to round-off, and the total area must match the
exact annulus sector to the quadratic-arc geometry error.
"""

from __future__ import annotations

import numpy as np
import pytest

from exofric.fe import polar_mesh, reference_data

skfem = pytest.importorskip("skfem")


def _skfem_mesh(mesh):
    corners = mesh.elements[:, [0, 2, 8, 6]]  # counter-clockwise vertices of each quad9
    used, t = np.unique(corners, return_inverse=True)
    m1 = skfem.MeshQuad1(mesh.nodes[used].T, t.reshape(corners.shape).T)
    m2 = skfem.MeshQuad2.from_mesh(m1)
    # move every straight midpoint onto the polar position our mesh uses: mid-radius, mid-angle
    doflocs = m2.doflocs.copy()
    nv = m1.p.shape[1]
    r = np.hypot(*m1.p)
    th = np.arctan2(m1.p[1], m1.p[0])
    facets = m1.facets  # (2, nedges)
    rm = 0.5 * (r[facets[0]] + r[facets[1]])
    tm = 0.5 * (th[facets[0]] + th[facets[1]])
    ne = facets.shape[1]
    doflocs[:, nv:nv + ne] = np.stack([rm * np.cos(tm), rm * np.sin(tm)])
    rc = r[m1.t].mean(axis=0)
    tc = th[m1.t].mean(axis=0)
    doflocs[:, nv + ne:] = np.stack([rc * np.cos(tc), rc * np.sin(tc)])
    return skfem.MeshQuad2(doflocs, m1.t)


@pytest.mark.parametrize("nr,nc", [(1, 2), (2, 6), (3, 5)])
def test_element_areas_and_moments_match_scikit_fem(nr, nc):
    A, B = 2.485, 4.15
    mesh = polar_mesh(A, B, nr, nc)  # quarter annulus, quad9
    ref = reference_data(mesh.nodes, mesh.elements, 2, 3)  # the solver's 3x3 rule
    ours_area = ref.w.sum(axis=1)
    # r^2 det J has degree 7 per direction: 5-point Gauss (exact to 9) here, intorder 9 below
    ref5 = reference_data(mesh.nodes, mesh.elements, 2, 5)
    X = np.einsum("qa,eai->eqi", ref5.N, mesh.nodes[mesh.elements])
    ours_r2 = np.einsum("eq,eq->e", ref5.w, (X**2).sum(axis=-1))

    sk = _skfem_mesh(mesh)
    basis = skfem.CellBasis(sk, skfem.ElementQuad2(), intorder=9)
    sk_area = basis.dx.sum(axis=1)
    x = basis.global_coordinates()
    sk_r2 = (basis.dx * (x[0] ** 2 + x[1] ** 2)).sum(axis=1)
    # same geometry, exact quadratures of polynomial integrands: round-off agreement
    np.testing.assert_allclose(ours_area, sk_area, rtol=1e-12)
    np.testing.assert_allclose(ours_r2, sk_r2, rtol=1e-12)


def test_arc_geometry_error_is_fourth_order():
    # quadratic edges through points on a circle: area error ~ h^4 (h = angular element size);
    # doubling the circumferential count must divide the error by ~16
    A, B = 2.485, 4.15
    exact = np.pi / 4 * (B**2 - A**2)
    errs = []
    for nc in (2, 4, 8):
        m = polar_mesh(A, B, 1, nc)
        errs.append(abs(reference_data(m.nodes, m.elements, 2, 3).w.sum() / exact - 1))
    ratios = np.array(errs[:-1]) / np.array(errs[1:])
    assert np.all((ratios > 14) & (ratios < 18)), (errs, ratios)
