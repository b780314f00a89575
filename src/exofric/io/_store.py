"""A directory of Parquet files, one per key, each written atomically, plus a JSON manifest.

Layout (``OUT/``): ``<prefix>-<key>-<tag>.parquet`` per key, where ``tag`` is one of a fixed
set of labels (e.g. a status); written to a hidden temporary file and renamed, so a killed
writer leaves only complete files and a directory listing tells what is finished.
``OUT/<manifest>`` is a JSON file (also written atomically). ``pandas.read_parquet(OUT)``
reads every part at once (pyarrow ignores files starting with ``_`` or ``.``).

Knows nothing of what the rows mean: the caller gives the Arrow schema and the tags.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from exofric.errors import InputError
from exofric.io._files import atomic_path, read_json, write_json

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa

__all__ = ["ParquetStore"]


class ParquetStore:
    """One Parquet file per key in a directory (created if missing), with a JSON manifest.

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
        """Key -> tag of every file present (the first tag in ``tags`` order wins)."""
        rank = {t: i for i, t in enumerate(self.tags)}
        found: dict[str, str] = {}
        for f in self.out.glob(f"{self.prefix}-*-*.parquet"):
            key, _, tag = f.stem.removeprefix(f"{self.prefix}-").rpartition("-")
            if tag in rank and (key not in found or rank[tag] < rank[found[key]]):
                found[key] = tag
        return found

    def write(self, key: str, tag: str, rows: pd.DataFrame) -> Path:
        """Write ``rows`` (the schema's columns) as the file of ``key`` atomically; return it.

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
        final = self.path(key, tag)
        with atomic_path(final) as tmp:
            pq.write_table(table, tmp)
        for other in self.tags:
            if other != tag:
                self.path(key, other).unlink(missing_ok=True)
        return final

    def read(self, keys: Iterable[str] | None = None) -> pd.DataFrame:
        """The rows of ``keys`` (default: every file), in that order, as one DataFrame.

        Parameters
        ----------
        keys : iterable of str, optional
            Keys to read; keys without a file are skipped. An empty result has the schema's
            columns.
        """
        import pyarrow as pa
        import pyarrow.parquet as pq

        have = self.finished()
        want = list(have) if keys is None else [k for k in keys if k in have]
        tables = [pq.read_table(self.path(k, have[k]), schema=self.schema) for k in want]
        if not tables:
            return self.schema.empty_table().to_pandas()
        return pa.concat_tables(tables).to_pandas()

    def write_manifest(self, data: Mapping[str, Any]) -> Path:
        """Write ``data`` (JSON-ready after :func:`~exofric.io.jsonable`) as the manifest.

        Parameters
        ----------
        data : mapping
            Plain data; written atomically to ``out/<manifest>``.
        """
        return write_json(dict(data), self.out / self.manifest, indent=1)

    def read_manifest(self) -> dict[str, Any] | None:
        """The manifest as a dict, or None when there is none yet."""
        p = self.out / self.manifest
        if not p.is_file():
            return None
        data = read_json(p)
        if not isinstance(data, dict):
            raise InputError(f"{p.name}: expected a JSON object")
        return data
