"""Material test files: one loading curve of stretch (or strain) against stress in MPa."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING

from exofric.errors import InputError
from exofric.io._files import read_table

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["read_stress_stretch"]

_KIND = re.compile(r"^\s*#\s*stress[_ ]kind\s*[:=]\s*(\S+)", re.IGNORECASE)


def read_stress_stretch(path: str | Path, stress_kind: str | None = None) -> pd.DataFrame:
    """Read a material test file: ``stretch`` (or ``strain``) and ``stress_mpa``, checked.

    A CSV with a header row; ``#`` lines are comments. Columns: ``stretch`` (unitless, > 0) or
    ``strain`` (engineering strain, unitless, > -1; ``stretch = 1 + strain``), and
    ``stress_mpa`` (MPa). The stress measure may be stated in a comment line
    ``# stress_kind: true`` (or ``engineering``); the ``stress_kind`` argument, when given,
    wins over the file. The curve must be one loading curve: stretch strictly monotonic.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    stress_kind : {'engineering', 'true'} or None
        The stress measure; None: the file's ``# stress_kind:`` line, else ``engineering``.

    Returns
    -------
    pandas.DataFrame
        Columns ``stretch`` (unitless) and ``stress_mpa`` (MPa); ``attrs["stress_kind"]``
        and ``attrs["source"]`` (the file name).

    Raises
    ------
    InputError
        One line naming the file, the row and the column: a missing column, stretch <= 0
        (strain <= -1), a stretch that does not keep rising (or falling), a bad stress kind.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "ux.csv"
    >>> _ = p.write_text("# stress_kind: true\\nstrain,stress_mpa\\n0.1,0.2\\n0.5,0.9\\n")
    >>> df = read_stress_stretch(p)
    >>> df["stretch"].tolist(), df.attrs["stress_kind"]
    ([1.1, 1.5], 'true')
    """
    import numpy as np

    p = Path(path)
    name = p.name
    df = read_table(p, ["stress_mpa"], ["stretch", "strain"], nonnegative=[], min_rows=1)
    kind_in_file = None
    for line in p.read_text(encoding="utf-8-sig").splitlines():
        m = _KIND.match(line)
        if m:
            kind_in_file = m.group(1).strip().lower()
            break
    kind = stress_kind if stress_kind is not None else (kind_in_file or "engineering")
    if kind not in ("engineering", "true"):
        where = "stress_kind" if stress_kind is not None else f"{name}: '# stress_kind:' line"
        raise InputError(f"{where} must be engineering or true, got {kind!r}",
                         param="stress_kind" if stress_kind is not None else None)
    if "stretch" in df.columns and "strain" in df.columns:
        raise InputError(f"{name}: give a 'stretch' or a 'strain' column, not both")
    if "stretch" in df.columns:
        col, lam = "stretch", df["stretch"].to_numpy(dtype=float)
    elif "strain" in df.columns:
        col, lam = "strain", 1.0 + df["strain"].to_numpy(dtype=float)
    else:
        raise InputError(f"{name}: missing column 'stretch' or 'strain' (with 'stress_mpa')")
    bad = np.flatnonzero(lam <= 0.0)
    if bad.size:
        i = int(bad[0])
        limit = "> 0" if col == "stretch" else "> -1"
        raise InputError(f"{name}: data row {i + 1}, column {col!r} must be {limit}, got "
                         f"{df[col].iloc[i]:g}")
    step = np.diff(lam)
    if step.size and not (np.all(step > 0.0) or np.all(step < 0.0)):
        sign = 1.0 if step[0] > 0 else -1.0
        i = int(np.flatnonzero(sign * step <= 0.0)[0]) + 1
        raise InputError(f"{name}: data row {i + 1}, column {col!r} is not monotonic "
                         f"({df[col].iloc[i - 1]:g} then {df[col].iloc[i]:g}): give one "
                         "loading curve per file")
    import pandas as pd

    out = pd.DataFrame({"stretch": lam, "stress_mpa": df["stress_mpa"].to_numpy(dtype=float)})
    out.attrs["stress_kind"] = kind
    out.attrs["source"] = name
    return out
