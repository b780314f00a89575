"""What a sweep's files mean: the sweep TOML and the result dataset's schema and statuses.

The file mechanics are :mod:`exofric.io` (:func:`~exofric.io.read_toml`,
:class:`~exofric.io.ParquetStore`); this module says what the files hold.

Dataset layout (``OUT/``): one Parquet file per finished design, written atomically (to a
hidden temporary file, then renamed) as soon as the design finishes, so a killed sweep
leaves only complete files. The file name carries the cache key and the status,
``design-<key>-<status>.parquet`` with status ``ok``, ``failed`` or ``skipped``; a
directory listing is enough to know what is finished. ``OUT/_sweep.json`` records the last
sweep definition. ``pandas.read_parquet(OUT)`` reads the whole dataset (files starting with
``_`` or ``.`` are ignored by pyarrow).

Rows: one per design and pressure (one row with ``pressure_mpa`` = NaN for failed and
skipped designs); columns and units in :data:`SCHEMA`.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa

from exofric.design._spec import SweepSpec, parse_sweep
from exofric.errors import InputError
from exofric.io import ParquetStore, read_toml

__all__ = ["SCHEMA", "STATUSES", "SweepStore", "load_sweep"]

STATUSES = ("ok", "failed", "skipped")

#: Columns of the dataset. Integers are 0 and floats NaN where there is no solve.
SCHEMA = pa.schema([
    ("key", pa.string()), ("design_index", pa.int64()), ("name", pa.string()),
    ("family", pa.string()), ("status", pa.string()), ("error", pa.string()),
    ("hole_mm", pa.float64()), ("tube_od_mm", pa.float64()), ("tube_id_mm", pa.float64()),
    ("wire_mm", pa.float64()), ("length_mm", pa.float64()), ("wall_mm", pa.float64()),
    ("clearance_mm", pa.float64()), ("shore", pa.float64()),
    ("c10_mpa", pa.float64()), ("c01_mpa", pa.float64()), ("d_per_mpa", pa.float64()),
    ("pressure_mpa", pa.float64()), ("squeeze_force_n", pa.float64()),
    ("squeeze_force_n_per_mm", pa.float64()), ("wall_force_n", pa.float64()),
    ("friction_n", pa.float64()), ("torque_nm", pa.float64()),
    ("gamma", pa.float64()), ("f0_n", pa.float64()), ("arm_radius_m", pa.float64()),
    ("deviation_pct", pa.float64()), ("in_validated_region", pa.bool_()),
    ("contact_onset_pressure_mpa", pa.float64()), ("max_penetration_mm", pa.float64()),
    ("max_stretch", pa.float64()),
    ("newton_iterations", pa.int64()), ("dofs", pa.int64()),
    ("solve_time_s", pa.float64()), ("task_time_s", pa.float64()),
    ("worker", pa.string()), ("blas_threads", pa.string()),
    ("run_id", pa.string()), ("finished_at", pa.string()),
])


def load_sweep(path: str | Path) -> SweepSpec:
    """Read and validate a sweep TOML file (see ``examples/sweep-small.toml``).

    ``parse_sweep(read_toml(path))``, named after the file's stem.

    Parameters
    ----------
    path : str or Path
        The sweep TOML file.

    Raises
    ------
    InputError
        Missing file, TOML syntax error (with the line), or an invalid definition.

    Examples
    --------
    >>> spec = load_sweep("examples/sweep-small.toml")      # path from the repository root
    >>> len(spec.designs), len(spec.skipped)
    (12, 4)
    """
    p = Path(path)
    try:
        data = read_toml(p)
    except FileNotFoundError:
        raise InputError(f"sweep file {p} does not exist") from None
    except OSError as exc:
        raise InputError(f"sweep file {p} cannot be read: {exc}") from None
    try:
        return parse_sweep(data, name=p.stem)
    except InputError as exc:
        raise InputError(f"{p}: {exc}") from None


class SweepStore:
    """A sweep's result directory (created if missing): design files with :data:`SCHEMA` rows.

    The file mechanics are :class:`exofric.io.ParquetStore`; this class fixes the schema, the
    statuses (:data:`STATUSES`), the ``design-`` prefix and the ``_sweep.json`` manifest.

    Parameters
    ----------
    out : str or Path
        The result directory.

    Examples
    --------
    >>> import tempfile
    >>> store = SweepStore(tempfile.mkdtemp())
    >>> store.finished()
    {}
    """

    def __init__(self, out: str | Path) -> None:
        self.out = Path(out)
        if self.out.exists() and not self.out.is_dir():
            raise InputError(f"out {self.out} exists and is not a directory")
        self._files = ParquetStore(self.out, SCHEMA, tags=STATUSES, prefix="design",
                                   manifest="_sweep.json")

    def remove_temporary(self) -> int:
        """Delete temporary files left by a killed writer; returns how many."""
        return self._files.remove_temporary()

    def finished(self) -> dict[str, str]:
        """Cache key -> status of every design file present (``ok`` wins over ``failed``)."""
        return self._files.finished()

    def write(self, key: str, status: str, rows: pd.DataFrame) -> Path:
        """Write one design's rows (columns of :data:`SCHEMA`) atomically; returns the file.

        A previous file of the same design with another status is removed afterwards.

        Parameters
        ----------
        key : str
            The design's cache key.
        status : str
            ``ok``, ``failed`` or ``skipped``.
        rows : pandas.DataFrame
            The design's rows (other columns are ignored).
        """
        if status not in STATUSES:
            raise InputError(f"status must be one of {', '.join(STATUSES)}, got {status!r}")
        return self._files.write(key, status, rows)

    def read(self, keys: Iterable[str] | None = None) -> pd.DataFrame:
        """The rows of ``keys`` (default: every design file) as a DataFrame.

        Parameters
        ----------
        keys : iterable of str, optional
            Cache keys, in the order wanted; keys without a file are skipped.
        """
        return self._files.read(keys)

    def write_manifest(self, spec: SweepSpec, extra: Mapping[str, Any] | None = None) -> Path:
        """Write ``_sweep.json``: the sweep definition (and ``extra``), atomically.

        Parameters
        ----------
        spec : SweepSpec
            The sweep (its ``to_dict()`` is written).
        extra : mapping, optional
            More keys, e.g. ``{"run_id": ...}``.
        """
        return self._files.write_manifest({**spec.to_dict(), **(extra or {})})
