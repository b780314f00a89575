"""Least-squares covariances: the one owner of the formulas every fit uses.

* :func:`lsq_covariance` -- s^2 (J^T J)^+ of a (nonlinear) least-squares fit at its optimum,
  through the SVD of J (never forming J^T J, whose condition number is the square of J's);
* :func:`residual_variance` -- s^2 = r.r / (n - p);
* :func:`standard_errors`, :func:`correlation` -- from a covariance;
* :func:`hc3_covariance` -- the heteroscedasticity-robust HC3 sandwich of OLS (MacKinnon &
  White 1985).

Used by the material fits, the calibrations, the plant identifications and the friction laws;
checked against statsmodels (``tests/test_lsq.py``). Units: whatever the parameters' are
(the covariance is in their units squared).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["correlation", "hc3_covariance", "lsq_covariance", "residual_variance",
           "standard_errors"]


def residual_variance(residuals: ArrayLike, n_params: int, *, min_dof: int = 0) -> float:
    """s^2 = r.r / (n - p), the residual variance of a least-squares fit.

    Parameters
    ----------
    residuals : array_like
        The n residuals at the optimum (units of the data).
    n_params : int
        Number p of fitted parameters.
    min_dof : int
        With ``min_dof`` >= 1 the divisor is max(n - p, min_dof) (a value even without degrees
        of freedom); with 0 (default) n <= p gives NaN.

    Returns
    -------
    float

    Examples
    --------
    >>> residual_variance([1.0, -1.0, 1.0, -1.0], 2)
    2.0
    >>> residual_variance([1.0], 1), residual_variance([1.0], 1, min_dof=1)
    (nan, 1.0)
    """
    r = np.asarray(residuals, dtype=float).ravel()
    dof = r.size - int(n_params)
    if min_dof >= 1:
        dof = max(dof, min_dof)
    return float(r @ r) / dof if dof > 0 else math.nan


def lsq_covariance(jac: ArrayLike, s2: float = 1.0, *, rcond: float = 1e-15) -> NDArray[np.float64]:
    """Covariance s^2 (J^T J)^+ of least-squares parameters from the Jacobian J at the optimum.

    Computed from the SVD J = U S V^T as s^2 V S^-2 V^T, with singular values below
    ``rcond`` x the largest dropped (a direction the data do not determine gets no variance
    rather than an overflow; look at the condition number to see it).

    Parameters
    ----------
    jac : array_like
        n x p Jacobian of the residuals with respect to the parameters (in the units of the
        residuals per unit of each parameter).
    s2 : float
        Residual variance (:func:`residual_variance`), or 1 when the residuals are already
        scaled by their standard deviations.
    rcond : float
        Relative cut-off of the singular values.

    Returns
    -------
    ndarray
        p x p covariance.

    Examples
    --------
    >>> lsq_covariance([[1.0, 0.0], [0.0, 2.0], [0.0, 0.0]], 4.0)
    array([[4., 0.],
           [0., 1.]])
    """
    j = np.atleast_2d(np.asarray(jac, dtype=float))
    _, sv, vt = np.linalg.svd(j, full_matrices=False)
    keep = sv > rcond * (sv[0] if sv.size else 0.0)
    inv2 = np.zeros_like(sv)
    inv2[keep] = 1.0 / sv[keep] ** 2
    return np.asarray(float(s2) * (vt.T * inv2) @ vt, dtype=float)


def standard_errors(cov: ArrayLike) -> NDArray[np.float64]:
    """sqrt(diag(cov)), negative round-off clipped to 0.

    Examples
    --------
    >>> standard_errors([[4.0, 1.0], [1.0, 9.0]]).tolist()
    [2.0, 3.0]
    """
    return np.sqrt(np.clip(np.diag(np.asarray(cov, dtype=float)), 0.0, None))


def correlation(cov: ArrayLike) -> NDArray[np.float64]:
    """Correlation matrix of a covariance (unit diagonal; NaN where a variance is 0).

    Examples
    --------
    >>> correlation([[4.0, 1.0], [1.0, 9.0]]).round(4).tolist()
    [[1.0, 0.1667], [0.1667, 1.0]]
    """
    c = np.asarray(cov, dtype=float)
    se = standard_errors(c)
    with np.errstate(all="ignore"):
        r = c / np.outer(se, se)
    np.fill_diagonal(r, 1.0)
    return np.asarray(r, dtype=float)


def hc3_covariance(x: ArrayLike, residuals: ArrayLike) -> NDArray[np.float64]:
    """HC3 sandwich covariance of OLS coefficients (MacKinnon & White 1985).

    (X^T X)^-1 X^T diag(e_i^2 / (1 - h_ii)^2) X (X^T X)^-1, with h_ii the leverages (a point
    of leverage 1 makes it NaN: its residual says nothing about the variance).

    Parameters
    ----------
    x : array_like
        n x p design matrix.
    residuals : array_like
        The n OLS residuals.

    Returns
    -------
    ndarray
        p x p covariance.

    Examples
    --------
    >>> x = np.c_[np.ones(4), [0.0, 1.0, 2.0, 3.0]]
    >>> hc3_covariance(x, [0.1, -0.2, 0.2, -0.1]).shape
    (2, 2)
    """
    xm = np.atleast_2d(np.asarray(x, dtype=float))
    if xm.shape[0] == 1 and np.ndim(x) == 1:
        xm = xm.T
    e = np.asarray(residuals, dtype=float).ravel()
    bread = np.linalg.inv(xm.T @ xm)
    h = np.einsum("ij,jk,ik->i", xm, bread, xm)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(h < 1.0, e**2 / (1.0 - h) ** 2, np.nan)   # a point of leverage 1: NaN
    meat = (xm * w[:, None]).T @ xm
    return np.asarray(bread @ meat @ bread, dtype=float)
