"""Every file exofric reads or writes: unit-checked tables, JSON, VTU meshes.

* :func:`read_table` -- a CSV with units in the headers (``pressure_mpa``, ``friction_n``),
  validated: one line naming the file, the row or column and what is allowed.
* :func:`jsonable`, :func:`write_json` -- JSON-ready values (NaN -> null) and an atomic write.
* :func:`write_vtu` -- a deformed FE mesh for ParaView.

Units: whatever the column suffixes say (mm, N, MPa, s, Nm, %).

Examples
--------
>>> from exofric import paper
>>> from exofric.io import read_table
>>> df = read_table(paper.data_path("table1_test.csv"), ["pressure_mpa", "outer_diameter_mm"])
>>> list(df.columns)[:2]
['pressure_mpa', 'outer_diameter_mm']
"""

from exofric.io._files import UNIT_SUFFIXES, jsonable, read_table, write_json
from exofric.io._vtu import QUAD9_TO_VTK, write_vtu

__all__ = ["jsonable", "QUAD9_TO_VTK", "read_table", "UNIT_SUFFIXES", "write_json", "write_vtu"]
