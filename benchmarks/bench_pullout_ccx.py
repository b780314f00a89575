"""Benchmark: independent 3-D CalculiX check of the wire pull-out (issue 39 acceptance).

Run: ``python benchmarks/bench_pullout_ccx.py [--full | --quick | --tubes-only] [--json]
[--out PATH]``. Without options (``make bench``): exofric against the stored CalculiX
references, a few seconds, no CalculiX, nothing written. ``--full``: the slices and their
studies (~35 min on the shared machine), written atomically after every run to
``tests/data/ccx_pullout.json`` (``complete`` false until the end) or ``--out``. ``--quick``:
two coarse slices (~2 min), written only with ``--out``. ``--tubes-only``: the held tubes and
their studies (``TUBE_RUNS``, the runs not yet stored; ~1 h CPU in all), written to
``tests/data/ccx_pullout_tube.json``. Every mode prints reference (CalculiX) vs exofric with
relative errors.

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
  periodic slice has no end fittings; exofric's ``ends="fixed"`` adds a soft foundation for
  the fittings of a 116 mm tube, +1-5 % on k0, reported too).
* held tubes (``--tubes-only``, ``TUBE_RUNS``, written to
  ``tests/data/ccx_pullout_tube.json`` under ``runs`` by tag): 5 and 10 mm of the base group
  and 5 mm of test 3, ends held axially (u_z = 0 on the end faces, in-plane free), the rigid
  wire pulled through it: F(delta) compared with ``pullout(..., ends="fixed")`` on the same
  structure and length with a rigid cable (``cable_ea_n`` 1e5 N: EA / L >= 3e3 N/mm against
  the tube's <= 40 N/mm. Not 1e9: exofric's shear-lag residual tolerance scales with EA / h,
  and with EA = 1e9 (30 mm) or 1e7 (5 mm, free ends) its pulled-end sliding force was 3-4 %
  off); studies along z of all three (and of the 5 mm base tube in the plane; TUBE_RUNS
  lists them). A 30 mm tube with graded elements along z (0.68 mm at the held faces, 2.7 mm
  in the middle) and 8 or 10 graded elements of 2-6 mm stalled in the inflation (see
  ``calculix_pullout``).

Measures: sliding force = the force at the end of the travel (its flatness over the last
three outputs is stored: < 4e-6); initial stiffness = F(d1) / d1 at the first output
d1 = 5e-4 x the travel (all arcs stuck there: F / delta is constant to 4e-7 over the next two
outputs); S_wire = radial parts of the wire's nodal reactions (at the end of the inflation and
along the pull: the change the reduced model neglects). For the held tube the early F / delta
is not an elastic stiffness (its end rows, held at u_z = 0 against the moving wire, slip at
once): the secant to 0.2 mm is compared.

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
fine meshes). With ends "fixed" k0 is 1-9 % higher (the fittings' foundation of a 116 mm tube,
not in a periodic slice). (Those numbers are from when the slices were stored; on the code of
2026-11-27 session 43 the default run prints +2.15 / -4.11 / -0.38 % and +4.91 / -0.59 / +1.72
% on k0: exofric's section has moved.)

Held tubes (0.6 MPa; secant to 0.2 mm in N/mm; CPU on one thread): sliding force +0.38 / +0.54 /
+0.59 % (5, 10 mm base, 5 mm test 3). Secants along z (2 x 20 in the plane; "g": 0.116 mm at
the held faces, graded geometrically to the middle):

* 5 mm base: 1 / 0.5 / 0.25 mm uniform 11.575 / 11.678 / 11.794 (+0.9, +1.0 % per halving:
  the steps grow, so no order of convergence is observable and no Richardson extrapolation is
  possible; 107-583 s CPU); g (to 0.93 mm, 12 elements) 11.790 (352 s); in the plane 2 x 20 ->
  3 x 30 at 1 mm +0.80 % (313 s). exofric 12.331: +4.55 % against the 0.25 mm run, +3.7 % with
  the in-plane step added.
* 10 mm base: 1 mm 17.276; g (to 1.43 mm, 18 elements, 12142 equations, 588 s CPU) 17.425
  (+0.86 %). exofric 18.322: +5.15 % against g, +4.3 % with the 5 mm tube's in-plane step.
* 5 mm test 3: 1 / 0.5 / 0.25 mm 13.609 / 13.684 / 13.811 (+0.55, +0.93 % per halving: growing
  steps again; the 0.25 mm run 13474 equations, 628 s CPU). exofric 14.529: +5.20 % against
  the 0.25 mm run, +4.4 % with the base tube's in-plane step. The graded run (12 elements,
  as the 5 mm base tube's) crawled in the pull at 0.165 mm (increments ~1e-6 mm with
  cutbacks, node-to-surface chatter) and was stopped by hand after 8.6 min CPU
  (``failures``).

The references rise monotonically with every refinement, so each error is an upper estimate
and the converged reference is above the finest run (bracket: [finest run, unknown]). So the
5 mm base tube is within the issue's 5 %, the 10 mm base and 5 mm test-3 tubes 0.15 / 0.20 %
above it against references that still rise. A uniform 0.125 mm run of the 5 mm base tube
(``n_z=40``, ~20 min CPU) is the next step. The smeared end-fitting foundation (before the
held zones) gave -8.9 / -17 % on the 5 / 10 mm base tubes. The 30 mm tube with 20 elements along
z graded 0.68 -> 2.7 mm stalled in the inflation (contact chatter past 0.65 P, stopped after 12
min; in ``failures``); 30 uniform 1 mm elements to 0.4 mm would take ~15 min of CPU.
"""

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
#: displacement of the secant stiffness compared on the held tube (mm)
SECANT_MM = 0.2
TUBE_LENGTHS_MM = (5.0, 10.0)


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
def solve(name: str, pressure: float, *, mesh: str = REFERENCE_MESH, kind: str = "slice",
          max_increment_mm: float = MAX_INCREMENT_MM, stick_slope: float = STICK_SLOPE,
          ccx: str = "ccx", **extra: Any) -> dict[str, Any]:
    """One 3-D run; its measures (N/mm for the slice, N for the tube) and times."""
    st = structure(name)
    geo = (st.hole_mm, st.tube_od_mm, st.tube_id_mm, st.wire_mm)
    opts = {**(SLICE if kind == "slice" else TUBE), **MESHES[mesh],
            "delta_max_mm": delta_max(pressure), **extra, "max_increment_mm": max_increment_mm,
            "stick_slope": stick_slope}
    r = ccxp.ccx_pullout(geo, material(), pressure, MU_WIRE, MU_WALL, ccx=ccx, **opts)
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
    r = pullout(setup, pressure, displacement_mm=delta_max(pressure), cycles=0,
                squeeze_result=sq)
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
    gives the secant alone: the same F(delta) to 0.03 % at 0.2 mm, 2 against 0.4 mm)."""

    structure: str
    pressure_mpa: float
    length_mm: float
    mesh: str = TUBE_MESH
    n_z: int = 5
    z_grading: float = 1.0
    travel_mm: float | None = None

    @property
    def tag(self) -> str:
        t = "full" if self.travel_mm is None else f"to{self.travel_mm:g}mm"
        return (f"{self.structure}/{self.length_mm:g}mm/{self.pressure_mpa:g}MPa/{self.mesh}/"
                f"z{self.n_z}" + (f"g{self.z_grading:g}" if self.z_grading != 1.0 else "")
                + f"/{t}")


#: the held tubes, in the order they were run. Full travel: the compared runs (sliding force
#: and secant); to 0.4 mm: the reference's convergence of the secant in the plane (2 x 20 ->
#: 3 x 30 elements) and along z (1 -> 0.5 -> 0.25 mm elements; 0.116 mm at the faces graded
#: to 0.93 mm in the middle of 5 mm, to 1.43 mm of 10 mm). Not listed: the 5 mm test-3 tube
#: graded as the base tube (``n_z=12, z_grading=8.0``), which crawled in the pull at 0.165 mm
#: and was stopped (in ``failures``). Also not listed (add them to run
#: them): the 30 mm tube, which stalled in the inflation with 20 elements graded 0.68 -> 2.7 mm
#: (``TubeRun("test 1", 0.6, 30.0, n_z=20, z_grading=4.0, travel_mm=0.4)``; 30 uniform
#: elements would take ~15 min of CPU), the 5 mm base tube with 0.125 mm elements
#: (``n_z=40``, ~20 min of CPU) and on 3 x 30 with 0.5 mm (``"3x30", n_z=10``, ~10 min)
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


def run_tubes(out: dict[str, Any], ccx: str = "ccx", note: Any = None,
              runs: tuple[TubeRun, ...] = TUBE_RUNS, save: Any = None) -> None:
    """Add the runs of ``runs`` not yet in ``out["runs"]`` (by tag), one at a time, calling
    ``save(out)`` after each; failures are recorded in ``out["failures"]``, not fatal."""
    rows = out.setdefault("runs", [])
    have = {r["tag"] for r in rows}
    out.setdefault("model", {}).update({"tube": TUBE, "secant_mm": SECANT_MM})
    for spec in runs:
        if spec.tag in have:
            continue
        if note is not None:
            note(f"[pullout-ccx] tube {spec.tag} ...")
        extra = {} if spec.travel_mm is None else {"delta_max_mm": spec.travel_mm}
        try:
            r = solve(spec.structure, spec.pressure_mpa, mesh=spec.mesh, kind="tube", ccx=ccx,
                      depth_mm=spec.length_mm, n_z=spec.n_z, z_grading=spec.z_grading,
                      **extra)
        except RuntimeError as exc:
            out.setdefault("failures", []).append({"tag": spec.tag,
                                                   "error": str(exc)[-2000:]})
        else:
            rows.append({"tag": spec.tag, "spec": dataclasses.asdict(spec), **r,
                         "secant_n_per_mm": _secant(r)})
        if save is not None:
            save(out)


def _fineness(r: dict[str, Any]) -> int:
    """A stored tube run's number of equations (the finest run of a tube has the most)."""
    return int(r["equations"])


def tube_groups(runs: list[dict[str, Any]]) -> dict[tuple[str, float, float], dict[str, Any]]:
    """The stored tube runs by (structure, length mm, pressure MPa): the finest full-travel
    run (``sliding``, or None), the finest run (``secant``; finest: most equations) and every
    run's secant to ``SECANT_MM`` (N/mm, by tag)."""
    out: dict[tuple[str, float, float], dict[str, Any]] = {}
    for r in runs:
        sp = r["spec"]
        g = out.setdefault((sp["structure"], sp["length_mm"], sp["pressure_mpa"]),
                           {"sliding": None, "secant": None, "secants": {}})
        g["secants"][r["tag"]] = r["secant_n_per_mm"]
        if sp["travel_mm"] is None and (g["sliding"] is None
                                        or _fineness(r) > _fineness(g["sliding"])):
            g["sliding"] = r
        if g["secant"] is None or _fineness(r) > _fineness(g["secant"]):
            g["secant"] = r
    return out


def _secant(r: dict[str, Any]) -> float:
    """F / delta at ``SECANT_MM`` (N/mm) of a stored tube run."""
    return float(np.interp(SECANT_MM, r["delta_mm"], r["force"])) / SECANT_MM


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
    for (name, length, pressure), g in tube_groups(ref.get("tube_runs", [])).items():
        t = exofric_tube(name, pressure, length)
        # the held tube's 3-D F / delta at 1e-3 mm is not an elastic stiffness (the end rows,
        # held at u_z = 0 against the moving wire, slip at once): the secant to SECANT_MM is
        # compared, against the finest run (most equations)
        ex_sec = float(np.interp(SECANT_MM, t["displacement_mm"], t["force_n"])) / SECANT_MM
        rows.append({"structure": name, "kind": f"tube{length:g}/secant",
                     "pressure_mpa": pressure,
                     "ref_sliding": g["sliding"]["sliding_force"] if g["sliding"] else math.nan,
                     "exofric_sliding": t["sliding_force_n"],
                     "ref_k0": g["secant"]["secant_n_per_mm"], "exofric_k0": ex_sec,
                     "ref_secants": g["secants"]})
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
    args = ap.parse_args(argv)
    if args.tubes_only:
        _run_tubes_cli(args.ccx)
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


def _run_tubes_cli(ccx: str) -> None:
    """``--tubes-only``: the stored tube file plus the runs of ``TUBE_RUNS`` it lacks."""
    t0 = time.perf_counter()
    tube: dict[str, Any] = (json.loads(OUT_TUBE.read_text()) if OUT_TUBE.exists() else
                            {"description": "CalculiX 3-D pull-out of short tubes held at "
                                            "their ends (see bench_pullout_ccx.py)"})
    run_tubes(tube, ccx, lambda m: print(m, file=sys.stderr, flush=True),
              save=lambda d: _write(d, OUT_TUBE))
    old = tube.get("provenance", {})
    tube["provenance"] = {
        "created_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "script": "benchmarks/bench_pullout_ccx.py --tubes-only",
        "ccx_version": _ccx_version(ccx), "platform": platform.platform(),
        "python": platform.python_version(), "threads": 1,
        "total_wall_time_s": time.perf_counter() - t0,
        "history": [*old.get("history", []), {k: v for k, v in old.items() if k != "history"}]}
    _write(tube, OUT_TUBE)


if __name__ == "__main__":
    main()
