"""What a sweep's files mean: the sweep TOML and the result dataset's schema and statuses.

The file mechanics are :mod:`exofric.io` (:func:`~exofric.io.read_toml`,
:class:`~exofric.io.ParquetStore`); this module says what the files hold.

Dataset layout (``OUT/``): one Parquet file per finished design, written atomically (to a
hidden temporary file, then renamed) as soon as the design finishes, so a killed sweep
leaves only complete files. The file name carries the cache key and the status,
``design-<key>-<status>.parquet`` with status ``ok``, ``failed`` or ``skipped``; a
directory listing is enough to know what is finished. ``OUT/_sweep.json`` records the last
sweep definition (atomically too). ``pandas.read_parquet(OUT)`` reads the whole dataset
(files and folders starting with ``_`` or ``.`` are ignored by pyarrow).

Integrity: each design file carries the SHA-256 of its rows in its Parquet metadata
(``exofric.sha256``, written with it). Every read verifies that the file parses, the
checksum, and that its derived columns (friction, torque, wall, clearance) equal the ones
re-derived from its primary values (:func:`check_rows`; the only check for files written
before checksums existed).
A file failing any of these is moved to ``OUT/_quarantine/`` and reported, and its design
counts as missing (a sweep solves it again). :func:`verify_sweep` checks a folder without
solving anything (``exofric sweep --verify OUT``).

Rows: one per design and pressure (one row with ``pressure_mpa`` = NaN for failed and
skipped designs); columns and units in :data:`SCHEMA`.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pyarrow as pa

from exofric._validate import checked_init
from exofric.design._spec import SweepSpec, parse_sweep
from exofric.errors import InputError
from exofric.io import ParquetStore, QuarantinedFile, read_toml

__all__ = ["SCHEMA", "STATUSES", "SweepCheck", "SweepStore", "check_rows", "load_sweep",
           "verify_sweep"]

#: The manifest's file name in a sweep folder.
MANIFEST = "_sweep.json"

#: The status of a design's rows in a sweep store: solved (``"ok"``), the solver failed
#: (``"failed"``), or not solved because the structure is impossible (``"skipped"``).
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
                                   manifest=MANIFEST)

    def remove_temporary(self) -> int:
        """Delete temporary files left by a killed writer (and orphaned checksums); returns
        how many."""
        return self._files.remove_temporary()

    def path(self, key: str, status: str) -> Path:
        """The design file ``OUT/design-<key>-<status>.parquet``.

        Parameters
        ----------
        key : str
            The design's cache key.
        status : str
            ``ok``, ``failed`` or ``skipped``.
        """
        return self._files.path(key, status)

    def load(self, keys: Iterable[str] | None = None, *, move: bool = True
             ) -> tuple[dict[str, tuple[str, pa.Table]], list[QuarantinedFile]]:
        """Verified design files: key -> (status, table), and the files that failed.

        Each file's Parquet structure, its rows' SHA-256 (when recorded) and
        :func:`check_rows` are verified; a failing file is moved to ``OUT/_quarantine/``
        (unless ``move`` is False) and listed instead.

        Parameters
        ----------
        keys : iterable of str, optional
            Cache keys (default: every design file); keys without a file are left out.
        move : bool
            Move failing files to ``OUT/_quarantine/``.
        """
        return self._files.load(keys, check_rows, move=move)

    def frame(self, tables: Iterable[pa.Table]) -> pd.DataFrame:
        """``tables`` (from :meth:`load`) as one DataFrame of :data:`SCHEMA` columns.

        Parameters
        ----------
        tables : iterable of pyarrow.Table
            Design tables.
        """
        return self._files.concat(list(tables))

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
        try:
            return self._files.write(key, status, rows)
        except OSError as exc:
            raise self._unwritable(self.path(key, status).name, exc) from None

    def _unwritable(self, name: str, exc: OSError) -> InputError:
        """One line naming the folder and the file that cannot be written (not the hidden
        temporary file the OS error names)."""
        return InputError(f"out {self.out}: cannot write {name} ({exc.strerror or exc})",
                          param="out")

    def read(self, keys: Iterable[str] | None = None) -> pd.DataFrame:
        """The rows of ``keys`` (default: every design file) as a DataFrame.

        Verified like :meth:`load`: failing files are quarantined and left out, with a
        :class:`RuntimeWarning` each.

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
        try:
            return self._files.write_manifest({**spec.to_dict(), **(extra or {})})
        except OSError as exc:
            raise self._unwritable(MANIFEST, exc) from None

    def read_manifest(self) -> dict[str, Any] | None:
        """``_sweep.json`` as a dict (None when missing); InputError when it is not JSON."""
        return self._files.read_manifest()


def check_rows(key: str, status: str, table: pa.Table) -> str:
    """Why a design file's rows cannot be trusted, or ``""``: its derived columns re-derived.

    The rows must be of design ``key`` with ``status`` (as the file name says), and
    ``friction_n`` = gamma N + F0 (NaN unless ok), ``torque_nm`` = friction x R,
    ``wall_mm`` = (d1 - ID) / 2 and ``clearance_mm`` = D - d1 - d2 must equal, bit for bit,
    the values computed again from the file's own primary columns (the writer computes them
    the same way). A changed squeeze force with the old friction, for example, fails.

    Parameters
    ----------
    key : str
        The cache key the file name carries.
    status : str
        The status the file name carries.
    table : pyarrow.Table
        The file's rows (:data:`SCHEMA`).

    Returns
    -------
    str
        ``""`` when consistent, else one line saying which column disagrees.

    Examples
    --------
    >>> row = {"key": ["k1"], "status": ["ok"], "squeeze_force_n": [100.0], "gamma": [0.5],
    ...        "f0_n": [0.0], "friction_n": [50.0], "arm_radius_m": [0.1], "torque_nm": [5.0],
    ...        "hole_mm": [10.0], "tube_od_mm": [8.3], "tube_id_mm": [4.9], "wire_mm": [1.6]}
    >>> row["wall_mm"], row["clearance_mm"] = [0.5 * (8.3 - 4.9)], [10.0 - 8.3 - 1.6]
    >>> check_rows("k1", "ok", pa.table(row))
    ''
    >>> check_rows("k1", "ok", pa.table({**row, "squeeze_force_n": [101.0]}))
    'stored friction_n disagrees with the one re-derived from squeeze_force_n, gamma, f0_n'
    """
    if table.num_rows == 0:
        return "the file has no rows"
    for col, want in (("key", key), ("status", status)):
        got = set(table.column(col).to_pylist())
        if got != {want}:
            return f"its rows have {col} {sorted(map(str, got))}, the file name says {want!r}"

    def c(name: str) -> np.ndarray:
        return np.asarray(table.column(name).to_numpy(zero_copy_only=False), dtype=float)

    friction = np.where(status == "ok", c("gamma") * c("squeeze_force_n") + c("f0_n"), np.nan)
    derived = (
        ("friction_n", friction, "squeeze_force_n, gamma, f0_n"),
        ("torque_nm", friction * c("arm_radius_m"), "friction_n, arm_radius_m"),
        ("wall_mm", 0.5 * (c("tube_od_mm") - c("tube_id_mm")), "tube_od_mm, tube_id_mm"),
        ("clearance_mm", c("hole_mm") - c("tube_od_mm") - c("wire_mm"),
         "hole_mm, tube_od_mm, wire_mm"),
    )
    for name, want_v, source in derived:
        if not np.array_equal(c(name), want_v, equal_nan=True):
            return f"stored {name} disagrees with the one re-derived from {source}"
    return ""


@checked_init
@dataclass(frozen=True)
class SweepCheck:
    """What :func:`verify_sweep` found in a sweep folder.

    Attributes
    ----------
    out : str
        The folder.
    manifest : str
        ``"ok"``, ``"missing"`` or ``"unreadable (...)"`` (``_sweep.json``, which lists the
        designs; without it missing designs cannot be told).
    designs : tuple of dict
        One per design of the manifest (then any other design file): ``key``, ``name``,
        ``state`` (``ok``, ``quarantined`` or ``missing``), ``status`` (``ok``, ``failed``,
        ``skipped`` or ``""``), ``file``, ``reason`` and ``moved_to`` (``""`` when not
        applicable), ``in_manifest``.

    Examples
    --------
    >>> c = SweepCheck("out", "ok", ({"key": "k", "name": "base", "state": "ok"},))
    >>> c.ok, c.exit_code, c.counts
    (True, 0, {'ok': 1, 'quarantined': 0, 'missing': 0})
    """

    out: str
    manifest: str
    designs: tuple[dict[str, Any], ...] = field(default=())

    @property
    def counts(self) -> dict[str, int]:
        """Designs per state (``ok``, ``quarantined``, ``missing``)."""
        states = [d["state"] for d in self.designs]
        return {s: states.count(s) for s in ("ok", "quarantined", "missing")}

    @property
    def ok(self) -> bool:
        """True when the manifest is readable and every design is present and verified."""
        return self.manifest == "ok" and all(d["state"] == "ok" for d in self.designs)

    @property
    def exit_code(self) -> int:
        """0 when :attr:`ok`, else 1 (``exofric sweep --verify``)."""
        return 0 if self.ok else 1

    @property
    def warnings(self) -> list[str]:
        """One line per quarantined file (as ``exofric sweep`` prints them)."""
        return [QuarantinedFile(d["key"], d["status"], d["file"], d["reason"],
                                d["moved_to"]).message()
                for d in self.designs if d["state"] == "quarantined"]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``out``, ``ok``, ``manifest``, ``counts``, ``designs``,
        ``warnings``."""
        return {"out": self.out, "ok": self.ok, "manifest": self.manifest,
                "counts": self.counts, "designs": [dict(d) for d in self.designs],
                "warnings": self.warnings}


def verify_sweep(out: str | Path) -> SweepCheck:
    """Check a sweep folder without solving anything: every design ok, quarantined or missing.

    Each design file is verified like a sweep reads it (:meth:`SweepStore.load`: Parquet
    structure, SHA-256 of the rows, :func:`check_rows`); failing files are moved to
    ``OUT/_quarantine/`` (so the next sweep solves them again). The designs expected are
    those of ``_sweep.json``.

    Parameters
    ----------
    out : str or Path
        The sweep folder.

    Returns
    -------
    SweepCheck

    Raises
    ------
    InputError
        ``out`` is not a sweep folder (missing, or neither ``_sweep.json`` nor design files).

    Examples
    --------
    >>> import tempfile
    >>> from exofric.design import run_sweep
    >>> spec = parse_sweep({"pressures_mpa": [0.6], "grid": {"wire_mm": [1.6, 2.0]},
    ...                     "solver": {"n_radial": 1, "n_circ": 12}})   # coarse mesh
    >>> out = tempfile.mkdtemp()
    >>> _ = run_sweep(spec, out, serial=True)
    >>> check = verify_sweep(out)
    >>> check.ok, check.counts
    (True, {'ok': 2, 'quarantined': 0, 'missing': 0})
    """
    p = Path(out)
    if not p.is_dir() or not ((p / MANIFEST).exists() or any(p.glob("design-*-*.parquet"))):
        raise InputError(f"{p} is not a sweep folder (no {MANIFEST} and no "
                         "design-*.parquet files)", param="")
    store = SweepStore(p)
    try:
        manifest = store.read_manifest()
        state = "missing" if manifest is None else "ok"
    except (InputError, OSError) as exc:
        manifest, state = None, f"unreadable ({' '.join(str(exc).split())})"
    listed: list[dict[str, Any]] = []
    if manifest is not None:
        raw = manifest.get("designs")
        if isinstance(raw, list) and all(isinstance(d, dict) and isinstance(d.get("key"), str)
                                         for d in raw):
            listed = raw
        else:
            state = "unreadable (no list of designs with keys)"
    have = store.finished()
    tables, bad = store.load()
    quarantined = {q.key: q for q in bad}
    rows: list[dict[str, Any]] = []
    names = {d["key"]: str(d.get("name", "")) for d in listed}
    keys = list(names) + [k for k in have if k not in names]
    for k in keys:
        row = {"key": k, "name": names.get(k, ""), "state": "missing", "status": "",
               "file": "", "reason": "", "moved_to": "", "in_manifest": k in names}
        if k in tables:
            row.update(state="ok", status=tables[k][0], file=str(store.path(k, tables[k][0])))
        elif k in quarantined:
            q = quarantined[k]
            row.update(state="quarantined", status=q.tag, file=q.file, reason=q.reason,
                       moved_to=q.moved_to)
        rows.append(row)
    return SweepCheck(str(p), state, tuple(rows))
