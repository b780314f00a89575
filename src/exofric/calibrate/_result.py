"""Inflation test data and calibration results (paper §3.3, Table 1, Fig 5b).

:class:`InflationData` holds validated (pressure, outer diameter) points, with an
optional known Shore hardness per point; :class:`CalibrationResult` is what every
calibration method returns, with :meth:`CalibrationResult.plot` drawing Fig 5b
(measured and simulated diameter against pressure, with the trial curves).

Units: pressures in MPa, diameters in mm, errors in %.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from exofric.errors import InputError
from exofric.material import MooneyRivlin

__all__ = ["InflationData", "Trial", "CalibrationResult", "relative_errors_pct"]

_REQUIRED = ("pressure_mpa", "outer_diameter_mm")


def relative_errors_pct(simulated_mm: np.ndarray, measured_mm: np.ndarray) -> np.ndarray:
    """Signed relative diameter errors ``100 (sim - meas) / meas`` in %.

    The paper's "average error" (Table 1) is the mean of their absolute values,
    relative to the *tested* diameter (checked against its printed numbers).

    Examples
    --------
    >>> relative_errors_pct(np.array([8.55]), np.array([8.53])).round(3).tolist()
    [0.234]
    """
    return 100.0 * (np.asarray(simulated_mm, float) / np.asarray(measured_mm, float) - 1.0)


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
        object.__setattr__(self, "pressure_mpa", p)
        object.__setattr__(self, "outer_diameter_mm", d)
        object.__setattr__(self, "shore", None if s is None else key)

    @classmethod
    def from_csv(cls, path: str | Path) -> InflationData:
        """Read ``pressure_mpa,outer_diameter_mm[,shore]`` CSV via :func:`exofric.io.read_table`.

        Columns in any order, extra columns ignored, ``#`` comments allowed. Raises
        :class:`InputError` (one line) for a missing column, a non-numeric/empty
        cell (naming the row), negative or NaN values, duplicate pressures (within
        a shore value) and fewer than two points.
        """
        from exofric.io import read_table

        df = read_table(path, _REQUIRED, ("shore",), unique_within=("pressure_mpa", "shore"),
                        min_rows=2)
        shore = df["shore"].to_numpy(float) if "shore" in df.columns else None
        return cls(df["pressure_mpa"].to_numpy(float), df["outer_diameter_mm"].to_numpy(float),
                   shore, Path(path).name)

    @classmethod
    def paper_test(cls) -> InflationData:
        """The paper's Table 1 test column (MPa, mm)."""
        from exofric import paper

        return cls.from_csv(paper.data_path("table1_test.csv"))

    @classmethod
    def paper_simulated(cls) -> InflationData:
        """The paper's four Table 1 ANSYS columns, with their Shore hardness per row."""
        from exofric import paper

        return cls.from_csv(paper.data_path("table1_simulated.csv"))

    def groups(self) -> list[tuple[float | None, np.ndarray]]:
        """``(shore or None, indices)`` for each hardness group (one group without shore)."""
        if self.shore is None:
            return [(None, np.arange(self.pressure_mpa.size))]
        return [(float(g), np.flatnonzero(self.shore == g)) for g in np.unique(self.shore)]

    def __len__(self) -> int:
        return int(self.pressure_mpa.size)


@dataclass(frozen=True)
class Trial:
    """One trial (hardness, tube ID) of a calibration and its errors (%)."""

    shore: float | None
    tube_id_mm: float
    average_error_pct: float
    mean_signed_error_pct: float
    max_error_pct: float
    outer_diameter_mm: tuple[float, ...]
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (non-finite errors of a failed trial become ``None``)."""
        from exofric.io import jsonable

        return jsonable({
            "shore": self.shore,
            "tube_id_mm": self.tube_id_mm,
            "average_error_pct": self.average_error_pct,
            "mean_signed_error_pct": self.mean_signed_error_pct,
            "max_error_pct": self.max_error_pct,
            "outer_diameter_mm": list(self.outer_diameter_mm),
            "note": self.note,
        })


@dataclass(frozen=True)
class CalibrationResult:
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
    n_model_calls: int = 0
    elapsed_s: float = field(default=float("nan"), compare=False)

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
        from exofric.io import jsonable

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

    def plot(self, path: str | Path) -> Path:
        """Draw Fig 5b: measured and simulated outer diameter (mm) vs pressure (MPa).

        Trial curves of the history are drawn thin and grey, the final curve bold.
        Writes a PNG/SVG/PDF (by suffix) and returns its path.
        """
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        d = self.data
        fig, ax = plt.subplots(figsize=(6.0, 4.2), dpi=120)
        od = self.tube_od_mm
        for gi, (g, idx) in enumerate(d.groups()):
            p = d.pressure_mpa[idx]
            # simulated curves start from the undeformed tube: OD at P = 0
            pc = p if p[0] == 0.0 else np.concatenate([[0.0], p])

            def curve(sim: np.ndarray, p: np.ndarray = p) -> np.ndarray:
                return sim if p[0] == 0.0 else np.concatenate([[od], sim])

            colour = f"C{gi % 10}"
            if g is None:
                for k, t in enumerate(self.history):
                    sim = np.asarray(t.outer_diameter_mm)[idx]
                    if not np.all(np.isfinite(sim)):
                        continue
                    ax.plot(pc, curve(sim), "-", color="0.7", lw=0.8, zorder=1)
                    if k < 6:  # label the first trials only (later ones crowd together)
                        ax.annotate(f"{t.shore:.4g}", (p[-1], sim[-1]), fontsize=6,
                                    color="0.5", xytext=(2, 0), textcoords="offset points")
            label = "" if g is None else f" (Shore {g:g})"
            ax.plot(p, d.outer_diameter_mm[idx], "o", color=colour, label=f"measured{label}",
                    zorder=3)
            ax.plot(pc, curve(self.simulated_mm[idx]), "-", color=colour, lw=2, zorder=2,
                    label=None if g is not None else f"model, Shore {self.shore:.4g}")
        ax.set_xlabel("inflation pressure P (MPa)")
        ax.set_ylabel("tube outer diameter (mm)")
        shore_txt = "known" if self.shore is None else f"{self.shore:.4g}"
        ax.set_title(f"{self.method} ({self.model}): Shore {shore_txt}, ID "
                     f"{self.tube_id_mm:.4g} mm, avg error {self.average_error_pct:.2f}%",
                     fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        out = Path(path)
        out.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(out)
        plt.close(fig)
        return out
