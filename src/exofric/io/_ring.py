"""Ring tensile test files: pin displacement (mm) against force (N)."""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from exofric.errors import InputError, warn_implausible
from exofric.io._files import read_table
from exofric.io._table import _decode

_HEADER = re.compile(r"^\s*#\s*([A-Za-z][A-Za-z0-9_]*)\s*[:=]\s*(.*?)\s*$")

__all__ = ["read_ring_test", "read_header_sizes", "RING_HEADER_KEYS"]

#: Sizes a ring-test file may state in ``# key: value`` header comments (mm).
RING_HEADER_KEYS = ("width_mm", "pin_mm", "ring_od_mm", "ring_id_mm")


def read_header_sizes(path: str | Path, keys: Sequence[str]) -> dict[str, float]:
    """Sizes (mm) stated in a CSV's header comments as ``# key: value`` lines.

    A test file can carry its own geometry, e.g. a ring test's ``# width_mm: 5`` and
    ``# pin_mm: 3`` or an inflation test's ``# tube_od_mm: 8.3``; command-line options
    override it. Keys are matched case-insensitively; only comment lines before the first data
    row count; each value must be a positive number.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    keys : sequence of str
        The keys to look for (e.g. :data:`RING_HEADER_KEYS`).

    Returns
    -------
    dict of str to float
        The keys found, with their values (mm).

    Raises
    ------
    InputError
        A stated value that is not a positive number (one line naming the file and the key).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "ring.csv"
    >>> _ = p.write_text("# width_mm: 5\\n# Pin_mm = 3\\ndisplacement_mm,force_n\\n1,1\\n")
    >>> read_header_sizes(p, RING_HEADER_KEYS)
    {'width_mm': 5.0, 'pin_mm': 3.0}
    """
    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise InputError(f"{p}: cannot be read ({exc.strerror or exc})") from None
    text = _decode(data, p.name)[0].decode("utf-8")  # UTF-16 or Latin-1 files too
    want = {k.lower(): k for k in keys}
    out: dict[str, float] = {}
    for line in text.splitlines():
        if not line.strip():
            continue
        if not line.lstrip().startswith("#"):
            break  # the header row: data follow
        m = _HEADER.match(line)
        if m is None or m.group(1).lower() not in want:
            continue
        key, raw = want[m.group(1).lower()], m.group(2).strip()
        try:
            v = float(raw)
        except ValueError:
            v = float("nan")
        if not (np.isfinite(v) and v > 0.0):
            raise InputError(f"{p.name}: header '# {key}:' must be a positive number (mm), got "
                             f"{raw!r}", param=key)
        out[key] = v
    return out


def read_ring_test(path: str | Path, columns: Mapping[str, str] | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Read a measured ring tensile test: ``displacement_mm`` and ``force_n``, checked.

    A table with a header row (any format and header spelling of
    :func:`exofric.io.read_measured_table`: a Bluehill export with its preamble, ``Extension
    (mm)`` mapped with ``columns``, other units converted); ``#`` lines are comments (the
    ring's sizes may be stated there, see :func:`read_header_sizes`); other columns are
    ignored. The
    displacement is the increase of the pins' separation from where they first touch the
    bore (mm), >= 0 and strictly increasing (one loading curve); the force is the machine's
    load on one pin (N).

    Parameters
    ----------
    path : str or Path
        The table.
    columns : mapping of str to str, optional
        ``{key: header}`` for columns with other names, e.g. ``{"displacement_mm":
        "Extension", "force_n": "Load"}``.

    Returns
    -------
    displacement_mm, force_n : ndarray
        Pin displacements (mm) and forces (N).

    Raises
    ------
    InputError
        One line naming the file, the column and the row: a missing column, a value that is
        not a number or NaN, a negative or non-increasing displacement.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "ring.csv"
    >>> _ = p.write_text("# ring 8.3/4.97 x 5 mm\\ndisplacement_mm,force_n\\n0.5,0.4\\n1,1.3\\n")
    >>> d, f = read_ring_test(p)
    >>> d.tolist(), f.tolist()
    ([0.5, 1.0], [0.4, 1.3])
    """
    p = Path(path)
    df = read_table(p, ["displacement_mm", "force_n"], nonnegative=["displacement_mm"],
                    min_rows=1, columns=columns)
    d = df["displacement_mm"].to_numpy(dtype=float)
    f = df["force_n"].to_numpy(dtype=float)
    for col, v in (("displacement_mm", d), ("force_n", f)):
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise InputError(f"{p.name}: data row {bad[0] + 1}, column '{col}' is not a "
                             f"finite number: {v[bad[0]]!r}")
    neg = np.flatnonzero(d < 0.0)
    if neg.size:
        raise InputError(f"{p.name}: data row {neg[0] + 1}, column 'displacement_mm' must be "
                         f">= 0 mm, got {d[neg[0]]:g}")
    back = np.flatnonzero(np.diff(d) <= 0.0)
    if back.size:
        k = int(back[0]) + 1
        raise InputError(f"{p.name}: data row {k + 1}, column 'displacement_mm' must increase "
                         f"strictly (one loading curve), got {d[k]:g} mm after {d[k - 1]:g}")
    neg = np.flatnonzero(f < 0.0)
    if neg.size:   # a tare offset can dip below 0 near the start; a whole curve below is a sign
        warn_implausible(f"{p.name}: column 'force_n' is negative in {neg.size} of {f.size} "
                         f"rows (from data row {neg[0] + 1}: {f[neg[0]]:g} N): the pins pull "
                         "the ring apart, its force is >= 0; check the sign convention")
    return d, f
