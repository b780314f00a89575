"""exofric's frictional squeeze against an independent CalculiX model (issue 15 acceptance).

The reference (``tests/data/ccx_friction_base.json``) comes from
``benchmarks/bench_friction_ccx.py``: CalculiX 2.20 (``ccx``), its own mesh (4 x 60 CPE8R,
rigid hole and wire meshed 64 elements per face), node-to-surface penalty contact with
``*FRICTION`` (mu 0.3, stick slope 1e3 MPa/mm: a tangential penalty with a Coulomb return
map), pressure ramped in increments of at most
0.025 MPa. Its own convergence studies (increments 0.05-0.00625 MPa: 0.04 %; meshes 3 x 45 vs
4 x 60: 0.07 %; stick slope 300-3000: 0.014 %; surface-to-surface vs node-to-surface: 0.2 %) are
in the file. Nothing of exofric is used to make it (only the material constants and sizes).

Tolerance: the issue's 1 % from 0.2 MPa for N. Measured (largest from 0.2 MPa, at 0.25 MPa,
where the two codes' frictionless models also differ by 0.36 %): both interfaces 0.27 %, the
wall alone 0.31 %, the wire alone 0.32 %; from 0.3 MPa at most 0.12 %. The wire alone moves N by
only 0.3 %, below that tolerance, so the tube-wire tangential force (the friction the wire feels
in the section's plane) and the normal-pressure integrals are compared as well (CalculiX's are
nodal reactions of the rigid faces split into radial and circumferential parts, on a different
contact discretisation).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from exofric.geometry import BASE, Structure
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze

REF = json.loads((Path(__file__).parent / "data" / "ccx_friction_base.json").read_text())
CASES = {"both": (0.3, 0.3), "wall_only": (0.3, 0.0), "wire_only": (0.0, 0.3)}


@pytest.fixture(scope="module")
def solved() -> dict[str, object]:
    s = REF["structure"]
    st = Structure(s["hole_mm"], s["tube_od_mm"], s["tube_id_mm"], s["wire_mm"],
                   BASE.length_mm)
    m = REF["material"]
    mat = MooneyRivlin(m["c10_mpa"], m["c01_mpa"], m["d_per_mpa"])
    p = np.asarray(REF["pressure_mpa"])
    return {k: squeeze(st, mat, p, mu_wall=mw, mu_wire=mr, gravity="none")
            for k, (mw, mr) in CASES.items()}


@pytest.mark.parametrize("case", list(CASES))
def test_squeeze_force_matches_calculix(solved: dict[str, object], case: str) -> None:
    r = solved[case]
    ref = np.asarray(REF["cases"][case]["squeeze_force_n_per_mm"])
    p = np.asarray(REF["pressure_mpa"])
    k = p >= 0.2 - 1e-12
    rel = np.abs(r.squeeze_force_n_per_mm[k] / ref[k] - 1)
    assert rel.max() < 0.01, (case, rel)


@pytest.mark.parametrize("case", list(CASES))
def test_friction_changes_n_as_calculix_does(solved: dict[str, object], case: str) -> None:
    """The change friction makes to N, against the frictionless model of each code (so that
    the codes' 0.1 % frictionless difference drops out): within 0.5 % of N (the effect is
    -9 % at 0.6 MPa with both interfaces, -0.3 % with the wire alone)."""
    p = np.asarray(REF["pressure_mpa"])
    k = p >= 0.2 - 1e-12
    ref0 = np.asarray(REF["cases"]["frictionless"]["squeeze_force_n_per_mm"])[k]
    ref = np.asarray(REF["cases"][case]["squeeze_force_n_per_mm"])[k]
    mw, mr = CASES[case]
    r = solved[case]
    st = r.structure
    ours0 = squeeze(st, r.material, p[k], gravity="none").squeeze_force_n_per_mm
    d_ours = r.squeeze_force_n_per_mm[k] / ours0 - 1
    d_ref = ref / ref0 - 1
    assert np.max(np.abs(d_ours - d_ref)) < 5e-3, (case, d_ours, d_ref)


def test_interface_integrals_match_calculix(solved: dict[str, object]) -> None:
    """Both interfaces at mu 0.3, from 0.3 MPa: the normal-pressure integrals of wire and wall
    within 1 % (measured 0.3 %), the magnitudes of the in-plane friction force on the wire and
    the wall within 8 % (measured: wall 0.3-1.4 %, wire 1-6 %; friction tractions are the least
    converged output, the wire's contact arc has ~7 nodes on exofric's standard mesh; a sign
    error or a factor 2 of the half model would show)."""
    r = solved["both"]
    c = REF["cases"]["both"]
    p = np.asarray(REF["pressure_mpa"])
    k = p >= 0.3 - 1e-12
    pairs = [(r.contact.wire_pressure_integral_n_per_mm, c["wire_normal_n_per_mm"], 0.01),
             (r.contact.wall_pressure_integral_n_per_mm, c["wall_normal_n_per_mm"], 0.01),
             (r.contact.wire_tangential_force_n_per_mm, np.abs(c["wire_tangential_n_per_mm"]),
              0.08),
             (r.contact.wall_tangential_force_n_per_mm, np.abs(c["wall_tangential_n_per_mm"]),
              0.08)]
    for ours, ref, tol in pairs:
        rel = np.abs(np.asarray(ours)[k] / np.asarray(ref)[k] - 1)
        assert rel.max() < tol, rel
