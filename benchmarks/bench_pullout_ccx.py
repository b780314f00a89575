"""Benchmark: independent 3-D CalculiX check of the wire pull-out (issue 39 acceptance).

Run: ``python benchmarks/bench_pullout_ccx.py [--full | --quick | --tubes-only [--tubes
REGEX]] [--json] [--out PATH]``. Without options (``make bench``): exofric against the stored
CalculiX references, a few seconds, no CalculiX, nothing written. ``--full``: the slices and their
studies (~35 min on the shared machine), written atomically after every run to
``tests/data/ccx_pullout.json`` (``complete`` false until the end) or ``--out``. ``--quick``:
two coarse slices (~2 min), written only with ``--out``. ``--tubes-only``: the held tubes and
their studies (``ALL_TUBE_RUNS``, the runs not yet stored, only those whose tag matches
``--tubes REGEX`` if given; 1-10 min CPU per run), written to
``tests/data/ccx_pullout_tube.json`` after every run, merged by tag under a lock with what is
on disk (two processes with different ``--tubes`` keep each other's runs). Every mode prints
reference (CalculiX) vs exofric with relative errors.

Problem (units mm, N, MPa, s): the base group (``exofric.geometry.BASE``, Table 3 test 1) and
Table 3 test 3 (hole 12.3, tube 10.2 / ID 6.108 (the base's ID scaled with the OD, as
``exofric.friction.paper_structures``), wire 2.0 mm), Shore 62.5 through
``MooneyRivlin.from_shore`` (constants only), weightless, mu_wire 0.3, mu_wall 0.5,
mu_wire_wall 0 (the wire-wall line contact does not exist between two rigid bodies in the
3-D model), pressures 0.2 ... 0.6 MPa.

Model: ``calculix_pullout.pullout_deck`` (CalculiX 2.20; module docstring there): C3D20R
bricks (ccx 2.20 has no hybrid C3D20H: "C3D20H is an unknown element type"), rigid hole and
wire as prescribed element layers, node-to-surface penalty contact with ``*FRICTION``; step 1
inflates (friction 1e-6, i.e. frictionless: the reference squeeze is exofric's frictionless
plane-strain squeeze), step 2 switches the friction on (``*CHANGE FRICTION``) and pulls the
wire along z with the pressure held.

* slice: 1 mm thick, 2 elements, periodic along z (``*EQUATION`` back = front, 3
  components): per mm of tube, compared with ``section_pullout(..., ends="free")`` (a
  periodic slice has no end fittings; exofric's ``ends="fixed"`` is reported too: since
  session 48 the fittings' rod acts only on the wall's slip, so with the wall holding it
  equals ``free``; before, a foundation spread by area put k0 1-12 % higher).
* held tubes (``--tubes-only``, ``ALL_TUBE_RUNS``, written to
  ``tests/data/ccx_pullout_tube.json`` under ``runs`` by tag): 5 mm of the base group and of
  test 3 at 0.2 / 0.4 / 0.6 MPa, 10 mm of the base group at 0.6 MPa, ends held axially (u_z =
  0 on the end faces, in-plane free), the rigid wire pulled through it: F(delta) compared with
  ``pullout(..., ends="fixed")`` on the same structure and length with a rigid cable
  (``cable_ea_n`` 1e5 N: EA / L >= 3e3 N/mm against the tube's <= 40 N/mm. Not 1e9: exofric's
  shear-lag residual tolerance scales with EA / h, and with EA = 1e9 (30 mm) or 1e7 (5 mm, free
  ends) its pulled-end sliding force was 3-4 % off); studies along z of all (and of the 5 mm
  base tube in the plane at 0.6 MPa; ``ALL_TUBE_RUNS`` lists them). A 30 mm tube with graded
  elements along z (0.68 mm at the held faces, 2.7 mm in the middle) and 8 or 10 graded
  elements of 2-6 mm stalled in the inflation (see ``calculix_pullout``); with 30 uniform
  elements of 1 mm it runs (``TUBE_RUNS_LONG``, session 45).

Measures: sliding force = the force at the end of the travel (its flatness over the last
three outputs is stored: < 4e-6); initial stiffness = F(d1) / d1 at the first output
d1 = 5e-4 x the travel (all arcs stuck there: F / delta is constant to 4e-7 over the next two
outputs); S_wire = radial parts of the wire's nodal reactions (at the end of the inflation and
along the pull: the change the reduced model neglects). For the held tube the early F / delta
is not an elastic stiffness (its end rows, held at u_z = 0 against the moving wire, slip at
once): two secants F(d) / d are compared, k1 at d1 = 0.1 mm (P / 0.6 MPa)^2 (0.011 / 0.044
/ 0.1 mm at 0.2 / 0.4 / 0.6 MPa; the 3-D force there is 0.30-0.42 x the sliding force, the
"half-sliding" secant) and k2 at d2 = 2 d1 (0.53-0.72 x; 0.2 mm at 0.6 MPa, the secant of the
first comparison); the slip displacement scales with P^2, and at 0.2 MPa the 5 mm tubes slide
fully by ~0.06 mm, so a fixed 0.2 mm would measure sliding there. The secant runs go to 4 d1
(d1, d2 the 10th and 20th of 40 even outputs); exofric's secants are read on its first-loading
path (finely stepped up to the breakaway; the even path to 0.7 mm interpolated over the knee
reads k1 at 0.2 MPa 1.2 % low). A run counts as sliding when its force is flat to 1e-5 over
its last three outputs (``PLATEAU_FLATNESS``).

Measured 2026-11-27 (ccx 2.20, one thread, a 2-core machine shared by several jobs; the JSON
has every number and time). Reference mesh 3 x 30 (2718 equations): CPU 50-107 s per run (wall
2-5 min). Convergence (base, changes of sliding force / k0): mesh 2 x 20 -> 3 x 30 +0.71 % /
+2.9 % at 0.2 MPa, -0.24 % / +1.5 % at 0.6 MPa; 3 x 30 -> 4 x 40 (75-163 s CPU) +0.28 % / -0.25
% at 0.6 MPa and -0.28 % / +2.2 % at 0.2 MPa (k0 at low pressure, few nodes on the short
contact arc, carries ~2 % of mesh noise; the 4 x 40 k0 equals exofric's there); largest
increment 0.05 / 0.0125 mm against 0.025: 0 / 0; stick slope 300 / 3000 MPa/mm against 1e3: 0 /
-0.44 %, 0 / +0.14 %. In 3-D the wire arc's normal-force integral moves by at most 0.23 % over
the pull, and the sliding force equals mu_wire x its inflated value to 0.02 %.

exofric vs 3-D slice (ends free), base group and test 3, 0.2 / 0.4 / 0.6 MPa: sliding force
+0.03 / +0.56 / +0.46 % and +0.01 / +0.33 / +0.31 %; initial stiffness +2.20 / -2.34 / +0.34 %
and +2.18 / -2.35 / +0.32 % (exofric's own k0 moves by up to 2.4 % between its standard and
fine meshes). With ends "fixed" k0 was 1-12 % higher until session 48 (the fittings' rod as a
foundation, which a periodic slice does not have; now it acts on the wall's slip only, and the
held section equals the free one while the wall holds). (Those numbers are from when the
slices were stored; on the code of 2026-11-27 session 43 the default run prints +2.15 / -4.11
/ -0.38 % and +4.91 / -0.59 / +1.72 % on k0: exofric's section has moved.)

Held tubes, issue 39's pressures (sessions 44-46; secants in N/mm, 2 x 20 in the plane; "1 / 0.5
/ 0.25 / 0.125 mm": uniform elements along z; "g": 0.116 mm at the held faces, graded
geometrically to the middle; CPU on one thread 63-628 s per run, the 0.125 mm runs 1010-1374 s;
errors are exofric's (vector held zone, session 46; the scalar zone in brackets) against the
finest run, the one with the most equations):

tube     P    sliding  k1 3-D: 1 / 0.5 / 0.25 / 0.125 mm  err k1            err k2
5 base   0.2  -1.33 %  9.934 / 9.545 / 9.330 / 8.828      -1.68 (+2.20) %   -2.74 (+0.54) %
5 base   0.4  +0.05 %  13.07 / 12.28 / 11.91 / 11.99      +3.36 (+7.40) %   +3.00 (+6.60) %
5 base   0.6  +0.38 %  14.58 / 14.16 / 14.01 / 13.96      +6.54 (+9.73) %   +1.54 (+4.13) %
10 base  0.6  +0.54 %  20.24 / g 19.53                    +8.74 (+9.68) %   +4.76 (+5.15) %
5 t3     0.2  -1.25 %  11.75 / 11.10 / 10.78 / 10.21      +0.58 (+4.32) %   -1.68 (+1.57) %
5 t3     0.4  +0.03 %  15.80 / 14.70 / 14.14              +2.56 (+6.56) %   +3.19 (+6.71) %
5 t3     0.6  +0.59 %  17.31 / 16.69 / 16.40              +6.71 (+10.36) %  +2.08 (+5.20) %

(k2 3-D: 8.015 / 7.899 / 7.727 / 7.667, 9.808 / 9.830 / 9.855 / 9.897, 11.57 / 11.68 / 11.79 /
11.84, 17.28 / g 17.42, 9.351 / 9.283 / 9.015 / 8.903, 11.59 / 11.48 / 11.54, 13.61 / 13.68 /
13.81.)

The 3-D k1 falls at every halving along z to 0.25 mm (-1.0 to -7.0 %). The halving to 0.125 mm
moves it by -0.37 / +0.70 % at 0.6 / 0.4 MPa (the reference levels off) but by -5.4 / -5.3 % at
0.2 MPa (both tubes, session 46: not converged there). k2 rises at 0.6 MPa (+0.55 to +1.0 % per
halving, then +0.40 %), falls at 0.2 MPa and moves by less than 1 % at 0.4 MPa: no order, no
extrapolation. In the plane 2 x 20 -> 3 x 30 (5 mm base, 0.6 MPa) moves k1 by +0.09 % on 1 mm
elements along z but +1.60 / +2.08 % on 0.5 / 0.25 mm, and 3 x 30 -> 4 x 40 on 0.5 mm by +0.61 %
(session 47, ``TUBE_RUNS_PLANE``; k2 +0.80 / +0.73 / +0.29 % and +0.49 %): once the faces are
resolved, 2 x 20 reads k1 2-3 % low (test 3 on 0.25 mm: +2.93 %). Both 5 mm tubes' finest
runs are then their 3 x 30, 0.25 mm ones (k1 14.306 / 16.886, k2 11.828 / 13.944 N/mm; exofric
+3.98 / +3.67 % and +1.66 / +1.11 %). Session 48: the 10 mm base tube graded on 3 x 30 (24784
equations, 2185 s CPU): k1 20.010 (+2.43 % over 2 x 20), k2 17.539; and exofric with the
fittings' rod on the wall's slip and 20 mm zones (the 5 and 10 mm tubes are wholly zones; the
table's errors move by < 0.3 points): k1 +3.88 / +3.42 % (5 mm base / test 3), +6.15 % (10 mm),
+3.53 % (30 mm against its 1 mm run; k2 +4.74 %, was +7.80 / +8.80 % with the rod as a
foundation). The sliding force is within the issue's 2 % at every pressure; the secants meet the
issue's 5 % everywhere but k1 at 0.6 MPa on the 10 mm base tube (tested at a stated bound until
session 49, ``HELD_K_BOUNDS`` in ``tests/test_pullout_reference.py``; docs/formulation.md section
12). The 30 mm tube on 3 x 30 with 0.25 mm faces (``TUBE_30_PLANE``) timed out in the inflation.
Session 49: the held zone's z grid refined to its own convergence (first element 0.125 mm, growth
1.25; k1 had been 0.9-1.6 % above the converged zone) gives k1 +2.81 / +2.28 % (5 mm base / test 3
at 0.6 MPa), +4.96 % (10 mm), +2.93 % (30 mm) and k2 +1.25 / +0.53, +3.58, +4.37 %: every secant
within 5 %, no bound left. The 10 mm tube on 4 x 40 (``TUBE_10_PLANE``) chattered in the pull.
The 5 mm base tube at 0.4 MPa on 1 mm elements stopped in ccx with "too many cutbacks" (one node,
7133 dof 2) pulled to 1.4, 1 or 0.5 mm (``failures``); its sliding force is from 0.5 mm elements
pulled to 0.5 mm. Earlier (the first comparison, 0.6 MPa only, k2): the smeared end-fitting
foundation (before the held zones) gave -8.9 / -17 % on the 5 / 10 mm base tubes; the test-3 tube
graded as the base tube's (12 elements) crawled in the pull at 0.165 mm (node-to-surface chatter)
and was stopped after 8.6 min CPU; the 30 mm tube with 20 elements graded 0.68 -> 2.7 mm stalled in
the inflation (contact chatter past 0.65 P, stopped after 12 min); both in ``failures``. """

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"
os.environ.setdefault("CCX_NPROC_EQUATION_SOLVER", "1")

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import re  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric.friction import paper_structures  # noqa: E402
from exofric.geometry import Structure  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import calculix_pullout as ccxp  # noqa: E402

SHORE = 62.5
MU_WIRE, MU_WALL = 0.3, 0.5
PRESSURES_MPA = (0.2, 0.4, 0.6)
TUBE_PRESSURES_MPA = (0.6,)
OUT = HERE.parent / "tests" / "data" / "ccx_pullout.json"
OUT_TUBE = HERE.parent / "tests" / "data" / "ccx_pullout_tube.json"
#: structure name -> Table 3 test number
STRUCTURES = {"test 1": 1, "test 3": 3}
MESHES: dict[str, dict[str, int]] = {
    "2x12": {"n_radial": 2, "n_circ": 12, "rigid_elements": 12},
    "2x20": {"n_radial": 2, "n_circ": 20, "rigid_elements": 16},
    "3x30": {"n_radial": 3, "n_circ": 30, "rigid_elements": 24},
    "4x40": {"n_radial": 4, "n_circ": 40, "rigid_elements": 32},
}
REFERENCE_MESH, COARSE_MESH, FINE_MESH = "3x30", "2x20", "4x40"
TUBE_MESH = "2x20"
DELTA_MAX_MM = 2.0
MAX_INCREMENT_MM = 0.025
STICK_SLOPE = ccxp.STICK_SLOPE
SLICE: dict[str, Any] = {"kind": "slice", "depth_mm": 1.0, "n_z": 2}
#: the held tube: 5 mm, 5 elements along z (1 mm: element and master-face aspect ratios like
#: the slice's; a 30 mm tube with 8 or 10 graded elements of 2-6 mm stalled in the inflation,
#: node-to-surface contact chattering on the elongated faces, see the module docstring)
TUBE: dict[str, Any] = {"kind": "tube", "depth_mm": 5.0, "n_z": 5, "z_grading": 1.0,
                        "ends": "fixed", "rigid_dz_mm": 0.5}
CABLE_EA_N = 1.0e5
#: displacements of the secants F / delta compared on the held tube at 0.6 MPa (mm): 0.1 mm,
#: where the 3-D force is 0.4 x the sliding force (the "half-sliding" secant, nearest an
#: initial stiffness), and 0.2 mm (0.7 x; the secant of the first 0.6 MPa comparison). At
#: other pressures :func:`secant_mm` scales them with P^2, as the slip displacement scales (at
#: 0.2 MPa the 5 mm tubes slide fully by ~0.06 mm: a fixed 0.2 mm would measure sliding)
SECANT_MM: tuple[float, float] = (0.1, 0.2)
SECANT_PRESSURE_MPA = 0.6
TUBE_LENGTHS_MM = (5.0, 10.0)


def secant_mm(pressure: float, at_06_mm: float = SECANT_MM[0]) -> float:
    """Displacement (mm) of a held tube's secant F / delta at ``pressure`` (MPa):
    ``at_06_mm`` (P / 0.6 MPa)^2; the first secant is at 0.0111 / 0.0444 / 0.1 mm at 0.2 /
    0.4 / 0.6 MPa, the second at twice that."""
    return at_06_mm * (pressure / SECANT_PRESSURE_MPA) ** 2


def secant_travel_mm(pressure: float) -> float:
    """Travel (mm) of the held tubes' secant runs: 4 x :func:`secant_mm` (0.4 mm at 0.6 MPa),
    so the secant displacements are the 10th and 20th of the 40 even outputs."""
    return 4.0 * secant_mm(pressure)


def structure(name: str) -> Structure:
    """The Table 3 structure (mm), length 116 mm."""
    return paper_structures()[STRUCTURES[name] - 1]


def material() -> MooneyRivlin:
    return MooneyRivlin.from_shore(SHORE)


def _ccx_version(ccx: str) -> str | None:
    try:
        out = subprocess.run([ccx, "-v"], capture_output=True, text=True, timeout=30,
                             check=False).stdout
    except OSError:
        return None
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else None


# ----------------------------------------------------------------------------- ccx runs
#: wall-clock limit of one CalculiX run (s; ``ccx_pullout``'s own default), unless the run
#: says otherwise (``TubeRun.timeout_s``)
CCX_TIMEOUT_S = 3600.0


def solve(name: str, pressure: float, *, mesh: str = REFERENCE_MESH, kind: str = "slice",
          max_increment_mm: float = MAX_INCREMENT_MM, stick_slope: float = STICK_SLOPE,
          ccx: str = "ccx", **extra: Any) -> dict[str, Any]:
    """One 3-D run; its measures (N/mm for the slice, N for the tube) and times."""
    st = structure(name)
    geo = (st.hole_mm, st.tube_od_mm, st.tube_id_mm, st.wire_mm)
    opts = {**(SLICE if kind == "slice" else TUBE), **MESHES[mesh],
            "delta_max_mm": delta_max(pressure), **extra, "max_increment_mm": max_increment_mm,
            "stick_slope": stick_slope}
    timeout_s = float(opts.pop("timeout_s", CCX_TIMEOUT_S))
    r = ccxp.ccx_pullout(geo, material(), pressure, MU_WIRE, MU_WALL, ccx=ccx,
                         timeout_s=timeout_s, **opts)
    f = r.force_per_mm if kind == "slice" else r.force_n
    k = f / r.delta_mm
    return {
        "structure": name, "pressure_mpa": pressure, "kind": kind, "mesh": mesh,
        "max_increment_mm": max_increment_mm, "stick_slope_mpa_per_mm": stick_slope,
        "options": {k_: v for k_, v in opts.items()},
        "delta_mm": r.delta_mm.tolist(), "force": f.tolist(),
        "force_unit": "N/mm" if kind == "slice" else "N",
        "sliding_force": float(f[-1]),
        "plateau_flatness": float(np.ptp(f[-3:]) / abs(f[-1])),
        "initial_stiffness": float(k[0]),
        "initial_stiffness_unit": "N/mm^2" if kind == "slice" else "N/mm",
        "stuck_secant_spread": float(abs(k[2] / k[0] - 1.0)),
        "wire_normal_n_per_mm": r.wire_normal_n_per_mm.tolist(),
        "wall_normal_n_per_mm": r.wall_normal_n_per_mm.tolist(),
        "inflated_wire_normal_n_per_mm": r.inflated_wire_normal_n_per_mm,
        "inflated_wall_normal_n_per_mm": r.inflated_wall_normal_n_per_mm,
        "squeeze_force_n_per_mm": r.squeeze_force_n_per_mm,
        "wire_normal_change_at_sliding": float(r.wire_normal_n_per_mm[-1]
                                               / r.inflated_wire_normal_n_per_mm - 1.0),
        "wire_normal_max_change": float(np.max(np.abs(
            r.wire_normal_n_per_mm / r.inflated_wire_normal_n_per_mm - 1.0))),
        "sliding_over_mu_s_inflated": float(f[-1] / (MU_WIRE * r.inflated_wire_normal_n_per_mm
                                                     * (1.0 if kind == "slice"
                                                        else opts["depth_mm"]))),
        **r.run,
    }


# ------------------------------------------------------------------------------ exofric
def exofric_side(name: str, pressures: tuple[float, ...]) -> dict[str, Any]:
    """exofric's section (ends free and fixed) at the pressures (MPa)."""
    from exofric.simulate import PulloutSetup, section_pullout, squeeze

    st = structure(name)
    mat = material()
    sq = squeeze(st, mat, list(pressures), gravity="none", keep_fields=True)
    out: dict[str, Any] = {"pressure_mpa": list(pressures)}
    for ends in ("free", "fixed"):
        setup = PulloutSetup(st, mat, mu_wire=MU_WIRE, mu_wall=MU_WALL, mu_wire_wall=0.0,
                             ends=ends)
        rows = [section_pullout(setup, p, squeeze_result=sq, squeeze_index=i)
                for i, p in enumerate(pressures)]
        out[ends] = {"initial_stiffness_n_per_mm2": [s.initial_stiffness_n_per_mm2 for s in rows],
                     "sliding_force_n_per_mm": [s.sliding_force_n_per_mm for s in rows],
                     "wire_pressure_integral_n_per_mm":
                         [s.wire_pressure_integral_n_per_mm for s in rows]}
    return out


def exofric_tube(name: str, pressure: float, length_mm: float) -> dict[str, Any]:
    """exofric's pull through a tube of ``length_mm`` held by its fittings, rigid cable."""
    from exofric.simulate import PulloutSetup, pullout, squeeze

    st = dataclasses.replace(structure(name), length_mm=length_mm)
    sq = squeeze(st, material(), [pressure], gravity="none", keep_fields=True)
    setup = PulloutSetup(st, material(), mu_wire=MU_WIRE, mu_wall=MU_WALL, mu_wire_wall=0.0,
                         ends="fixed", cable_ea_n=CABLE_EA_N)
    # first_loading: fine steps up to past the breakaway, so F(secant_mm) is read on a step
    # (the even 60-step path to 0.7 mm at 0.2 MPa interpolates over the knee: -1.2 %)
    r = pullout(setup, pressure, displacement_mm=delta_max(pressure), cycles=0,
                squeeze_result=sq, first_loading=True)
    return {"length_mm": length_mm,
            "initial_stiffness_n_per_mm": length_mm * r.section.initial_stiffness_n_per_mm2,
            "sliding_force_n": float(r.force_n[-1]), "static_force_n": r.static_force_n,
            "displacement_mm": r.displacement_mm.tolist(), "force_n": r.force_n.tolist()}


def _rel(a: float, b: float) -> float:
    return float(a / b - 1.0)


# ---------------------------------------------------------------------------------- run
def delta_max(pressure: float) -> float:
    """Pull travel (mm): past the full slip (0.14 / 0.56 / 1.05 mm for the base group, 1.30 mm
    for test 3 at 0.2 / 0.4 / 0.6 MPa), fewer increments at low pressure."""
    return float(min(DELTA_MAX_MM, max(0.5, math.ceil(10 * DELTA_MAX_MM * pressure / 0.6) / 10)))


def _header(quick: bool, names: list[str], mesh: str) -> dict[str, Any]:
    mat = material()
    return {
        "description": "CalculiX 3-D reference of the wire pull-out (issue 39): periodic "
                       "slice (per mm) and a 30 mm tube held at its ends; sliding force and "
                       "initial stiffness",
        "units": {"pressure": "MPa", "slice force": "N/mm", "slice stiffness": "N/mm^2",
                  "tube force": "N", "tube stiffness": "N/mm", "length": "mm",
                  "stick_slope": "MPa/mm", "time": "s"},
        "structures": {n: dataclasses.asdict(structure(n)) for n in names},
        "material": {"shore_a": SHORE, "c10_mpa": mat.c10_mpa, "c01_mpa": mat.c01_mpa,
                     "d_per_mpa": mat.d_per_mpa, "gravity": "none (weightless)"},
        "friction": {"mu_wire": MU_WIRE, "mu_wall": MU_WALL, "mu_wire_wall": 0.0,
                     "inflation": "frictionless (mu 1e-6), friction switched on for the pull"},
        "model": {"code": "CalculiX ccx (benchmarks/calculix_pullout.py pullout_deck)",
                  "element": "C3D20R (ccx 2.20 has no C3D20H)",
                  "reference_mesh": mesh, "meshes": MESHES, "slice": SLICE, "tube": TUBE,
                  "tube_mesh": TUBE_MESH,
                  "delta_max_mm": "min(2, max(0.5, 2 P / 0.6 MPa rounded up to 0.1 mm))",
                  "max_increment_mm": MAX_INCREMENT_MM, "stick_slope_mpa_per_mm": STICK_SLOPE,
                  "penalty_mpa_per_mm": ccxp.PENALTY, "contact": "NODE TO SURFACE",
                  "first_increment_mm": ccxp.FIRST_INCREMENT_MM},
        "slices": {n: [] for n in names}, "tubes": {}, "quick": quick, "complete": False,
    }


def run(quick: bool = False, ccx: str = "ccx", log: Any = None,
        save: Any = None) -> dict[str, Any]:
    """Slices of both structures, then the studies (unless quick); ``save(out)`` after each
    run (a checkpoint: ``complete`` is False until the end)."""
    def note(msg: str) -> None:
        if log is not None:
            print(msg, file=log, flush=True)

    def keep() -> None:
        if save is not None:
            save(out)

    mesh = COARSE_MESH if quick else REFERENCE_MESH
    names = ["test 1"] if quick else list(STRUCTURES)
    pressures = (0.2, 0.6) if quick else PRESSURES_MPA
    out = _header(quick, names, mesh)
    for name in names:
        for p in pressures:
            note(f"[pullout-ccx] slice {name} {p} MPa on {mesh} ...")
            out["slices"][name].append(solve(name, p, mesh=mesh, ccx=ccx))
            keep()
    if not quick:
        out["convergence"] = {"measure": "relative change of the sliding force and the "
                                         "initial stiffness vs the baseline run (base group)"}
        _studies(out, ccx, note, keep)
    out["complete"] = True
    return out


@dataclasses.dataclass(frozen=True)
class TubeRun:
    """One held-tube CalculiX run: structure, pressure (MPa), length (mm), in-plane mesh (a
    ``MESHES`` key), elements along z, largest / smallest element along z (smallest at both
    ends), and the travel (mm; None: :func:`delta_max`, to full sliding; a shorter travel
    gives the secant alone: the same F(delta) to 0.03 % at 0.2 mm, 2 against 0.4 mm); with
    ``z_growth`` the sizes grow by that factor per element from each face up to ``z_grading``
    x the smallest and stay there (a uniform middle; tag suffix ``q``); ``timeout_s`` (s,
    wall clock) stops a run that CalculiX has not finished (recorded in ``failures``)."""

    structure: str
    pressure_mpa: float
    length_mm: float
    mesh: str = TUBE_MESH
    n_z: int = 5
    z_grading: float = 1.0
    travel_mm: float | None = None
    z_growth: float | None = None
    timeout_s: float = CCX_TIMEOUT_S

    @property
    def tag(self) -> str:
        t = "full" if self.travel_mm is None else f"to{self.travel_mm:g}mm"
        return (f"{self.structure}/{self.length_mm:g}mm/{self.pressure_mpa:g}MPa/{self.mesh}/"
                f"z{self.n_z}" + (f"g{self.z_grading:g}" if self.z_grading != 1.0 else "")
                + (f"q{self.z_growth:g}" if self.z_growth is not None else "") + f"/{t}")


#: the held tubes, in the order they were run. Full travel: the compared runs (sliding force
#: and secant); to 0.4 mm: the reference's convergence of the secant in the plane (2 x 20 ->
#: 3 x 30 elements) and along z (1 -> 0.5 -> 0.25 mm elements; 0.116 mm at the faces graded
#: to 0.93 mm in the middle of 5 mm, to 1.43 mm of 10 mm). Not listed: the 5 mm test-3 tube
#: graded as the base tube (``n_z=12, z_grading=8.0``), which crawled in the pull at 0.165 mm
#: and was stopped (in ``failures``). Also not listed (add them to run
#: them): the 30 mm tube with 20 elements graded 0.68 -> 2.7 mm, which stalled in the inflation
#: (``TubeRun("test 1", 0.6, 30.0, n_z=20, z_grading=4.0, travel_mm=0.4)``; 30 uniform
#: elements run: ``TUBE_RUNS_LONG``) and the 5 mm base tube on 3 x 30 with 0.5 mm
#: (``"3x30", n_z=10``, ~10 min). The 0.125 mm run is ``TUBE_RUNS_FINE``
TUBE_RUNS: tuple[TubeRun, ...] = (
    TubeRun("test 1", 0.6, 5.0),
    TubeRun("test 1", 0.6, 10.0, n_z=10),
    TubeRun("test 1", 0.6, 5.0, n_z=10),
    TubeRun("test 1", 0.6, 5.0, travel_mm=0.4),
    TubeRun("test 1", 0.6, 5.0, "3x30", travel_mm=0.4),
    TubeRun("test 3", 0.6, 5.0),
    TubeRun("test 1", 0.6, 5.0, n_z=20, travel_mm=0.4),
    TubeRun("test 3", 0.6, 5.0, n_z=10, travel_mm=0.4),
    TubeRun("test 1", 0.6, 5.0, n_z=12, z_grading=8.0, travel_mm=0.4),
    TubeRun("test 1", 0.6, 10.0, n_z=18, z_grading=12.37, travel_mm=0.4),
    TubeRun("test 3", 0.6, 5.0, n_z=20, travel_mm=0.4),
)
#: the 5 mm tubes of both structures at 0.2 and 0.4 MPa (session 44): full travel on 1 mm
#: elements, then the secant runs (to :func:`secant_travel_mm`) on 1 / 0.5 / 0.25 mm
TUBE_RUNS_LOW_P: tuple[TubeRun, ...] = tuple(
    r for name in STRUCTURES for r in (
        TubeRun(name, 0.2, 5.0), TubeRun(name, 0.4, 5.0),
        *(TubeRun(name, p, 5.0, n_z=n, travel_mm=secant_travel_mm(p))
          for p in (0.2, 0.4) for n in (5, 10, 20))))
#: the 5 mm base tube at 0.4 MPa to full sliding (~0.2 mm): on 1 mm elements ccx 2.20 stopped
#: with "too many cutbacks" (at one node, 7133 dof 2) whether pulled to 1.4 (the full travel),
#: 1 or 0.5 mm (in ``failures``); on 0.5 mm elements to 0.5 mm
TUBE_RUNS_RETRY: tuple[TubeRun, ...] = (TubeRun("test 1", 0.4, 5.0, travel_mm=1.0),
                                        TubeRun("test 1", 0.4, 5.0, travel_mm=0.5),
                                        TubeRun("test 1", 0.4, 5.0, n_z=10, travel_mm=0.5))
#: the 5 mm base tube at 0.6 MPa (session 44) and 0.4 MPa (session 45), and both 5 mm tubes at
#: 0.2 MPa (session 46), on 0.125 mm elements along z (does the reference level off?)
TUBE_RUNS_FINE: tuple[TubeRun, ...] = (
    TubeRun("test 1", 0.6, 5.0, n_z=40, travel_mm=0.4),
    TubeRun("test 1", 0.4, 5.0, n_z=40, travel_mm=secant_travel_mm(0.4)),
    *(TubeRun(name, 0.2, 5.0, n_z=40, travel_mm=secant_travel_mm(0.2)) for name in STRUCTURES))
#: the issue's 30 mm tube at 0.6 MPa on 30 uniform 1 mm elements along z (session 45; graded
#: elements of 0.68-2.7 mm stalled in the inflation, see above): 20134 equations, 1195 s CPU;
#: exofric k1 +8.31 %, k2 +9.01 % against it (not refined at the faces: docs section 12)
TUBE_RUNS_LONG: tuple[TubeRun, ...] = (TubeRun("test 1", 0.6, 30.0, n_z=30, travel_mm=0.4),)
#: the reference's convergence in the plane where the held faces are resolved along z
#: (session 47): 3 x 30 against 2 x 20 on 0.5 and 0.25 mm elements and 4 x 40 on 0.5 mm, the
#: 5 mm base tube at 0.6 MPa (2 x 20 -> 3 x 30 on 1 mm elements moved k1 by +0.09 %; on 0.5 /
#: 0.25 mm by +1.60 / +2.08 %, and 3 x 30 -> 4 x 40 on 0.5 mm by +0.61 %); test 3 on 3 x 30 and
#: 0.25 mm (+2.93 %)
TUBE_RUNS_PLANE: tuple[TubeRun, ...] = (TubeRun("test 1", 0.6, 5.0, "3x30", n_z=10,
                                                travel_mm=0.4),
                                        TubeRun("test 1", 0.6, 5.0, "3x30", n_z=20,
                                                travel_mm=0.4),
                                        TubeRun("test 1", 0.6, 5.0, "4x40", n_z=10,
                                                travel_mm=0.4),
                                        TubeRun("test 3", 0.6, 5.0, "3x30", n_z=20,
                                                travel_mm=0.4),
                                        TubeRun("test 1", 0.6, 10.0, "3x30", n_z=18,
                                                z_grading=12.37, travel_mm=0.4))
#: the 30 mm tube on 3 x 30 with 0.25 mm at the held faces, growing x 1.25 to 1.43 mm and
#: uniform beyond (41k equations; session 48): it crawled in the inflation from 0.60 P
#: (increments down to 0.002 P, node-to-surface chatter) and hit ccx_pullout's 1 h timeout at
#: 0.853 P (in ``failures``). Not in ``ALL_TUBE_RUNS``; add it to run it
TUBE_30_PLANE = TubeRun("test 1", 0.6, 30.0, "3x30", n_z=30, z_grading=5.72, travel_mm=0.4,
                        z_growth=1.25)
#: the 10 mm tube on 4 x 40, graded as on 3 x 30 (session 49, the plane's next step for its
#: k1): the inflation passed (~38 min) but the pull's third increment (2e-5 mm) was cut back
#: to 1e-6 mm with the residual stuck near 0.015 N (753 contact elements: stick/slip chatter)
#: and the run was stopped (in ``failures``). Not in ``ALL_TUBE_RUNS``; add it to run it
TUBE_10_PLANE = TubeRun("test 1", 0.6, 10.0, "4x40", n_z=18, z_grading=12.37, travel_mm=0.4,
                        timeout_s=4 * CCX_TIMEOUT_S)
ALL_TUBE_RUNS = (TUBE_RUNS + TUBE_RUNS_LOW_P + TUBE_RUNS_RETRY + TUBE_RUNS_FINE + TUBE_RUNS_LONG
                 + TUBE_RUNS_PLANE)


def run_tubes(out: dict[str, Any], ccx: str = "ccx", note: Any = None,
              runs: tuple[TubeRun, ...] = ALL_TUBE_RUNS, save: Any = None) -> None:
    """Add the runs of ``runs`` not yet in ``out["runs"]`` (by tag), one at a time, calling
    ``save(out)`` after each; failures are recorded in ``out["failures"]``, not fatal."""
    rows = out.setdefault("runs", [])
    have = {r["tag"] for r in rows}
    out.setdefault("model", {}).update({
        "tube": TUBE, "secant_mm": [f"{d:g} (P / {SECANT_PRESSURE_MPA:g} MPa)^2"
                                    for d in SECANT_MM]})
    for spec in runs:
        if spec.tag in have:
            continue
        if note is not None:
            note(f"[pullout-ccx] tube {spec.tag} ...")
        extra: dict[str, Any] = ({} if spec.travel_mm is None
                                 else {"delta_max_mm": spec.travel_mm})
        if spec.z_growth is not None:
            extra["z_growth"] = spec.z_growth
        extra["timeout_s"] = spec.timeout_s
        try:
            r = solve(spec.structure, spec.pressure_mpa, mesh=spec.mesh, kind="tube", ccx=ccx,
                      depth_mm=spec.length_mm, n_z=spec.n_z, z_grading=spec.z_grading,
                      **extra)
        except (RuntimeError, subprocess.TimeoutExpired) as exc:
            # a run past ccx_pullout's timeout (1 h) is a failure too, not the end of the study
            out.setdefault("failures", []).append({"tag": spec.tag,
                                                   "error": str(exc)[-2000:]})
        else:
            rows.append({"tag": spec.tag, "spec": dataclasses.asdict(spec), **r,
                         **_secant_fields(r)})
        if save is not None:
            save(out)


#: a tube run has reached full sliding when its force changes by less than this (relative)
#: over its last three outputs (full-travel runs: < 4e-7; runs stopped at the secant: > 4e-3)
PLATEAU_FLATNESS = 1e-5


def _fineness(r: dict[str, Any]) -> int:
    """A stored tube run's number of equations (the finest run of a tube has the most)."""
    return int(r["equations"])


def tube_groups(runs: list[dict[str, Any]]) -> dict[tuple[str, float, float], dict[str, Any]]:
    """The stored tube runs by (structure, length mm, pressure MPa): the finest run that
    reached full sliding (``sliding``: its force flat to ``PLATEAU_FLATNESS``, or None), the
    finest run (``secant``; finest: most equations) and every run's secants at
    :func:`secant_mm` (N/mm, by tag, one per ``SECANT_MM``)."""
    out: dict[tuple[str, float, float], dict[str, Any]] = {}
    for r in runs:
        sp = r["spec"]
        g = out.setdefault((sp["structure"], sp["length_mm"], sp["pressure_mpa"]),
                           {"sliding": None, "secant": None, "secants": {}})
        g["secants"][r["tag"]] = [_secant(r, d) for d in SECANT_MM]
        if r["plateau_flatness"] < PLATEAU_FLATNESS and (g["sliding"] is None
                                        or _fineness(r) > _fineness(g["sliding"])):
            g["sliding"] = r
        if g["secant"] is None or _fineness(r) > _fineness(g["secant"]):
            g["secant"] = r
    return out


def _secant_fields(r: dict[str, Any]) -> dict[str, list[float]]:
    """A tube run's stored secants: displacements (mm) and F / delta (N/mm), per ``SECANT_MM``."""
    return {"secant_mm": [secant_mm(r["pressure_mpa"], d) for d in SECANT_MM],
            "secant_n_per_mm": [_secant(r, d) for d in SECANT_MM]}


def _secant(r: dict[str, Any], at_06_mm: float = SECANT_MM[0]) -> float:
    """F / delta at :func:`secant_mm` (N/mm) of a stored tube run."""
    d = secant_mm(r["pressure_mpa"], at_06_mm)
    return float(np.interp(d, r["delta_mm"], r["force"])) / d


def _row(r: dict[str, Any], base: dict[str, Any]) -> dict[str, Any]:
    keep = ("pressure_mpa", "mesh", "max_increment_mm", "stick_slope_mpa_per_mm",
            "sliding_force", "initial_stiffness", "cpu_time_s", "wall_time_s",
            "incrementation")
    return {k: r[k] for k in keep} | {
        "baseline_mesh": base["mesh"],
        "sliding_change": _rel(r["sliding_force"], base["sliding_force"]),
        "stiffness_change": _rel(r["initial_stiffness"], base["initial_stiffness"])}


def _studies(out: dict[str, Any], ccx: str, note: Any, keep: Any) -> None:
    """Into ``out["convergence"]``: coarse mesh (0.2, 0.6 MPa) against the reference mesh;
    increment and stick slope (0.6 MPa, coarse mesh, against the coarse run); then the fine
    mesh (0.6 and 0.2 MPa; last, the costly ones on a shared machine). Base group."""
    ref = {r["pressure_mpa"]: r for r in out["slices"]["test 1"]}
    conv = out["convergence"]
    conv["mesh"] = []
    coarse = {}
    for p in (0.2, 0.6):
        note(f"[pullout-ccx] mesh study {COARSE_MESH} {p} MPa ...")
        coarse[p] = solve("test 1", p, mesh=COARSE_MESH, ccx=ccx)
        conv["mesh"].append(_row(coarse[p], ref[p]))
        keep()
    conv["increment"] = []
    for inc in (2.0 * MAX_INCREMENT_MM, 0.5 * MAX_INCREMENT_MM):
        note(f"[pullout-ccx] increment study {inc} mm ...")
        r = solve("test 1", 0.6, mesh=COARSE_MESH, max_increment_mm=inc, ccx=ccx)
        conv["increment"].append(_row(r, coarse[0.6]))
        keep()
    conv["stick_slope"] = []
    for slope in (0.3 * STICK_SLOPE, 3.0 * STICK_SLOPE):
        note(f"[pullout-ccx] stick slope study {slope} MPa/mm ...")
        r = solve("test 1", 0.6, mesh=COARSE_MESH, stick_slope=slope, ccx=ccx)
        conv["stick_slope"].append(_row(r, coarse[0.6]))
        keep()
    for p in (0.6, 0.2):
        note(f"[pullout-ccx] mesh study {FINE_MESH} {p} MPa ...")
        conv["mesh"].append(_row(solve("test 1", p, mesh=FINE_MESH, ccx=ccx), ref[p]))
        keep()


def compare(ref: dict[str, Any]) -> list[dict[str, Any]]:
    """exofric against the stored reference: one row per structure, kind and pressure."""
    rows = []
    for name, runs in ref["slices"].items():
        p = tuple(r["pressure_mpa"] for r in runs)
        ex = exofric_side(name, p)
        for i, r in enumerate(runs):
            for ends in ("free", "fixed"):
                e = ex[ends]
                rows.append({"structure": name, "kind": f"slice/{ends}", "pressure_mpa": p[i],
                             "ref_sliding": r["sliding_force"],
                             "exofric_sliding": e["sliding_force_n_per_mm"][i],
                             "ref_k0": r["initial_stiffness"],
                             "exofric_k0": e["initial_stiffness_n_per_mm2"][i]})
    for (name, length, pressure), g in sorted(tube_groups(ref.get("tube_runs", [])).items()):
        t = exofric_tube(name, pressure, length)
        # the held tube's 3-D F / delta at 1e-3 mm is not an elastic stiffness (the end rows,
        # held at u_z = 0 against the moving wire, slip at once): the secant to secant_mm(P)
        # is compared, against the finest run (most equations)
        for i, at in enumerate(SECANT_MM):
            d_s = secant_mm(pressure, at)
            ex_sec = float(np.interp(d_s, t["displacement_mm"], t["force_n"])) / d_s
            rows.append({"structure": name, "kind": f"tube{length:g}/k{i + 1}",
                         "pressure_mpa": pressure, "secant_mm": d_s,
                         "ref_sliding": (g["sliding"]["sliding_force"] if g["sliding"]
                                         else math.nan),
                         "exofric_sliding": t["sliding_force_n"],
                         "ref_k0": _secant(g["secant"], at), "exofric_k0": ex_sec,
                         "ref_secants": {k: v[i] for k, v in g["secants"].items()}})
    for row in rows:
        row["err_sliding"] = _rel(row["exofric_sliding"], row["ref_sliding"])
        row["err_k0"] = _rel(row["exofric_k0"], row["ref_k0"])
    return rows


def _table(rows: list[dict[str, Any]]) -> str:
    head = (f"{'structure':9} {'kind':13} {'P MPa':>5} {'ref slide':>10} {'exofric':>10} "
            f"{'err':>7} {'ref k0':>9} {'exofric':>9} {'err':>7}")
    lines = [head, "-" * len(head)]
    for r in rows:
        lines.append(f"{r['structure']:9} {r['kind']:13} {r['pressure_mpa']:5.2f} "
                     f"{r['ref_sliding']:10.5g} {r['exofric_sliding']:10.5g} "
                     f"{100 * r['err_sliding']:6.2f}% {r['ref_k0']:9.5g} "
                     f"{r['exofric_k0']:9.5g} {100 * r['err_k0']:6.2f}%")
    return "\n".join(lines)


def _write(data: dict[str, Any], path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=path.parent, delete=False, suffix=".tmp") as fh:
        json.dump(data, fh, indent=1)
        tmp = Path(fh.name)
    tmp.replace(path)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--full", action="store_true",
                      help="run the slices and studies (~35 min); writes "
                           "tests/data/ccx_pullout.json")
    mode.add_argument("--quick", action="store_true",
                      help="base group, 0.2/0.6 MPa, coarse; writes nothing unless --out")
    mode.add_argument("--tubes-only", action="store_true",
                      help="run the held tubes not yet stored; writes "
                           "tests/data/ccx_pullout_tube.json")
    mode.add_argument("--compare-only", action="store_true",
                      help="the default: no CalculiX, exofric against the stored references")
    ap.add_argument("--json", action="store_true", help="print the JSON")
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--ccx", default="ccx")
    ap.add_argument("--tubes", default=None, metavar="REGEX",
                    help="with --tubes-only: only the runs whose tag matches (e.g. 'test 3/')")
    args = ap.parse_args(argv)
    if args.tubes_only:
        _run_tubes_cli(args.ccx, args.tubes)
        data = json.loads(OUT.read_text())
    elif args.full or args.quick:
        t0 = time.perf_counter()
        prov = {
            "created_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
            "script": "benchmarks/bench_pullout_ccx.py" + (" --quick" if args.quick else " --full"),
            "ccx_version": _ccx_version(args.ccx), "platform": platform.platform(),
            "python": platform.python_version(), "threads": 1,
        }
        path = args.out or (None if args.quick else OUT)
        data = run(args.quick, args.ccx, sys.stderr,
                   None if path is None else (lambda d: _write({**d, "provenance": prov}, path)))
        data["provenance"] = {**prov, "total_wall_time_s": time.perf_counter() - t0}
        if path is not None:
            _write(data, path)
    else:
        data = json.loads((args.out or OUT).read_text())
    if OUT_TUBE.exists():
        data["tube_runs"] = json.loads(OUT_TUBE.read_text()).get("runs", [])
    rows = compare(data)
    data["comparison"] = rows
    print(_table(rows))
    if args.json:
        print(json.dumps(data, indent=1))
    return data


def _merge_write(data: dict[str, Any], path: Path) -> None:
    """Write ``data`` to ``path`` after merging in (by tag) the runs and failures another
    process stored there meanwhile, under an exclusive lock: two ``--tubes-only`` processes
    (different ``--tubes``) never lose each other's runs."""
    import fcntl

    with open(Path(tempfile.gettempdir()) / f"{path.name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if path.exists():
            disk = json.loads(path.read_text())
            for key in ("runs", "failures"):
                # extended in place: run_tubes appends to the same list
                rows = data.setdefault(key, [])
                have = {(r["tag"], r.get("error")) for r in rows}
                rows.extend(r for r in disk.get(key, []) if (r["tag"], r.get("error")) not in have)
        _write(data, path)


def _run_tubes_cli(ccx: str, pattern: str | None = None) -> None:
    """``--tubes-only``: the stored tube file plus the runs of ``ALL_TUBE_RUNS`` it lacks (those
    whose tag matches ``pattern`` if given)."""
    t0 = time.perf_counter()
    tube: dict[str, Any] = (json.loads(OUT_TUBE.read_text()) if OUT_TUBE.exists() else
                            {"description": "CalculiX 3-D pull-out of short tubes held at "
                                            "their ends (see bench_pullout_ccx.py)"})
    runs = tuple(r for r in ALL_TUBE_RUNS if pattern is None or re.search(pattern, r.tag))
    run_tubes(tube, ccx, lambda m: print(m, file=sys.stderr, flush=True), runs=runs,
              save=lambda d: _merge_write(d, OUT_TUBE))
    old = tube.get("provenance", {})
    tube["provenance"] = {
        "created_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "script": "benchmarks/bench_pullout_ccx.py --tubes-only",
        "ccx_version": _ccx_version(ccx), "platform": platform.platform(),
        "python": platform.python_version(), "threads": 1,
        "total_wall_time_s": time.perf_counter() - t0,
        "history": [*old.get("history", []), {k: v for k, v in old.items() if k != "history"}]}
    _merge_write(tube, OUT_TUBE)


if __name__ == "__main__":
    main()
