"""Vectorised homogeneous stresses of every model with their parameter Jacobians (for fits).

For the fit (:func:`exofric.material.fit_material`) every model's nominal stress along a
homogeneous incompressible path is written as closed forms in the stretch ``l`` (arrays), with
the analytic Jacobian with respect to the parameters:

* neo-Hookean, Mooney-Rivlin and Yeoh are linear in their parameters, ``P = X(l) c`` with
  ``P = 2 g(l) (W1 + k(l) W2)``: uniaxial ``g = l - l^-2``, ``k = 1/l``; equibiaxial
  ``g = l - l^-5``, ``k = l^2``; planar ``g = l - l^-3``, ``k = 1``; and ``W1 = dW/dI1``
  (C10: 1, C20: 2 (I1 - 3), C30: 3 (I1 - 3)^2), ``W2 = dW/dI2`` (C01: 1);
* Ogden: ``P = sum_i mu_i psi(l, a_i)``, ``psi = (2 / a) (l^(a-1) - l^(c a - 1))`` with the
  lateral exponent ``c = -1/2`` (uniaxial), ``-2`` (equibiaxial), ``-1`` (planar);
  ``dpsi/da = -psi / a + (2 / a) ln l (l^(a-1) - c l^(c a - 1))``.

Every expression is complex-safe, so the tangent ``dP/dl`` and its Jacobian come from the
complex step ``Im f(l + i h) / h`` (exact to rounding); Ogden's in closed form,
``dpsi/dl = (2 / a) ((a - 1) l^(a-2) - (c a - 1) l^(c a - 2))``. These are the same stresses as
:meth:`HyperelasticModel.stress_mpa` (tests/test_material_real_data.py checks them against it
and against finite differences). Units: MPa, stretch and exponents unitless.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

__all__: list[str] = []

_LATERAL = {"uniaxial": -0.5, "biaxial": -2.0, "planar": -1.0}
_H = 1e-30


def _invariant_columns(name: str, mode: str, lam: Any) -> Any:
    """``X(l)`` of the models linear in their parameters: one column per parameter."""
    import numpy as np

    if mode == "uniaxial":
        g, k, i1 = 2.0 * (lam - lam ** -2.0), 1.0 / lam, lam * lam + 2.0 / lam
    elif mode == "biaxial":
        g, k, i1 = 2.0 * (lam - lam ** -5.0), lam * lam, 2.0 * lam * lam + lam ** -4.0
    else:
        g, k, i1 = 2.0 * (lam - lam ** -3.0), lam * 0.0 + 1.0, lam * lam + 1.0 + lam ** -2.0
    if name == "neo-hookean":
        cols = [g]
    elif name == "mooney-rivlin":
        cols = [g, g * k]
    else:  # yeoh
        e = i1 - 3.0
        cols = [g, 2.0 * g * e, 3.0 * g * e * e]
    return np.stack(cols, axis=-1)


def stress_jac(name: str, mode: str, lam: Any, x: Any) -> tuple[Any, Any]:
    """Nominal stress ``P`` (MPa) and its Jacobian ``dP/dx`` at stretches ``lam``.

    Parameters
    ----------
    name : str
        Model name (``neo-hookean``, ``mooney-rivlin``, ``yeoh``, ``ogden1``..``ogden3``).
    mode : str
        ``uniaxial``, ``biaxial`` or ``planar``.
    lam : numpy.ndarray
        Stretches (unitless), real or complex (complex step).
    x : numpy.ndarray
        Parameters in the order of ``HYPERELASTIC_MODELS[name]``.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        ``P`` of shape ``(n,)`` in MPa and ``dP/dx`` of shape ``(n, p)``.
    """
    import numpy as np

    x = np.asarray(x, dtype=float)
    if not name.startswith("ogden"):
        cols = _invariant_columns(name, mode, lam)
        return cols @ x, cols
    c = _LATERAL[mode]
    mu, a = x[0::2], x[1::2]
    log_l = np.log(lam)[..., None]
    u = np.exp((a - 1.0) * log_l)
    v = np.exp((c * a - 1.0) * log_l)
    psi = (2.0 / a) * (u - v)
    jac = np.empty(np.shape(lam) + (x.size,), dtype=psi.dtype)
    jac[..., 0::2] = psi
    jac[..., 1::2] = mu * ((2.0 / a) * (log_l * (u - c * v)) - psi / a)
    return psi @ mu, jac


def ogden_columns(mode: str, lam: NDArray[np.float64],
                  alpha: Any) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Ogden's per-term columns ``psi(l, a)`` and ``dpsi/da`` for many exponents at once.

    ``P = sum_i mu_i psi(l, a_i)`` along the path, ``psi = (2 / a) (l^(a-1) - l^(c a - 1))``;
    for the vectorised multi-start of the fit (every start's exponents in one call).

    Parameters
    ----------
    mode : str
        ``uniaxial``, ``biaxial`` or ``planar``.
    lam : numpy.ndarray
        Real stretches (unitless), > 0, shape ``(N,)``.
    alpha : array_like
        Exponents (unitless, nonzero) of any shape ``(..., n)``.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        ``psi`` and ``dpsi/da`` of shape ``(..., N, n)`` (MPa per MPa of mu: unitless).
    """
    import numpy as np

    c = _LATERAL[mode]
    log_l = np.log(np.asarray(lam, dtype=float))[:, None]
    a = np.asarray(alpha, dtype=float)[..., None, :]
    with np.errstate(all="ignore"):
        u = np.exp((a - 1.0) * log_l)
        v = np.exp((c * a - 1.0) * log_l)
        psi = (2.0 / a) * (u - v)
        dpsi = (2.0 / a) * (log_l * (u - c * v)) - psi / a
    return psi, dpsi


def tangent_jac(name: str, mode: str, lam: NDArray[np.float64],
                x: Any) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Tangent ``dP/dl`` (MPa) and its Jacobian ``d(dP/dl)/dx``, by the complex step.

    Parameters
    ----------
    name, mode : str
        As :func:`stress_jac`.
    lam : numpy.ndarray
        Real stretches (unitless), > 0.
    x : numpy.ndarray
        Parameters.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        ``dP/dl`` of shape ``(n,)`` and its Jacobian ``(n, p)``, MPa.
    """
    import numpy as np

    lam = np.asarray(lam, dtype=float)
    x = np.asarray(x, dtype=float)
    if name.startswith("ogden"):
        return _ogden_tangent(mode, lam, x)
    p, jac = stress_jac(name, mode, lam + 1j * _H, x)
    return np.imag(p) / _H, np.imag(jac) / _H


def _ogden_tangent(mode: str, lam: NDArray[np.float64],
                   x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Ogden's ``dP/dl = sum_i mu_i t(l, a_i)`` in closed form, ``t = dpsi/dl = (2 / a)
    ((a - 1) l^(a-2) - (c a - 1) l^(c a - 2))``, and its Jacobian: ``t`` on mu_i,
    ``mu_i dt/da`` on a_i (MPa)."""
    import numpy as np

    c = _LATERAL[mode]
    mu, a = x[0::2], x[1::2]
    log_l = np.log(lam)[:, None]
    u2 = np.exp((a - 2.0) * log_l)
    v2 = np.exp((c * a - 2.0) * log_l)
    t = (2.0 / a) * ((a - 1.0) * u2 - (c * a - 1.0) * v2)
    dt = (2.0 / a) * (u2 * (1.0 + (a - 1.0) * log_l) - c * v2 * (1.0 + (c * a - 1.0) * log_l)) \
        - t / a
    jac = np.empty(lam.shape + (x.size,))
    jac[:, 0::2] = t
    jac[:, 1::2] = mu * dt
    return t @ mu, jac


def shear_modulus_grad(name: str, n_params: int) -> NDArray[np.float64]:
    """``d mu / dx``: mu is linear in the parameters of every model (MPa per parameter unit).

    Parameters
    ----------
    name : str
        Model name.
    n_params : int
        Number of parameters.

    Returns
    -------
    numpy.ndarray
        The gradient (Ogden: 1 on each ``mu_i``, 0 on the exponents).
    """
    import numpy as np

    g = np.zeros(n_params)
    if name.startswith("ogden"):
        g[0::2] = 1.0
    elif name == "mooney-rivlin":
        g[:2] = 2.0
    else:
        g[0] = 2.0
    return g
