"""Every file exofric reads or writes: unit-checked tables, TOML, JSON, Parquet stores, VTU.

* :func:`read_measured_table` -- one reader for every measured table (CSV/TSV/``;`` with
  decimal commas, UTF-16/Latin-1, vendor preambles, units rows, LabVIEW LVM, NI TDMS, Parquet,
  xlsx), headers with units in any spelling (``pressure_kpa``, ``Pressure (kPa)``,
  ``Force [N]``) converted with pint to exofric's columns; the rig readers below use it.
* :func:`read_table` -- such a table with units in the headers (``pressure_mpa``,
  ``friction_n``), validated: one line naming the file, the row or column and what is allowed.
* :func:`read_inflation_table`, :func:`read_squeeze_curve`, :func:`read_friction_table`,
  :func:`read_step_response` -- the rig and curve files, as validated DataFrames
  (``attrs["source"]`` is the file name); domain classes build themselves from them.
* :func:`read_raw_log`, :func:`write_raw_log`, :func:`parse_column_map` -- raw rig logs (CSV,
  Parquet, NI TDMS) converted to s, MPa, N, mm with pint (:data:`RAW_QUANTITIES`), checked for
  NaN bursts, time going back and gaps; ``columns`` (``--columns``) maps other headers.
* :func:`read_stress_stretch` -- a material test curve as tensile machines write it (load and
  extension with the specimen's sizes, engineering or true strain and stress, any format of
  the table reader) to stretch and stress in MPa for :func:`exofric.material.fit_material`;
  :func:`tensile_stress_stretch` the same conversion on a DataFrame (:data:`TENSILE_ROLES`).
* :func:`read_gait`, :class:`GaitData`, :func:`gait_data_path` -- walking data (knee angle,
  moment) from OpenSim ``.sto``/``.mot`` and tables; the shipped OpenSim stride.
* :func:`is_raw_log` -- whether a file is a raw rig log (a time series) or a results table.
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

from exofric._lazy import lazy_package

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
    from exofric.io._gait import GAIT_DATA_FILE, GaitData, gait_data_path, read_gait
    from exofric.io._material import TENSILE_ROLES, read_stress_stretch, tensile_stress_stretch
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
    from exofric.io._table import is_raw_log, read_measured_table
    from exofric.io._vtu import QUAD9_TO_VTK, write_vtu


# Lazy facade (PEP 562): ``jsonable`` or ``read_toml`` does not load the rig, Parquet and VTU
# modules; each name is loaded from its module on first use. The TYPE_CHECKING imports above
# are the one list of public names: __all__ and the facade are derived from them
# (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
