"""Inflation test data and calibration results (paper §3.3, Table 1, Fig 5b).

:class:`InflationData` holds validated (pressure, outer diameter) points, with an
optional known Shore hardness per point; :class:`CalibrationResult` is what every
calibration method returns, with :meth:`CalibrationResult.plot` drawing Fig 5b
(measured and simulated diameter against pressure, with the trial curves) and
:meth:`CalibrationResult.to_frame` giving the trial history as a table.

Units: pressures in MPa, diameters in mm, errors in %.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric import defaults
from exofric._display import DisplayMixin
from exofric._json import jsonable
from exofric._validate import checked_init
from exofric.errors import InputError, warn_implausible
from exofric.material import MooneyRivlin

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["InflationData", "Trial", "CalibrationResult", "relative_errors_pct"]

_REQUIRED = ("pressure_mpa", "outer_diameter_mm")


def relative_errors_pct(simulated_mm: np.ndarray, measured_mm: np.ndarray) -> np.ndarray:
    """Signed relative diameter errors ``100 (sim - meas) / meas`` in %.

    The paper's "average error" (Table 1) is the mean of their absolute values,
    relative to the *tested* diameter (checked against its printed numbers).

    Parameters
    ----------
    simulated_mm : array-like
        Simulated outer diameters (mm).
    measured_mm : array-like
        Measured outer diameters (mm), > 0, same shape.

    Returns
    -------
    numpy.ndarray
        Errors (%).

    Examples
    --------
    >>> relative_errors_pct(np.array([8.55]), np.array([8.53])).round(3).tolist()
    [0.234]
    """
    return 100.0 * (np.asarray(simulated_mm, float) / np.asarray(measured_mm, float) - 1.0)


def _check_growth(name: str, where: str, p: np.ndarray, od: np.ndarray) -> None:
    """An inflating tube grows: the plausibility rule of :class:`InflationData`.

    With ``tol = defaults.PLAUSIBLE_OD_DROP_REL x`` the diameter (0.5%, above measurement
    scatter): a net drop from the lowest to the highest pressure larger than ``tol`` is an
    error (impossible: columns swapped, or not an inflation test); a drop between consecutive
    pressures larger than ``tol``, or no growth at all, is a warning.
    """
    tol = defaults.PLAUSIBLE_OD_DROP_REL * float(np.max(od))
    first, last = (float(p[0]), float(od[0])), (float(p[-1]), float(od[-1]))
    if last[1] < first[1] - tol:
        raise InputError(f"{name}: outer_diameter_mm falls from {first[1]:g} mm at {first[0]:g} "
                         f"MPa to {last[1]:g} mm at {last[0]:g} MPa{where}; an inflating tube "
                         "grows (are the columns swapped?)")
    drops = np.flatnonzero(np.diff(od) < -tol)
    if drops.size:
        k = int(drops[0])
        warn_implausible(f"{name}: outer_diameter_mm falls from {od[k]:g} to {od[k + 1]:g} mm "
                         f"between {p[k]:g} and {p[k + 1]:g} MPa{where}, more than the "
                         f"{100 * defaults.PLAUSIBLE_OD_DROP_REL:g}% scatter allowed; check "
                         "that row")
    elif last[1] <= first[1]:
        warn_implausible(f"{name}: outer_diameter_mm does not grow from {first[0]:g} to "
                         f"{last[0]:g} MPa{where}; the fit will find no hardness that explains "
                         "it")


@checked_init
@dataclass(frozen=True)
class InflationData:
    """Validated inflation test points, sorted by (shore, pressure).

    Attributes
    ----------
    pressure_mpa : numpy.ndarray
        Inflation pressures (MPa), >= 0, unique (within each shore value).
    outer_diameter_mm : numpy.ndarray
        Measured tube outer diameters (mm), > 0.
    shore : numpy.ndarray or None
        Known Shore A hardness of each point (then only the tube ID is fitted).
    source : str
        Where the data came from (file name), for messages.

    Examples
    --------
    >>> d = InflationData(np.array([0.2, 0.1]), np.array([8.78, 8.53]))
    >>> d.pressure_mpa.tolist()
    [0.1, 0.2]
    """

    pressure_mpa: np.ndarray
    outer_diameter_mm: np.ndarray
    shore: np.ndarray | None = None
    source: str = ""

    def __post_init__(self) -> None:
        name = self.source or "inflation data"
        p = np.asarray(self.pressure_mpa, dtype=float).ravel()
        d = np.asarray(self.outer_diameter_mm, dtype=float).ravel()
        s = None if self.shore is None else np.asarray(self.shore, dtype=float).ravel()
        if p.size != d.size or (s is not None and s.size != p.size):
            raise InputError(f"{name}: pressure_mpa, outer_diameter_mm (and shore) must have "
                             "the same length")
        for col, v in (("pressure_mpa", p), ("outer_diameter_mm", d), ("shore", s)):
            if v is None:
                continue
            bad = ~np.isfinite(v)
            if bad.any():
                raise InputError(f"{name}: data row {int(np.argmax(bad)) + 1}, column {col!r} "
                                 "must be a finite number")
        if (p < 0).any():
            raise InputError(f"{name}: data row {int(np.argmax(p < 0)) + 1}, column "
                             f"'pressure_mpa' must be >= 0 MPa, got {p[p < 0][0]:g}")
        if (d <= 0).any():
            raise InputError(f"{name}: data row {int(np.argmax(d <= 0)) + 1}, column "
                             f"'outer_diameter_mm' must be > 0 mm, got {d[d <= 0][0]:g}")
        if s is not None and ((s <= 0) | (s >= 100)).any():
            k = int(np.argmax((s <= 0) | (s >= 100)))
            raise InputError(f"{name}: data row {k + 1}, column 'shore' must be in (0, 100) "
                             f"Shore A, got {s[k]:g}")
        key = np.zeros_like(p) if s is None else s
        order = np.lexsort((p, key))
        p, d, key = p[order], d[order], key[order]
        for g in np.unique(key):
            pg = p[key == g]
            where = "" if s is None else f" in shore {g:g}"
            dup = pg[1:][np.diff(pg) == 0]
            if dup.size:
                raise InputError(f"{name}: duplicate pressure_mpa {dup[0]:g}{where}")
            if pg.size < 2:
                raise InputError(f"{name}: needs at least 2 data rows{where}, got {pg.size}")
            _check_growth(name, where, pg, d[key == g])
        # Normalised at construction, where a frozen dataclass sets its fields (through
        # object.__setattr__, as its generated __init__ does): the rows stored sorted (by shore,
        # then pressure) as float arrays, whatever is given.
        object.__setattr__(self, "pressure_mpa", p)
        object.__setattr__(self, "outer_diameter_mm", d)
        object.__setattr__(self, "shore", None if s is None else key)

    @classmethod
    def from_frame(cls, df: Any, source: str | None = None) -> InflationData:
        """Build from a table with ``pressure_mpa``, ``outer_diameter_mm`` [, ``shore``] columns.

        ``df`` is a :class:`pandas.DataFrame` (or any mapping of column -> values), e.g. from
        :func:`exofric.io.read_inflation_table`; ``source`` defaults to
        ``df.attrs["source"]`` (the file name, for messages). Raises :class:`InputError`
        (one line) for a missing column and everything :class:`InflationData` refuses.

        Parameters
        ----------
        df : pandas.DataFrame or mapping
            Columns ``pressure_mpa`` (MPa), ``outer_diameter_mm`` (mm) and optionally
            ``shore`` (Shore A).
        source : str, optional
            Name for messages (default ``df.attrs["source"]``).

        Examples
        --------
        >>> import pandas as pd
        >>> df = pd.DataFrame({"pressure_mpa": [0.2, 0.1], "outer_diameter_mm": [8.78, 8.53]})
        >>> InflationData.from_frame(df, "rig.csv").outer_diameter_mm.tolist()
        [8.53, 8.78]
        """
        if source is None:
            source = str(getattr(df, "attrs", {}).get("source", ""))
        cols = list(getattr(df, "columns", df))
        for col in _REQUIRED:
            if col not in cols:
                raise InputError(f"{source or 'inflation data'}: missing column {col!r} "
                                 f"(required: {', '.join(_REQUIRED)}; found: "
                                 f"{', '.join(map(str, cols)) or 'none'})")
        shore = np.asarray(df["shore"], dtype=float) if "shore" in cols else None
        return cls(np.asarray(df["pressure_mpa"], dtype=float),
                   np.asarray(df["outer_diameter_mm"], dtype=float), shore, source)

    @classmethod
    def paper_test(cls) -> InflationData:
        """The paper's Table 1 test column (MPa, mm), from its shipped CSV."""
        from exofric import paper

        return cls.from_frame(paper.table1_points("test"))

    @classmethod
    def paper_simulated(cls) -> InflationData:
        """The paper's four Table 1 ANSYS columns, with their Shore hardness per row."""
        from exofric import paper

        return cls.from_frame(paper.table1_points("simulated"))

    def groups(self) -> list[tuple[float | None, np.ndarray]]:
        """``(shore or None, indices)`` for each hardness group (one group without shore)."""
        if self.shore is None:
            return [(None, np.arange(self.pressure_mpa.size))]
        return [(float(g), np.flatnonzero(self.shore == g)) for g in np.unique(self.shore)]

    def __len__(self) -> int:
        return int(self.pressure_mpa.size)


@checked_init
@dataclass(frozen=True)
class Trial:
    """One trial (hardness, tube ID) of a calibration and its errors (%).

    Attributes
    ----------
    shore : float or None
        Trial Shore A hardness (None when the data carry their own).
    tube_id_mm : float
        Trial tube inner diameter (mm).
    average_error_pct, mean_signed_error_pct, max_error_pct : float
        Mean absolute, mean signed and largest absolute relative diameter error (%);
        ``inf`` when the model failed.
    outer_diameter_mm : tuple of float
        Model outer diameters (mm) at the data points (NaN when the model failed).
    note : str
        Why the model failed, if it did.

    Examples
    --------
    >>> t = Trial(62.5, 4.97, 0.2, 0.1, 0.4, (8.5, 8.8))
    >>> t.to_dict()["average_error_pct"]
    0.2
    """

    shore: float | None
    tube_id_mm: float
    average_error_pct: float
    mean_signed_error_pct: float
    max_error_pct: float
    outer_diameter_mm: tuple[float, ...]
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (non-finite errors of a failed trial become ``None``)."""
        return jsonable({
            "shore": self.shore,
            "tube_id_mm": self.tube_id_mm,
            "average_error_pct": self.average_error_pct,
            "mean_signed_error_pct": self.mean_signed_error_pct,
            "max_error_pct": self.max_error_pct,
            "outer_diameter_mm": list(self.outer_diameter_mm),
            "note": self.note,
        })


@checked_init
@dataclass(frozen=True)
class CalibrationResult(DisplayMixin):
    """Identified Shore hardness and/or tube inner diameter, with errors and history.

    Attributes
    ----------
    method : str
        ``'bisection'``, ``'bounded'``, ``'joint'`` or ``'known-hardness'``.
    model : str
        Forward model used (``'fe'``, ``'1d'``, ``'paper-table1'``, ...).
    tube_od_mm, tube_id_mm : float
        Undeformed tube diameters (mm); the ID is fitted by ``joint``/``known-hardness``.
    shore : float or None
        Identified (or fixed) Shore A hardness; None for ``known-hardness``.
    material : MooneyRivlin or None
        Constants (MPa, 1/MPa) at ``shore``.
    data : InflationData
        The measured points.
    simulated_mm : numpy.ndarray
        Model outer diameters (mm) at the data points.
    history : tuple of Trial
        Every distinct trial, in the order evaluated.
    converged : bool
        Whether the method met its stopping criterion.
    notes : tuple of str
        Caveats (e.g. hardness and wall thickness not separable).
    shore_stderr, tube_id_stderr_mm, correlation : float or None
        Least-squares standard errors (Shore A, mm) and their correlation.
    identifiable : bool
        False when the joint fit ends on a bound of its search: the data cannot determine
        both hardness and ID (a note says what data would).
    tol_pct : float or None
        Stopping tolerance on the average error (%), for the bracketing methods.
    bracket : tuple of float or None
        Hardness bracket searched (Shore A), for the bracketing methods.
    n_model_calls : int
        Forward-model evaluations actually computed (cache misses).
    elapsed_s : float
        Wall time of the calibration (s).

    Examples
    --------
    >>> from exofric.calibration import calibrate
    >>> r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=4.97, model="paper-table1")
    >>> r.method, r.shore, [t.shore for t in r.history]
    ('bisection', 62.5, [60.0, 65.0, 70.0, 62.5])
    """

    method: str
    model: str
    tube_od_mm: float
    tube_id_mm: float
    shore: float | None
    material: MooneyRivlin | None
    data: InflationData
    simulated_mm: np.ndarray
    history: tuple[Trial, ...]
    converged: bool
    notes: tuple[str, ...] = ()
    tol_pct: float | None = None
    bracket: tuple[float, float] | None = None
    shore_stderr: float | None = None
    tube_id_stderr_mm: float | None = None
    correlation: float | None = None
    identifiable: bool = True
    n_model_calls: int = 0
    elapsed_s: float = field(default=float("nan"), compare=False)

    @property
    def status(self) -> str:
        """The outcome in words: ``converged``, ``weakly identified`` (converged, but hardness
        and ID correlate above 0.99: wide standard errors), ``not identifiable`` (the joint fit
        ended on a bound), ``tolerance not met`` (a bracketing method whose best average error
        stays above ``tol_pct``) or ``not converged``."""
        if not self.identifiable:
            return "not identifiable"
        if self.converged:
            weak = self.correlation is not None and abs(self.correlation) > 0.99
            return "weakly identified" if weak else "converged"
        if self.tol_pct is not None and self.method in ("bisection", "bounded") \
                and self.average_error_pct > self.tol_pct:
            return "tolerance not met"
        return "not converged"

    @property
    def residuals_pct(self) -> np.ndarray:
        """Signed relative errors ``100 (sim - meas)/meas`` (%) at each data point."""
        return relative_errors_pct(self.simulated_mm, self.data.outer_diameter_mm)

    @property
    def average_error_pct(self) -> float:
        """Mean absolute relative diameter error (%), the paper's criterion."""
        return float(np.mean(np.abs(self.residuals_pct)))

    @property
    def max_error_pct(self) -> float:
        """Largest absolute relative diameter error (%)."""
        return float(np.max(np.abs(self.residuals_pct)))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict with unit-suffixed keys (mm, MPa, %, s)."""
        d = self.data
        points = [
            {
                "pressure_mpa": float(d.pressure_mpa[i]),
                **({} if d.shore is None else {"shore": float(d.shore[i])}),
                "measured_outer_diameter_mm": float(d.outer_diameter_mm[i]),
                "simulated_outer_diameter_mm": float(self.simulated_mm[i]),
                "residual_pct": float(self.residuals_pct[i]),
            }
            for i in range(len(d))
        ]
        out: dict[str, Any] = {
            "method": self.method,
            "model": self.model,
            "shore": self.shore,
            "tube_od_mm": self.tube_od_mm,
            "tube_id_mm": self.tube_id_mm,
            "average_error_pct": self.average_error_pct,
            "max_error_pct": self.max_error_pct,
            "converged": self.converged,
            "status": self.status,
            "identifiable": self.identifiable,
            "tol_pct": self.tol_pct,
            "bracket": None if self.bracket is None else list(self.bracket),
            "material": None if self.material is None else self.material.to_dict(),
            "points": points,
            "history": [t.to_dict() for t in self.history],
            "notes": list(self.notes),
            "n_model_calls": self.n_model_calls,
            "elapsed_s": self.elapsed_s,
        }
        if self.shore_stderr is not None:
            out["shore_stderr"] = self.shore_stderr
        if self.tube_id_stderr_mm is not None:
            out["tube_id_stderr_mm"] = self.tube_id_stderr_mm
        if self.correlation is not None:
            out["correlation"] = self.correlation
        return jsonable(out)

    def to_frame(self) -> pd.DataFrame:
        """The trial history as a DataFrame: one row per trial, in the order evaluated.

        Columns: ``trial`` (1, 2, ...), ``shore`` (Shore A; NaN for known hardness),
        ``tube_id_mm``, ``average_error_pct``, ``mean_signed_error_pct``, ``max_error_pct``
        and ``note``.

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> from exofric.calibration import InflationData, calibrate
        >>> r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=4.97,
        ...               model="paper-table1")
        >>> r.to_frame()[["trial", "shore"]].values.tolist()   # the paper's trial order
        [[1.0, 60.0], [2.0, 65.0], [3.0, 70.0], [4.0, 62.5]]
        """
        import pandas as pd

        h = self.history
        return pd.DataFrame({
            "trial": np.arange(1, len(h) + 1),
            "shore": np.array([np.nan if t.shore is None else t.shore for t in h], dtype=float),
            "tube_id_mm": np.array([t.tube_id_mm for t in h], dtype=float),
            "average_error_pct": np.array([t.average_error_pct for t in h], dtype=float),
            "mean_signed_error_pct": np.array([t.mean_signed_error_pct for t in h], dtype=float),
            "max_error_pct": np.array([t.max_error_pct for t in h], dtype=float),
            "note": [t.note for t in h],
        })

    def plot(self, ax: Any | None = None) -> Any:
        """Draw Fig 5b: measured and simulated outer diameter (mm) against pressure (MPa).

        Trial curves of the history are drawn thin and grey, the final curve bold
        (:func:`exofric.plots.plot_calibration`). Write it with :func:`exofric.plots.save`.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes

        Examples
        --------
        >>> from exofric.calibration import InflationData, calibrate
        >>> r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=4.97,
        ...               model="paper-table1")
        >>> ax = r.plot()
        >>> len(ax.lines)        # 4 trials, the measured points, the final curve
        6
        """
        from exofric.plots import plot_calibration

        return plot_calibration(self, ax)
