"""Every file exofric reads or writes: unit-checked tables, TOML, JSON, Parquet stores, VTU.

* :func:`read_table` -- a CSV with units in the headers (``pressure_mpa``, ``friction_n``),
  validated: one line naming the file, the row or column and what is allowed.
* :func:`read_inflation_table`, :func:`read_squeeze_curve`, :func:`read_friction_table`,
  :func:`read_step_response` -- the rig and curve files, as validated DataFrames
  (``attrs["source"]`` is the file name); domain classes build themselves from them.
* :func:`read_raw_log`, :func:`write_raw_log`, :func:`parse_column_map` -- raw rig logs (CSV,
  Parquet, NI TDMS) converted to s, MPa, N, mm with pint (:data:`RAW_QUANTITIES`), checked for
  NaN bursts, time going back and gaps; ``--columns`` maps other headers.
* :func:`read_stress_stretch` -- a material test curve (stretch or strain, stress in MPa, an
  optional ``# stress_kind:`` line) for :func:`exofric.material.fit_material`.
* :func:`read_toml`, :func:`read_json` -- a dict, or one line naming the file, line and column.
* :func:`jsonable`, :func:`write_json`, :func:`write_text`, :func:`atomic_path` -- JSON-ready
  values (NaN -> null) and atomic writes (temporary file in the same directory, then
  :func:`os.replace`): never a partial file under the final name.
* :class:`ParquetStore` -- one Parquet file per key, written atomically with a SHA-256 sidecar
  and verified when read (failures go to a ``_quarantine/`` folder as :class:`QuarantinedFile`),
  plus a JSON manifest.
* :func:`write_vtu` -- a deformed FE mesh for ParaView.

``io`` knows file formats, not exofric's domain types; it imports only :mod:`exofric.errors`.
Units: whatever the column suffixes say (mm, N, MPa, s, Nm, %).

Examples
--------
>>> from exofric import paper
>>> from exofric.io import read_table
>>> df = read_table(paper.data_path("table1_test.csv"), ["pressure_mpa", "outer_diameter_mm"])
>>> list(df.columns)[:2]
['pressure_mpa', 'outer_diameter_mm']
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import facade

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.io._files import (
        UNIT_SUFFIXES,
        atomic_path,
        jsonable,
        read_json,
        read_table,
        read_toml,
        write_json,
        write_text,
    )
    from exofric.io._material import read_stress_stretch
    from exofric.io._rawlog import (
        RAW_QUANTITIES,
        parse_column_map,
        read_raw_log,
        write_raw_log,
    )
    from exofric.io._rig import (
        read_friction_table,
        read_inflation_table,
        read_squeeze_curve,
        read_step_response,
    )
    from exofric.io._ring import RING_HEADER_KEYS, read_header_sizes, read_ring_test
    from exofric.io._store import ParquetStore, QuarantinedFile
    from exofric.io._vtu import QUAD9_TO_VTK, write_vtu

# Lazy facade (PEP 562): ``jsonable`` or ``read_toml`` does not load the rig, Parquet and VTU
# modules; each name is loaded from its module on first use (exofric/__init__.py does the same one
# level up).
_MODULES: dict[str, tuple[str, ...]] = {
    "_files": (
        "UNIT_SUFFIXES", "atomic_path", "jsonable", "read_json", "read_table", "read_toml",
        "write_json", "write_text",
    ),
    "_material": ("read_stress_stretch",),
    "_rawlog": ("RAW_QUANTITIES", "parse_column_map", "read_raw_log", "write_raw_log"),
    "_ring": ("RING_HEADER_KEYS", "read_header_sizes", "read_ring_test"),
    "_rig": (
        "read_friction_table", "read_inflation_table", "read_squeeze_curve", "read_step_response",
    ),
    "_store": ("ParquetStore", "QuarantinedFile"),
    "_vtu": ("QUAD9_TO_VTK", "write_vtu"),
}
_HOME = {name: mod for mod, names in _MODULES.items() for name in names}

__all__ = [
    "atomic_path", "jsonable", "parse_column_map", "ParquetStore", "QUAD9_TO_VTK",
    "QuarantinedFile", "RAW_QUANTITIES", "read_friction_table", "read_inflation_table",
    "read_header_sizes", "read_json", "read_raw_log", "read_ring_test", "RING_HEADER_KEYS",
    "read_squeeze_curve", "read_step_response",
    "read_stress_stretch", "read_table", "read_toml", "UNIT_SUFFIXES", "write_json",
    "write_raw_log", "write_text", "write_vtu",
]

__getattr__, __dir__ = facade(__name__, _HOME, __all__)
