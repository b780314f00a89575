"""exofric's pull-out against an independent 3-D CalculiX model (issue 39 acceptance).

The reference (``tests/data/ccx_pullout.json``) comes from ``benchmarks/bench_pullout_ccx.py``
(deck writer ``benchmarks/calculix_pullout.py``; nothing of exofric is used to make it, only
the material constants and sizes): CalculiX 2.20, the tube as 20-node bricks (C3D20R: ccx
2.20 has no hybrid C3D20H) extruded from a structured polar mesh of the half section
(3 x 30 elements, graded toward the wire), rigid hole and wire as prescribed element layers,
node-to-surface penalty contact with ``*FRICTION`` (stick slope 1e3 MPa/mm). Step 1 inflates
the bore (follower pressure; friction 1e-6, i.e. frictionless: exofric's frictionless
plane-strain squeeze is the matching start), step 2 switches the friction on (mu_wire 0.3,
mu_wall 0.5; ``*CHANGE FRICTION``), holds the pressure and pulls the rigid wire along the tube
axis by up to 2 mm. The normal pressures are free to change in 3-D: the reduced model's held
pressures (no reverse coupling) are what is tested.

* Slice: 1 mm thick, periodic along z (``*EQUATION`` ties the back face to the front for all
  three components): the section far from the ends, per mm. Compared with
  ``section_pullout(..., ends="free")`` (a periodic slice has no end fittings) at 0.2, 0.4,
  0.6 MPa on the base group (Table 3 test 1) and test 3, mu_wire_wall = 0 (two rigid bodies
  have no line contact in the 3-D model).
* Held tube (``tests/data/ccx_pullout_tube.json``): base group, 0.6 MPa, 5 (and 10) mm with
  the end faces held axially (u_z = 0), compared with ``pullout(..., ends="fixed",
  cable_ea_n=1e5)`` on the same length (the 3-D wire is rigid; EA / L >= 1e4 N/mm against the
  tube's ~15 N/mm). Only the sliding force is tested there (the 3-D end rows, held against
  the moving wire, slip at once, so its early F / delta is no elastic stiffness; the reduced
  model's end-fitting foundation is a long-rod model: the secant to 0.2 mm is 11.57 / 17.28
  N/mm in 3-D against 10.54 / 14.34 N/mm for 5 / 10 mm, -8.9 % / -17 %, reported by the
  benchmark, not tested: the 3-D tube's convergence along z was not studied).

Measures: sliding force = force at the end of the travel (flat to 4e-6); initial stiffness =
F / delta at delta = 5e-4 x the travel (constant to 4e-7 over the next outputs: all stuck).

The reference's own convergence (base group): mesh 3 x 30 -> 4 x 40 at 0.6 MPa moves the
sliding force by 0.28 % and k0 by 0.25 % (2 x 20 -> 3 x 30: 0.7 % / 2.9 % at 0.2 MPa, 0.24 % /
1.5 % at 0.6 MPa; 3 x 30 -> 4 x 40 at 0.2 MPa: -0.28 % / +2.2 %, i.e. k0 at low pressure, with
few nodes on the short contact arc, carries ~2 % of mesh noise, and the 4 x 40 value 0.3725
N/mm^2 equals exofric's 0.3725); halving or doubling the largest increment: 0; stick slope 300
or 3000 instead of 1e3 MPa/mm: k0 -0.44 % / +0.14 %, sliding 0. In 3-D the wire arc's normal-
force integral moves by at most 0.23 % during the pull.

Tolerances: the issue's, from 0.2 MPa: sliding force within 2 %, initial stiffness within 5 %.
Measured (exofric standard mesh vs 3-D, 0.2 / 0.4 / 0.6 MPa): sliding force +0.03 / +0.56 /
+0.46 % (base), +0.01 / +0.33 / +0.31 % (test 3); initial stiffness +2.20 / -2.34 / +0.34 %
(base), +2.18 / -2.35 / +0.32 % (test 3); held 5 / 10 mm tubes' sliding force +0.63 / +0.59 %.
The k0 errors are of the size of either code's discretisation (exofric's k0 moves by up to 2.4
% between its standard and fine meshes).
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from exofric.geometry import Structure
from exofric.material import MooneyRivlin
from exofric.simulate import pullout, section_pullout, squeeze

REF = json.loads((Path(__file__).parent / "data" / "ccx_pullout.json").read_text())
MU = REF["friction"]
SLIDE_TOL, K0_TOL = 0.02, 0.05


def _structure(name: str) -> Structure:
    s = REF["structures"][name]
    return Structure(s["hole_mm"], s["tube_od_mm"], s["tube_id_mm"], s["wire_mm"],
                     s["length_mm"], s["name"])


def _material() -> MooneyRivlin:
    m = REF["material"]
    return MooneyRivlin(m["c10_mpa"], m["c01_mpa"], m["d_per_mpa"])


@pytest.fixture(scope="module")
def exo() -> dict[str, Any]:
    """One frictionless squeeze per structure (weightless, fields kept), the sections at the
    reference pressures, and the 30 mm tube where stored."""
    out: dict[str, Any] = {}
    mat = _material()
    for name, runs in REF["slices"].items():
        st = _structure(name)
        p = [r["pressure_mpa"] for r in runs]
        sq = squeeze(st, mat, p, gravity="none", keep_fields=True)
        secs = [section_pullout(st, mat, pk, mu_wire=MU["mu_wire"], mu_wall=MU["mu_wall"],
                                mu_wire_wall=0.0, ends="free", squeeze_result=sq,
                                squeeze_index=i) for i, pk in enumerate(p)]
        out[name] = {"sections": secs}
    return out


@pytest.mark.parametrize("name", list(REF["slices"]))
def test_slice_sliding_force_matches_3d(exo: dict[str, Any], name: str) -> None:
    """Sliding force per mm (mu_wire S_wire with the squeeze's held S_wire) within 2 % of the
    3-D slice from 0.2 MPa."""
    ref = np.array([r["sliding_force"] for r in REF["slices"][name]])
    ours = np.array([s.sliding_force_n_per_mm for s in exo[name]["sections"]])
    rel = np.abs(ours / ref - 1.0)
    assert rel.max() < SLIDE_TOL, (name, rel)


@pytest.mark.parametrize("name", list(REF["slices"]))
def test_slice_initial_stiffness_matches_3d(exo: dict[str, Any], name: str) -> None:
    """Initial (all-stuck) stiffness per mm within 5 % of the 3-D slice from 0.2 MPa."""
    ref = np.array([r["initial_stiffness"] for r in REF["slices"][name]])
    ours = np.array([s.initial_stiffness_n_per_mm2 for s in exo[name]["sections"]])
    rel = np.abs(ours / ref - 1.0)
    assert rel.max() < K0_TOL, (name, rel)


def test_3d_pressures_barely_move_during_the_pull() -> None:
    """The 3-D model's wire-arc normal-force integral changes by less than 1 % from the
    inflated state over the whole pull (the reduced model holds it): the reverse coupling is
    small in the mean even where |grad w| reaches 0.6."""
    for runs in REF["slices"].values():
        for r in runs:
            assert r["wire_normal_max_change"] < 0.01, r["pressure_mpa"]


TUBE_REF = Path(__file__).parent / "data" / "ccx_pullout_tube.json"
TUBES = json.loads(TUBE_REF.read_text())["tubes"] if TUBE_REF.exists() else {}


def test_held_tube_sliding_force_matches_3d() -> None:
    """5 mm tube held at its end faces (u_z = 0), rigid wire pulled 2 mm at 0.6 MPa: the
    pulled-end force of ``pullout(..., ends="fixed")`` on L = 5 mm at the end of the travel
    within 2 % of the 3-D one. (Its early F(delta) is not tested: the 3-D end rows, held
    against the moving wire, slip at once, and the reduced model's end-fitting foundation is a
    long-rod model; the secants are reported by the benchmark.)"""
    assert TUBES, "no held-tube reference stored (bench_pullout_ccx.py --tubes-only)"
    mat = _material()
    for name, runs in TUBES.items():
        st = _structure(name)
        for r in runs:
            st_l = dataclasses.replace(st, length_mm=r["options"]["depth_mm"])
            sq = squeeze(st_l, mat, [r["pressure_mpa"]], gravity="none", keep_fields=True)
            # cable EA 1e5 N: rigid against the tube (EA / L = 2e4 N/mm vs ~15 N/mm)
            t = pullout(st_l, mat, r["pressure_mpa"], mu_wire=MU["mu_wire"],
                        mu_wall=MU["mu_wall"], mu_wire_wall=0.0, ends="fixed",
                        cable_ea_n=1e5, displacement_mm=r["delta_mm"][-1], cycles=0,
                        squeeze_result=sq)
            rel = abs(t.force_n[-1] / r["sliding_force"] - 1.0)
            assert rel < SLIDE_TOL, (name, r["pressure_mpa"], rel)
