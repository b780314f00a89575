"""The friction force along the wire's contact arc against CalculiX (issue 35, item 3).

``wire_tangential_force_n_per_mm`` (T_wire, N per mm of tube, full section) is the integral over
the tube-wire contact arc of the magnitude of the friction traction the tube exerts on the wire
(2 x the sum of the half model's nodal friction forces; ``benchmarks/bench_tangential.py``
defines both codes' numbers). The reference ``tests/data/ccx_tangential_base.json`` comes from
``benchmarks/bench_tangential.py``: CalculiX 2.20 (``ccx``), its own CPE8R meshes of the base
group (4, 8 and 16 x 60, graded 10:1 toward the wire), node-to-surface penalty contact with
``*FRICTION`` (mu 0.3 on the wire, the wall frictionless), stick slopes 300 .. 1e4 MPa/mm,
increments down to 0.00625 MPa; nothing of exofric is used to make it (only the material
constants and sizes). T_wire is the sum of the circumferential parts of the rigid wire nodes'
reactions there, a different contact discretisation from exofric's.

What the comparison has to allow for is documented in ``docs/formulation.md`` (section 13)
and measured in the JSON: at 0.1-0.2 MPa the contact arc is 0.06-0.16 mm long, and T_wire
there depends on the mesh under the contact (both codes), on the load steps in which the arc
grows (exofric on fine meshes) and on the stick slope (CalculiX). The tolerances below are the
measured agreement plus the spread of the reference's own studies, stated per test.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from exofric import defaults
from exofric.fe import MeshSpec, NewtonSettings
from exofric.geometry import BASE, Structure
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze

DATA = Path(__file__).parent / "data" / "ccx_tangential_base.json"
REF = json.loads(DATA.read_text())
P = np.asarray(REF["pressure_mpa"])
#: CalculiX's finest mesh: 16 x 60 CPE8R, graded 10:1 toward the wire, stick slope 1e3 MPa/mm
REF_RUN = "mesh_16x60"


def _structure() -> Structure:
    s = REF["structure"]
    return Structure(s["hole_mm"], s["tube_od_mm"], s["tube_id_mm"], s["wire_mm"],
                     BASE.length_mm)


def _material() -> MooneyRivlin:
    m = REF["material"]
    return MooneyRivlin(m["c10_mpa"], m["c01_mpa"], m["d_per_mpa"])


def _ref(name: str) -> np.ndarray:
    return np.asarray(REF["ccx"][name]["tangential_n_per_mm"])


#: exofric's current answer: the standard accuracy's mesh (``squeeze(accuracy="standard")``
#: returns this mesh's T_wire; its nested coarse mesh only feeds the error estimate of N), the
#: default penalty and load steps.
MESH = MeshSpec(**{k: v for k, v in defaults.SQUEEZE_ACCURACY["standard"].items()
                   if k != "coarsen"})


@pytest.fixture(scope="module")
def standard() -> object:
    r = squeeze(_structure(), _material(), P, mu_wall=0.0, mu_wire=REF["friction"]["mu_wire"],
                gravity="none", accuracy="standard", keep_fields=False)
    assert r.mesh == MESH  # T_wire is the standard mesh's; the nested one feeds the estimates
    return r


def test_reference_says_what_it_is() -> None:
    """The stored reference names its code, version, meshes and penalties, and holds the runs
    the comparison and docs/formulation.md section 13 use (no solve)."""
    assert REF["provenance"]["ccx_version"]
    for name in (REF_RUN, "mesh_8x60", "slope_1e3", "slope_300", "slope_3e3", "slope_1e4",
                 "inc_0.00625"):
        run = REF["ccx"][name]
        assert "error" not in run, name
        opts = run["options"]
        assert opts["n_radial"] > 0 and opts["n_circ"] > 0 and opts["stick_slope"] > 0
        assert len(run["tangential_n_per_mm"]) == P.size


def test_wire_tangential_force_matches_calculix(standard: object) -> None:
    """exofric's standard answer for T_wire against CalculiX's finest run (16 x 60).

    Tolerances: 40 % for 0.2 <= P < 0.35 MPa, 10 % from 0.35 MPa, 5 % at 0.6 MPa. They are the
    standard mesh's discretisation error, not the codes' disagreement: 4 elements through the
    wall and 3-5 nodes on the half contact arc at 0.2-0.3 MPa. Measured on the two standard
    meshes of issue 35: 4 x 32 graded 6:1 toward the wire (before): -9.1 / +7.4 / +12.8 % at
    0.2 / 0.25 / 0.3 MPa, <= 5.0 % from 0.35, +1.8 % at 0.6; with 10 of the 32 elements graded
    toward the wall (finer at the wire along the surface, not through the wall): +30.1 / +25.6
    / +13.6 %, <= 9.2 % from 0.35, +2.5 % at 0.6. exofric's resolved run (12 x 96, steps
    0.003125 MPa; ``benchmarks/bench_tangential.py``) is within +5.0 / +6.7 / +3.5 % of this
    reference at 0.2 / 0.25 / 0.3 MPa and 2.3 % from 0.35 MPa; the reference itself still moves
    by -21 % at 0.2 MPa and -1 % at 0.3 MPa from 8 to 16 elements through the wall. Below 0.2
    MPa neither code resolves the arc (0.003-0.009 N/mm at 0.1 MPa over all runs): not
    compared. The issue's reference (2.1x this one at 0.2 MPa) or a lost factor 2 of the half
    model would fail. Same penalty as the reference's stick slope (1e3 N/mm^3)."""
    r = standard
    slope = REF["ccx"][REF_RUN]["options"]["stick_slope"]
    assert r.contact.friction_penalty == pytest.approx(slope)
    ours = np.asarray(r.contact.wire_tangential_force_n_per_mm)
    ref = _ref(REF_RUN)
    rel = ours / np.where(ref > 0, ref, np.nan) - 1.0
    k = P >= 0.2 - 1e-12
    assert np.max(np.abs(rel[k])) < 0.40, rel
    k = P >= 0.35 - 1e-12
    assert np.max(np.abs(rel[k])) < 0.10, rel
    assert abs(rel[-1]) < 0.05, rel
    # the normal-pressure integral on the same arc agrees far better (6:1 standard mesh: <= 0.4 %
    # from 0.2 MPa, <= 0.15 % from 0.3 MPa): the difference is in the friction traction, not in
    # the contact
    s_ref = np.asarray(REF["ccx"][REF_RUN]["normal_n_per_mm"])
    s = np.asarray(r.contact.wire_pressure_integral_n_per_mm)
    k = P >= 0.2 - 1e-12
    assert np.max(np.abs(s[k] / s_ref[k] - 1.0)) < 0.01


def test_wire_tangential_estimate_brackets_the_calculix_difference(standard: object) -> None:
    """T_wire's own two-mesh estimate (``estimate.wire_tangential_pct``) is >= its actual
    difference from CalculiX's finest run wherever the run compares (from 0.2 MPa), and it is
    not N's estimate: N's 2.2 % at 0.2 MPa would hide T_wire's +30 %.

    No allowance is made for the reference's own error (it moves by -21 % at 0.2 MPa from 8 to
    16 elements through the wall): measured on the standard level, estimate / |difference| is
    93.6 / 29.7, 93.6 / 25.4, 93.6 / 13.4 % at 0.2 / 0.25 / 0.3 MPa and 14.3 / 2.5 % at 0.6 MPa,
    so the test fails only if the estimate shrinks below the difference. At 0.1 MPa (no wire
    contact on the nested mesh) the estimate is flagged unreliable and says 100 %. Meshes tried
    for a standard level that resolves T_wire at <= 1.5x the cost (4 x 32 graded 3:1 or 12:1, 4 x
    40, 6 x 24, 6 x 32, 8 x 32): none within 5 % from 0.2 MPa (+5 .. +76 % there; the error
    swings with how the few contact nodes fall), hence the estimate instead.
    """
    r = standard
    est = r.estimate.wire_tangential_pct
    assert est is not None and r.estimate.reliable is not None
    ours = np.asarray(r.contact.wire_tangential_force_n_per_mm)
    ref = _ref(REF_RUN)
    k = P >= 0.2 - 1e-12
    err = 100.0 * np.abs(ours[k] / ref[k] - 1.0)
    assert np.all(r.estimate.reliable[k])
    assert np.all(est[k] >= err), (est[k], err)
    assert est[P == 0.2][0] > 5.0 * r.estimate.pct[P == 0.2][0]  # its own, not N's
    d = r.to_dict()
    assert d["wire_tangential_force_error_estimate_pct"] == pytest.approx(est.tolist())
    # without friction on the wire there is nothing to estimate
    r0 = squeeze(_structure(), _material(), [0.3], gravity="none", accuracy="draft",
                 keep_fields=False)
    assert r0.estimate.wire_tangential_pct is None


# ---------------------------------------------------------------- converged references (issue 35)
CONV = json.loads((Path(__file__).parent / "data" / "ccx_tangential_converged.json").read_text())
P_CONV = np.asarray(CONV["pressure_mpa"])
#: exofric's mesh in the fast test: the coarsest of its convergence sequence (6 x 48 quad9, graded
#: 20:1 toward the wire, load sub-steps <= 0.003125 MPa; ~2 s)
CONV_RUN = "6x48_step_0.003125"


def _converged(code: str) -> tuple[np.ndarray, np.ndarray]:
    """(pressures MPa, extrapolated T_wire N/mm) of ``code``'s stored convergence study."""
    c = CONV["converged"][code]
    return (np.asarray(c["pressure_mpa"]),
            np.asarray([q["extrapolated"] for q in c["per_pressure"]]))


def test_converged_references_say_what_they_are() -> None:
    """Both codes' mesh sequences are stored with their meshes, penalties, steps and CPU times,
    and each converged: the finest step of its sequence moves T_wire by < 2 % from 0.2 MPa, or
    the observed order is >= 1 (Richardson applies); no solve."""
    prov = CONV["provenance"]
    assert prov["ccx_version"] and "--converge" in prov["command"]
    for code in ("ccx", "exofric"):
        c = CONV["converged"][code]
        assert len(c["meshes"]) == 3
        for name in c["meshes"]:
            assert "error" not in CONV[code][name] and CONV[code][name]["cpu_time_s"] > 0
        for q in c["per_pressure"]:
            assert abs(q["last_change_pct"]) < 2.0 or (q["order"] or 0.0) >= 1.0, q


def test_converged_wire_tangential_forces_agree() -> None:
    """exofric's and CalculiX's mesh-converged T_wire agree within 5 % from 0.2 MPa (the
    issue's acceptance; no solve: both are stored, CalculiX's made by ccx alone).

    Each value is its code's three-mesh sequence (every element about halved per step, fixed
    gradings), Richardson-extrapolated with the observed order where the changes shrink
    monotonically, else its finest mesh (CalculiX at 0.2 MPa: 4 x 40 -> 8 x 80 -> 16 x 160
    changes -11 % then +1.1 %). The comparison is then between two converged numbers, unlike
    ``test_wire_tangential_force_matches_calculix`` (against CalculiX 16 x 60, which still moves
    by -21 % at 0.2 MPa between 8 and 16 elements through the wall)."""
    pc, ref = _converged("ccx")
    pe, ours = _converged("exofric")
    assert np.array_equal(pc, pe) and pc[0] == pytest.approx(0.2)
    rel = ours / ref - 1.0
    assert np.all(np.abs(rel) < 0.05), rel


def test_wire_tangential_force_matches_converged_calculix() -> None:
    """exofric solved now on the coarsest mesh of its sequence against CalculiX's converged
    T_wire at 0.2, 0.25, 0.3 MPa.

    Tolerance per pressure: 5 % (the issue's acceptance) + this mesh's own discretisation error,
    |T(6 x 48) / T(exofric extrapolated) - 1| from the stored study (19.7 / 10.2 / 5.9 % at
    0.2 / 0.25 / 0.3 MPa: what refining to 12 x 96 and 24 x 192 removes), so 24.7 / 15.2 /
    10.9 %; measured +15.3 / +8.3 / +4.4 %. A lost factor 2 or the issue's reference (~0.038
    N/mm at 0.2 MPa, +105 %) would fail. Same penalty as CalculiX's stick slope (1e3)."""
    pc, ref = _converged("ccx")
    _, ext = _converged("exofric")
    run = CONV["exofric"][CONV_RUN]
    (nr, nc), grading, step = run["mesh"], run["grading"], run["max_step_mpa"]
    k = np.isin(np.round(P_CONV, 10), np.round(pc, 10))
    own = np.abs(np.asarray(run["tangential_n_per_mm"])[k] / ext - 1.0)
    r = squeeze(_structure(), _material(), P_CONV, mu_wall=0.0,
                mu_wire=CONV["friction"]["mu_wire"], gravity="none",
                mesh=MeshSpec(nr, nc, grading=grading), keep_fields=False,
                settings=NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "max_step": step}))
    assert r.contact.friction_penalty == pytest.approx(
        CONV["ccx"][CONV["converged"]["ccx"]["meshes"][-1]]["options"]["stick_slope"])
    ours = np.asarray(r.contact.wire_tangential_force_n_per_mm)[k]
    rel = ours / ref - 1.0
    assert np.all(np.abs(rel) <= 0.05 + own), (rel, own)
