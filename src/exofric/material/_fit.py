"""Fit a hyperelastic model to uniaxial, equibiaxial and planar test data at once.

Least squares (:func:`scipy.optimize.least_squares`, trust-region reflective, bounded) on the
nominal (engineering) stress of every data point of every mode given, stacked in one residual
vector. Data given as true (Cauchy) stress are converted first: in all three modes the loaded
direction's ``sigma = l P``.

Residuals are **absolute** (MPa) by default: a rig's stress error is mostly the load cell's
and the area's, roughly the same size at every point, and absolute residuals stay defined at
``P = 0`` (the unloaded point). ``residuals="relative"`` divides by the measured stress
(what many papers and FElupe's ``relative=True`` fit), weighting the small-strain points
more; it refuses data with a zero stress.

Parameter uncertainty: the covariance ``s^2 (J^T J)^+`` from the Jacobian ``J`` of the
residuals at the optimum and the residual variance ``s^2 = SSR / (n - p)``; standard errors are
its diagonal's square roots, the correlation matrix its normalised form (a linearisation: with a
bound active or strongly correlated parameters they are indicative only).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from exofric.errors import InputError, warn_implausible
from exofric.material._hyperelastic import (
    HYPERELASTIC_MODELS,
    MODES,
    STRESS_KINDS,
    HyperelasticModel,
    StabilityCheck,
    material_model,
)
from exofric.material._models import MaterialRangeWarning

if TYPE_CHECKING:
    import numpy as np
    import pandas as pd
    from numpy.typing import ArrayLike, NDArray

__all__ = ["MaterialFit", "ModeFit", "fit_material"]

RESIDUALS = ("absolute", "relative")


@dataclass(frozen=True)
class ModeFit:
    """Data and goodness of fit of one test mode.

    Attributes
    ----------
    mode : str
        ``uniaxial``, ``biaxial`` or ``planar``.
    stretch : numpy.ndarray
        Stretches of the data (unitless).
    stress_mpa : numpy.ndarray
        Measured nominal (engineering) stress in MPa (converted from true stress if so given).
    fitted_mpa : numpy.ndarray
        The fitted model's nominal stress at the same stretches, MPa.
    r2 : float
        Coefficient of determination of the nominal stress (unitless; NaN for one point).
    rms_mpa : float
        Root-mean-square of ``fitted - measured`` in MPa.
    stress_kind : str
        How the data were given: ``engineering`` or ``true``.

    Examples
    --------
    >>> from exofric.material import fit_material, treloar_1944
    >>> fit = fit_material("neo-hookean", **treloar_1944())
    >>> fit.modes["uniaxial"].stretch.size
    24
    """

    mode: str
    stretch: NDArray[np.float64]
    stress_mpa: NDArray[np.float64]
    fitted_mpa: NDArray[np.float64]
    r2: float
    rms_mpa: float
    stress_kind: str = "engineering"

    @property
    def residual_mpa(self) -> NDArray[np.float64]:
        """``fitted - measured`` nominal stress per point, MPa."""
        return self.fitted_mpa - self.stress_mpa

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: points, stretch range, R^2, RMS (MPa), stress kind.

        Returns
        -------
        dict
            Keys ``n_points``, ``stretch_min``, ``stretch_max``, ``r2``, ``rms_mpa``,
            ``stress_kind``.
        """
        return {"n_points": int(self.stretch.size), "stretch_min": float(self.stretch.min()),
                "stretch_max": float(self.stretch.max()), "r2": self.r2,
                "rms_mpa": self.rms_mpa, "stress_kind": self.stress_kind}


@dataclass(frozen=True)
class MaterialFit:
    """A hyperelastic model fitted to test data, with its uncertainty and stability.

    Attributes
    ----------
    model : HyperelasticModel
        The fitted model (parameters in MPa or unitless, d in 1/MPa).
    stderr : tuple of float
        Standard error of each parameter, same order and unit as ``model.params`` (NaN when
        there are no more points than parameters).
    correlation : numpy.ndarray
        Correlation matrix of the parameters (unitless, p x p).
    modes : dict of str to ModeFit
        Per mode fitted: data, fitted stress, R^2 and RMS (MPa).
    stability : StabilityCheck
        Drucker check (``dP/dl > 0`` on all three paths) over the data's stretch range.
    residuals : str
        ``absolute`` (MPa) or ``relative`` (unitless) residuals were minimised.
    cost : float
        Half the sum of squared residuals at the optimum (MPa^2 for absolute residuals).
    warnings : tuple of str
        What the fit warned about (instability allowed, parameters near a bound, strong
        correlation).

    Examples
    --------
    >>> from exofric.material import fit_material, treloar_1944
    >>> fit = fit_material("yeoh", **treloar_1944())
    >>> fit.stability.stable, round(fit.modes["uniaxial"].r2, 3)
    (True, 0.995)
    """

    model: HyperelasticModel
    stderr: tuple[float, ...]
    correlation: NDArray[np.float64]
    modes: dict[str, ModeFit]
    stability: StabilityCheck
    residuals: str = "absolute"
    cost: float = 0.0
    warnings: tuple[str, ...] = field(default=())

    @property
    def stretch_range(self) -> tuple[float, float]:
        """Smallest and largest stretch of the data, all modes (unitless), with 1 included."""
        lo = min([1.0, *(float(m.stretch.min()) for m in self.modes.values())])
        hi = max([1.0, *(float(m.stretch.max()) for m in self.modes.values())])
        return lo, hi

    def stress_mpa(self, mode: str, stretch: ArrayLike,
                   kind: str = "engineering") -> NDArray[np.float64]:
        """The fitted model's stress (MPa); warns outside the data's stretch range.

        A :class:`MaterialRangeWarning` says when a stretch lies outside the range of that
        mode's data (with 1 included), or when the mode had no data: the model then
        extrapolates.

        Parameters
        ----------
        mode : {'uniaxial', 'biaxial', 'planar'}
            The homogeneous test mode.
        stretch : array_like of float
            Stretch (unitless), > 0.
        kind : {'engineering', 'true'}
            Nominal or Cauchy stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa.
        """
        import numpy as np

        out = self.model.stress_mpa(mode, stretch, kind)
        lam = np.asarray(stretch, dtype=float)
        m = self.modes.get(mode)
        if m is None:
            warnings.warn(f"the fit had no {mode} data: its {mode} stress is a prediction",
                          MaterialRangeWarning, stacklevel=2)
        else:
            lo, hi = min(1.0, float(m.stretch.min())), max(1.0, float(m.stretch.max()))
            if np.any(lam < lo) or np.any(lam > hi):
                warnings.warn(f"{mode} stretch outside the fitted data's range {lo:g}-{hi:g}: "
                              "the model extrapolates", MaterialRangeWarning, stacklevel=2)
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: model, params (with units), standard errors, correlation, modes.

        Returns
        -------
        dict
            ``model``, ``params`` and ``stderr`` by name (``_mpa`` suffix: MPa),
            ``param_units``, ``correlation`` (``names``, ``matrix``), ``shear_modulus_mpa``,
            ``d_per_mpa``, ``bulk_modulus_mpa``, ``residuals``, ``modes`` (R^2, RMS in MPa,
            stretch range), ``stability`` and ``warnings``.
        """
        names = self.model.param_names
        d = self.model.to_dict()
        d.update({
            "param_units": {n: "MPa" if n.endswith("_mpa") else "unitless" for n in names},
            "stderr": dict(zip(names, self.stderr, strict=True)),
            "correlation": {"names": list(names),
                            "matrix": [[float(v) for v in row] for row in self.correlation]},
            "residuals": self.residuals,
            "modes": {k: m.to_dict() for k, m in self.modes.items()},
            "stability": self.stability.to_dict(),
            "warnings": list(self.warnings),
        })
        return d

    def to_frame(self) -> pd.DataFrame:
        """One row per data point: mode, stretch, measured and fitted stress, residual (MPa).

        Returns
        -------
        pandas.DataFrame
            Columns ``mode``, ``stretch``, ``stress_mpa``, ``fitted_mpa``, ``residual_mpa``.
        """
        import pandas as pd

        frames = [pd.DataFrame({"mode": k, "stretch": m.stretch, "stress_mpa": m.stress_mpa,
                                "fitted_mpa": m.fitted_mpa, "residual_mpa": m.residual_mpa})
                  for k, m in self.modes.items()]
        return pd.concat(frames, ignore_index=True)

    def plot(self, fig: Any | None = None) -> Any:
        """Data and fitted curves per mode (nominal stress, MPa) over a residual panel.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            An empty figure to draw on (default a new one).

        Returns
        -------
        matplotlib Figure
        """
        from exofric.plots import plot_material_fit

        return plot_material_fit(self, fig)


def _mode_data(mode: str, data: Any, kind: str) -> tuple[NDArray[np.float64],
                                                        NDArray[np.float64]]:
    import numpy as np

    try:
        stretch, stress = data
        lam = np.asarray(stretch, dtype=float).ravel()
        p = np.asarray(stress, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{mode} must be a pair (stretch, stress_mpa) of number lists",
                         param=mode) from None
    if lam.size != p.size:
        raise InputError(f"{mode}: stretch and stress_mpa must have the same length, got "
                         f"{lam.size} and {p.size}", param=mode)
    if lam.size == 0:
        raise InputError(f"{mode}: no data points", param=mode)
    for name, a in (("stretch", lam), ("stress_mpa", p)):
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise InputError(f"{mode}: {name} must be finite, got {a[bad[0]]} at index "
                             f"{bad[0]}", param=mode)
    bad = np.flatnonzero(lam <= 0.0)
    if bad.size:
        raise InputError(f"{mode}: stretch must be > 0 (unitless), got {lam[bad[0]]:g} at index "
                         f"{bad[0]}", param=mode)
    step = np.diff(lam)
    if lam.size > 1 and not (np.all(step > 0.0) or np.all(step < 0.0)):
        i = int(np.flatnonzero(step * (1 if step[0] > 0 else -1) <= 0.0)[0]) + 1
        raise InputError(f"{mode}: stretch must be strictly monotonic (one loading curve), got "
                         f"{lam[i - 1]:g} then {lam[i]:g} at index {i}", param=mode)
    if kind == "true":
        p = p / lam  # sigma = l P in the loaded direction of all three modes
    return lam, p


def _g0(data: dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]) -> float:
    """A shear-modulus estimate (MPa): neo-Hookean moduli of the points nearest l = 1."""
    import numpy as np

    est = []
    for mode, (lam, p) in data.items():
        l1, l2, l3 = lam, *({"uniaxial": (lam ** -0.5, lam ** -0.5), "biaxial": (lam, lam ** -2),
                             "planar": (np.ones_like(lam), 1 / lam)}[mode])
        k = l2 if mode == "uniaxial" else l3
        den = (l1 ** 2 - k ** 2) / lam
        ok = np.abs(den) > 1e-9
        g = p[ok] / den[ok]
        order = np.argsort(np.abs(np.log(lam[ok])))[:3]
        est.extend(g[order].tolist())
    g0 = float(np.median(est)) if est else 1.0
    return g0 if np.isfinite(g0) and g0 > 0 else 1.0


def _starts(name: str, g: float) -> list[tuple[list[float], list[float], list[float]]]:
    """Initial guesses and bounds ``(x0, lower, upper)`` for each start."""
    inf = float("inf")
    if name == "neo-hookean":
        return [([g / 2], [0.0], [inf])]
    if name == "mooney-rivlin":
        return [([0.4 * g, 0.1 * g], [-inf, -inf], [inf, inf])]
    if name == "yeoh":
        return [([g / 2, -1e-2 * g, 1e-4 * g], [0.0, -inf, -inf], [inf, inf, inf])]
    n = int(name[-1])
    table: dict[int, list[tuple[float, ...]]] = {1: [(2.0,), (1.3,), (3.0,)],
                2: [(1.5, 5.0), (2.0, -2.0), (3.0, -1.0)],
                3: [(1.3, 5.0, -2.0), (2.0, 4.0, -2.0), (1.0, 3.0, -1.0)]}
    patterns = table[n]
    out = []
    for alphas in patterns:
        mus = [0.95 * g] + [0.02 * g * (1 if a > 0 else -1) for a in alphas[1:]]
        x0 = [v for pair in zip(mus, alphas, strict=True) for v in pair]
        lo = [v for _ in range(n) for v in (-100 * max(g, 1e-3), -30.0)]
        hi = [v for _ in range(n) for v in (100 * max(g, 1e-3), 30.0)]
        out.append((x0, lo, hi))
    return out


def fit_material(
    model: str,
    uniaxial: Any = None,
    biaxial: Any = None,
    planar: Any = None,
    *,
    stress_kind: str | dict[str, str] = "engineering",
    residuals: str = "absolute",
    d: float | None = None,
    poisson: float = 0.498,
    allow_unstable: bool = False,
) -> MaterialFit:
    """Fit a hyperelastic model to one or several homogeneous test modes at once.

    Parameters
    ----------
    model : str
        Model name (see :func:`material_model`): ``neo-hookean``, ``mooney-rivlin``, ``yeoh``,
        ``ogden1``, ``ogden2``, ``ogden3``.
    uniaxial, biaxial, planar : (array_like, array_like) or None
        Per test mode, ``(stretch, stress_mpa)``: stretch of the loaded direction (unitless,
        > 0, strictly monotonic) and its stress in MPa. At least one mode.
    stress_kind : {'engineering', 'true'} or dict
        How the stresses are given: nominal (force per undeformed area) or Cauchy (true);
        one for all modes or a dict per mode.
    residuals : {'absolute', 'relative'}
        Minimise ``P_model - P_data`` (MPa; default) or ``(P_model - P_data) / P_data``.
    d : float, optional
        Incompressibility parameter d of the result in 1/MPa (not fitted: the homogeneous
        tests are incompressible). Default from ``poisson`` and the fitted shear modulus.
    poisson : float
        Small-strain Poisson ratio nu in (0, 0.5) for the default d (``2 (1 - 2 nu) / mu``).
    allow_unstable : bool
        Accept a fit that is Drucker-unstable within the data's stretch range (then a
        warning); default: :class:`~exofric.errors.InputError`.

    Returns
    -------
    MaterialFit

    Raises
    ------
    InputError
        Unknown model, bad data (stretch <= 0, not monotonic, lengths), fewer points than
        parameters, no mode given, or an unstable fit without ``allow_unstable``.

    Examples
    --------
    >>> import numpy as np
    >>> stretch = np.linspace(1.1, 3.0, 8)
    >>> stress = 2 * 0.2 * (stretch - stretch**-2)       # neo-Hookean C10 = 0.2 MPa
    >>> fit = fit_material("neo-hookean", uniaxial=(stretch, stress))
    >>> round(fit.model.params[0], 6), fit.stability.stable
    (0.2, True)
    """
    import numpy as np
    from scipy.optimize import least_squares

    if not isinstance(model, str):
        raise InputError(f"model must be a model name, got {model!r}", param="model")
    name = model.strip().lower().replace("_", "-")
    name = {"neohookean": "neo-hookean", "mooneyrivlin": "mooney-rivlin"}.get(name, name)
    if name not in HYPERELASTIC_MODELS:
        raise InputError(f"model must be one of {', '.join(HYPERELASTIC_MODELS)}, got "
                         f"{model!r}", param="model")
    if residuals not in RESIDUALS:
        raise InputError(f"residuals must be one of {', '.join(RESIDUALS)}, got {residuals!r}",
                         param="residuals")
    kinds = (dict(stress_kind) if isinstance(stress_kind, dict)
             else dict.fromkeys(MODES, stress_kind))
    for k, v in kinds.items():
        if k not in MODES or v not in STRESS_KINDS:
            raise InputError(f"stress_kind must be one of {', '.join(STRESS_KINDS)} (per mode: "
                             f"{', '.join(MODES)}), got {k}={v!r}", param="stress_kind")
    given = {"uniaxial": uniaxial, "biaxial": biaxial, "planar": planar}
    data = {m: _mode_data(m, v, kinds.get(m, "engineering"))
            for m, v in given.items() if v is not None}
    if not data:
        raise InputError("fit_material needs data of at least one mode (uniaxial, biaxial, "
                         "planar)", param="uniaxial")
    n_par = len(HYPERELASTIC_MODELS[name])
    n_pts = sum(lam.size for lam, _ in data.values())
    if n_pts < n_par:
        raise InputError(f"{name} has {n_par} parameters: it needs at least {n_par} data "
                         f"points, got {n_pts}", param="model")
    if residuals == "relative":
        for m, (_, p) in data.items():
            zero = np.flatnonzero(p == 0.0)
            if zero.size:
                raise InputError(f"residuals 'relative' divides by the stress, but {m} has 0 at "
                                 f"index {zero[0]}: use 'absolute' or drop the point",
                                 param="residuals")
    lam_all = np.concatenate([lam for lam, _ in data.values()])
    p_all = np.concatenate([p for _, p in data.values()])
    scale = p_all if residuals == "relative" else np.ones_like(p_all)
    modes = list(data)

    def predict(x: NDArray[np.float64]) -> NDArray[np.float64]:
        mdl = _unchecked(name, x)
        return np.concatenate([np.asarray(mdl._stress(m, data[m][0], "engineering"))
                               for m in modes])

    def resid(x: NDArray[np.float64]) -> NDArray[np.float64]:
        with np.errstate(all="ignore"):
            r = (predict(x) - p_all) / scale
        return np.where(np.isfinite(r), r, 1e6)

    best = None
    g0 = _g0(data)
    for x0, lo, hi in _starts(name, g0):
        res = least_squares(resid, np.asarray(x0), bounds=(lo, hi), method="trf",
                            x_scale="jac", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=20000)
        if best is None or res.cost < best.cost:
            best = res
    assert best is not None
    x = best.x
    notes: list[str] = []
    dof = n_pts - n_par
    jac = best.jac
    if dof > 0:
        cov = np.linalg.pinv(jac.T @ jac) * (2.0 * best.cost / dof)
        se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        with np.errstate(all="ignore"):
            corr = cov / np.outer(se, se)
    else:
        se = np.full(n_par, np.nan)
        corr = np.full((n_par, n_par), np.nan)
    np.fill_diagonal(corr, 1.0)
    off = np.abs(corr[~np.eye(n_par, dtype=bool)])
    if off.size and np.nanmax(off) > 0.99:
        notes.append(f"parameters strongly correlated (|r| = {np.nanmax(off):.3f}): the data "
                     "do not pin each one down; add another test mode or a simpler model")
    x0_lo, x0_hi = (np.asarray(b, dtype=float) for b in _starts(name, g0)[0][1:])
    at_bound = (np.isfinite(x0_lo) & (np.abs(x - x0_lo) <= 1e-9 * np.maximum(1, np.abs(x0_lo))))
    at_bound |= np.isfinite(x0_hi) & (np.abs(x - x0_hi) <= 1e-9 * np.maximum(1, np.abs(x0_hi)))
    if np.any(at_bound):
        names = ", ".join(np.asarray(HYPERELASTIC_MODELS[name])[at_bound])
        notes.append(f"{names} at a bound of the fit: its standard error is indicative only")
    try:
        fitted = material_model(name, x, d=d, poisson=poisson)
    except InputError as exc:
        raise InputError(f"the {name} fit gives an invalid material ({exc}); try another "
                         "model", param="model") from None
    mode_fits = {}
    for m in modes:
        lam, p = data[m]
        f = np.asarray(fitted._stress(m, lam, "engineering"), dtype=float)
        ss_res = float(np.sum((f - p) ** 2))
        ss_tot = float(np.sum((p - p.mean()) ** 2))
        r2 = 1.0 - ss_res / ss_tot if p.size > 1 and ss_tot > 0 else float("nan")
        mode_fits[m] = ModeFit(m, lam, p, f, r2, float(np.sqrt(ss_res / p.size)),
                               kinds.get(m, "engineering"))
    lam_lo = min(1.0, float(lam_all.min()))
    lam_hi = max(1.0, float(lam_all.max()))
    stab = fitted.stability(lam_lo, lam_hi)
    if not stab.stable:
        where = ", ".join(f"{k} from stretch {v:.3g}" for k, v in stab.unstable_from.items()
                          if v is not None)
        msg = (f"the {name} fit is Drucker-unstable (dP/dl <= 0) inside the data's stretch "
               f"range {lam_lo:g}-{lam_hi:g}: {where}")
        if not allow_unstable:
            raise InputError(f"model: {msg}; use another model or allow_unstable",
                             param="model")
        notes.append(msg)
    for note in notes:
        warn_implausible(note)
    return MaterialFit(fitted, tuple(float(v) for v in se), corr, mode_fits, stab, residuals,
                       float(best.cost), tuple(notes))


def _unchecked(name: str, x: NDArray[np.float64]) -> HyperelasticModel:
    """A model without the input checks (inside the optimiser, where x may be anything)."""
    m = object.__new__(HyperelasticModel)
    object.__setattr__(m, "name", name)
    object.__setattr__(m, "params", tuple(float(v) for v in x))
    object.__setattr__(m, "d_per_mpa", 1.0)
    return m
