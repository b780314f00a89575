"""exofric's weightless squeeze force N(P) against a stored, independent FElupe reference.

The reference ``tests/data/squeeze_reference_felupe.json`` was made by
``benchmarks/make_squeeze_reference.py`` with the independent FElupe model
(``benchmarks/felupe_models.py``: FElupe's three-field element and rigid-cylinder penalty
contact, nothing of exofric's FE code) on fine meshes graded toward the wire, practically
without weight; the file records its mesh study, penalty and density studies and
provenance. Issue 18 asks the default accuracy ("standard") to be within 1% of the
mesh-converged N from the first output pressure where N >= 1% of N(0.6 MPa).

Units: mm, N, MPa; N per unit depth (N/mm), full section.
"""

from __future__ import annotations

import json
import sys
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from exofric.geometry import Structure
from exofric.material import MooneyRivlin
from exofric.simulate import SqueezeResult, squeeze

DATA = Path(__file__).resolve().parent / "data" / "squeeze_reference_felupe.json"
REF: dict[str, Any] = json.loads(DATA.read_text())
P = np.array(REF["pressure_mpa"])
MAT = MooneyRivlin.from_shore(REF["material"]["shore_a"])
NAMES = list(REF["structures"])

#: Issue 18's acceptance target for the default accuracy: 1% relative from the first
#: pressure where N_ref >= 1% of N_ref(0.6 MPa). The reference's own mesh error there is
#: <= 0.2% (its mesh study, checked below), so a 1% bound on the difference leaves exofric
#: at least 0.8% of its own error budget: the test can fail on a real regression.
REL_TOL = 0.01
#: Where the reference has no wire contact (N_ref = 0) exofric's N must be 0 up to the
#: Newton tolerance of its force balance (1e-9 x P x R <= 3e-9 N/mm): a force of 1e-6 N/mm
#: (5e-7 of N(0.6 MPa)) is a contact that should not exist or a regulariser leaking into N.
ZERO_ATOL_N_PER_MM = 1e-6


def _structure(name: str) -> Structure:
    """Structure (mm) of a stored reference case."""
    d = REF["structures"][name]
    return Structure(d["hole_mm"], d["tube_od_mm"], d["tube_id_mm"], d["wire_mm"],
                     d["length_mm"], name)


def _ref_n(name: str) -> np.ndarray:
    """Reference N (N/mm, full section) per pressure."""
    return np.array(REF["structures"][name]["squeeze_force_n_per_mm"])


def _significant(n: np.ndarray) -> np.ndarray:
    """Mask of pressures from the first where N >= 1% of N(0.6 MPa) on."""
    first = np.flatnonzero(n >= REF["significance_fraction"] * n[-1])[0]
    return np.arange(n.size) >= first


@cache
def _solve(dims: tuple[float, float, float, float, float], name: str) -> SqueezeResult:
    """exofric's weightless squeeze at the default accuracy (cached per structure, mm)."""
    return squeeze(Structure(*dims, name), MAT, P, gravity="none", keep_fields=False)


def _dims(d: dict[str, Any]) -> tuple[float, float, float, float, float]:
    """(hole, tube OD, tube ID, wire, length) in mm of a stored reference structure."""
    return (d["hole_mm"], d["tube_od_mm"], d["tube_id_mm"], d["wire_mm"], d["length_mm"])


def _exofric(name: str) -> SqueezeResult:
    """exofric's weightless squeeze of a Table 3 reference case (cached)."""
    return _solve(_dims(REF["structures"][name]), name)


def test_reference_is_mesh_converged_and_weightless() -> None:
    """The stored reference meets its own acceptance: mesh, penalty and weight errors."""
    for name in NAMES:
        d = REF["structures"][name]
        sig = _significant(_ref_n(name))
        change = np.array([np.nan if c is None else c
                           for c in d["mesh_study"]["change_to_finer_pct"]])
        # mesh study: reference vs 1.5x finer mesh, <= 0.2% where N is significant (the
        # brief's bound, five times below the 1% acceptance) and <= 0.05% from 0.3 MPa
        assert np.nanmax(change[sig]) <= 0.2, (name, change)
        assert np.nanmax(change[P >= 0.3]) <= 0.05, (name, change)
        # penalty penetration far below any geometric scale (clearances >= 0.1 mm)
        assert max(d["max_penetration_mm"]) < 1e-3
    # weightless limit: N is linear in the (vanishing) weight; 10x or 0.1x the density
    # moves N by < 1e-6 N/mm, i.e. < 3e-5 of the smallest significant reference N
    for change in REF["density_study"]["change_n_per_mm"].values():
        assert np.max(np.abs(change)) < 1e-6
    # penalty 10x stiffer moves N by < 0.02% where N is significant
    pen = np.array([np.nan if c is None else c for c in REF["penalty_study"]["change_pct"]])
    st = REF["penalty_study"]["structure"]
    assert np.nanmax(pen[_significant(_ref_n(st))]) < 0.02


@pytest.mark.parametrize("name", NAMES)
def test_reference_onset_matches_free_inflation(name: str) -> None:
    """FElupe's first wire contact brackets the 1D free-inflation onset (OD = D - d2)."""
    # Without weight and friction the tube floats until it spans wall to wire, i.e. until
    # its free OD (exofric.simulate.compressible_inflation, an independent 1D solution)
    # reaches D - d2: the reference must be 0 below and > 0 above that pressure.
    onset = REF["structures"][name]["onset_1d_mpa"]
    n = _ref_n(name)
    assert np.all(n[P < onset] == 0.0)
    assert np.all(n[P > onset] > 0.0)


@pytest.mark.parametrize("name", NAMES)
def test_squeeze_matches_felupe_reference(name: str) -> None:
    """Default accuracy: within 1% from the first significant pressure, 0 before contact."""
    n_ref = _ref_n(name)
    n = _exofric(name).squeeze_force_n_per_mm
    sig = _significant(n_ref)
    np.testing.assert_allclose(n[sig], n_ref[sig], rtol=REL_TOL)
    zero = n_ref == 0.0
    np.testing.assert_allclose(n[zero], 0.0, atol=ZERO_ATOL_N_PER_MM)


@pytest.mark.parametrize("name", NAMES)
def test_error_estimate_brackets_the_error(name: str) -> None:
    """The reported n_error_estimate_pct is >= the actual error against the reference."""
    n_ref = _ref_n(name)
    r = _exofric(name)
    assert r.estimate.pct is not None
    sig = _significant(n_ref)
    err_pct = 100.0 * np.abs(r.squeeze_force_n_per_mm[sig] / n_ref[sig] - 1.0)
    # the reference's own error (<= 0.2%, mesh study) could make a correct estimate look
    # too small only where the estimate is that tight; no margin is granted beyond it
    ref_err = np.array(REF["structures"][name]["mesh_study"]["change_to_finer_pct"],
                       dtype=float)[sig]
    assert np.all(r.estimate.pct[sig] + ref_err >= err_pct), (
        r.estimate.pct[sig], err_pct)


@pytest.mark.slow
def test_felupe_reproduces_the_stored_reference() -> None:
    """Re-run FElupe on a coarse mesh: it agrees with the stored reference (anti-rot)."""
    pytest.importorskip("felupe", reason="FElupe (GPL-3 test extra) is not installed")
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from felupe_models import SqueezeSetup, felupe_squeeze_model

    chk = REF["coarse_check"]
    name = chk["structure"]
    m = REF["model"]
    setup = SqueezeSetup.from_structure(
        _structure(name), MAT, density_t_per_mm3=m["density_t_per_mm3"],
        penalty=m["penalty_n_per_mm2"], max_increment_mpa=m["max_increment_mpa"],
        **chk["mesh"])
    n = felupe_squeeze_model(P, setup).squeeze_force_n_per_mm
    n = np.maximum(n, 0.0)
    n_ref = _ref_n(name)
    stored = np.array(chk["squeeze_force_n_per_mm"])
    # 1) the coarse run reproduces the stored coarse run: same code, same mesh, so only
    #    Newton tolerances (1.5e-8 of the reactions) and BLAS round-off separate them;
    #    1e-5 relative flags any change in FElupe or in the model
    np.testing.assert_allclose(n, stored, rtol=1e-5, atol=1e-9)
    # 2) and it lies within its mesh-study distance of the reference: the stored deviation
    #    plus the 1e-5 above (the reference itself cannot have moved)
    dev = np.array([0.0 if c is None else c for c in chk["deviation_from_reference_pct"]])
    pos = n_ref > 0
    rel = 100.0 * np.abs(n[pos] / n_ref[pos] - 1.0)
    assert np.all(rel <= dev[pos] + 1e-3), (rel, dev[pos])
    assert np.all(n[~pos] == 0.0)


# --- issue 35: contact onset, the estimate's reliability, the interpolated patch edge ----------

#: The independent FElupe reference of issue 35's thick-wall structures (ID/OD 0.54-0.55, larger
#: clearances, wires 1.1-2 mm): ``benchmarks/make_squeeze_reference.py --set onset``.
ONSET_DATA = DATA.with_name("squeeze_reference_felupe_onset.json")
#: exofric's own mesh-convergence study of the same structures (not independent: kept as a
#: second, finer-grained check and compared with the FElupe file)
CONVERGENCE_DATA = DATA.with_name("squeeze_reference_onset_convergence.json")
ONSET: dict[str, Any] = json.loads(ONSET_DATA.read_text())
ONSET_NAMES = list(ONSET["structures"])
#: The reference's own mesh error where the acceptance is tested: its change to the 1.5x finer
#: mesh (12 x 240 vs 8 x 160) from the first significant pressure (the finer mesh is run up to
#: 0.16 MPa past the 1D onset, where the Table 3 file's study shows the largest changes).
ONSET_MESH_TOL_PCT = 0.2


def _change_pct(d: dict[str, Any], key: str) -> np.ndarray:
    """A stored mesh study's change (%) per pressure, NaN where it was not computed."""
    return np.array([np.nan if c is None else c for c in d["mesh_study"][key]], dtype=float)


def test_onset_reference_is_mesh_converged() -> None:
    """The thick-wall FElupe reference: mesh study and penalty penetration (no solve)."""
    assert ONSET["model"]["code"].startswith("FElupe")
    for name, d in ONSET["structures"].items():
        n = np.array(d["squeeze_force_n_per_mm"])
        change = _change_pct(d, "change_to_finer_pct")[_significant(n)]
        assert np.isfinite(change[:2]).all(), name  # the first two significant outputs studied
        assert np.nanmax(change) <= ONSET_MESH_TOL_PCT, (name, change)
        assert max(d["max_penetration_mm"]) < 1e-3


@pytest.mark.parametrize("name", ONSET_NAMES)
def test_onset_reference_matches_free_inflation(name: str) -> None:
    """FElupe's first wire contact brackets the 1D free-inflation onset (OD = D - d2)."""
    d = ONSET["structures"][name]
    n = np.array(d["squeeze_force_n_per_mm"])
    assert np.all(n[P < d["onset_1d_mpa"]] == 0.0)
    assert np.all(n[P > d["onset_1d_mpa"]] > 0.0)


def _acceptance_cases() -> list[tuple[str, dict[str, Any], np.ndarray]]:
    """(name, stored structure, the reference's own error in %) of both FElupe files."""
    out = []
    for ref in (REF, ONSET):
        for name, d in ref["structures"].items():
            out.append((name, d, np.nan_to_num(_change_pct(d, "change_to_finer_pct"))))
    return out


def test_issue35_acceptance_against_independent_references() -> None:
    """Issue 35's acceptance over 11 structures and both FElupe references (6 Table 3: thin
    walls ID/OD 0.60; 5 thick: ID/OD 0.54-0.55; both with clearances D - d1 - d2 of 0.1-0.6 mm
    and wires of 1.1-2 mm): 'standard' within 1 % wherever N >= 1 % of N(0.6 MPa), and its
    error estimate >= the actual error at every such pressure, flagged unreliable or not.

    Tolerances: the 1 % is the issue's; the estimate is granted the reference's own mesh error
    (its change to the 1.5x finer FElupe mesh, <= 0.2 %; 0 where that mesh was not run), nothing
    more. The number of significant pressures whose estimate is flagged unreliable (the nested
    coarse mesh's wire patch has < 2 nodes) is pinned: it is the first significant pressure of
    the structures whose contact is born just before it.
    """
    cases = _acceptance_cases()
    ratios = {d["tube_id_mm"] / d["tube_od_mm"] for _, d, _ in cases}
    assert len(cases) >= 10 and min(ratios) < 0.56 and max(ratios) > 0.59
    assert {min(d["wire_mm"] for _, d, _ in cases), max(d["wire_mm"] for _, d, _ in cases)} \
        == {1.1, 2.0}
    worst, flagged, points = 0.0, 0, 0
    for name, d, ref_err in cases:
        r = _solve(_dims(d), name)
        n_ref = np.array(d["squeeze_force_n_per_mm"])
        sig = _significant(n_ref)
        err = 100.0 * np.abs(r.squeeze_force_n_per_mm[sig] / n_ref[sig] - 1.0)
        assert r.estimate.pct is not None and r.estimate.reliable is not None
        assert np.all(err <= 100.0 * REL_TOL), (name, err)
        assert np.all(r.estimate.pct[sig] + ref_err[sig] >= err), (name, err, r.estimate.pct)
        worst = max(worst, float(err.max()))
        flagged += int(np.sum(~r.estimate.reliable[sig]))
        points += int(sig.sum())
    # measured 2026-11-27: 5 of 101 flagged (the first significant pressure of test 1 and of the
    # thick walls d2 = 1.6, d2 = 1.1, D = 10.2 and test 2), their estimates 4.1-13.6 % against
    # errors <= 0.58 %; the estimate / error ratio is >= 2.0 everywhere; worst error 0.575 %
    # (thick, d2 = 1.1 at 0.35 MPa, 0.03 MPa after its onset)
    assert flagged <= 5 and points == 101, (flagged, points)
    assert worst < 100.0 * REL_TOL


def test_onset_references_agree() -> None:
    """The independent FElupe reference and exofric's own convergence study (8 x 192, a
    different element, contact and mesh) agree where N is significant (no solve).

    Measured: <= 0.131 % (at the first significant pressure, 0.03-0.05 MPa after the onset),
    <= 0.03 % from the second on. Tolerance 0.2 %: the convergence study's own change from its
    half mesh is up to 0.47 % there, FElupe's to its finer mesh <= 0.04 %; 0.2 % is what both
    codes being right within their studies allows without letting a real 1 % error through.
    """
    conv = json.loads(CONVERGENCE_DATA.read_text())["structures"]
    assert set(conv) == set(ONSET_NAMES)
    for name, d in ONSET["structures"].items():
        n = np.array(d["squeeze_force_n_per_mm"])
        c = np.array(conv[name]["squeeze_force_n_per_mm"])
        sig = _significant(n)
        np.testing.assert_allclose(c[sig], n[sig], rtol=0.002, err_msg=name)


def test_patch_edge_is_exact_for_a_hertz_patch() -> None:
    """The interpolated edge recovers the half-width a of p ~ sqrt(a^2 - x^2) (closed form).

    Penalty pressure = eps (-gap): a Hertz profile sampled at nodes 0.03 mm apart gives a
    back to round-off (the p^2-linear-in-x^2 fit is exact for it), whatever a's position
    between nodes; the last node in contact is off by up to one node spacing. Outside, a gap
    ~ (x - a)^(3/2) with only the centre node in contact also gives a back exactly.
    """
    from exofric.fe import patch_edge

    x = np.arange(0.0, 0.6, 0.03)
    for a in (0.101, 0.115, 0.128, 0.29):
        gap = np.where(x < a, -1e-5 * np.sqrt(np.maximum(a**2 - x**2, 0.0)), 1e-3)
        assert abs(patch_edge(x, gap) - a) < 1e-12
        last = x[gap <= 0].max()
        assert abs(last - a) > 1e-3  # what counting nodes reports
        one = np.where(x == 0.0, -1e-6, (np.maximum(x - 0.02, 0.0)) ** 1.5)
        assert abs(patch_edge(x, one) - 0.02) < 1e-12


def test_two_sided_levels_are_nested() -> None:
    """Each level's coarse mesh's element boundaries are a subset of its fine mesh's."""
    from exofric import defaults
    from exofric.fe import half_boundaries
    from exofric.simulate._common import resolve_accuracy

    for level in defaults.SQUEEZE_ACCURACY:
        _, fine, coarse = resolve_accuracy(level, None, defaults.SQUEEZE_ACCURACY)
        assert coarse is not None and fine.wall_elements > 0
        bf, bc = half_boundaries(fine), half_boundaries(coarse)
        assert bf is not None and bc is not None
        np.testing.assert_allclose(bc, bf[::2], atol=1e-13)  # every other boundary kept


def test_reference_estimate_flags() -> None:
    """The stored Table 3 references: wherever the estimate claims to be reliable it bounds
    the error; the JSON carries the flags."""
    for name in NAMES:
        r = _exofric(name)
        n_ref = _ref_n(name)
        sig = _significant(n_ref)
        assert r.estimate.reliable is not None
        rel = r.estimate.reliable[sig]
        err_pct = 100.0 * np.abs(r.squeeze_force_n_per_mm[sig] / n_ref[sig] - 1.0)
        assert r.estimate.pct is not None
        assert np.all(err_pct[rel] <= r.estimate.pct[sig][rel]), name
        assert r.to_dict()["n_error_estimate_reliable"] == [bool(v) for v in r.estimate.reliable]


def _onset_cases(path: Path) -> list[tuple[str, dict[str, Any]]]:
    """(name, stored structure) of an issue-35 reference file, [] if it is not there."""
    if not path.exists():
        return []
    return list(json.loads(path.read_text())["structures"].items())


def _check_thick(name: str, d: dict[str, Any], ref_err_pct: np.ndarray) -> None:
    """'standard' within 1% where N >= 1% of N(0.6); the estimate >= the error there."""
    n_ref = np.array(d["squeeze_force_n_per_mm"])
    r = _solve(_dims(d), name)
    sig = _significant(n_ref)
    np.testing.assert_allclose(r.squeeze_force_n_per_mm[sig], n_ref[sig], rtol=REL_TOL)
    err = 100.0 * np.abs(r.squeeze_force_n_per_mm[sig] / n_ref[sig] - 1.0)
    assert r.estimate.pct is not None and r.estimate.reliable is not None
    # the reference's own error (its mesh study) is granted, nothing more
    assert np.all(err <= r.estimate.pct[sig] + ref_err_pct[sig]), (name, err,
                                                                    r.estimate.pct[sig])


@pytest.mark.parametrize(("name", "d"), _onset_cases(CONVERGENCE_DATA),
                         ids=[n for n, _ in _onset_cases(CONVERGENCE_DATA)])
def test_thick_walls_against_the_convergence_reference(name: str, d: dict[str, Any]) -> None:
    """Issue 35: thick walls (ID/OD 0.54), larger clearances, wires 1.1-2 mm, against a mesh
    convergence study (8 x 192 two-sided graded, ~6x finer than 'standard' at the contacts;
    its error bounded by its change from the nested 4 x 96 mesh, order >= 1)."""
    change = np.array([np.nan if c is None else c
                       for c in d["mesh_study"]["change_to_half_pct"]])
    # the reference mesh's change from its nested half: <= 0.5% at the first significant
    # pressure, <= 0.13% from the third on (order ~1.2: its own error is smaller still)
    assert np.nanmax(change[_significant(np.array(d["squeeze_force_n_per_mm"]))]) <= 0.5
    _check_thick(name, d, np.nan_to_num(change))


def test_cli_table_marks_unreliable_estimates(cli: Any) -> None:
    """`exofric squeeze`'s table marks an estimate flagged unreliable with '*' and says why
    in a footnote; the JSON's flags are the same pressures (base group, draft: at 0.15 MPa the
    nested 1 x 12 mesh's wire patch is one node, at 0.16 MPa two)."""
    args = ["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97", "--wire", "1.6",
            "--shore", "62.5", "--pressures", "0.15,0.16", "--accuracy", "draft"]
    d = cli([*args, "--json"]).json()
    assert d["n_error_estimate_reliable"] == [False, True]
    r = cli(args)
    assert r.code == 0, r.err
    # table rows only: the title's wrapped "(solved in 0.16 s)" once matched the pressure
    rows = [ln for ln in r.out.splitlines()
            if ln.startswith("│") and ln.lstrip("│ ").startswith(("0.15 ", "0.16 "))]
    assert len(rows) == 2
    assert rows[0].rstrip(" │").endswith("*") and not rows[1].rstrip(" │").endswith("*")
    assert "* estimate unreliable at 1 pressure(s)" in r.out
