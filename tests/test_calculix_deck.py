"""The CalculiX decks of ``benchmarks/calculix_models.py`` (used by ``bench_peers.py``).

Text checks of the decks (material, load, boundary conditions, contact), the mesh and the
``.dat`` parser always run; the two that run ``ccx`` (free inflation vs the 1-D reference,
squeeze vs the stored FElupe reference) are skipped when CalculiX is not on PATH
(``make calculix`` installs it). Units: mm, N, MPa.
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

import calculix_models as cm  # noqa: E402

from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import compressible_inflation  # noqa: E402

MAT = MooneyRivlin.from_shore(62.5)
P = [0.05, 0.3, 0.6]
needs_ccx = pytest.mark.skipif(cm.ccx_available() is None, reason="CalculiX (ccx) not on PATH")


def _block(text: str, keyword: str) -> list[str]:
    """Data lines after the first line starting with ``keyword`` up to the next keyword."""
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if line.upper().startswith(keyword.upper()))
    out = []
    for line in lines[k + 1:]:
        if line.startswith("*"):
            break
        out.append(line)
    return out


def test_polar_quad8_nodes_on_circles_counter_clockwise() -> None:
    nodes, elems, grid = cm.polar_quad8(2.0, 3.0, 2, 5, -0.5 * np.pi, 0.5 * np.pi, grading=4.0,
                                        center=(1.0, -2.0))
    xy = {k: np.array(v) - (1.0, -2.0) for k, v in nodes.items()}
    radii = {round(float(np.hypot(*v)), 9) for v in xy.values()}
    assert radii == {2.0, 2.25, 2.5, 2.75, 3.0}
    assert len(nodes) == 5 * 11 - 2 * 5 and len(elems) == 10  # no element-centre nodes
    for conn in elems.values():
        c = np.array([xy[k] for k in conn[:4]])
        area = 0.5 * np.sum(c[:, 0] * np.roll(c[:, 1], -1) - np.roll(c[:, 0], -1) * c[:, 1])
        assert area > 0  # corners counter-clockwise
        r = [float(np.hypot(*xy[k])) for k in conn]
        # face 4 (nodes 4-8-1) and face 2 (2-6-3) are arcs, inner and outer
        assert r[3] == pytest.approx(r[7]) == pytest.approx(r[0])
        assert r[1] == pytest.approx(r[5]) == pytest.approx(r[2]) == pytest.approx(r[0] + 0.5)
    inner = [e for e, conn in elems.items() if conn[0] in set(grid[0])]
    assert len(inner) == 5
    # element angles shrink toward theta1 by the grading
    t = np.unwrap([np.arctan2(*xy[grid[0, j]][::-1]) for j in range(0, 11, 2)])
    d = np.diff(t)
    assert d[0] / d[-1] == pytest.approx(4.0)


def test_inflate_deck_text() -> None:
    deck = cm.inflate_deck(8.3, 4.97, MAT, P, n_radial=2, n_circ=6, controls=(1e-4, 1e-3))
    text = deck.text
    c10, c01, d1 = (float(v) for v in _block(text, "*HYPERELASTIC, MOONEY-RIVLIN")[0].split(","))
    assert (c10, c01) == pytest.approx((MAT.c10_mpa, MAT.c01_mpa), rel=1e-10)
    # (J-1)^2/D1 = exofric's (J-1)^2/d, K = 2/d
    assert d1 == pytest.approx(MAT.d_per_mpa, rel=1e-10)
    assert "*STEP, NLGEOM" in text and "*STATIC" in text
    assert [float(v.rstrip(",")) for v in _block(text, "*TIME POINTS")] == P
    dload = _block(text, "*DLOAD")
    assert len(dload) == 6 and all(re.fullmatch(r"\d+, P4, 0\.6", s) for s in dload)
    assert _block(text, "*BOUNDARY") == ["NY0, 2, 2", "NX0, 1, 1"]
    assert _block(text, "*CONTROLS") == ["0.0001, 0.001"]
    assert sum(1 for _ in _block(text, "*ELEMENT")) == 12
    assert "TYPE=CPE8R" in text
    out = deck.initial_xy[deck.probes["out"]]
    assert out == pytest.approx((4.15, 0.0))


def test_squeeze_deck_text() -> None:
    deck = cm.squeeze_deck(P, MAT, n_radial=2, n_circ=20, penalty=2e4, rigid_elements=16,
                           contact="NODE TO SURFACE")
    text = deck.text
    assert text.count("*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE") == 2
    assert "STUBE, SHOLE" in text and "STUBE, SWIRE" in text
    assert _block(text, "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR") == ["20000"]
    assert "*FRICTION" not in text  # frictionless
    assert len(_block(text, "*SURFACE, NAME=STUBE")) == 20
    assert all(s.endswith("S4") for s in _block(text, "*SURFACE, NAME=SHOLE"))
    assert all(s.endswith("S2") for s in _block(text, "*SURFACE, NAME=SWIRE"))
    assert _block(text, "*BOUNDARY") == ["NSYM, 1, 1", "NBOTTOM, 2, 2", "NHOLE, 1, 2",
                                          "NWIRE, 1, 2"]
    assert len(_block(text, "*DLOAD")) == 20
    # the bottom outer node sits on the hole wall, the top one 0.1 mm below the wire
    xy = deck.initial_xy
    assert xy[deck.probes["bottom"]] == pytest.approx((0.0, -5.0))
    top = max(xy.values(), key=lambda v: v[1])
    assert top == pytest.approx((0.0, 3.3))


def test_parse_dat() -> None:
    dat = """
 total force (fx,fy,fz) for set NWIRE and time  0.6000000E+00

        1.000000E-03 -1.036683E+00  0.000000E+00

 displacements (vx,vy,vz) for set NPROBE and time  0.5000000E-01

         1  7.613992E-02  0.000000E+00  0.000000E+00
        41  4.614907E-02  1.000000E-03  0.000000E+00
"""
    t = cm.parse_dat(dat)
    assert t[("total force", "NWIRE", 0.6)]["total"] == pytest.approx([1e-3, -1.036683, 0.0])
    u = t[("displacements", "NPROBE", 0.05)]
    assert sorted(u) == [1, 41] and u[41] == pytest.approx([0.04614907, 1e-3, 0.0])


@needs_ccx
def test_ccx_inflation_matches_1d_reference(tmp_path: Path) -> None:
    r = cm.ccx_inflate(8.3, 4.97, MAT, P, n_radial=2, n_circ=6, controls=(1e-4, 1e-3),
                       workdir=tmp_path)
    ref = compressible_inflation(8.3, 4.97, MAT, P).outer_diameter_mm
    assert np.max(np.abs(r.outer_diameter_mm / ref - 1.0)) < 5e-4


@needs_ccx
def test_ccx_squeeze_matches_felupe_reference(tmp_path: Path) -> None:
    r = cm.ccx_squeeze(P, MAT, n_radial=2, n_circ=20, contact="NODE TO SURFACE",
                       rigid_elements=32, max_increment_mpa=0.1, workdir=tmp_path)
    data = json.loads((ROOT / "tests" / "data" / "squeeze_reference_felupe.json").read_text())
    ref_p = np.array(data["pressure_mpa"])
    ref_n = np.array(data["structures"]["test 1"]["squeeze_force_n_per_mm"])
    ref = np.interp(P, ref_p, ref_n)  # the three pressures are stored ones
    n = r.squeeze_force_n_per_mm
    assert n[0] == 0.0  # the wire is first touched at ~0.054 MPa
    assert n[1:] == pytest.approx(ref[1:], rel=5e-3)  # 2 x 20 mesh: within 0.5%
    assert r.wall_force_n_per_mm == pytest.approx(n, rel=1e-3, abs=1e-6)  # equilibrium
