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
* Held tubes (``tests/data/ccx_pullout_tube.json``, ``runs``): 5 mm of the base group and of test 3
  at 0.2, 0.4 and 0.6 MPa and 10 mm of the base group at 0.6 MPa, the end faces held axially (u_z =
  0, in-plane free), the rigid wire pulled to full sliding (a run counts as sliding when its force
  is flat to 1e-5 over its last three outputs), and secant runs on 1 / 0.5 / 0.25 mm elements along
  z (the 10 mm tube: 1 mm and graded from 0.116 mm; the 5 mm base tube at 0.6 MPa also on 3 x 30 in
  the plane on 1 / 0.5 / 0.25 mm and on 4 x 40 on 0.5 mm; test 3 at 0.6 MPa on 3 x 30 and 0.25 mm,
  session 47). Compared with ``pullout(..., ends="fixed", cable_ea_n=1e5)`` on the same length (the
  3-D wire is rigid; EA / L >= 3e3 N/mm against the tube's <= 40 N/mm): the sliding force (finest
  sliding run) and two secants F(d) / d (finest run: most equations), k1 at d1 = 0.1 mm (P / 0.6
  MPa)^2, where the 3-D force is 0.30-0.42 x the sliding force, and k2 at 2 d1 (0.53-0.72 x; 0.2 mm
  at 0.6 MPa). The 3-D end rows, held against the moving wire, slip at once, so the early F / delta
  is no elastic stiffness; the slip displacement scales with P^2 (at 0.2 MPa the tubes slide fully
  by ~0.06 mm). The reduced model solves the zones next to the held faces in 3-D (the vector zone,
  session 46; docs/formulation.md section 12, "The vector zone"). Measured (exofric at the
  defaults of session 49 vs the finest run; base 0.2 / 0.4 / 0.6 MPa, 10 mm base 0.6, test 3 0.2 /
  0.4 / 0.6): sliding force -1.33 / +0.05 / +0.38, +0.54, -1.25 / +0.03 / +0.59 %; k1 -2.18 /
  +2.32 / +2.81, +4.96, -0.11 / +1.16 / +2.28 %; k2 -3.00 / +2.64 / +1.25, +3.58, -2.01 / +2.81 /
  +0.53 % (both 5 mm tubes at 0.6 MPa against their 3 x 30 runs on 0.25 mm, session 47, the 10 mm
  tube against its graded 3 x 30 run, session 48; once the faces are resolved along z, 2 x 20
  reads k1 2-3 % low) (the scalar zone: k1 +1.56 / +6.29 / +5.96, +5.72, +3.52 / +5.16 / +5.94 %,
  k2 +0.31 / +6.19 / +3.77, +3.87, +1.37 / +6.28 / +3.60 %). The 3-D k1 falls at every halving
  along z to 0.25 mm (-1.0 to -7.0 %); k2 rises at 0.6 MPa, falls at 0.2 MPa, moves < 1 % at 0.4
  MPa (no order). On 0.125 mm elements the 5 mm base tube's k1 moves -0.37 / +0.70 % at 0.6 / 0.4
  MPa (the reference levels off), but both 5 mm tubes' k1 at 0.2 MPa falls another 5.4 / 5.3 %
  (not converged there). Every case is within the issue's 5 %. The 30 mm tube (its reference
  unrefined at the faces, ``UNREFINED``) is +2.93 / +4.37 % on k1 / k2 (+7.80 / +8.80 % before the
  fittings' rod moved to the wall's slip, session 48).

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
Measured (exofric standard mesh vs 3-D, 0.2 / 0.4 / 0.6 MPa) on the code of 2026-11-27
(session 43; exofric's section has moved since the reference was stored, the 3-D numbers did
not): sliding force -0.27 / +0.61 / +0.40 % (base), -0.22 / +0.38 / +0.28 % (test 3); initial
stiffness +2.15 / -4.11 / -0.38 % (base), +4.91 / -0.59 / +1.72 % (test 3) (when stored: +2.20
/ -2.34 / +0.34 % and +2.18 / -2.35 / +0.32 %); held tubes as above.
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
from exofric.simulate import PulloutSetup, pullout, section_pullout, squeeze

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
        setup = PulloutSetup(st, mat, mu_wire=MU["mu_wire"], mu_wall=MU["mu_wall"],
                             mu_wire_wall=0.0, ends="free")
        secs = [section_pullout(setup, pk, squeeze_result=sq, squeeze_index=i)
                for i, pk in enumerate(p)]
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
TUBE_DATA = json.loads(TUBE_REF.read_text()) if TUBE_REF.exists() else {}
#: displacements (mm) of the held tubes' two secants F / delta at 0.6 MPa, scaled with
#: (P / 0.6 MPa)^2 at other pressures (as the slip displacement scales; the rule of
#: ``bench_pullout_ccx.secant_mm``): k1 where the 3-D force is ~0.4 x the sliding force (the
#: "half-sliding" secant, nearest an initial stiffness), k2 at ~0.7 x (0.2 mm at 0.6 MPa, the
#: secant of the first comparison). A fixed 0.2 mm would measure sliding at 0.2 MPa (the 5 mm
#: tubes slide fully by ~0.06 mm there).
SECANT_AT_06_MM = (0.1, 0.2)
#: a run has reached full sliding when its force is flat to this over the last three outputs
PLATEAU_FLATNESS = 1e-5


def _secant_mm(pressure: float, i: int) -> float:
    """Displacement (mm) of secant k{i + 1} at ``pressure`` (MPa)."""
    return SECANT_AT_06_MM[i] * (pressure / 0.6) ** 2


def _k(delta_mm: Any, force_n: Any, d_mm: float) -> float:
    """Secant F(d) / d (N/mm) of a force-displacement curve (linear interpolation)."""
    return float(np.interp(d_mm, delta_mm, force_n)) / d_mm


def _fineness(r: dict[str, Any]) -> int:
    """A stored run's number of equations (the finest run of a tube has the most)."""
    return int(r["equations"])


def _groups() -> dict[tuple[str, float, float], list[dict[str, Any]]]:
    """The stored 3-D held-tube runs by (structure, length mm, pressure MPa)."""
    out: dict[tuple[str, float, float], list[dict[str, Any]]] = {}
    for r in TUBE_DATA.get("runs", []):
        sp = r["spec"]
        out.setdefault((sp["structure"], sp["length_mm"], sp["pressure_mpa"]), []).append(r)
    return dict(sorted(out.items()))


GROUPS = _groups()


def _tube_id(key: tuple[Any, ...]) -> str:
    return f"{key[0]}/{key[1]:g}mm/{key[2]:g}MPa" + (f"/k{key[3] + 1}" if len(key) > 3 else "")


def _sliding_ref(runs: list[dict[str, Any]]) -> dict[str, Any] | None:
    """The finest run that reached full sliding (force flat to PLATEAU_FLATNESS), if any."""
    full = [r for r in runs if r["plateau_flatness"] < PLATEAU_FLATNESS]
    return max(full, key=_fineness) if full else None


@pytest.fixture(scope="module")
def held() -> dict[tuple[str, float, float], Any]:
    """``pullout(..., ends="fixed")`` on each stored held tube's structure, length and pressure
    (cable EA 1e5 N: rigid against the tube, EA / L >= 3e3 N/mm vs <= 40 N/mm), first loading
    (finely stepped to past the breakaway, so the secants are read on steps, not interpolated
    over the knee)."""
    assert GROUPS, "no held-tube reference stored (bench_pullout_ccx.py --tubes-only)"
    mat = _material()
    out = {}
    for (name, length, pressure), runs in GROUPS.items():
        st_l = dataclasses.replace(_structure(name), length_mm=length)
        sq = squeeze(st_l, mat, [pressure], gravity="none", keep_fields=True)
        setup = PulloutSetup(st_l, mat, mu_wire=MU["mu_wire"], mu_wall=MU["mu_wall"],
                             mu_wire_wall=0.0, ends="fixed", cable_ea_n=1e5)
        travel = max(r["delta_mm"][-1] for r in runs)
        out[(name, length, pressure)] = pullout(setup, pressure, displacement_mm=travel,
                                                cycles=0, squeeze_result=sq,
                                                first_loading=True)
    return out


def test_held_tubes_cover_two_structures_from_0_2_mpa() -> None:
    """The issue asks, from 0.2 MPa, for the base group and one other Table 3 structure: the
    5 mm tubes of both have a 3-D run pulled to full sliding at 0.2, 0.4 and 0.6 MPa."""
    have = {k for k, runs in GROUPS.items() if _sliding_ref(runs) is not None}
    want = {(n, 5.0, p) for n in ("test 1", "test 3") for p in (0.2, 0.4, 0.6)}
    assert want <= have, want - have


SLIDING_KEYS = [k for k, runs in GROUPS.items() if _sliding_ref(runs) is not None]


@pytest.mark.parametrize("key", SLIDING_KEYS, ids=_tube_id)
def test_held_tube_sliding_force_matches_3d(held: dict[tuple[str, float, float], Any],
                                            key: tuple[str, float, float]) -> None:
    """Tubes held at their end faces (u_z = 0), rigid wire pulled to full sliding: the
    pulled-end force of ``pullout(..., ends="fixed")`` at the end of the travel within 2 % of
    the 3-D one (the finest run that reached full sliding)."""
    ref = _sliding_ref(GROUPS[key])
    assert ref is not None
    t = held[key]
    rel = abs(float(np.interp(ref["delta_mm"][-1], t.displacement_mm, t.force_n))
              / ref["sliding_force"] - 1.0)
    assert rel < SLIDE_TOL, (key, rel)


def test_held_tube_secants_are_before_the_plateau() -> None:
    """Both secant displacements measure the stiffness, not the sliding: on every tube with a
    sliding run, the finest 3-D force there is 0.25-0.6 (k1) and 0.45-0.85 (k2) of the
    sliding force (measured 0.30-0.42 and 0.53-0.72; a data check)."""
    for key, runs in GROUPS.items():
        slide = _sliding_ref(runs)
        if slide is None:
            continue
        fine = max(runs, key=_fineness)
        for i, (lo, hi) in enumerate(((0.25, 0.6), (0.45, 0.85))):
            d = _secant_mm(key[2], i)
            share = float(np.interp(d, fine["delta_mm"], fine["force"])) / slide["sliding_force"]
            assert lo < share < hi, (key, i, share)


#: a tube's finest run counts as refined along z when its elements next to the held faces are
#: at most this long (mm): the 0.25 mm runs, the graded runs (0.116 mm)
REFINED_FACE_MM = 0.25


def _face_element_mm(spec: dict[str, Any]) -> float:
    """Length (mm) of a stored run's elements next to the held faces, by the deck's own
    grading (``calculix_pullout._graded``, the one owner) on the stored run's spec."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from calculix_pullout import _graded

    zb = _graded(float(spec["length_mm"]), int(spec["n_z"]), float(spec["z_grading"]),
                 spec.get("z_growth"))
    return float(zb[1] - zb[0])


#: tubes whose only 3-D runs are not refined at the held faces, and why: their secants are
#: compared (within 5 %) against a reference that is known to move with
#: refinement
UNREFINED: dict[tuple[str, float, float], str] = {
    ("test 1", 30.0, 0.6): "the issue's 30 mm tube: 30 uniform 1 mm elements along z, 20134 "
                           "equations, 1195 s CPU (graded elements stalled in the inflation; "
                           "3 x 30 with 0.25 mm faces timed out there at 0.85 P, session 48)",
}


def test_every_finest_reference_is_refined_along_z() -> None:
    """Every stored tube's finest run (the secants' reference) has elements of at most 0.25
    mm next to the held faces, so the 5 % test below covers every tube and pressure; except
    the tubes listed in ``UNREFINED``, which must really be unrefined (no stale entry)."""
    coarse = {k: _face_element_mm(max(runs, key=_fineness)["spec"])
              for k, runs in GROUPS.items()}
    assert all(v <= REFINED_FACE_MM for k, v in coarse.items() if k not in UNREFINED), coarse
    assert all(coarse[k] > REFINED_FACE_MM for k in UNREFINED), coarse


# Until session 49 the 10 mm base tube's k1 at 0.6 MPa was tested at a stated bound of 7 %
# (measured +6.15 % against its graded 3 x 30 run; +8.74 % against 2 x 20, and the 5 mm tubes'
# k1 at 0.6 MPa +6.5 / +6.7 % against theirs, until the 3 x 30 runs of session 47). Session 49
# refined the zone's z grid to its own convergence (0.25 / 1.5 -> 0.125 / 1.25: the held tubes'
# k1 had been 0.9-1.6 % above the converged zone, tests/test_pullout_held_zone.py): +4.96 %, and
# no case needs a bound. The 10 mm tube's reference on 4 x 40 did not get through CalculiX's
# pull (``failures``); on the 5 mm tube 3 x 30 -> 4 x 40 raised k1 by 0.61 %.
SECANT_KEYS = [(*k, i) for k in GROUPS for i in range(len(SECANT_AT_06_MM))]


@pytest.mark.parametrize("key", SECANT_KEYS, ids=_tube_id)
def test_held_tube_secant_within_5pct_of_finest_reference(
        held: dict[tuple[str, float, float], Any], key: tuple[str, float, float, int]) -> None:
    """Every tube, pressure and secant against the finest 3-D run (most equations; <= 0.25
    mm at the held faces but for ``UNREFINED``): within the issue's 5 % (measured: -3.00 to
    +4.96 %, the largest k1 of the 10 mm tube at 0.6 MPa)."""
    name, length, pressure, i = key
    ref = max(GROUPS[name, length, pressure], key=_fineness)
    d = _secant_mm(pressure, i)
    t = held[name, length, pressure]
    rel = _k(t.displacement_mm, t.force_n, d) / _k(ref["delta_mm"], ref["force"], d) - 1.0
    assert abs(rel) < K0_TOL, (key, rel)


def _uniform_z(runs: list[dict[str, Any]], i: int) -> list[float]:
    """The secant k{i + 1} (N/mm) of a tube's 2 x 20 runs with uniform elements along z, by
    element count (1, 0.5, 0.25 ... mm on 5 mm); of several, the one with the shortest travel
    (the secant run, whose outputs fall on the secant displacements)."""
    best: dict[int, dict[str, Any]] = {}
    for r in runs:
        sp = r["spec"]
        if r["mesh"] == "2x20" and sp["z_grading"] == 1.0 and (
                sp["n_z"] not in best or r["delta_mm"][-1] < best[sp["n_z"]]["delta_mm"][-1]):
            best[sp["n_z"]] = r
    d = _secant_mm(runs[0]["spec"]["pressure_mpa"], i)
    return [_k(best[n]["delta_mm"], best[n]["force"], d) for n in sorted(best)]


def test_held_tube_reference_rises_with_refinement() -> None:
    """The stored 3-D secants k2 of the 5 mm base tube at 0.6 MPa (2 x 20) rise monotonically
    as the elements along z halve (1 -> 0.125 mm: +0.89 / +1.00 / +0.40 %, tested < 1.5 %) and in
    the plane (2 x 20 -> 3 x 30 at 1 mm, by less than 1.5 %): the first comparison's basis of
    reading k2's error there as an upper estimate (a data check; the runs are CalculiX's)."""
    runs = GROUPS["test 1", 5.0, 0.6]
    steps = np.diff(_uniform_z(runs, 1))
    assert len(steps) >= 2 and np.all(steps > 0.0), steps
    z = _uniform_z(runs, 1)
    assert np.all(np.diff(z) / z[:-1] < 0.015), z
    d = _secant_mm(0.6, 1)
    k = {r["mesh"]: _k(r["delta_mm"], r["force"], d) for r in runs
         if r["spec"]["n_z"] == 5 and r["spec"]["travel_mm"] is not None}
    assert 0.0 < k["3x30"] / k["2x20"] - 1.0 < 0.015, k


def test_k1_reference_rises_with_refinement_in_the_plane() -> None:
    """The 5 mm tubes at 0.6 MPa: once the held faces are resolved along z, the 3-D k1 rises
    as the plane is refined. On the base tube 2 x 20 -> 3 x 30 moves it by +0.09 % on 1 mm
    elements along z, +1.60 % on 0.5 mm and +2.08 % on 0.25 mm; 3 x 30 -> 4 x 40 on 0.5 mm by
    +0.61 % (k2: +0.80 / +0.73 / +0.29 % and +0.49 %); on test 3, 2 x 20 -> 3 x 30 on 0.25 mm
    by +2.93 % (k2 +0.96 %); on the 10 mm base tube graded along z by +2.43 % (session 48).
    The 2 x 20 references of the other tubes therefore read k1 at 0.6
    MPa 2-3 % low (their exofric errors are upper estimates), and both tubes' finest runs (most
    equations) are the 3 x 30, 0.25 mm ones, the 10 mm tube's its graded 3 x 30 run (a data
    check: the runs are CalculiX's; tested:
    each refinement in the plane raises k1 from 0.5 mm, the first by 1-3.5 % and the second by
    less than the first)."""
    runs = GROUPS["test 1", 5.0, 0.6]
    d = _secant_mm(0.6, 0)
    k: dict[tuple[str, int], float] = {}
    for r in runs:
        if r["spec"]["z_grading"] == 1.0:
            k.setdefault((r["mesh"], r["spec"]["n_z"]), _k(r["delta_mm"], r["force"], d))
    for n in (10, 20):
        assert 0.01 < k["3x30", n] / k["2x20", n] - 1 < 0.035, (n, k)
    second = k["4x40", 10] / k["3x30", 10] - 1
    assert 0.0 < second < k["3x30", 10] / k["2x20", 10] - 1, k
    t3 = {r["mesh"]: _k(r["delta_mm"], r["force"], d) for r in GROUPS["test 3", 5.0, 0.6]
          if r["spec"]["n_z"] == 20}
    assert 0.01 < t3["3x30"] / t3["2x20"] - 1 < 0.035, t3
    for key in (("test 1", 5.0, 0.6), ("test 3", 5.0, 0.6)):
        finest = max(GROUPS[key], key=_fineness)
        assert (finest["mesh"], finest["spec"]["n_z"]) == ("3x30", 20), key
    # the 10 mm base tube, graded along z (0.116 mm at the faces): 2 x 20 -> 3 x 30 +2.43 %
    ten = {r["mesh"]: _k(r["delta_mm"], r["force"], d) for r in GROUPS["test 1", 10.0, 0.6]
           if r["spec"]["z_grading"] != 1.0}
    assert 0.01 < ten["3x30"] / ten["2x20"] - 1 < 0.035, ten
    assert max(GROUPS["test 1", 10.0, 0.6], key=_fineness)["mesh"] == "3x30"


def test_k1_reference_falls_with_refinement_along_z_then_levels_off_from_0_4_mpa() -> None:
    """Every tube's 3-D secant k1 (~0.4 x the sliding force) falls at every halving of the
    elements along z down to 0.25 mm (measured -1.0 to -7.0 %, tested < 0 and the last < 4.5 %
    in size). The one halving past it, to 0.125 mm: at 0.4 and 0.6 MPa (the 5 mm base tube) it
    moves k1 by less than 1 % (measured +0.70 / -0.37 %): the reference levels off there. At 0.2
    MPa (both 5 mm tubes, session 46) it keeps falling, by more than the halving before
    (measured -5.4 / -5.3 % after -2.3 / -2.9 %; tested -8 to -3 %): the low-pressure k1, read
    at 0.011 mm, is not converged in the reference, so exofric's error there (vector zone
    -1.7 / +0.6 % against 0.125 mm) is an error against a stiff reference (a data check; the
    runs are CalculiX's)."""
    for key, runs in GROUPS.items():
        z = np.array(_uniform_z(runs, 0))
        if len(z) < 2:
            continue
        steps = np.diff(z) / z[:-1]
        coarse, fine = steps[:2], steps[2:]   # 1 -> 0.5 -> 0.25 mm, then 0.125 mm
        assert np.all(coarse < 0.0), (key, steps)
        assert abs(coarse[-1]) < 0.045, (key, steps)
        if key[2] >= 0.4:
            assert np.all(np.abs(fine) < 0.01), (key, steps)
        else:
            assert np.all((-0.08 < fine) & (fine < -0.03)), (key, steps)


def test_scalar_zone_kinematics_are_softer_than_3d_on_a_held_annulus() -> None:
    """The stored CalculiX check behind docs/formulation.md's statement on the zone's scalar
    kinematics (``benchmarks/calculix_heldzone.py``; a data check, no exofric): on held
    axisymmetric annuli the scalar equation (u_r = 0, E_z = 3 G) carries less force than linear
    3-D elasticity in every variant, by more than the 3-D mesh change (1.8 %)."""
    data = json.loads((Path(__file__).parent / "data" / "ccx_pullout_heldzone.json").read_text())
    ratios = [v["scalar_over_3d"] for k, r in data.items() if k.startswith("L")
              for v in r["variants"]]
    assert len(ratios) == 4 and max(ratios) < 0.9, ratios
    for k, r in data.items():
        if k.startswith("L"):
            assert abs(r["unit_check_scalar_over_closed_form"] - 1.0) < 1e-5, k


def test_inflation_stretch_softens_the_3d_held_zone_and_pressure_hardly_moves_it() -> None:
    """The stored CalculiX check behind docs/formulation.md's "The cause" (session 45; a data
    check, no exofric): the held annulus inflated first loses stiffness at every step of the
    bore's hoop stretch (1 -> 1.84: measured -27 / -36 % on 5 / 10 mm, tested > 20 %), while the
    bore pressure itself moves it by < 5 % (measured -0.05 % unstretched, +2.1 / +3.7 % at
    stretch 1.50); the exofric-like scalar zone (E_z = 3 G) is 19-27 % below 3-D unstretched and
    within 1 % of it at 1.50; and the 3-D mesh moves the force by < 2.5 % (16 x 250 against 8 x
    100: -1.8 %), a tenth of the stretch's effect."""
    data = json.loads((Path(__file__).parent / "data" / "ccx_pullout_heldzone.json").read_text())
    inf = data["inflated"]
    assert len(inf["lengths"]) == 2
    for row in inf["lengths"]:
        f = np.array(row["force_by_ur0"])
        assert np.all(np.diff(row["inner_stretch"]) > 0) and np.all(np.diff(f) < 0), f
        assert f[-1] / f[0] < 0.8, f
        for forces in row["force_by_pressure"].values():
            assert max(abs(np.array(forces) / forces[0] - 1.0)) < 0.05, forces
        scalar = row["scalar_by_ez_over_g"]["3"]
        assert 0.7 < scalar / f[0] < 0.85, (scalar, f[0])
        k = row["ur0_mm"].index(0.85)
        assert abs(scalar / f[k] - 1.0) < 0.01, (scalar, f[k])
    chk = inf["fine_mesh_check"]
    assert abs(chk["force"] / chk["force_mesh"] - 1.0) < 0.025, chk


def test_the_held_tubes_excess_sits_in_the_zone_interior() -> None:
    """Where along z the held tube's remaining excess sits (docs/formulation.md section 12):
    exofric's held zone (the vector zone, session 46), against the stored 3-D friction force
    per slice of the 5 mm base tube (``benchmarks/calculix_zprofile.py``, 0.5 mm elements along
    z: at 0.2 MPa that grid's k1 is 8 % above the 0.125 mm run's). At 0.2 MPa the zone's
    interior (0.4-2.5 mm from a held face) is within 6 % of the 3-D force (measured -4.7 /
    -4.4 % at d1 / 2 d1; the scalar zone: 0.0 / -0.1 %); at 0.6 MPa it is above it at d1 by
    the k1 excess this file bounds elsewhere (measured +11.1 %, held within 5-15 %: a measured
    bound, not a tolerance; the scalar zone +16.2 %) and within 6 % at 2 d1 (+3.3 %), while
    next to the faces the 3-D halves' mean and exofric agree within 6 % at 0.6 MPa (measured
    -1.6 / +3.6 %; at 0.2 MPa exofric is 8-16 % low there, bounded at 20 %)."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    import calculix_zprofile as zp

    data = json.loads((Path(__file__).parent / "data" / "ccx_pullout_zprofile.json").read_text())
    runs = {r["ccx"]["pressure_mpa"]: r["ccx"] for r in data["runs"]}
    assert set(runs) == {0.2, 0.6}
    for p, c in runs.items():
        e = zp.exofric_profile(p, np.array(c["delta_mm"]))
        d1 = 0.1 * (p / 0.6) ** 2
        r1, r2 = (zp.compare(c, e, d) for d in (d1, 2 * d1))
        interior = r1["interior_exofric_n"] / r1["interior_3d_n"] - 1.0
        interior2 = r2["interior_exofric_n"] / r2["interior_3d_n"] - 1.0
        if p == 0.2:
            assert abs(interior) < 0.06 and abs(interior2) < 0.06, (r1, r2)
            assert -0.2 < r1["face_exofric_n"] / r1["face_3d_n"] - 1.0 < 0.0, r1
        else:
            assert 0.05 < interior < 0.15, r1
            assert abs(interior2) < 0.06, r2
            for r in (r1, r2):
                assert abs(r["face_exofric_n"] / r["face_3d_n"] - 1.0) < 0.06, r
