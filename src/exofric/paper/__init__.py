"""The paper (Ma et al., Actuators 2021) as data: its printed numbers with provenance, its notes.

Everything printed in the paper that exofric reproduces or checks lives in
``exofric/paper/data/paper.toml`` (tables, scalars, Eq 8) and two CSVs (Table 1 test and
simulated columns); the discrepancies we found are in ``exofric/paper/notes.md``. Nothing here
computes.

Units: mm, N, MPa, s (Nm for torque), as in the files' keys.

Examples
--------
>>> from exofric import paper
>>> paper.scalar("gamma")
0.7168
>>> paper.table3()[0]["hole_mm"]
10.0
"""

from exofric.paper._data import (
    data_path,
    eq8,
    load,
    notes_path,
    scalar,
    table1,
    table1_points,
    table2,
    table3,
    table4,
    to_dict,
)

__all__ = [
    "data_path",
    "eq8",
    "load",
    "notes_path",
    "scalar",
    "table1",
    "table1_points",
    "table2",
    "table3",
    "table4",
    "to_dict",
]

# every public function checks its arguments' kinds (InputError naming the parameter)
from exofric._lazy import export_checked  # noqa: E402

export_checked(__name__)
