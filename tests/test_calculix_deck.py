"""The CalculiX decks of ``benchmarks/calculix_models.py`` (``bench_peers.py``,
``bench_friction_ccx.py``).

Text checks of the decks (material, load, boundary conditions, contact; issue 15's friction:
``*FRICTION`` with the right mu on the right contact pair only, and mu = 0 writing the deck of
before byte for byte), the mesh and the ``.dat`` parser (with the split of the rigid bodies'
nodal forces into normal and tangential parts) always run; the two that run ``ccx`` (free
inflation vs the 1-D reference, squeeze vs the stored FElupe reference) are skipped when
CalculiX is not on PATH (``make calculix`` installs it). Units: mm, N, MPa.
"""

from __future__ import annotations

import hashlib
import json
import re
import sys
from pathlib import Path
from typing import Any

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


#: Mooney-Rivlin constants (c10, c01 MPa, d 1/MPa) fixed here so that the deck hashes below
#: do not depend on exofric's Shore conversion.
MAT_FIXED = (0.6354497354497354, 0.03177248677248677, 0.005995004163197341)


@pytest.mark.parametrize(("setup", "sha256"), [
    ({"n_radial": 2, "n_circ": 8, "rigid_elements": 8},
     "b66313307974f2f76da01d037bd45d1fc3a6484449c3a67e027ad8e93bea115f"),
    ({"n_radial": 2, "n_circ": 8, "rigid_elements": 8, "contact": "SURFACE TO SURFACE",
      "penalty": 2e4, "max_increment_mpa": 0.02, "controls": (1e-4, 1e-3)},
     "74a8779e4bfad51b6eb6d7b9e3378f4752e9e9dab88e2bafc6114067387b1195"),
])
def test_squeeze_deck_frictionless_is_the_deck_before_friction(setup: dict[str, Any],
                                                               sha256: str) -> None:
    # the hashes are of the decks written before mu_wall / mu_wire existed: mu = 0 (default
    # or explicit, any stick slope) must write them byte for byte
    extras: list[dict[str, Any]] = [{}, {"mu_wall": 0.0, "mu_wire": 0.0}, {"stick_slope": 5.0}]
    for extra in extras:
        text = cm.squeeze_deck(P, MAT_FIXED, **setup, **extra).text
        assert hashlib.sha256(text.encode()).hexdigest() == sha256
    deck = cm.squeeze_deck(P, MAT_FIXED, **setup)
    assert "mu_wall" not in deck.mesh and "stick_slope" not in deck.mesh


def _interactions(text: str) -> tuple[dict[str, tuple[float, float] | None], dict[str, str],
                                      dict[str, float]]:
    """(interaction -> (mu, stick slope) or None, master surface -> interaction,
    interaction -> penalty) of a squeeze deck."""
    lines = text.splitlines()
    friction: dict[str, tuple[float, float] | None] = {}
    penalty: dict[str, float] = {}
    pairs: dict[str, str] = {}
    current = None
    for k, line in enumerate(lines):
        if line.startswith("*SURFACE INTERACTION"):
            current = line.split("NAME=")[1].strip()
            friction[current] = None
        elif line.startswith("*SURFACE BEHAVIOR"):
            assert current is not None
            penalty[current] = float(lines[k + 1])
        elif line.startswith("*FRICTION"):
            assert current is not None
            mu, slope = (float(v) for v in lines[k + 1].split(","))
            friction[current] = (mu, slope)
        elif line.startswith("*CONTACT PAIR"):
            m = re.search(r"INTERACTION=(\w+)", line)
            assert m is not None
            name = m.group(1)
            slave, master = (v.strip() for v in lines[k + 1].split(","))
            assert slave == "STUBE"
            pairs[master] = name
    return friction, pairs, penalty


@pytest.mark.parametrize(("mu_wall", "mu_wire"), [(0.3, 0.3), (0.3, 0.0), (0.0, 0.3),
                                                  (0.15, 0.45)])
def test_squeeze_deck_friction_cards_on_the_right_pair(mu_wall: float, mu_wire: float) -> None:
    deck = cm.squeeze_deck(P, MAT, n_radial=2, n_circ=20, penalty=2e4, rigid_elements=16,
                           mu_wall=mu_wall, mu_wire=mu_wire, stick_slope=500.0)
    friction, pairs, penalty = _interactions(deck.text)
    # one interaction per pair, same normal penalty on both
    assert pairs == {"SHOLE": "SIWALL", "SWIRE": "SIWIRE"}
    assert penalty == {"SIWALL": 2e4, "SIWIRE": 2e4}
    for name, mu in (("SIWALL", mu_wall), ("SIWIRE", mu_wire)):
        # CalculiX rejects mu = 0 in *FRICTION: a frictionless pair gets no card at all
        assert friction[name] == (None if mu == 0.0 else (pytest.approx(mu), 500.0))
    assert deck.text.count("*FRICTION") == (mu_wall > 0) + (mu_wire > 0)
    # *FRICTION belongs to the model definition: before the step
    assert deck.text.rindex("*FRICTION") < deck.text.index("*STEP")
    assert deck.mesh["mu_wall"] == mu_wall and deck.mesh["mu_wire"] == mu_wire
    assert deck.mesh["stick_slope"] == 500.0
    # everything else is the frictionless deck
    plain = cm.squeeze_deck(P, MAT, n_radial=2, n_circ=20, penalty=2e4, rigid_elements=16)
    cut = "*SURFACE INTERACTION"
    assert deck.text[:deck.text.index(cut)] == plain.text[:plain.text.index(cut)]
    assert (deck.text[deck.text.index("*TIME POINTS"):]
            == plain.text[plain.text.index("*TIME POINTS"):])


def test_squeeze_deck_friction_default_stick_slope_and_input_checks() -> None:
    friction, _, _ = _interactions(cm.squeeze_deck(P, MAT, n_circ=20, mu_wire=0.3).text)
    assert friction["SIWIRE"] == (0.3, cm.STICK_SLOPE)
    bads: list[dict[str, Any]] = [{"mu_wall": -0.1}, {"mu_wire": float("nan")},
                                  {"mu_wall": 0.3, "stick_slope": 0.0},
                                  {"mu_wire": 0.3, "stick_slope": -1.0}]
    for bad in bads:
        with pytest.raises(ValueError, match="mu_wall|mu_wire|stick_slope"):
            cm.squeeze_deck(P, MAT, n_circ=20, **bad)


def test_squeeze_deck_node_forces_split_into_normal_and_tangential() -> None:
    deck = cm.squeeze_deck([0.6], MAT, n_radial=2, n_circ=8, rigid_elements=6,
                           mu_wall=0.3, node_forces=True)
    assert "*NODE PRINT, NSET=NWIRE, TIME POINTS=OUT\nRF\n" in deck.text
    assert "*NODE PRINT, NSET=NHOLE, TIME POINTS=OUT\nRF\n" in deck.text
    assert "NSET=NWIRE, TIME POINTS" not in cm.squeeze_deck([0.6], MAT, n_circ=8).text
    wire, hole = deck.rigid["wire"], deck.rigid["hole"]
    assert wire["center"] == pytest.approx((0.0, 4.2)) and hole["center"] == (0.0, 0.0)

    def node_at(rigid: dict, radius: float, deg: float) -> int:
        c = np.asarray(rigid["center"])
        want = c + radius * np.array([np.cos(np.radians(deg)), np.sin(np.radians(deg))])
        return next(k for k, v in rigid["xy"].items() if np.allclose(v, want, atol=1e-9))

    def force(deg: float, normal: float, tangential: float) -> np.ndarray:
        er = np.array([np.cos(np.radians(deg)), np.sin(np.radians(deg))])
        return normal * er + tangential * np.array([-er[1], er[0]])

    # synthetic reactions (half model): the wire pushes the tube outward (2 N/mm normal,
    # 0.5 counter-clockwise), the hole inward (3 normal, 1 clockwise), bottom node 0.25 up
    fw = force(-60.0, 2.0, 0.5)
    fh = force(-75.0, -3.0, -1.0)
    kw, kh, kb = node_at(wire, 0.8, -60.0), node_at(hole, 5.0, -75.0), deck.probes["bottom"]

    def table(name: str, nset: str, rows: dict[int, np.ndarray]) -> str:
        body = "".join(f"{k:10d}  {v[0]: .6E}  {v[1]: .6E}  0.000000E+00\n"
                       for k, v in rows.items())
        return f"\n {name} (fx,fy,fz) for set {nset} and time  0.6000000E+00\n\n{body}"

    def total(nset: str, v: np.ndarray) -> str:
        return (f"\n total force (fx,fy,fz) for set {nset} and time  0.6000000E+00\n\n"
                f"        {v[0]: .6E}  {v[1]: .6E}  0.000000E+00\n")

    zero = {k: np.zeros(2) for k in deck.initial_xy}
    dat = (total("NWIRE", fw) + total("NHOLE", fh)
           + table("forces", "NBOTTOM", {kb: np.array([0.0, 0.25])})
           + table("displacements", "NOUTER", zero)
           + table("forces", "NWIRE", {k: (fw if k == kw else np.zeros(2)) for k in wire["xy"]})
           + table("forces", "NHOLE", {k: (fh if k == kh else np.zeros(2)) for k in hole["xy"]}))
    run = cm.CcxRun(0.0, 0.0, None, None, dat, "", 0)
    r = cm.read_squeeze(deck, run)
    assert r.squeeze_force_n_per_mm == pytest.approx([-2.0 * fw[1]], rel=1e-6)
    ci = r.contact_integrals
    assert ci is not None
    assert ci["wire"]["normal_n_per_mm"] == pytest.approx([4.0], rel=1e-6)
    assert ci["wire"]["tangential_n_per_mm"] == pytest.approx([1.0], rel=1e-6)
    assert ci["wall"]["normal_n_per_mm"] == pytest.approx([6.5], rel=1e-6)
    assert ci["wall"]["tangential_n_per_mm"] == pytest.approx([-2.0], rel=1e-6)
    # without the per-node tables there are no integrals
    plain = "".join(dat.split("\n forces (fx,fy,fz) for set NWIRE")[:1])
    assert cm.read_squeeze(deck, cm.CcxRun(0.0, 0.0, None, None, plain, "", 0)
                           ).contact_integrals is None


def test_increments_from_sta() -> None:
    sta = """SUMMARY OF JOB INFORMATION
  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME
     1          1     1     3  0.500000E-01  0.500000E-01  0.500000E-01
     1          2     1U   17  0.500000E-01  0.500000E-01  0.500000E-01
     1          2     2     8  0.625000E-01  0.625000E-01  0.125000E-01
     1          3     1     3  0.750000E-01  0.750000E-01  0.125000E-01
"""
    assert cm.increments(sta) == {"increments": 3, "cutbacks": 1, "iterations": 31,
                                  "min_increment": 0.0125, "max_increment": 0.05}
    assert cm.increments("")["increments"] == 0


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
