"""A directory of Parquet files, one per key, each written atomically and checksummed, plus a
JSON manifest.

Layout (``OUT/``): ``<prefix>-<key>-<tag>.parquet`` per key, where ``tag`` is one of a fixed
set of labels (e.g. a status); written to a hidden temporary file and renamed, so a killed
writer leaves only complete files and a directory listing tells what is finished.

Each file carries, in its Parquet key-value metadata (``exofric.sha256``), the SHA-256 of its
rows (:func:`content_sha256`: every column's values, exactly); it is inside the file, so it is
written atomically with it and cannot go missing or stale. Every read verifies that the file
parses, that the checksum matches the rows read, and the caller's own row check; a file that
fails is moved to ``OUT/_quarantine/`` and reported as a :class:`QuarantinedFile` instead of
being trusted. Files written before checksums existed (no such metadata) are verified by the
row check only. ``OUT/<manifest>`` is a JSON file (also written atomically).
``pandas.read_parquet(OUT)`` reads every part at once (pyarrow ignores files and folders
starting with ``_`` or ``.``, so the quarantine is not read).

Knows nothing of what the rows mean: the caller gives the Arrow schema, the tags and,
optionally, a row check.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from exofric._validate import checked_init
from exofric.errors import InputError
from exofric.io._files import atomic_path, read_json, write_json

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa

__all__ = ["ParquetStore", "QuarantinedFile"]

#: Sub-folder of a store for the files that failed verification.
QUARANTINE = "_quarantine"
#: Parquet key-value metadata key holding :func:`content_sha256` of the file's rows.
CHECKSUM_KEY = b"exofric.sha256"

#: ``check(key, tag, table)`` -> "" when the rows are fine, else the reason (one line).
RowCheck = Callable[[str, str, "pa.Table"], str]


def _one_line(exc: BaseException, limit: int = 160) -> str:
    """``Type: message`` on one line, at most ``limit`` characters."""
    msg = " ".join(str(exc).split()) or "(no message)"
    text = f"{type(exc).__name__}: {msg}"
    return text if len(text) <= limit else text[: limit - 3] + "..."


def content_sha256(table: pa.Table) -> str:
    """SHA-256 (hex) of a table's rows: column names and every value, exactly.

    Values are hashed as JSON of :meth:`pyarrow.Array.to_pylist` (floats by their shortest
    exact ``repr``, NaN and nulls distinct), so the digest does not depend on the Parquet
    encoding, compression or pyarrow version, and any changed value changes it.
    """
    h = hashlib.sha256()
    for name in table.column_names:
        h.update(name.encode() + b"\0")
        h.update(json.dumps(table.column(name).to_pylist()).encode() + b"\n")
    return h.hexdigest()


@checked_init
@dataclass(frozen=True)
class QuarantinedFile:
    """A stored file that failed verification and is no longer trusted.

    Attributes
    ----------
    key : str
        The part's key.
    tag : str
        Its tag (e.g. status) from the file name.
    file : str
        The file (path as found in the store).
    reason : str
        Why it is not trusted (one line): unreadable, checksum mismatch, failed row check.
    moved_to : str
        Where it was moved (``OUT/_quarantine/...``); ``""`` when it could not be moved (the
        reason then says why) or was not asked to be.

    Examples
    --------
    >>> q = QuarantinedFile("a1", "ok", "out/part-a1-ok.parquet", "checksum mismatch",
    ...                     "out/_quarantine/part-a1-ok.parquet")
    >>> q.message()
    'out/part-a1-ok.parquet: checksum mismatch; moved to out/_quarantine/part-a1-ok.parquet'
    """

    key: str
    tag: str
    file: str
    reason: str
    moved_to: str = ""

    def message(self) -> str:
        """One line: the file, the reason and where it went."""
        where = f"; moved to {self.moved_to}" if self.moved_to else ""
        return f"{self.file}: {self.reason}{where}"

    def to_dict(self) -> dict[str, str]:
        """JSON-ready dict (``key``, ``tag``, ``file``, ``reason``, ``moved_to``)."""
        return {"key": self.key, "tag": self.tag, "file": self.file, "reason": self.reason,
                "moved_to": self.moved_to}


class ParquetStore:
    """One Parquet file per key in a directory (created if missing), with a JSON manifest.

    Every file is written atomically with the SHA-256 of its rows in its metadata and verified
    when loaded: a file that fails is moved to ``out/_quarantine/`` and reported
    (:class:`QuarantinedFile`).

    Parameters
    ----------
    out : str or Path
        The directory.
    schema : pyarrow.Schema
        Columns (and types) of every file; :meth:`write` takes these columns of a frame.
    tags : sequence of str
        Allowed tags, in priority order: when files of one key carry several tags,
        :meth:`finished` reports the first in this order.
    prefix : str
        File name prefix (no ``-`` at the ends, must not start with ``_`` or ``.``).
    manifest : str
        File name of the JSON manifest in ``out``.

    Examples
    --------
    >>> import tempfile, pyarrow as pa, pandas as pd
    >>> store = ParquetStore(tempfile.mkdtemp(), pa.schema([("force_n", pa.float64())]),
    ...                      tags=("ok", "failed"))
    >>> _ = store.write("a1", "ok", pd.DataFrame({"force_n": [1.5, 2.5]}))
    >>> store.finished(), store.read()["force_n"].tolist()
    ({'a1': 'ok'}, [1.5, 2.5])
    >>> import struct                                     # change 2.5 N to 3.5 N in the file
    >>> f = store.path("a1", "ok")
    >>> _ = f.write_bytes(f.read_bytes().replace(struct.pack("<d", 2.5), struct.pack("<d", 3.5)))
    >>> tables, bad = store.load()
    >>> tables, bad[0].reason[:17], bad[0].moved_to.endswith("_quarantine/part-a1-ok.parquet")
    ({}, 'checksum mismatch', True)
    """

    def __init__(self, out: str | Path, schema: pa.Schema, *, tags: Sequence[str] = ("ok",),
                 prefix: str = "part", manifest: str = "_manifest.json") -> None:
        if not tags or any("-" in t or not t for t in tags):
            raise InputError(f"tags must be non-empty names without '-', got {list(tags)}")
        if not prefix or prefix[0] in "_.-" or prefix.endswith("-"):
            raise InputError(f"prefix must not start with '_', '.' or '-', got {prefix!r}")
        self.out = Path(out)
        self.schema = schema
        self.tags = tuple(tags)
        self.prefix = prefix
        self.manifest = manifest
        if self.out.exists() and not self.out.is_dir():
            raise InputError(f"{self.out} exists and is not a directory")
        self.out.mkdir(parents=True, exist_ok=True)

    def path(self, key: str, tag: str) -> Path:
        """The file of ``key`` with ``tag``: ``out/<prefix>-<key>-<tag>.parquet``.

        Parameters
        ----------
        key : str
            The part's key (no ``-`` needed at the ends; may contain ``-``).
        tag : str
            One of ``tags``.
        """
        return self.out / f"{self.prefix}-{key}-{tag}.parquet"

    def remove_temporary(self) -> int:
        """Delete temporary files left by a killed writer; returns how many."""
        stale = (list(self.out.glob(f".{self.prefix}-*.tmp"))
                 + list(self.out.glob(f".{self.manifest}.*.tmp")))
        for f in stale:
            f.unlink(missing_ok=True)
        return len(stale)

    def finished(self) -> dict[str, str]:
        """Key -> tag of every file present (the first tag in ``tags`` order wins); not verified
        (:meth:`load` verifies)."""
        rank = {t: i for i, t in enumerate(self.tags)}
        found: dict[str, str] = {}
        for f in self.out.glob(f"{self.prefix}-*-*.parquet"):
            key, _, tag = f.stem.removeprefix(f"{self.prefix}-").rpartition("-")
            if tag in rank and (key not in found or rank[tag] < rank[found[key]]):
                found[key] = tag
        return found

    def write(self, key: str, tag: str, rows: pd.DataFrame) -> Path:
        """Write ``rows`` (the schema's columns) as the file of ``key`` atomically; return it.

        The rows' :func:`content_sha256` goes into the file's metadata (``exofric.sha256``).
        A file of the same key with another tag is removed afterwards.

        Parameters
        ----------
        key : str
            The part's key.
        tag : str
            One of ``tags``.
        rows : pandas.DataFrame
            The rows; columns of the schema are taken (others ignored), index dropped.
        """
        import pyarrow as pa
        import pyarrow.parquet as pq

        if tag not in self.tags:
            raise InputError(f"tag must be one of {', '.join(self.tags)}, got {tag!r}")
        table = pa.Table.from_pandas(rows[self.schema.names], schema=self.schema,
                                     preserve_index=False)
        table = table.replace_schema_metadata(
            {**(table.schema.metadata or {}), CHECKSUM_KEY: content_sha256(table).encode()})
        final = self.path(key, tag)
        with atomic_path(final) as tmp:
            pq.write_table(table, tmp)
        for other in self.tags:
            if other != tag:
                self.path(key, other).unlink(missing_ok=True)
        return final

    def verify(self, key: str, tag: str, check: RowCheck | None = None
               ) -> tuple[pa.Table | None, str]:
        """Read and verify the file of ``key``: ``(table, "")``, or ``(None, reason)``.

        Verified: that the bytes parse as Parquet with the schema, that the rows match the
        SHA-256 in the file's metadata (files written before checksums existed have none),
        and ``check(key, tag, table)`` (the caller's row check, e.g. re-derived columns).
        Nothing is moved (see :meth:`quarantine`).

        Parameters
        ----------
        key : str
            The part's key.
        tag : str
            One of ``tags``.
        check : callable, optional
            ``check(key, tag, table)`` returning ``""`` or the reason the rows are wrong.
        """
        import pyarrow as pa
        import pyarrow.parquet as pq

        f = self.path(key, tag)
        try:
            data = f.read_bytes()
        except OSError as exc:
            return None, f"cannot be read ({_one_line(exc)})"
        try:
            meta = pq.read_metadata(pa.BufferReader(data)).metadata or {}
            table = pq.read_table(pa.BufferReader(data), schema=self.schema)
            actual = content_sha256(table) if CHECKSUM_KEY in meta else ""
        except Exception as exc:  # ArrowInvalid, OSError...: whatever a damaged file raises
            return None, f"not a readable Parquet file ({_one_line(exc)})"
        if CHECKSUM_KEY in meta:
            recorded = meta[CHECKSUM_KEY].decode("ascii", "replace")
            if actual != recorded:
                return None, (f"checksum mismatch (SHA-256 of the rows {actual[:12]}..., "
                              f"recorded {recorded[:12]}...): the file changed after it was "
                              "written")
        if check is not None:
            reason = check(key, tag, table)
            if reason:
                return None, reason
        return table, ""

    def quarantine(self, key: str, tag: str, reason: str) -> QuarantinedFile:
        """Move the file of ``key`` to ``out/_quarantine/``; never raises.

        An existing quarantined file of the same name is kept (the new one gets a ``.1``,
        ``.2``... suffix). If the move fails (read-only folder...), the file stays and the
        returned reason says so.

        Parameters
        ----------
        key : str
            The part's key.
        tag : str
            One of ``tags``.
        reason : str
            Why (one line), from :meth:`verify`.
        """
        f = self.path(key, tag)
        q = self.out / QUARANTINE
        try:
            q.mkdir(exist_ok=True)
            dest, n = q / f.name, 0
            while dest.exists():
                n += 1
                dest = q / f"{f.name}.{n}"
            os.replace(f, dest)
        except OSError as exc:
            return QuarantinedFile(key, tag, str(f), f"{reason} (could not move it to "
                                   f"{QUARANTINE}/: {exc.strerror or exc})")
        return QuarantinedFile(key, tag, str(f), reason, str(dest))

    def load(self, keys: Iterable[str] | None = None, check: RowCheck | None = None,
             *, move: bool = True) -> tuple[dict[str, tuple[str, pa.Table]],
                                           list[QuarantinedFile]]:
        """The verified tables of ``keys`` and the files that failed (:meth:`verify`).

        Parameters
        ----------
        keys : iterable of str, optional
            Keys to load (default: every file); keys without a file are left out.
        check : callable, optional
            The row check passed to :meth:`verify`.
        move : bool
            Move failed files to ``out/_quarantine/`` (:meth:`quarantine`).

        Returns
        -------
        tables : dict
            Key -> (tag, pyarrow.Table) of every file that passed, in ``keys`` order.
        bad : list of QuarantinedFile
            The files that did not; their keys count as missing.
        """
        have = self.finished()
        want = list(have) if keys is None else [k for k in keys if k in have]
        good: dict[str, tuple[str, pa.Table]] = {}
        bad: list[QuarantinedFile] = []
        for k in want:
            table, reason = self.verify(k, have[k], check)
            if table is not None:
                good[k] = (have[k], table)
            elif move:
                bad.append(self.quarantine(k, have[k], reason))
            else:
                bad.append(QuarantinedFile(k, have[k], str(self.path(k, have[k])), reason))
        return good, bad

    def read(self, keys: Iterable[str] | None = None) -> pd.DataFrame:
        """The rows of ``keys`` (default: every file), in that order, as one DataFrame.

        Files failing verification are quarantined (:meth:`load`) and left out, with a
        :class:`RuntimeWarning` each.

        Parameters
        ----------
        keys : iterable of str, optional
            Keys to read; keys without a file are skipped. An empty result has the schema's
            columns.
        """
        import warnings

        tables, bad = self.load(keys)
        for q in bad:
            warnings.warn(q.message(), RuntimeWarning, stacklevel=2)
        return self.concat([t for _, t in tables.values()])

    def concat(self, tables: Sequence[pa.Table]) -> pd.DataFrame:
        """``tables`` (of the schema) as one DataFrame; an empty one has the schema's columns.

        Parameters
        ----------
        tables : sequence of pyarrow.Table
            Tables of :attr:`schema`, e.g. from :meth:`load`.
        """
        import pyarrow as pa

        if not tables:
            return self.schema.empty_table().to_pandas()
        return pa.concat_tables(list(tables)).to_pandas()

    def write_manifest(self, data: Mapping[str, Any]) -> Path:
        """Write ``data`` (JSON-ready after :func:`~exofric.io.jsonable`) as the manifest.

        Parameters
        ----------
        data : mapping
            Plain data; written atomically to ``out/<manifest>``.
        """
        return write_json(dict(data), self.out / self.manifest, indent=1)

    def read_manifest(self) -> dict[str, Any] | None:
        """The manifest as a dict, or None when there is none yet.

        Raises :class:`~exofric.errors.InputError` (one line) when it is not a JSON object.
        """
        p = self.out / self.manifest
        if not p.is_file():
            return None
        data = read_json(p)
        if not isinstance(data, dict):
            raise InputError(f"{p.name}: expected a JSON object")
        return data

