"""Ring tensile test files: pin displacement (mm) against force (N)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exofric.errors import InputError
from exofric.io._files import read_table

__all__ = ["read_ring_test"]


def read_ring_test(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Read a measured ring tensile test: ``displacement_mm`` and ``force_n``, checked.

    A CSV with a header row; ``#`` lines are comments; other columns are ignored. The
    displacement is the increase of the pins' separation from where they first touch the
    bore (mm), >= 0 and strictly increasing (one loading curve); the force is the machine's
    load on one pin (N).

    Parameters
    ----------
    path : str or Path
        The CSV file.

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
                    min_rows=1)
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
    return d, f
