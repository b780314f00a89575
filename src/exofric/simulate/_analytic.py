"""Closed-form and 1D references for the free inflation of a thick tube (plane strain).

Two independent references the 2D FE solver is checked against:

* :func:`incompressible_inflation`: the exact incompressible plane-strain solution.
  In plane strain (stretch_z = 1) and J = 1, Mooney-Rivlin reduces to neo-Hookean
  with ``mu = 2 (C10 + C01)``. With undeformed radii A < B, deformed inner radius a,
  ``c = a^2 - A^2`` and ``b = sqrt(B^2 + c)``::

      P = int_a^b mu (r^2/(r^2-c) - (r^2-c)/r^2) / r dr
        = mu/2 [ ln(a^2 B^2 / (A^2 b^2)) + c (1/a^2 - 1/b^2) ]

  which rises monotonically to the limit pressure ``mu ln(B/A)`` as a -> infinity.
* :func:`compressible_inflation`: the same problem for the real, slightly
  compressible Mooney-Rivlin energy of Eq 2 (ANSYS's deviatoric split
  ``U = C10(I1b-3) + C01(I2b-3) + (J-1)^2/d``), solved as a 1D radial
  large-deformation boundary value problem with ``scipy.integrate.solve_bvp``
  (tolerance 1e-8; 1e-6 and 1e-8 agree to 1e-8 relative): equilibrium
  ``d(P_rR)/dR + (P_rR - P_tT)/R = 0`` with ``P_rR(A) = -P r(A)/A`` (follower
  pressure) and ``P_rR(B) = 0``.

Units: mm, MPa.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import ConvergenceError, InputError, check_positive, check_pressures
from exofric.material import MooneyRivlin

if TYPE_CHECKING:
    import pandas as pd

    from exofric.material import HyperelasticModel

__all__ = [
    "incompressible_pressure",
    "incompressible_inflation",
    "incompressible_limit_pressure",
    "compressible_inflation",
    "InflationCurve",
    "tube_inflation",
    "TubeInflationCurve",
]


@checked_init
@dataclass(frozen=True)
class InflationCurve(DisplayMixin):
    """Tube diameters (mm) at each pressure (MPa) from a reference solution.

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    outer_diameter_mm, inner_diameter_mm : ndarray
        Deformed outer and inner diameters (mm) at each pressure.
    method : str
        Which reference produced the curve (e.g. ``"incompressible closed form
        (plane strain)"``).

    Examples
    --------
    >>> c = incompressible_inflation(8.3, 4.97, 1.4, [0.2])
    >>> round(float(c.outer_diameter_mm[0]), 3)
    8.72
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    inner_diameter_mm: np.ndarray
    method: str

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict."""
        return {
            "method": self.method,
            "pressure_mpa": self.pressure_mpa.tolist(),
            "outer_diameter_mm": self.outer_diameter_mm.tolist(),
            "inner_diameter_mm": self.inner_diameter_mm.tolist(),
        }


def _radii(tube_od_mm: float, tube_id_mm: float) -> tuple[float, float]:
    od = check_positive("tube_od_mm", tube_od_mm, "mm")
    idm = check_positive("tube_id_mm", tube_id_mm, "mm")
    if idm >= od:
        raise InputError(f"tube_id_mm must be < tube_od_mm ({od:g} mm), got {idm:g}")
    return 0.5 * idm, 0.5 * od


def incompressible_pressure(a: float | np.ndarray, A: float, B: float, mu: float) -> np.ndarray:
    """Pressure (MPa) that inflates the inner radius from ``A`` to ``a`` (mm), J = 1.

    Parameters
    ----------
    a : float or array-like
        Deformed inner radius (mm), ``a >= A``.
    A, B : float
        Undeformed inner and outer radii (mm), ``0 < A < B``.
    mu : float
        Shear modulus (MPa).

    Returns
    -------
    numpy.ndarray
        Internal pressure (MPa), same shape as ``a``.

    Examples
    --------
    >>> float(incompressible_pressure(2.485, 2.485, 4.15, 1.0))
    0.0
    """
    a = np.asarray(a, dtype=float)
    c = a**2 - A**2
    b2 = B**2 + c
    return 0.5 * mu * (np.log(a**2 * B**2 / (A**2 * b2)) + c * (1.0 / a**2 - 1.0 / b2))


def incompressible_limit_pressure(tube_od_mm: float, tube_id_mm: float, mu_mpa: float) -> float:
    """Asymptotic pressure ``mu ln(B/A)`` (MPa): no free-inflation equilibrium above it.

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner diameters (mm), ``0 < tube_id_mm < tube_od_mm``.
    mu_mpa : float
        Shear modulus (MPa).

    Returns
    -------
    float
        Limit pressure (MPa).

    Examples
    --------
    >>> round(incompressible_limit_pressure(8.3, 4.97, 1.4), 3)
    0.718
    """
    A, B = _radii(tube_od_mm, tube_id_mm)
    return float(mu_mpa * np.log(B / A))


def incompressible_inflation(
    tube_od_mm: float, tube_id_mm: float, mu_mpa: float, pressures_mpa: np.ndarray | list[float]
) -> InflationCurve:
    """Exact incompressible plane-strain inflation of a neo-Hookean tube.

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner diameters (mm).
    mu_mpa : float
        Shear modulus (MPa); for Mooney-Rivlin in plane strain ``2 (C10 + C01)``.
    pressures_mpa : array-like
        Internal pressures (MPa), each below the limit pressure ``mu ln(B/A)``.

    Returns
    -------
    InflationCurve
        Outer and inner diameters (mm).

    Examples
    --------
    >>> c = incompressible_inflation(8.3, 4.97, 1.33444, [0.1, 0.4])
    >>> [round(float(x), 3) for x in c.outer_diameter_mm]
    [8.495, 9.576]
    """
    A, B = _radii(tube_od_mm, tube_id_mm)
    mu = check_positive("mu_mpa", mu_mpa, "MPa")
    p = np.asarray(pressures_mpa, dtype=float)
    if p.ndim != 1 or not np.all(np.isfinite(p)) or np.any(p < 0):
        raise InputError("pressures_mpa must be finite and >= 0 MPa")
    plim = mu * np.log(B / A)
    if np.any(p >= plim):
        raise InputError(
            f"pressure {p.max():g} MPa is at or above the tube's limit pressure {plim:.4g} MPa "
            "(mu ln(B/A)): no free-inflation equilibrium exists"
        )
    from exofric._roots import brentq  # not scipy.optimize: 0.15 s of start-up

    a = np.empty_like(p)
    for i, pi in enumerate(p):
        if pi == 0.0:
            a[i] = A
            continue
        hi = A * 2.0
        while incompressible_pressure(hi, A, B, mu) < pi:
            hi *= 2.0
        a[i] = brentq(
            lambda x, pi=pi: float(incompressible_pressure(x, A, B, mu)) - pi,
            A,
            hi,
            xtol=1e-14,
            rtol=1e-15,
        )
    b = np.sqrt(B**2 + a**2 - A**2)
    return InflationCurve(p, 2.0 * b, 2.0 * a, "incompressible closed form (plane strain)")


def _piola(lr: np.ndarray, lt: np.ndarray, m: MooneyRivlin) -> tuple[np.ndarray, np.ndarray]:
    """First Piola stresses (P_rR, P_tT) of Eq 2 in plane strain for stretches (lr, lt)."""
    J = lr * lt
    s = lr**2 + lt**2  # I1 - 1 (in-plane |F|^2)
    f_s = m.c10_mpa * J ** (-2 / 3) + m.c01_mpa * J ** (-4 / 3)
    f_J = (
        -2 / 3 * m.c10_mpa * J ** (-5 / 3) * (s + 1)
        - 4 / 3 * m.c01_mpa * J ** (-7 / 3) * s
        + 2 / 3 * m.c01_mpa * J ** (-1 / 3)
        + 2.0 * (J - 1.0) / m.d_per_mpa
    )
    return 2.0 * f_s * lr + f_J * lt, 2.0 * f_s * lt + f_J * lr


def _piola_jac(lr: np.ndarray, lt: np.ndarray, m: MooneyRivlin) -> tuple[np.ndarray, np.ndarray]:
    """d P_rR / d lr and d P_rR / d lt by the complex step (exact to round-off)."""
    h = 1e-30
    drr = _piola(lr + 1j * h, lt.astype(complex), m)[0].imag / h
    drt = _piola(lr.astype(complex), lt + 1j * h, m)[0].imag / h
    return drr, drt


def compressible_inflation(
    tube_od_mm: float,
    tube_id_mm: float,
    material: MooneyRivlin,
    pressures_mpa: np.ndarray | list[float],
    *,
    tol: float = 1e-8,
) -> InflationCurve:
    """Compressible plane-strain inflation of a Mooney-Rivlin tube (1D radial BVP).

    Solves the radial equilibrium for the exact energy of Eq 2 (with its
    volumetric term) by collocation (``scipy.integrate.solve_bvp``), continuing
    in pressure from the undeformed state. Independent of the 2D FE code.

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed diameters (mm).
    material : MooneyRivlin
        C10, C01 (MPa) and d (1/MPa).
    pressures_mpa : array-like
        Strictly increasing pressures (MPa).
    tol : float
        Collocation tolerance of solve_bvp (unitless, relative), > 0.

    Returns
    -------
    InflationCurve
        Outer and inner diameters (mm).

    Examples
    --------
    >>> from exofric.material import MooneyRivlin
    >>> c = compressible_inflation(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.4])
    >>> round(float(c.outer_diameter_mm[0]), 3)
    9.584
    """
    from scipy.integrate import solve_bvp  # lazy: scipy.integrate only when this runs

    A, B = _radii(tube_od_mm, tube_id_mm)
    p_req = check_pressures("pressures_mpa", pressures_mpa)

    def rhs(R: np.ndarray, y: np.ndarray) -> np.ndarray:
        r, lr = y
        lt = r / R
        P_rR, P_tT = _piola(lr, lt, material)
        drr, drt = _piola_jac(lr, lt, material)
        dlt = (lr - lt) / R
        dlr = -((P_rR - P_tT) / R + drt * dlt) / drr
        return np.vstack([lr, dlr])

    R = np.linspace(A, B, 41)
    y = np.vstack([R.copy(), np.ones_like(R)])
    out_o = np.empty_like(p_req)
    out_i = np.empty_like(p_req)
    p_done = 0.0
    for k, p_target in enumerate(p_req):
        # continuation in sub-steps of at most 0.02 MPa for robust initial guesses
        n_sub = max(1, int(np.ceil((p_target - p_done) / 0.02)))
        for p in np.linspace(p_done, p_target, n_sub + 1)[1:]:

            def bc(ya: np.ndarray, yb: np.ndarray, p: float = p) -> np.ndarray:
                return np.array(
                    [
                        _piola(np.array(ya[1]), np.array(ya[0] / A), material)[0] + p * ya[0] / A,
                        _piola(np.array(yb[1]), np.array(yb[0] / B), material)[0],
                    ]
                )

            sol = solve_bvp(rhs, bc, R, y, tol=tol, max_nodes=20000, bc_tol=1e-12)
            if not sol.success:
                raise ConvergenceError(
                    f"1D reference did not converge at {p:.4g} MPa ({sol.message}); the pressure "
                    "may exceed the tube's limit pressure",
                    reached=p_done,
                )
            R, y = sol.x, sol.y
            p_done = float(p)
        out_i[k] = 2.0 * y[0, 0]
        out_o[k] = 2.0 * y[0, -1]
    return InflationCurve(p_req, out_o, out_i, "compressible 1D radial BVP (solve_bvp)")


# --- generalised plane strain: closed / open ends ---------------------------------------------

#: The end conditions :func:`tube_inflation` knows, in the order its messages list them.
TUBE_ENDS: tuple[str, ...] = ("closed", "open", "plane-strain")
_GAUSS_POINTS = 64  # Gauss-Legendre nodes across the wall (integrands smooth in R: ~1e-14 rel.)


@checked_init
@dataclass(frozen=True)
class TubeInflationCurve(DisplayMixin):
    """Tube diameters (mm) and axial stretch at each pressure (MPa), incompressible reference.

    Attributes
    ----------
    pressure_mpa : ndarray
        Pressures (MPa).
    outer_diameter_mm, inner_diameter_mm : ndarray
        Deformed outer and inner diameters (mm) at each pressure.
    axial_stretch : ndarray
        Uniform axial stretch ``l_z`` (unitless) at each pressure; 1 in plane strain.
    ends : str
        End condition: ``"closed"``, ``"open"`` or ``"plane-strain"``.
    method : str
        Which reference produced the curve.

    Examples
    --------
    >>> from exofric.material import MooneyRivlin
    >>> c = tube_inflation(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.2], ends="open")
    >>> round(float(c.axial_stretch[0]), 4) < 1.0
    True
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    inner_diameter_mm: np.ndarray
    axial_stretch: np.ndarray
    ends: str
    method: str

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict (unit-suffixed keys; ``axial_stretch`` is unitless).

        Returns
        -------
        dict
            ``method``, ``ends`` and the per-pressure lists.
        """
        return {
            "method": self.method,
            "ends": self.ends,
            "pressure_mpa": self.pressure_mpa.tolist(),
            "outer_diameter_mm": self.outer_diameter_mm.tolist(),
            "inner_diameter_mm": self.inner_diameter_mm.tolist(),
            "axial_stretch": self.axial_stretch.tolist(),
        }

    def to_frame(self) -> pd.DataFrame:
        """One row per pressure: ``pressure_mpa``, ``outer_diameter_mm``, ``inner_diameter_mm``,
        ``axial_stretch`` (unitless).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.material import MooneyRivlin
        >>> c = tube_inflation(8.3, 4.97, MooneyRivlin.from_shore(62.5), [0.0, 0.1])
        >>> list(c.to_frame().columns)
        ['pressure_mpa', 'outer_diameter_mm', 'inner_diameter_mm', 'axial_stretch']
        """
        import pandas as pd

        return pd.DataFrame({
            "pressure_mpa": self.pressure_mpa,
            "outer_diameter_mm": self.outer_diameter_mm,
            "inner_diameter_mm": self.inner_diameter_mm,
            "axial_stretch": self.axial_stretch,
        })


def _principal_tensions(
    model: HyperelasticModel,
) -> Callable[[np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, ...]]:
    """``(l1, l2, l3) -> t_i = l_i dW/dl_i`` (MPa) up to one common hydrostatic term.

    Own closed forms for an incompressible material (J = 1), written from the energies in the
    module docstring of :mod:`exofric.material._hyperelastic`, not taken from the FE code: only
    differences ``t_i - t_j`` are used, so the term common to all three (the isochoric
    projection, the pressure) drops out. MR uses ``I2 = sum l_i^-2`` at J = 1.
    """
    p = model.params
    name = model.name
    if name.startswith("ogden"):
        pairs = list(zip(p[0::2], p[1::2], strict=True))

        def ogden(l1: np.ndarray, l2: np.ndarray, l3: np.ndarray) -> tuple[np.ndarray, ...]:
            out = []
            for li in (l1, l2, l3):
                ti = np.zeros_like(li)
                for m, a in pairs:
                    ti = ti + 2.0 * m / a * li**a
                out.append(ti)
            return tuple(out)

        return ogden
    c10 = p[0]
    c01 = p[1] if name == "mooney-rivlin" else 0.0
    c20, c30 = (p[1], p[2]) if name == "yeoh" else (0.0, 0.0)

    def invariant(l1: np.ndarray, l2: np.ndarray, l3: np.ndarray) -> tuple[np.ndarray, ...]:
        i1m3 = l1 * l1 + l2 * l2 + l3 * l3 - 3.0
        w1 = c10 + 2.0 * c20 * i1m3 + 3.0 * c30 * i1m3**2
        return tuple(2.0 * w1 * li * li - 2.0 * c01 / (li * li) for li in (l1, l2, l3))

    return invariant


def tube_inflation(
    tube_od_mm: float,
    tube_id_mm: float,
    material: MooneyRivlin | HyperelasticModel,
    pressures_mpa: np.ndarray | list[float],
    *,
    ends: str = "closed",
) -> TubeInflationCurve:
    """Incompressible inflation of a thick tube with closed or open ends (generalised plane strain).

    Semi-analytic reference for the FE solver with one uniform axial stretch unknown.
    Undeformed radii ``A < B``; deformed inner radius ``a`` and uniform axial stretch ``l_z``;
    exactly incompressible (``d`` is ignored)::

        r^2 = a^2 + (R^2 - A^2)/l_z,   l_t = r/R,   l_r = 1/(l_t l_z)
        P   = int_a^b (s_tt - s_rr) / r dr                          (radial equilibrium)
        F   = pi int_a^b (2 s_zz - s_tt - s_rr) r dr                (reduced axial force)

    with ``s_tt - s_rr = t_t - t_r``, ``s_zz - s_rr = t_z - t_r`` and ``t_i = l_i dW/dl_i``.
    Integrating ``d(r^2 s_rr)/dr = r (s_rr + s_tt)`` gives the wall's axial force
    ``N = 2 pi int s_zz r dr = F + P pi a^2``. Closed ends (the caps carry the pressure,
    ``N = P pi a^2``): ``F = 0``; open ends (``N = 0``): ``F = -P pi a^2``; plane strain:
    ``l_z = 1`` (the first equation alone). The integrals are taken over ``R`` by a 64-point
    Gauss-Legendre rule (``r dr = R dR / l_z``; 16 points already agree with adaptive
    quadrature to 1e-14); ``(a, l_z)`` by ``scipy.optimize.root`` (residuals below 1e-11 of
    ``mu ln(B/A)`` and ``mu pi (B^2 - A^2)``) with continuation in pressure from the
    undeformed state, in steps that keep ``a`` growing by less than 10 %.

    Parameters
    ----------
    tube_od_mm, tube_id_mm : float
        Undeformed outer and inner diameters (mm), ``0 < tube_id_mm < tube_od_mm``.
    material : MooneyRivlin or HyperelasticModel
        C10, C01 (MPa), or any model of :func:`~exofric.material.material_model`
        (neo-Hookean, Mooney-Rivlin, Yeoh, Ogden 1-3; ABAQUS Ogden convention).
    pressures_mpa : array-like
        Strictly increasing internal pressures (MPa), ``>= 0``.
    ends : {'closed', 'open', 'plane-strain'}
        End condition (unitless label): closed ends with caps, open (free) ends, or plane
        strain (``l_z = 1``; equals :func:`incompressible_inflation` for neo-Hookean and
        Mooney-Rivlin with ``mu = 2 (C10 + C01)``).

    Returns
    -------
    TubeInflationCurve
        Outer and inner diameters (mm) and axial stretch (unitless) at each pressure.

    Raises
    ------
    InputError
        Bad diameters, pressures, material or ``ends`` (one line naming the field).
    ConvergenceError
        Past the limit pressure (no equilibrium on the loading branch): names the pressure;
        ``reached`` is the last converged pressure (MPa).

    Examples
    --------
    >>> from exofric.material import MooneyRivlin
    >>> m = MooneyRivlin.from_shore(62.5)
    >>> c = tube_inflation(8.3, 4.97, m, [0.1, 0.4], ends="closed")
    >>> [round(float(x), 3) for x in c.outer_diameter_mm]
    [8.492, 9.501]
    >>> [round(float(x), 4) for x in c.axial_stretch]
    [1.0009, 1.0304]
    """
    from exofric.material import HyperelasticModel

    A, B = _radii(tube_od_mm, tube_id_mm)
    if not isinstance(ends, str) or ends not in TUBE_ENDS:
        raise InputError(f"ends must be one of {', '.join(TUBE_ENDS)}, got {ends!r}",
                         param="ends")
    if isinstance(material, MooneyRivlin):
        model = material.to_model()
    elif isinstance(material, HyperelasticModel):
        model = material
    else:
        raise InputError("material must be a MooneyRivlin or a HyperelasticModel, got "
                         f"{type(material).__name__}", param="material")
    p_req = check_pressures("pressures_mpa", pressures_mpa)
    from scipy.optimize import root  # lazy: scipy.optimize only when a reference is computed

    tension = _principal_tensions(model)
    mu = model.shear_modulus_mpa
    xg, wg = np.polynomial.legendre.leggauss(_GAUSS_POINTS)
    Rg = 0.5 * (B + A) + 0.5 * (B - A) * xg
    wg = 0.5 * (B - A) * wg
    p_scale = mu * np.log(B / A)  # plane-strain neo-Hookean limit pressure: a pressure scale
    f_scale = mu * np.pi * (B**2 - A**2)
    free_z = ends != "plane-strain"

    def state(x: np.ndarray) -> tuple[float, float, np.ndarray, np.ndarray]:
        a = A * np.exp(x[0])
        lz = float(np.exp(x[1])) if free_z else 1.0
        r2 = a * a + (Rg * Rg - A * A) / lz
        lt = np.sqrt(r2) / Rg
        t_r, t_t, t_z = tension(1.0 / (lt * lz), lt, np.full_like(lt, lz))
        return a, lz, r2, np.vstack([t_t - t_r, t_z - t_r])

    def residual(x: np.ndarray, p: float) -> np.ndarray:
        a, lz, r2, d = state(x)
        pressure = float(np.sum(wg * d[0] * Rg / (lz * r2)))
        res = [(pressure - p) / p_scale]
        if free_z:
            force = np.pi * float(np.sum(wg * (2.0 * d[1] - d[0]) * Rg / lz))
            target = 0.0 if ends == "closed" else -p * np.pi * a * a
            res.append((force - target) / f_scale)
        return np.asarray(res)

    x = np.zeros(2 if free_z else 1)
    p_done = 0.0
    step = p_scale / 20.0
    a_out = np.empty_like(p_req)
    lz_out = np.empty_like(p_req)
    for k, p_target in enumerate(p_req):
        while p_done < p_target:
            p = min(p_target, p_done + step)
            sol = root(residual, x, args=(p,), method="hybr", options={"xtol": 1e-14})
            # accept: residual 1e-11 of the scales, a step in ln a below 0.1 and a growing
            # (the loading branch, continued in small steps), a <= 1e3 B
            ok = bool(np.all(np.isfinite(sol.x)) and np.max(np.abs(sol.fun)) < 1e-11)
            ok = ok and x[0] <= sol.x[0] < x[0] + 0.1 and A * np.exp(sol.x[0]) <= 1e3 * B
            if not ok:
                step *= 0.5
                if step < 1e-9 * p_scale:
                    raise ConvergenceError(
                        f"tube_inflation: no equilibrium at {p_target:g} MPa ({ends} ends): "
                        f"past the limit pressure, last converged {p_done:.6g} MPa",
                        reached=p_done,
                    )
                continue
            x = sol.x
            p_done = p
            step = min(2.0 * step, p_scale / 20.0)
        a_out[k], lz_out[k] = state(x)[:2]
    b_out = np.sqrt(a_out**2 + (B**2 - A**2) / lz_out)
    method = f"incompressible semi-analytic, generalised plane strain ({ends} ends)"
    if not free_z:
        method = "incompressible semi-analytic (plane strain)"
    return TubeInflationCurve(p_req, 2.0 * b_out, 2.0 * a_out, lz_out, ends, method)
