"""The I/O edge of sweeps: reading sweep TOML files and the Parquet result dataset.

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

import json
import os
import tomllib
import uuid
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from exofric.design._spec import SweepSpec, parse_sweep
from exofric.errors import InputError
from exofric.io import jsonable

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

    Raises
    ------
    InputError
        Missing file, TOML syntax error (with the line), or an invalid definition.

    Examples
    --------
    >>> spec = load_sweep("examples/sweep-small.toml")      # doctest: +SKIP
    >>> len(spec.designs), len(spec.skipped)                # doctest: +SKIP
    (12, 4)
    """
    p = Path(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"sweep file {p} does not exist") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"sweep file {p} cannot be read: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"sweep file {p} is not valid TOML: {exc}") from None
    try:
        return parse_sweep(data, name=p.stem)
    except InputError as exc:
        raise InputError(f"{p}: {exc}") from None


class SweepStore:
    """A sweep's result directory (created if missing).

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
            raise InputError(f"--out {self.out} exists and is not a directory")
        self.out.mkdir(parents=True, exist_ok=True)

    def remove_temporary(self) -> int:
        """Delete temporary files left by a killed writer; returns how many."""
        stale = list(self.out.glob(".design-*.tmp")) + list(self.out.glob("._sweep.json.*.tmp"))
        for f in stale:
            f.unlink(missing_ok=True)
        return len(stale)

    def _path(self, key: str, status: str) -> Path:
        return self.out / f"design-{key}-{status}.parquet"

    def finished(self) -> dict[str, str]:
        """Cache key -> status of every design file present (``ok`` wins over ``failed``)."""
        found: dict[str, str] = {}
        for f in self.out.glob("design-*-*.parquet"):
            key, _, status = f.stem.removeprefix("design-").rpartition("-")
            if status in STATUSES and found.get(key) != "ok":
                found[key] = status
        return found

    def write(self, key: str, status: str, rows: pd.DataFrame) -> Path:
        """Write one design's rows (columns of :data:`SCHEMA`) atomically; returns the file.

        A previous file of the same design with another status is removed afterwards.
        """
        if status not in STATUSES:
            raise InputError(f"status must be one of {', '.join(STATUSES)}, got {status!r}")
        table = pa.Table.from_pandas(rows[SCHEMA.names], schema=SCHEMA, preserve_index=False)
        final = self._path(key, status)
        tmp = self.out / f".{final.name}.{uuid.uuid4().hex}.tmp"
        pq.write_table(table, tmp)
        os.replace(tmp, final)
        for other in STATUSES:
            if other != status and self._path(key, other).exists():
                self._path(key, other).unlink()
        return final

    def read(self, keys: Iterable[str] | None = None) -> pd.DataFrame:
        """The rows of ``keys`` (default: every design file) as a DataFrame."""
        have = self.finished()
        want = list(have) if keys is None else [k for k in keys if k in have]
        tables = [pq.read_table(self._path(k, have[k]), schema=SCHEMA) for k in want]
        if not tables:
            return SCHEMA.empty_table().to_pandas()
        return pa.concat_tables(tables).to_pandas()

    def write_manifest(self, spec: SweepSpec, extra: Mapping[str, Any] | None = None) -> Path:
        """Write ``_sweep.json``: the sweep definition (and ``extra``), atomically."""
        path = self.out / "_sweep.json"
        tmp = self.out / f".{path.name}.{uuid.uuid4().hex}.tmp"
        tmp.write_text(json.dumps(jsonable({**spec.to_dict(), **(extra or {})}), indent=1))
        os.replace(tmp, path)
        return path
