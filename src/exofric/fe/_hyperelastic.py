"""Vectorised plane-strain Mooney-Rivlin (Eq 2) with a mixed u/p volumetric treatment.

Strain energy (ANSYS convention, stretch_z = 1), with ``s = |F|^2`` of the
in-plane deformation gradient F (2x2) and ``J = det F``::

    W_iso = C10 (J^-2/3 (s + 1) - 3) + C01 (J^-4/3 s + J^2/3 - 3)
    U     = (J - 1)^2 / d = K/2 (J - 1)^2,   K = 2/d

(``I1 = s + 1`` and ``I2 = s + J^2`` in plane strain). Because ``dJ/dF = cof F``
is linear in F, stress and tangent follow in closed form from the scalar
derivatives of ``W_iso(s, J)``::

    P = 2 W_s F + W_J cof F
    A = 2 W_sJ (F x cof + cof x F) + W_JJ cof x cof + 2 W_s I + W_J D(cof)

Mixed formulation (``'mixed'``): a discontinuous pressure ``p = Np . p_e``
(Np = [1, xi, eta] for quad9, i.e. Bathe's 9/3 element; [1] for quad4 = Q1/P0)
is condensed element by element. Stationarity of
``int p (J - 1) - p^2 / (2K)`` gives ``p_e = K M^-1 g``, ``g = int Np (J - 1)``,
so the volumetric energy is ``(K/2) g^T M^-1 g`` with the exact tangent
``K G^T M^-1 G + int p D(cof)``, ``G = int Np (cof : grad N)``. ``'displacement'``
evaluates U at every Gauss point instead (this locks for nu -> 0.5; kept to show it).

Other invariant models (:func:`exofric.material.material_model`) use the same scheme with
``Ib1 = J^-2/3 (s + 1)``: neo-Hookean ``C10 (Ib1 - 3)`` and Yeoh ``sum_i Ci0 (Ib1 - 3)^i``
(:func:`yeoh_plane_strain`; neo-Hookean is Yeoh with C20 = C30 = 0), whose ``W_iso`` is
not linear in s, so the tangent gains ``4 W_ss F x F``. :class:`PlaneStrainMaterial` adapts
a :class:`~exofric.material.MooneyRivlin` or a
:class:`~exofric.material.HyperelasticModel` to the body (Mooney-Rivlin keeps its own
kernel, :func:`mooney_rivlin_plane_strain`). Ogden, a function of the principal stretches,
is one of (s, J) too in plane strain (:func:`ogden_plane_strain`): with ``l1,2 = sqrt(J)
exp(+-eta)``, ``s = 2 J cosh 2 eta``, so each term is smooth in (s, J) at equal stretches.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from exofric.errors import InputError
from exofric.fe._elements import ReferenceData, reference_data
from exofric.fe._mesh import TubeMesh
from exofric.material import HyperelasticModel, MooneyRivlin

__all__ = ["HyperelasticBody", "PlaneStrainMaterial", "isochoric_derivatives",
           "mooney_rivlin_plane_strain", "stress_from_derivatives",
           "ogden_plane_strain", "yeoh_plane_strain", "DCOF"]

#: d(cof F)/dF for 2x2 F: cof = [[F11, -F10], [-F01, F00]].
DCOF = np.zeros((2, 2, 2, 2))
DCOF[0, 0, 1, 1] = DCOF[1, 1, 0, 0] = 1.0
DCOF[0, 1, 1, 0] = DCOF[1, 0, 0, 1] = -1.0


def _cof(F: np.ndarray) -> np.ndarray:
    c = np.empty_like(F)
    c[..., 0, 0], c[..., 1, 1] = F[..., 1, 1], F[..., 0, 0]
    c[..., 0, 1], c[..., 1, 0] = -F[..., 1, 0], -F[..., 0, 1]
    return c


#: cof F as a signed permutation of the flattened F = [F00, F01, F10, F11].
_COF_PERM = np.array([3, 2, 1, 0])
_COF_SIGN = np.array([1.0, -1.0, -1.0, 1.0])
_DCOF4 = DCOF.reshape(4, 4)
_I4F = np.eye(4)


def _piola(shape: tuple[int, ...], f: np.ndarray, c: np.ndarray, W: np.ndarray,
           Ws: np.ndarray, WJ: np.ndarray,
           second: tuple[np.ndarray | None, np.ndarray, np.ndarray] | None
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """W, P and A of a plane-strain energy ``W(s, J)`` from its derivatives (one owner).

    ``P = 2 W_s F + W_J cof F`` and ``A = 4 W_ss F x F + 2 W_sJ (F x cof + cof x F) +
    W_JJ cof x cof + 2 W_s I + W_J Dcof``; ``second = (W_ss or None when it is zero, W_sJ,
    W_JJ)``, None for the stress only. ``f``, ``c``: F and cof F flattened (n, 4).
    """
    P = 2.0 * Ws[:, None] * f + WJ[:, None] * c
    if second is None:
        return W.reshape(shape), P.reshape(*shape, 2, 2), None
    Wss, WsJ, WJJ = second
    fc = f[:, :, None] * c[:, None, :]
    A = (2.0 * WsJ[:, None, None] * (fc + fc.transpose(0, 2, 1))
         + WJJ[:, None, None] * (c[:, :, None] * c[:, None, :])
         + 2.0 * Ws[:, None, None] * _I4F
         + WJ[:, None, None] * _DCOF4)
    if Wss is not None:
        A = 4.0 * Wss[:, None, None] * (f[:, :, None] * f[:, None, :]) + A
    return W.reshape(shape), P.reshape(*shape, 2, 2), A.reshape(*shape, 2, 2, 2, 2)


def mooney_rivlin_plane_strain(
    F: np.ndarray, c10: float, c01: float, tangent: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Isochoric Mooney-Rivlin energy density, first Piola stress and tangent.

    Parameters
    ----------
    F : ndarray (..., 2, 2)
        In-plane deformation gradients (det > 0).
    c10, c01 : float
        Material constants (MPa).
    tangent : bool
        Also return ``A = dP/dF`` (..., 2, 2, 2, 2).

    Returns
    -------
    W, P, A
        Energy density (MPa = N mm/mm^3), stress (MPa), tangent (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> W, P, A = mooney_rivlin_plane_strain(np.eye(2)[None], 0.6, 0.03)
    >>> float(W[0]), float(abs(P).max()) < 1e-14
    (0.0, True)
    """
    shape = F.shape[:-2]
    f = F.reshape(-1, 4)
    c = f[:, _COF_PERM] * _COF_SIGN  # cof F, flattened
    J = f[:, 0] * f[:, 3] - f[:, 1] * f[:, 2]
    s = np.einsum("pi,pi->p", f, f)
    jm13 = 1.0 / np.cbrt(J)  # J^-1/3
    j23 = jm13 * jm13  # J^-2/3
    j43 = j23 * j23  # J^-4/3
    W = c10 * (j23 * (s + 1.0) - 3.0) + c01 * (j43 * s + J * jm13 - 3.0)
    Ws = c10 * j23 + c01 * j43
    iJ = 1.0 / J
    WJ = (-2.0 / 3.0 * c10 * j23 * iJ * (s + 1.0) - 4.0 / 3.0 * c01 * j43 * iJ * s
          + 2.0 / 3.0 * c01 * jm13)
    if not tangent:
        return _piola(shape, f, c, W, Ws, WJ, None)
    WsJ = (-2.0 / 3.0 * c10 * j23 - 4.0 / 3.0 * c01 * j43) * iJ
    WJJ = (10.0 / 9.0 * c10 * j23 * (s + 1.0) + 28.0 / 9.0 * c01 * j43 * s) * iJ * iJ \
        - 2.0 / 9.0 * c01 * j43
    return _piola(shape, f, c, W, Ws, WJ, (None, WsJ, WJJ))


def yeoh_plane_strain(
    F: np.ndarray, c10: float, c20: float, c30: float, tangent: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Isochoric Yeoh energy density, first Piola stress and tangent (plane strain).

    ``W_iso = C10 x + C20 x^2 + C30 x^3`` with ``x = Ib1 - 3 = J^-2/3 (s + 1) - 3``;
    neo-Hookean is ``C20 = C30 = 0``. With ``W' = dW/dx``, ``W'' = d2W/dx2`` and
    ``x_s = J^-2/3``, ``x_J = -2/3 J^-5/3 (s + 1)``::

        W_s = W' x_s,  W_J = W' x_J,  W_ss = W'' x_s^2,
        W_sJ = W'' x_s x_J - 2/3 W' J^-5/3,  W_JJ = W'' x_J^2 + 10/9 W' J^-8/3 (s + 1)
        P = 2 W_s F + W_J cof F
        A = 4 W_ss F x F + 2 W_sJ (F x cof + cof x F) + W_JJ cof x cof + 2 W_s I + W_J D(cof)

    Parameters
    ----------
    F : ndarray (..., 2, 2)
        In-plane deformation gradients (det > 0).
    c10, c20, c30 : float
        Yeoh constants (MPa).
    tangent : bool
        Also return ``A = dP/dF`` (..., 2, 2, 2, 2).

    Returns
    -------
    W, P, A
        Energy density (MPa = N mm/mm^3), stress (MPa), tangent (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> W, P, A = yeoh_plane_strain(np.eye(2)[None], 0.19, -0.0019, 4.1e-5)
    >>> float(W[0]), float(abs(P).max()) < 1e-14
    (0.0, True)
    """
    shape = F.shape[:-2]
    f = F.reshape(-1, 4)
    c = f[:, _COF_PERM] * _COF_SIGN  # cof F, flattened
    J = f[:, 0] * f[:, 3] - f[:, 1] * f[:, 2]
    s = np.einsum("pi,pi->p", f, f)
    jm13 = 1.0 / np.cbrt(J)  # J^-1/3
    j23 = jm13 * jm13  # J^-2/3
    iJ = 1.0 / J
    x = j23 * (s + 1.0) - 3.0
    W = ((c30 * x + c20) * x + c10) * x
    W1 = c10 + (2.0 * c20 + 3.0 * c30 * x) * x
    # operation order as in mooney_rivlin_plane_strain: C20 = C30 = 0 is bit-identical to it
    Ws = W1 * j23
    WJ = -2.0 / 3.0 * W1 * j23 * iJ * (s + 1.0)
    if not tangent:
        return _piola(shape, f, c, W, Ws, WJ, None)
    W2 = 2.0 * c20 + 6.0 * c30 * x
    xJ = -2.0 / 3.0 * j23 * iJ * (s + 1.0)
    Wss = W2 * j23 * j23
    WsJ = W2 * j23 * xJ - 2.0 / 3.0 * W1 * j23 * iJ
    WJJ = W2 * xJ * xJ + 10.0 / 9.0 * W1 * j23 * (s + 1.0) * iJ * iJ
    return _piola(shape, f, c, W, Ws, WJ, (Wss, WsJ, WJJ))


def _chebyshev_t(nu: float, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``h(c) = cosh(nu arccosh c)`` and its first two c-derivatives at ``c = 1 + y``, y >= 0.

    Closed form for ``y >= 1e-2``; below, the series ``h = 2F1(-nu, nu; 1/2; -y/2)``
    (analytic at equal stretches, ``h'(1) = nu^2``, ``h''(1) = nu^2 (nu^2 - 1) / 3``), whose
    12 terms are exact to round-off there while the closed form loses ``eps / y``.
    """
    big = y >= 1e-2
    yb = np.where(big, y, 1.0)
    sh = np.sqrt(yb * (yb + 2.0))  # sinh x, x = arccosh c
    x = np.log1p(yb + sh)
    ch_n, sh_n = np.cosh(nu * x), np.sinh(nu * x)
    h_b = ch_n
    h1_b = nu * sh_n / sh
    h2_b = (nu * nu * ch_n * sh - nu * sh_n * (1.0 + yb)) / sh**3
    z = np.where(big, 0.0, -0.5 * y)
    r = 1.0
    h, d1, d2 = np.ones_like(z), np.zeros_like(z), np.zeros_like(z)
    zk = np.ones_like(z)  # z^k
    zk1 = np.zeros_like(z)  # z^(k-1)
    zk2 = np.zeros_like(z)  # z^(k-2)
    for k in range(1, 13):
        r *= ((k - 1) ** 2 - nu * nu) / ((k - 0.5) * k)
        zk2, zk1, zk = zk1, zk, zk * z
        h += r * zk
        d1 += k * r * zk1
        d2 += k * (k - 1) * r * zk2
    return (np.where(big, h_b, h), np.where(big, h1_b, -0.5 * d1),
            np.where(big, h2_b, 0.25 * d2))


def ogden_plane_strain(
    F: np.ndarray, mus: tuple[float, ...], alphas: tuple[float, ...], tangent: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Isochoric Ogden energy density, first Piola stress and tangent (plane strain).

    ``W_iso = sum_k 2 mu_k / a_k^2 (lb1^a_k + lb2^a_k + lb3^a_k - 3)`` (ABAQUS). With the
    in-plane stretches ``l1,2 = sqrt(J) exp(+-eta)`` and ``l3 = 1``, ``c = cosh 2 eta =
    s / (2 J)``, each term is ``2 mu / a^2 (2 J^(a/6) T(c) + J^(-a/3) - 3)`` with
    ``T(c) = cosh(a/2 arccosh c)``, a smooth function of (s, J) also at equal stretches
    (``c = 1``, where :func:`_chebyshev_t` switches to its series). ``c - 1 = ((F00 - F11)^2 +
    (F01 + F10)^2) / (2 J)`` is computed without cancellation. Stress and tangent then follow
    from W_s, W_J, W_ss, W_sJ, W_JJ as in :func:`yeoh_plane_strain`.

    Parameters
    ----------
    F : ndarray (..., 2, 2)
        In-plane deformation gradients (det > 0).
    mus : tuple of float
        Ogden moduli mu_k (MPa).
    alphas : tuple of float
        Ogden exponents a_k (unitless, nonzero).
    tangent : bool
        Also return ``A = dP/dF`` (..., 2, 2, 2, 2).

    Returns
    -------
    W, P, A
        Energy density (MPa = N mm/mm^3), stress (MPa), tangent (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> W, P, A = ogden_plane_strain(np.eye(2)[None], (0.6,), (1.5,))
    >>> float(W[0]), float(abs(P).max()) < 1e-14
    (0.0, True)
    """
    shape = F.shape[:-2]
    f = F.reshape(-1, 4)
    cf = f[:, _COF_PERM] * _COF_SIGN  # cof F, flattened
    J = f[:, 0] * f[:, 3] - f[:, 1] * f[:, 2]
    iJ = 1.0 / J
    lnJ = np.log(J)
    y = 0.5 * ((f[:, 0] - f[:, 3]) ** 2 + (f[:, 1] + f[:, 2]) ** 2) * iJ  # c - 1 >= 0
    c = 1.0 + y
    W = np.zeros_like(J)
    Ws, WJ = np.zeros_like(J), np.zeros_like(J)
    Wss, WsJ, WJJ = np.zeros_like(J), np.zeros_like(J), np.zeros_like(J)
    for mu, a in zip(mus, alphas, strict=True):
        A0 = 2.0 * mu / (a * a)
        e1, e2 = a / 6.0, -a / 3.0
        h, h1, h2 = _chebyshev_t(0.5 * a, y)
        j1 = np.exp((e1 - 1.0) * lnJ)  # J^(e1-1)
        j2 = np.exp((e2 - 1.0) * lnJ)  # J^(e2-1)
        W += A0 * (2.0 * j1 * J * h + j2 * J - 3.0)
        Ws += A0 * j1 * h1
        WJ += A0 * (2.0 * e1 * j1 * h - 2.0 * j1 * c * h1 + e2 * j2)
        if tangent:
            Wss += 0.5 * A0 * j1 * iJ * h2
            WsJ += A0 * j1 * iJ * ((e1 - 1.0) * h1 - c * h2)
            WJJ += A0 * (j1 * iJ * (2.0 * e1 * (e1 - 1.0) * h - 4.0 * (e1 - 1.0) * c * h1
                                    + 2.0 * c * c * h2)
                         + e2 * (e2 - 1.0) * j2 * iJ)
    return _piola(shape, f, cf, W, Ws, WJ, (Wss, WsJ, WJJ) if tangent else None)


def _poly(coefs: tuple[float, ...], exps: tuple[tuple[float, float, float], ...],
          x: np.ndarray, lnx: np.ndarray, second: bool
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """``sum_k c_k s^e0 J^e1 l^e2`` at ``x = (s, J, l)`` (..., 3), its gradient and Hessian.

    All terms at once (``lnx = log x``): ``m_k = c_k exp(lnx . e_k)``, ``dm_k/dx_i = e_i m_k /
    x_i``, ``d2m_k/dx_i dx_j = (e_i e_j - delta_ij e_i) m_k / (x_i x_j)``.
    """
    E = np.asarray(exps, dtype=float)  # (k, 3)
    m = np.exp(lnx @ E.T) * np.asarray(coefs, dtype=float)  # (..., k)
    W = m.sum(axis=-1)
    G = (m @ E) / x
    if not second:
        return W, G, None
    Q = (E[:, :, None] * E[:, None, :] - E[:, :, None] * np.eye(3)).reshape(len(E), 9)
    H = (m @ Q).reshape(*m.shape[:-1], 3, 3) / (x[..., :, None] * x[..., None, :])
    return W, G, H


#: Exponents of (s, J, l) of Ib1 = s J^-2/3 l^-2/3 + J^-2/3 l^4/3 and Ib2 = s J^-4/3 l^2/3 +
#: J^2/3 l^-4/3 (see :func:`isochoric_derivatives`).
_IB1 = ((1.0, -2.0 / 3.0, -2.0 / 3.0), (0.0, -2.0 / 3.0, 4.0 / 3.0))
_IB2 = ((1.0, -4.0 / 3.0, 2.0 / 3.0), (0.0, 2.0 / 3.0, -4.0 / 3.0))


def isochoric_derivatives(
    model: PlaneStrainMaterial, s: np.ndarray, J: np.ndarray, lz: np.ndarray,
    second: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Isochoric energy ``W_iso(s, J, l)`` of a 3D block-diagonal deformation and its derivatives.

    For ``F = blockdiag(F2, l)`` with the in-plane ``F2`` (``s = |F2|^2``, ``J = det F2``) and
    the out-of-plane stretch ``l`` (generalised plane strain, plane stress), ``J3 = J l`` and
    the invariants are monomials in (s, J, l)::

        Ib1 = J3^-2/3 (s + l^2)     = s J^-2/3 l^-2/3 + J^-2/3 l^4/3
        Ib2 = J3^-4/3 (s l^2 + J^2) = s J^-4/3 l^2/3  + J^2/3 l^-4/3

    (``tr C^2 = s^2 - 2 J^2 + l^4``). Mooney-Rivlin is linear in them, neo-Hookean and Yeoh a
    polynomial of ``Ib1 - 3``. Ogden's in-plane isochoric stretches give
    ``lb1^a + lb2^a = 2 J^(a/6) l^(-a/3) T(c)``, ``c = s / (2 J)``, ``T = cosh(a/2 arccosh c)``
    (smooth at c = 1, see :func:`ogden_plane_strain`), and ``lb3^a = J^(-a/3) l^(2a/3)``.
    The volumetric term ``(J l - 1)^2 / d`` is the caller's. At ``l = 1`` this is the
    plane-strain energy of :meth:`PlaneStrainMaterial.stress` (a test checks the two
    derivations against each other).

    Parameters
    ----------
    model : PlaneStrainMaterial
        The material (any model).
    s, J, lz : ndarray
        ``|F2|^2``, ``det F2`` and the out-of-plane stretch l (unitless, J, l > 0), same
        shape (broadcast).
    second : bool
        Also return the second derivatives.

    Returns
    -------
    W : ndarray (...)
        Energy density (MPa).
    G : ndarray (..., 3)
        ``[W_s, W_J, W_l]`` (MPa).
    H : ndarray (..., 3, 3) or None
        Second derivatives in the order (s, J, l) (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.material import material_model
    >>> m = PlaneStrainMaterial(material_model("neo-hookean", [0.2]))
    >>> W, G, H = isochoric_derivatives(m, np.array([2.0]), np.array([1.0]), np.array([1.0]))
    >>> float(W[0]), np.round(G[0], 6).tolist()  # undeformed: W_l = 0
    (0.0, [0.2, -0.4, 0.0])
    """
    x = np.stack(np.broadcast_arrays(np.asarray(s, float), np.asarray(J, float),
                                     np.asarray(lz, float)), axis=-1)
    lnx = np.log(x)
    shape = x.shape[:-1]
    name, co = model.name, model.coeffs
    if name == "mooney-rivlin":
        c10, c01 = co
        W, G, H = _poly((c10, c10, c01, c01), _IB1 + _IB2, x, lnx, second)
        return W - 3.0 * (c10 + c01), G, H
    if not name.startswith("ogden"):  # neo-Hookean and Yeoh: a polynomial of Ib1 - 3
        c10, c20, c30 = co
        I1, g1, h1 = _poly((1.0, 1.0), _IB1, x, lnx, second)
        xi = I1 - 3.0
        W = ((c30 * xi + c20) * xi + c10) * xi
        w1 = c10 + (2.0 * c20 + 3.0 * c30 * xi) * xi
        G = w1[..., None] * g1
        H = None
        if h1 is not None:
            w2 = 2.0 * c20 + 6.0 * c30 * xi
            H = w2[..., None, None] * (g1[..., :, None] * g1[..., None, :]) \
                + w1[..., None, None] * h1
        return W, G, H
    W = np.zeros(shape)
    G = np.zeros((*shape, 3))
    H = np.zeros((*shape, 3, 3)) if second else None
    sv, Jv = x[..., 0], x[..., 1]
    c = 0.5 * sv / Jv
    gc = np.zeros((*shape, 3))
    gc[..., 0], gc[..., 1] = 0.5 / Jv, -c / Jv
    hc = np.zeros((*shape, 3, 3))
    hc[..., 0, 1] = hc[..., 1, 0] = -0.5 / Jv**2
    hc[..., 1, 1] = 2.0 * c / Jv**2
    for mu, a in zip(co[0::2], co[1::2], strict=True):
        A0 = 2.0 * mu / (a * a)
        h0, h1, h2 = _chebyshev_t(0.5 * a, np.maximum(c - 1.0, 0.0))
        # 2 A0 J^(a/6) l^(-a/3) T(c) + A0 J^(-a/3) l^(2a/3) - 3 A0
        m, gm, hm = _poly((2.0 * A0,), ((0.0, a / 6.0, -a / 3.0),), x, lnx, second)
        m3, g3, h3 = _poly((A0,), ((0.0, -a / 3.0, 2.0 * a / 3.0),), x, lnx, second)
        W = W + m * h0 + m3 - 3.0 * A0
        G += h0[..., None] * gm + (m * h1)[..., None] * gc + g3
        if H is not None and hm is not None and h3 is not None:
            cross = gm[..., :, None] * gc[..., None, :]
            H += (h0[..., None, None] * hm + h1[..., None, None] * (cross + np.swapaxes(
                cross, -1, -2)) + (m * h2)[..., None, None] * (gc[..., :, None]
                                                               * gc[..., None, :])
                  + (m * h1)[..., None, None] * hc + h3)
    return W, G, H


def stress_from_derivatives(
    f: np.ndarray, G: np.ndarray, H: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """In-plane first Piola stress and tangents from the derivatives of ``W(s, J, l)``.

    With ``s = |F|^2``, ``J = det F`` (``dJ/dF = cof F``, linear in F) and ``l`` held::

        P    = 2 W_s F + W_J cof F
        A    = 4 W_ss F x F + 2 W_sJ (F x cof + cof x F) + W_JJ cof x cof + 2 W_s I + W_J Dcof
        A_Fl = d2W / dF dl = 2 W_sl F + W_Jl cof F

    Parameters
    ----------
    f : ndarray (..., 4)
        In-plane F flattened ``[F00, F01, F10, F11]``.
    G : ndarray (..., 3)
        ``[W_s, W_J, W_l]`` (MPa), e.g. from :func:`isochoric_derivatives`.
    H : ndarray (..., 3, 3) or None
        Second derivatives (MPa); None: stress only.

    Returns
    -------
    P : ndarray (..., 4)
        First Piola stress (MPa).
    A : ndarray (..., 4, 4) or None
        ``dP/dF`` at fixed l (MPa).
    A_Fl : ndarray (..., 4) or None
        ``dP/dl`` (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> f = np.array([[1.0, 0.0, 0.0, 1.0]])
    >>> P, _, _ = stress_from_derivatives(f, np.array([[0.5, -0.5, 0.0]]), None)
    >>> P.tolist()  # 2 W_s F + W_J cof F at F = I (MPa)
    [[0.5, 0.0, 0.0, 0.5]]
    """
    c = f[..., _COF_PERM] * _COF_SIGN
    Ws, WJ = G[..., 0], G[..., 1]
    P = 2.0 * Ws[..., None] * f + WJ[..., None] * c
    if H is None:
        return P, None, None
    fc = f[..., :, None] * c[..., None, :]
    A = (4.0 * H[..., 0, 0, None, None] * (f[..., :, None] * f[..., None, :])
         + 2.0 * H[..., 0, 1, None, None] * (fc + np.swapaxes(fc, -1, -2))
         + H[..., 1, 1, None, None] * (c[..., :, None] * c[..., None, :])
         + 2.0 * Ws[..., None, None] * _I4F + WJ[..., None, None] * _DCOF4)
    Al = 2.0 * H[..., 0, 2, None] * f + H[..., 1, 2, None] * c
    return P, A, Al


class PlaneStrainMaterial:
    """A material as the FE body sees it: isochoric kernel, bulk and shear moduli.

    Adapts a :class:`~exofric.material.MooneyRivlin` (its own kernel, unchanged) or a
    :class:`~exofric.material.HyperelasticModel` (neo-Hookean and Yeoh through
    :func:`yeoh_plane_strain`, Mooney-Rivlin through :func:`mooney_rivlin_plane_strain`,
    Ogden through :func:`ogden_plane_strain`).
    Every model has the volumetric term ``(J - 1)^2 / d``, ``K = 2 / d``.

    Parameters
    ----------
    material : MooneyRivlin or HyperelasticModel or PlaneStrainMaterial
        The material (MPa, 1/MPa).

    Attributes
    ----------
    source : MooneyRivlin or HyperelasticModel
        The material given (what results report through :meth:`to_dict`).
    name : str
        ``mooney-rivlin``, ``neo-hookean``, ``yeoh``, ``ogden1``, ``ogden2`` or ``ogden3``.
    shear_modulus, bulk_modulus : float
        Initial shear modulus mu and bulk modulus K = 2/d (MPa).

    Raises
    ------
    InputError
        For another type.

    Examples
    --------
    >>> from exofric.material import material_model
    >>> m = PlaneStrainMaterial(material_model("yeoh", [0.19, -0.0019, 4.1e-5]))
    >>> m.name, round(m.shear_modulus, 3)
    ('yeoh', 0.38)
    """

    def __init__(self, material: Any) -> None:
        if isinstance(material, PlaneStrainMaterial):
            material = material.source
        self.source: MooneyRivlin | HyperelasticModel = material
        if isinstance(material, MooneyRivlin):
            self.name = "mooney-rivlin"
            self.coeffs: tuple[float, ...] = (material.c10_mpa, material.c01_mpa)
            self.shear_modulus = float(material.shear_modulus)
            self.bulk_modulus = float(material.bulk_modulus)
        elif isinstance(material, HyperelasticModel):
            self.name = material.name
            pr = material.params
            self.coeffs = {"neo-hookean": (pr[0], 0.0, 0.0)}.get(material.name, pr)
            self.shear_modulus = float(material.shear_modulus_mpa)
            self.bulk_modulus = float(material.bulk_modulus_mpa)
        else:
            raise InputError("material must be a MooneyRivlin or a HyperelasticModel (from "
                             f"material_model), got {type(material).__name__}",
                             param="material")

    def stress(
        self, F: np.ndarray, tangent: bool = True
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """Isochoric energy density, first Piola stress and tangent at F (..., 2, 2).

        Parameters
        ----------
        F : ndarray (..., 2, 2)
            In-plane deformation gradients (det > 0).
        tangent : bool
            Also return ``A = dP/dF``.

        Returns
        -------
        W, P, A
            MPa (see :func:`mooney_rivlin_plane_strain`).
        """
        if self.name == "mooney-rivlin":
            return mooney_rivlin_plane_strain(F, self.coeffs[0], self.coeffs[1], tangent)
        if self.name.startswith("ogden"):
            return ogden_plane_strain(F, self.coeffs[0::2], self.coeffs[1::2], tangent)
        c10, c20, c30 = self.coeffs
        return yeoh_plane_strain(F, c10, c20, c30, tangent)

    def szz_iso(self, s: np.ndarray, J: np.ndarray) -> np.ndarray:
        """Isochoric out-of-plane Cauchy stress (MPa) at ``s = |F|^2`` and ``J = det F``.

        Parameters
        ----------
        s, J : ndarray
            ``|F|^2`` and ``det F`` of the in-plane F (unitless).

        Returns
        -------
        ndarray
            ``sigma_zz`` without the pressure (MPa).
        """
        j23 = J ** (-2.0 / 3.0)
        if self.name == "mooney-rivlin":
            c10, c01 = self.coeffs
            j43 = J ** (-4.0 / 3.0)
            out: np.ndarray = (c10 * j23 * (2.0 - 2.0 / 3.0 * (s + 1.0))
                               + c01 * j43 * (2.0 * s - 4.0 / 3.0 * (s + J**2))) / J
            return out
        if self.name.startswith("ogden"):
            # tau_3 = sum 2 mu / a (lb3^a - (lb1^a + lb2^a + lb3^a) / 3), lb3 = J^-1/3
            y = 0.5 * s / J - 1.0
            out = np.zeros_like(j23)
            for mu, a in zip(self.coeffs[0::2], self.coeffs[1::2], strict=True):
                h = np.cosh(0.5 * a * np.arccosh(np.maximum(1.0 + y, 1.0)))
                out = out + 2.0 * mu / a * 2.0 / 3.0 * (J ** (-a / 3.0) - J ** (a / 6.0) * h)
            return out / J
        c10, c20, c30 = self.coeffs
        x = j23 * (s + 1.0) - 3.0
        w1 = c10 + (2.0 * c20 + 3.0 * c30 * x) * x
        out = w1 * j23 * (2.0 - 2.0 / 3.0 * (s + 1.0)) / J
        return out

    def to_dict(self) -> dict[str, Any]:
        """The given material's dict (:meth:`MooneyRivlin.to_dict` or its model's)."""
        return dict(self.source.to_dict())


@dataclass
class ElementState:
    """Element-level results of one evaluation (internal to the solver)."""

    energy: float
    fe: np.ndarray  # (e, 2n) element internal forces (N per mm depth)
    ke: np.ndarray | None  # (e, 2n, 2n) element tangents (N/mm per mm depth)
    valid: bool  # False if any J <= 0 (inverted element)
    # generalised plane strain (:meth:`HyperelasticBody.evaluate_axial`): the axial force
    # dW/dl (e,) (N), its coupling to the nodal dofs d2W/du dl (e, 2n) (N/mm) and d2W/dl2 (e,)
    fl: np.ndarray | None = None
    kel: np.ndarray | None = None
    kll: np.ndarray | None = None

    def with_axial(self) -> np.ndarray:
        """Element tangents bordered by the axial stretch: (e, 2n + 1, 2n + 1), N/mm per mm.

        The last row and column are ``kel`` and ``kll`` (generalised plane strain, the element
        dofs followed by the axial one).
        """
        assert self.ke is not None and self.kel is not None and self.kll is not None
        ne, k = self.ke.shape[:2]
        out = np.empty((ne, k + 1, k + 1))
        out[:, :k, :k] = self.ke
        out[:, :k, k] = out[:, k, :k] = self.kel
        out[:, k, k] = self.kll
        return out


class HyperelasticBody:
    """A meshed hyperelastic body in plane strain (precomputed element data).

    Parameters
    ----------
    mesh : TubeMesh
        The mesh (mm).
    material : MooneyRivlin or HyperelasticModel or PlaneStrainMaterial
        Constants C10, C01 (MPa) and d (1/MPa), or a neo-Hookean, Mooney-Rivlin or Yeoh
        model from :func:`~exofric.material.material_model` (Ogden too).
    formulation : {'mixed', 'displacement'}
        Mixed u/p (default; locking-free) or plain displacement (locks).
    n_gauss : int, optional
        Gauss points per direction (default 3 for quad9, 2 for quad4).

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.fe import polar_mesh
    >>> from exofric.material import MooneyRivlin
    >>> body = HyperelasticBody(polar_mesh(2.485, 4.15, 2, 4), MooneyRivlin.from_shore(62.5))
    >>> body.max_stretch(np.zeros(2 * 45))  # undeformed (unitless)
    1.0
    """

    def __init__(
        self,
        mesh: TubeMesh,
        material: MooneyRivlin | HyperelasticModel | PlaneStrainMaterial,
        formulation: str = "mixed",
        n_gauss: int | None = None,
    ) -> None:
        if formulation not in ("mixed", "displacement"):
            raise InputError(f"formulation must be 'mixed' or 'displacement', got {formulation!r}")
        self.mesh = mesh
        self.material = material
        self.model = PlaneStrainMaterial(material)
        self.formulation = formulation
        ng = n_gauss or (3 if mesh.order == 2 else 2)
        self.ref: ReferenceData = reference_data(mesh.nodes, mesh.elements, mesh.order, ng)
        n = mesh.elements.shape[1]
        self.n_local = n
        self.edofs = (2 * mesh.elements[:, :, None] + np.arange(2)).reshape(-1, 2 * n)
        self.K = self.model.bulk_modulus
        # Reshaped gradients so every contraction below is one batched matmul.
        d = self.ref.dNdX  # (e, q, n, 2)
        ne, nq = d.shape[:2]
        self._dN_nqj = np.ascontiguousarray(d.transpose(0, 2, 1, 3).reshape(ne, n, 2 * nq))
        # Constant B-matrix (total Lagrangian): dF[2i+j] = sum_{b,k} B[2i+j, 2b+k] du[2b+k]
        # with B[2i+j, 2b+k] = delta_ik dN_b/dX_j; wBT carries the quadrature weights.
        B = np.zeros((ne, nq, 4, 2 * n))
        for i in range(2):
            for j in range(2):
                B[:, :, 2 * i + j, i::2] = d[:, :, :, j]
        self._B = B
        self._wBT = np.ascontiguousarray(
            (B * self.ref.w[:, :, None, None]).transpose(0, 3, 1, 2).reshape(ne, 2 * n, 4 * nq))
        self._wNp = np.ascontiguousarray(
            (self.ref.w[:, :, None] * self.ref.Np[None]).transpose(0, 2, 1))  # (e, m, q)

    def deformation_gradient(self, u: np.ndarray) -> np.ndarray:
        """F at every element and quadrature point, shape (e, q, 2, 2).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.

        Returns
        -------
        ndarray (e, q, 2, 2)
            Deformation gradient (unitless).
        """
        ne, n = len(self.edofs), self.n_local
        ue = u[self.edofs].reshape(ne, n, 2).transpose(0, 2, 1)  # (e, i, n)
        g = (ue @ self._dN_nqj).reshape(ne, 2, -1, 2).transpose(0, 2, 1, 3)  # (e, q, i, j)
        return np.eye(2) + g

    def evaluate(self, u: np.ndarray, tangent: bool = True) -> ElementState:
        """Energy, element forces and element tangents at displacement ``u`` (mm).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        tangent : bool
            Also compute the element tangent matrices.

        Returns
        -------
        ElementState
            Energy (N mm per mm depth), element forces (N per mm depth), tangents
            (N/mm per mm depth) and a validity flag (False for an inverted element).
        """
        r = self.ref
        F = self.deformation_gradient(u)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        if np.any(J <= 1e-8) or not np.all(np.isfinite(J)):
            return ElementState(np.inf, np.empty(0), None, False)
        W, P, A = self.model.stress(F, tangent)
        cof = _cof(F)
        ne = len(self.edofs)
        ke = None
        if self.formulation == "mixed":
            g = np.einsum("eq,qm,eq->em", r.w, r.Np, J - 1.0)
            pe = self.K * np.einsum("emk,ek->em", r.Minv, g)
            p = pe @ r.Np.T  # (e, q)
            e_vol = 0.5 * self.K * float(np.einsum("em,em->", g, pe / self.K))
            P = P + p[..., None, None] * cof
            if tangent:
                assert A is not None
                A = A + p[..., None, None, None, None] * DCOF
                cofB = cof.reshape(ne, -1, 1, 4) @ self._B  # (e, q, 1, 2n): dJ/du
                G = self._wNp @ cofB[:, :, 0, :]  # (e, m, 2n)
                ke = self.K * (G.transpose(0, 2, 1) @ (r.Minv @ G))
        else:
            e_vol = float(np.einsum("eq,eq->", r.w, 0.5 * self.K * (J - 1.0) ** 2))
            P = P + (self.K * (J - 1.0))[..., None, None] * cof
            if tangent:
                assert A is not None
                A = A + self.K * (
                    np.einsum("...ij,...kl->...ijkl", cof, cof)
                    + (J - 1.0)[..., None, None, None, None] * DCOF
                )
        energy = float(np.einsum("eq,eq->", r.w, W)) + e_vol
        nq = P.shape[1]
        fe = (self._wBT @ P.reshape(ne, 4 * nq, 1))[..., 0]  # sum_q w B^T P
        if tangent:
            assert A is not None
            BD = (A.reshape(ne, nq, 4, 4) @ self._B).reshape(ne, 4 * nq, -1)
            kk = self._wBT @ BD  # sum_q w B^T A B
            ke = kk if ke is None else ke + kk
        return ElementState(energy, fe, ke, True)

    def evaluate_axial(self, u: np.ndarray, stretch: float, tangent: bool = True
                       ) -> ElementState:
        """Generalised plane strain: the body with a uniform axial stretch ``stretch``.

        ``F = blockdiag(F2, l)``; the energy per unit reference length is ``int W(F2, l)
        dA`` with the isochoric part from :func:`isochoric_derivatives` and the volumetric
        part on ``J3 = J l`` (mixed: ``p`` condensed on ``J l - 1``). Besides the element
        forces and tangents of :meth:`evaluate` it returns the axial force ``dW/dl`` and its
        couplings. At ``l = 1`` forces and tangents are those of :meth:`evaluate` (tested).

        Parameters
        ----------
        u : ndarray (2 n_nodes,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        stretch : float
            Axial stretch l (unitless, > 0).
        tangent : bool
            Also compute the tangents.

        Returns
        -------
        ElementState
            With ``fl`` (N per element, per unit reference length: the axial force is its
            sum), ``kel`` (e, 2n) and ``kll`` (e,) set.

        Examples
        --------
        >>> import numpy as np
        >>> from exofric.fe import polar_mesh
        >>> from exofric.material import MooneyRivlin
        >>> body = HyperelasticBody(polar_mesh(2.485, 4.15, 2, 4), MooneyRivlin.from_shore(62.5))
        >>> st = body.evaluate_axial(np.zeros(90), 1.0)
        >>> bool(abs(st.fl).max() < 1e-12)  # undeformed: no axial force (N)
        True
        """
        r = self.ref
        lz = float(stretch)
        F = self.deformation_gradient(u)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        if (np.any(J <= 1e-8) or not np.all(np.isfinite(J)) or not np.isfinite(lz)
                or lz <= 1e-8):
            return ElementState(np.inf, np.empty(0), None, False)
        ne, nq = J.shape
        f = F.reshape(ne, nq, 4)
        c = f[..., _COF_PERM] * _COF_SIGN
        s = np.einsum("eqi,eqi->eq", f, f)
        W, G, H = isochoric_derivatives(self.model, s, J, np.full_like(J, lz), tangent)
        P, A_, Al_ = stress_from_derivatives(f, G, H)
        Pl = G[..., 2].copy()
        if tangent:
            assert H is not None and A_ is not None and Al_ is not None
            A, Al = A_, Al_
            All = H[..., 2, 2].copy()
        j3m1 = J * lz - 1.0
        kvol = None
        if self.formulation == "mixed":
            g = np.einsum("eq,qm,eq->em", r.w, r.Np, j3m1)
            pe = self.K * np.einsum("emk,ek->em", r.Minv, g)
            p = pe @ r.Np.T  # (e, q)
            e_vol = 0.5 * float(np.einsum("em,em->", g, pe))
            P = P + (p * lz)[..., None] * c
            Pl = Pl + p * J
            if tangent:
                A = A + (p * lz)[..., None, None] * _DCOF4
                Al = Al + p[..., None] * c
                cofB = (c.reshape(ne, nq, 1, 4) @ self._B)[:, :, 0, :]  # (e, q, 2n): dJ/du
                Gx = np.concatenate([lz * (self._wNp @ cofB),
                                     (self._wNp @ J[..., None])], axis=2)  # (e, m, 2n + 1)
                kvol = self.K * (Gx.transpose(0, 2, 1) @ (r.Minv @ Gx))
        else:
            e_vol = float(np.einsum("eq,eq->", r.w, 0.5 * self.K * j3m1**2))
            kp = self.K * j3m1
            P = P + (kp * lz)[..., None] * c
            Pl = Pl + kp * J
            if tangent:
                A = A + self.K * ((lz * lz) * (c[..., :, None] * c[..., None, :])) \
                    + (kp * lz)[..., None, None] * _DCOF4
                Al = Al + (self.K * J * lz + kp)[..., None] * c
                All = All + self.K * J * J
        energy = float(np.einsum("eq,eq->", r.w, W)) + e_vol
        fe = (self._wBT @ P.reshape(ne, 4 * nq, 1))[..., 0]
        fl = np.einsum("eq,eq->e", r.w, Pl)
        if not tangent:
            return ElementState(energy, fe, None, True, fl)
        BD = (A @ self._B).reshape(ne, 4 * nq, -1)
        ke = self._wBT @ BD
        kel = (self._wBT @ Al.reshape(ne, 4 * nq, 1))[..., 0]
        kll = np.einsum("eq,eq->e", r.w, All)
        if kvol is not None:
            ke = ke + kvol[:, :-1, :-1]
            kel = kel + kvol[:, :-1, -1]
            kll = kll + kvol[:, -1, -1]
        return ElementState(energy, fe, ke, True, fl, kel, kll)

    def max_stretch(self, u: np.ndarray) -> float:
        """Largest in-plane principal stretch over all quadrature points at ``u``.

        From the eigenvalues of C = F^T F (2x2, closed form): lambda^2 = (tr C + sqrt(tr C^2
        - 4 det C)) / 2 with det C = J^2.

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.

        Returns
        -------
        float
            Largest principal stretch (unitless).
        """
        F = self.deformation_gradient(u)
        C = np.einsum("...ki,...kj->...ij", F, F)
        tr = C[..., 0, 0] + C[..., 1, 1]
        det = C[..., 0, 0] * C[..., 1, 1] - C[..., 0, 1] * C[..., 1, 0]
        lam2 = 0.5 * (tr + np.sqrt(np.maximum(tr * tr - 4.0 * det, 0.0)))
        return float(np.sqrt(lam2.max()))

    def element_pressure(self, u: np.ndarray, stretch: float = 1.0) -> np.ndarray:
        """Hydrostatic pressure field p (MPa, tension positive) at quadrature points (e, q).

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        stretch : float
            Axial stretch l of generalised plane strain (unitless; 1: plane strain).
        """
        F = self.deformation_gradient(u)
        J = (F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]) * stretch
        r = self.ref
        if self.formulation == "mixed":
            g = np.einsum("eq,qm,eq->em", r.w, r.Np, J - 1.0)
            return (self.K * np.einsum("emk,ek->em", r.Minv, g)) @ r.Np.T
        return self.K * (J - 1.0)

    def cauchy_stress(self, u: np.ndarray, stretch: float = 1.0) -> np.ndarray:
        """Cauchy stress (MPa) at quadrature points: (e, q, 4) = [sxx, syy, sxy, szz].

        Parameters
        ----------
        u : ndarray (n_dofs,)
            Nodal displacements (mm), flattened ``[ux0, uy0, ux1, ...]``.
        stretch : float
            Axial stretch l of generalised plane strain (unitless; 1: plane strain).
        """
        F = self.deformation_gradient(u)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        s = np.einsum("...ij,...ij->...", F, F)
        p = self.element_pressure(u, stretch)
        if stretch == 1.0:
            _, P, _ = self.model.stress(F, tangent=False)
            P = P + p[..., None, None] * _cof(F)
            sig = np.einsum("...ij,...kj->...ik", P, F) / J[..., None, None]
            szz = self.model.szz_iso(s, J) + p
            return np.stack([sig[..., 0, 0], sig[..., 1, 1], sig[..., 0, 1], szz], axis=-1)
        # sigma = P F^T / J3 with J3 = J l; in-plane P = 2 W_s F + W_J cof F + p l cof F and
        # the axial P_zz = W_l + p J, so sigma_zz = l P_zz / J3 = (W_l + p J) / J
        _, G, _ = isochoric_derivatives(self.model, s, J, np.full_like(J, stretch), False)
        P = (2.0 * G[..., 0, None, None] * F
             + (G[..., 1] + p * stretch)[..., None, None] * _cof(F))
        sig = np.einsum("...ij,...kj->...ik", P, F) / (J * stretch)[..., None, None]
        szz = (G[..., 2] + p * J) / J
        return np.stack([sig[..., 0, 0], sig[..., 1, 1], sig[..., 0, 1], szz], axis=-1)


def von_mises(stress: np.ndarray) -> np.ndarray:
    """Von Mises stress (MPa) from ``[sxx, syy, sxy, szz]`` in the last axis.

    Parameters
    ----------
    stress : ndarray (..., 4)
        Cauchy stress components ``[sxx, syy, sxy, szz]`` (MPa).

    Returns
    -------
    ndarray (...)
        Von Mises stress (MPa).

    Examples
    --------
    >>> import numpy as np
    >>> float(von_mises(np.array([1.0, 0.0, 0.0, 0.0])))  # uniaxial 1 MPa
    1.0
    """
    sxx, syy, sxy, szz = np.moveaxis(stress, -1, 0)
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy**2)
