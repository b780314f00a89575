"""Tolerances propagated to the squeezing force N(P) (issue 19, second part).

Real tubes, holes and wires have tolerances, and the tube's ID and hardness are uncertain (the
paper prints no ID; +-0.35 mm of ID moves N(0.3 MPa) by -25/+30 %). Each tolerance is a normal
distribution (a standard deviation around the nominal value); :func:`squeeze_tolerances`
propagates them to N(P) with scrambled Sobol quasi-Monte Carlo (``scipy.stats.qmc``) and reports
percentile bands, and ranks the tolerances by their first-order contribution to the variance of N
at each pressure (central finite differences at the nominal design times the standard
deviation: a linearisation, stated as such).

Tolerance names: ``hole_mm``, ``tube_od_mm``, ``tube_id_mm``, ``wire_mm`` (mm) and ``shore``
(Shore A; the material follows Eqs 3-6 of the paper).

Units: mm, MPa, N.

Examples
--------
>>> from exofric.geometry import BASE
>>> r = squeeze_tolerances(BASE, 62.5, [0.6], {"tube_id_mm": 0.05}, samples=8,
...                        accuracy="draft")
>>> r.percentiles_n[50][0] > 0.0, r.ranking[0][0]
(True, 'tube_id_mm')
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from exofric.errors import ConvergenceError, InputError, check_positive, check_seed
from exofric.geometry import Structure
from exofric.simulate._squeeze import squeeze

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["TOLERANCE_NAMES", "ToleranceResult", "squeeze_tolerances"]

#: What can carry a tolerance (mm, except shore in Shore A).
TOLERANCE_NAMES = ("hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm", "shore")
_PCTS = (5, 50, 95)


@dataclass(frozen=True)
class ToleranceResult:
    """Percentile bands of N(P) under tolerances, and which tolerance matters most.

    Attributes
    ----------
    pressure_mpa : tuple of float
        Pressures (MPa).
    nominal_n : tuple of float
        N(P) of the nominal design (N, total over the length).
    percentiles_n : dict of int -> tuple of float
        5th, 50th and 95th percentiles of N(P) over the samples (N).
    samples_n : ndarray
        N(P) of every sample (N), shape (samples, pressures).
    ranking : tuple of (str, tuple of float)
        Tolerances by decreasing first-order share of the variance of N at the highest pressure,
        with their share (0-1) at each pressure.
    tolerances : dict of str -> float
        The standard deviations (mm or Shore A).
    failed : int
        Samples whose squeeze did not converge or whose geometry was impossible (left out).

    Examples
    --------
    >>> ToleranceResult.__name__
    'ToleranceResult'
    """

    pressure_mpa: tuple[float, ...]
    nominal_n: tuple[float, ...]
    percentiles_n: dict[int, tuple[float, ...]]
    samples_n: NDArray[np.float64]
    ranking: tuple[tuple[str, tuple[float, ...]], ...]
    tolerances: dict[str, float]
    failed: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``squeeze_force_n`` (nominal) and ``squeeze_force_n_p05/p50/p95`` (N)."""
        d: dict[str, Any] = {"pressure_mpa": list(self.pressure_mpa),
                             "squeeze_force_n": list(self.nominal_n)}
        for q, v in self.percentiles_n.items():
            d[f"squeeze_force_n_p{q:02d}"] = list(v)
        d["sensitivity"] = [{"tolerance": k, "variance_share": list(v)}
                            for k, v in self.ranking]
        d["tolerances"] = dict(self.tolerances)
        d["samples"] = int(self.samples_n.shape[0])
        d["failed"] = self.failed
        return d

    def to_frame(self) -> pd.DataFrame:
        """One row per pressure: nominal N and its percentiles (N).

        Returns
        -------
        pandas.DataFrame
        """
        import pandas as pd

        cols = {"pressure_mpa": self.pressure_mpa, "squeeze_force_n": self.nominal_n}
        cols.update({f"squeeze_force_n_p{q:02d}": v for q, v in self.percentiles_n.items()})
        return pd.DataFrame(cols)


def _design(structure: Structure, shore: float, name: str, value: float
            ) -> tuple[Structure, float]:
    if name == "shore":
        return structure, value
    changes: dict[str, Any] = {name: value}
    return replace(structure, **changes), shore


def squeeze_tolerances(
    structure: Structure,
    shore: float,
    pressures_mpa: ArrayLike,
    tolerances: dict[str, float],
    *,
    samples: int = 64,
    seed: int = 0,
    solver: Callable[..., Any] | None = None,
    **squeeze_options: Any,
) -> ToleranceResult:
    """Propagate normal tolerances on the sizes and the hardness to N(P) (module docstring).

    Parameters
    ----------
    structure : Structure
        The nominal design (mm).
    shore : float
        Nominal Shore A hardness (the material follows the paper's Eqs 3-6).
    pressures_mpa : array_like
        Strictly increasing pressures (MPa).
    tolerances : dict
        Standard deviation per name in :data:`TOLERANCE_NAMES` (mm, Shore A), > 0 and smaller
        than the nominal value.
    samples : int
        Quasi-Monte Carlo samples (8-4096; a power of 2 keeps the Sobol sequence balanced).
    seed : int
        Seed of the scrambled Sobol sequence.
    solver : callable, optional
        ``solver(structure, material, pressures_mpa)`` returning an object with
        ``squeeze_force_n`` (N), used instead of :func:`squeeze` (e.g. a clearance distribution
        around each sample's nominal clearance, :func:`squeeze_with_clearance`).
    **squeeze_options
        Passed to :func:`exofric.simulate.squeeze`.

    Returns
    -------
    ToleranceResult

    Raises
    ------
    InputError
        Unknown tolerance names, a non-positive sd, an sd not smaller than the nominal value,
        an impossible nominal design, or fewer than 4 samples that solve.
    ConvergenceError
        The nominal design's squeeze does not converge.

    Examples
    --------
    >>> from exofric.geometry import BASE
    >>> try:
    ...     squeeze_tolerances(BASE, 62.5, [0.6], {"colour": 1.0})
    ... except ValueError as exc:
    ...     print(str(exc)[:38])
    tolerances: unknown name 'colour' (kno
    """
    from scipy.stats import norm, qmc

    from exofric.material import MooneyRivlin

    if not tolerances:
        raise InputError("tolerances must name at least one of " + ", ".join(TOLERANCE_NAMES))
    names = list(tolerances)
    for k in names:
        if k not in TOLERANCE_NAMES:
            raise InputError(f"tolerances: unknown name {k!r} (known: "
                             f"{', '.join(TOLERANCE_NAMES)})", param="tolerances")
    nominal = {k: (float(shore) if k == "shore" else float(getattr(structure, k))) for k in names}
    sd = {}
    for k in names:
        sd[k] = check_positive(f"tolerance {k}", tolerances[k])
        if sd[k] >= nominal[k]:
            raise InputError(f"tolerance {k} = {sd[k]:g} is not smaller than the value "
                             f"{nominal[k]:g}", param="tolerances")
    if not isinstance(samples, int) or not 8 <= samples <= 4096:
        raise InputError(f"samples must be an integer in [8, 4096], got {samples!r}")
    seed = check_seed("seed", seed)
    p = np.asarray(pressures_mpa, dtype=float).ravel()
    squeeze_options.setdefault("keep_fields", False)

    def run(values: dict[str, float]) -> NDArray[np.float64]:
        """N(P) (N) of the design with ``values`` changed."""
        st, sh = structure, float(shore)
        for k, v in values.items():
            st, sh = _design(st, sh, k, v)
        mat = MooneyRivlin.from_shore(sh)
        r = solver(st, mat, p) if solver is not None else squeeze(st, mat, p, **squeeze_options)
        return np.asarray(r.squeeze_force_n, dtype=float)

    def solve(values: dict[str, float]) -> NDArray[np.float64] | None:
        """As ``run``, None for a sample that cannot be solved (impossible or not converged)."""
        try:
            return run(values)
        except (InputError, ConvergenceError):
            return None

    base = run({})    # the nominal design's own InputError or ConvergenceError reaches the user
    u = qmc.Sobol(d=len(names), scramble=True, seed=seed).random(samples)
    z = norm.ppf(np.clip(u, 1e-12, 1 - 1e-12))
    rows, failed = [], 0
    for zi in z:
        r = solve({k: nominal[k] + sd[k] * float(zi[j]) for j, k in enumerate(names)})
        if r is None:
            failed += 1
        else:
            rows.append(r)
    if len(rows) < 4:
        raise InputError(f"only {len(rows)} of {samples} samples solved: the tolerances make "
                         "most designs impossible (tube and wire must fit the hole)")
    arr = np.array(rows)
    pct = {q: tuple(np.percentile(arr, q, axis=0).tolist()) for q in _PCTS}
    # first-order variance shares from central differences at the nominal design
    contrib = []
    for k in names:
        hi = solve({k: nominal[k] + 0.5 * sd[k]})
        lo = solve({k: nominal[k] - 0.5 * sd[k]})
        slope_sd = np.zeros_like(base) if hi is None or lo is None else (hi - lo)
        contrib.append(slope_sd**2)
    c = np.array(contrib)
    total = c.sum(axis=0)
    share = np.divide(c, total, out=np.zeros_like(c), where=total > 0)
    order = np.argsort(-share[:, -1])
    ranking = tuple((names[i], tuple(share[i].tolist())) for i in order)
    return ToleranceResult(tuple(p.tolist()), tuple(base.tolist()), pct, arr, ranking,
                           {k: sd[k] for k in names}, failed)
