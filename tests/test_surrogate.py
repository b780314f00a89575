"""Dimensionless groups, applicability distance and the design surrogate (issue 19, part).

References: the scale-free plane-strain problem (every length x 1.5 with the penalty / 1.5,
or G, P and the penalty x 1.7: the squeeze number N/(P L d2) is unchanged, to 1e-6);
central FE differences for the group scales (within 15 % of :data:`GROUP_SCALES`); the
paper's accepted (2-5) and failed (6-7) tests on either side of the threshold; a made-up law
linear in the surrogate's variables (onset per clearance; contact stiffness over q_on, t/d1,
d2/d1, sqrt(s)), reproduced to 1e-8; a brute-force
refit without each design for the rank-update leave-one-out (to 1e-8); SciPy's
``RBFInterpolator`` for the interpolant itself (the same function space, to 1e-10); the full FE
search
of ``examples/sweep-small.toml`` for the surrogate search (same best design).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.stats import qmc

from exofric.design import (
    APPLICABILITY_THRESHOLD,
    GROUP_SCALES,
    applicability,
    candidate_designs,
    fit_surrogate,
    load_sweep,
    parse_sweep,
    run_sweep,
    search_designs,
    squeeze_number,
    surrogate_search,
    sweep_groups,
)
from exofric.errors import InputError
from exofric.friction import paper_structures
from exofric.geometry import BASE, Structure
from exofric.material import MooneyRivlin
from exofric.simulate import squeeze

ROOT = Path(__file__).resolve().parents[1]
MAT = MooneyRivlin.from_shore(62.5)
P = [0.1, 0.3, 0.45, 0.6]
PEN = 1e5


def _n(s: Structure, mat: MooneyRivlin = MAT, p: list[float] = P, pen: float = PEN
       ) -> np.ndarray:
    return np.asarray(squeeze(s, mat, p, keep_fields=False, gravity="none", penalty=pen,
                              accuracy="draft").squeeze_force_n)


def test_similar_designs_collapse_on_one_squeeze_number_curve() -> None:
    """Same groups (size x 1.5 and L x 2; or G, P and penalty x 1.7): same N/(P L d2)."""
    r0 = squeeze_number(_n(BASE), P, BASE.length_mm, BASE.wire_mm)
    big = Structure(15.0, 12.45, 7.455, 2.4, 232.0)                  # every length x 1.5, L x 2
    r1 = squeeze_number(_n(big, pen=PEN / 1.5), P, big.length_mm, big.wire_mm)
    np.testing.assert_allclose(r1, r0, rtol=1e-6, atol=1e-12)
    k = 1.7                                                          # stiffer: same P/G
    stiff = MooneyRivlin(MAT.c10_mpa * k, MAT.c01_mpa * k, MAT.d_per_mpa / k)
    pk = [k * x for x in P]
    r2 = squeeze_number(_n(BASE, stiff, pk, PEN * k), pk, BASE.length_mm, BASE.wire_mm)
    np.testing.assert_allclose(r2, r0, rtol=1e-6, atol=1e-12)
    assert applicability(big, MAT.shear_modulus).distance < 1e-12


def test_group_scales_are_the_fe_sensitivities() -> None:
    """Each scale: the group change moving N(P) of the base by 10 % of N(0.6) on average."""
    p = [round(0.05 * i, 2) for i in range(1, 13)]
    n06 = _n(BASE, p=p)[-1]
    d, d1, id_, d2, L = (BASE.hole_mm, BASE.tube_od_mm, BASE.tube_id_mm, BASE.wire_mm,
                         BASE.length_mm)
    m = MAT

    def scale(make, h: float) -> float:
        return 0.1 / (np.mean(np.abs(make(h) - make(-h))) / (2 * h) / n06)

    got = {
        "clearance_ratio": scale(lambda h: _n(Structure(d + h * d1, d1, id_, d2, L), p=p), 0.004),
        "wall_ratio": scale(lambda h: _n(Structure(d, d1, id_ - 2 * h * d1, d2, L), p=p), 0.01),
        "wire_ratio": scale(lambda h: _n(Structure(d + h * d1, d1, id_, d2 + h * d1, L), p=p),
                            0.02),
        "log_shear_modulus": scale(lambda h: _n(BASE, MooneyRivlin(
            m.c10_mpa * np.exp(h), m.c01_mpa * np.exp(h), m.d_per_mpa / np.exp(h)), p=p), 0.05),
    }
    for k, v in got.items():
        assert v == pytest.approx(GROUP_SCALES[k], rel=0.15), (k, v)


def test_threshold_separates_the_papers_accepted_and_failed_tests() -> None:
    dist = [applicability(s, MAT.shear_modulus) for s in paper_structures()]
    assert dist[0].distance == 0.0
    assert max(a.distance for a in dist[1:5]) < APPLICABILITY_THRESHOLD
    assert min(a.distance for a in dist[5:]) > APPLICABILITY_THRESHOLD
    assert not dist[6].inside and dist[6].to_dict()["deviation_pct"] == pytest.approx(45.5,
                                                                                     abs=0.1)
    with pytest.raises(InputError, match="calibration"):
        applicability(BASE, 1.3, calibration=[])


def _training_spec(n: int, seed: int) -> dict:
    """Designs quasi-random in the groups of examples/sweep-small.toml (base wall ratio)."""
    u = qmc.Sobol(3, seed=seed).random(n)
    designs = []
    for i, (a, c, w) in enumerate(u):
        d1, cr, wr = 8.0 + 1.0 * a, 0.145 * c, 0.12 + 0.13 * w
        designs.append({"name": f"t{i}", "tube_od_mm": round(d1, 4),
                        "tube_id_mm": round(d1 * 4.97 / 8.3, 4),
                        "hole_mm": round(d1 * (1 + cr + wr), 4), "wire_mm": round(d1 * wr, 4)})
    return {"name": "train", "pressures_mpa": [round(0.05 * i, 2) for i in range(1, 13)],
            "design": designs}


@pytest.mark.parametrize(("n", "k"), [(60, 4), (12, 3)])
def test_interpolant_equals_scipys_rbf_interpolator(n: int, k: int) -> None:
    """The hand-written interpolant (kept for its exact block leave-one-out) is the function
    SciPy's ``RBFInterpolator`` builds with the same kernel and polynomial degree: quintic
    -r^5 with a quadratic for 60 points in 4-D, cubic r^3 with a linear one for 12 in 3-D.
    Tolerance 1e-10 on values of order 1: both solve the same well-posed linear system, only
    the rounding differs (observed 7e-14)."""
    from scipy.interpolate import RBFInterpolator

    from exofric.design._surrogate import _RBF

    rng = np.random.default_rng(0)
    z = rng.random((n, k))
    y = np.sin(3.0 * z).sum(axis=1)
    ours = _RBF(z, y)
    kernel = {5: "quintic", 3: "cubic"}[ours.power]
    ref = RBFInterpolator(z, y, kernel=kernel, degree=ours.degree)
    q = rng.random((300, k))
    np.testing.assert_allclose(ours(q), ref(q), rtol=0.0, atol=1e-10)
    assert (ours.power, ours.degree) == ((5, 2) if n == 60 else (3, 1))


@pytest.fixture(scope="module")
def training(tmp_path_factory: pytest.TempPathFactory) -> pd.DataFrame:
    out = tmp_path_factory.mktemp("train")
    return run_sweep(parse_sweep(_training_spec(32, 3)), out, serial=True).frame


def _same_scales(a: dict, b: dict) -> bool:
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def test_leave_one_out_equals_a_refit_without_the_design(training: pd.DataFrame) -> None:
    s = fit_surrogate(training)
    keys = list(dict.fromkeys(training["key"]))
    checked = 0
    for key in keys:
        if checked == 3:
            break
        rest = fit_surrogate(training[training["key"] != key], loo=False)
        g = training[training["key"] == key].assign(
            shear_modulus_mpa=lambda f: 2 * (f["c10_mpa"] + f["c01_mpa"]))
        # the LOO keeps the full fit's input scalings, a refit rescales when the design set a
        # range (the groups', the onset's, the largest P/G - q_on); the others:
        if not _same_scales(rest._scales, s._scales):
            continue
        n_refit = rest.predict(g.iloc[:1], g["pressure_mpa"])[0]
        err = np.max(np.abs(n_refit - g["squeeze_force_n"].to_numpy()))
        row = s.loo.set_index("key").loc[key]
        assert row["loo_max_error_n"] == pytest.approx(err, rel=1e-6, abs=1e-8)
        checked += 1
    assert checked == 3


def _law_frame(n: int, seed: int) -> pd.DataFrame:
    """Sweep rows of a made-up law in the surrogate's function space: onset per clearance
    h = q_on / (c/d1) = 2 + 4 t/d1 and contact stiffness k = N / (G L d2 s) =
    1 + q_on + 0.5 d2/d1 + 0.3 sqrt(s), s = P/G - q_on (both linear in the stages' inputs)."""
    u = qmc.Sobol(4, seed=seed).random(n)
    c, t, w = 0.01 + 0.14 * u[:, 0], 0.15 + 0.1 * u[:, 1], 0.12 + 0.14 * u[:, 2]
    d1, length = 8.0, 100.0
    gm = 1.2 + 0.6 * u[:, 3]                            # G = 2 (C10 + C01), MPa
    q_on = c * (2.0 + 4.0 * t)
    p = np.array([round(0.05 * i, 2) for i in range(1, 13)])
    s = p[None, :] / gm[:, None] - q_on[:, None]
    k = 1.0 + q_on[:, None] + 0.5 * w[:, None] + 0.3 * np.sqrt(np.maximum(s, 0.0))
    force = np.where(s > 0, k * s * gm[:, None] * length * w[:, None] * d1, 0.0)
    rep = np.repeat(np.arange(n), len(p))
    return pd.DataFrame({
        "key": [f"d{i}" for i in rep], "name": [f"d{i}" for i in rep], "status": "ok",
        "hole_mm": (d1 * (1 + c + w))[rep], "tube_od_mm": d1, "tube_id_mm": (d1 * (1 - 2 * t))[rep],
        "wire_mm": (d1 * w)[rep], "length_mm": length, "c10_mpa": (gm / 2 / 1.05)[rep],
        "c01_mpa": (gm / 2 * 0.05 / 1.05)[rep], "pressure_mpa": np.tile(p, n),
        "contact_onset_pressure_mpa": (q_on * gm)[rep], "squeeze_force_n": force.ravel()})


def test_surrogate_reproduces_a_law_in_its_variables() -> None:
    """Closed form: a law linear in the onset per clearance and in the stiffness k over
    (q_on, t/d1, d2/d1, sqrt(s)) is reproduced to rounding (1e-8 of N(0.6)) at designs it was
    not trained on, onset included, with N = 0 up to the onset and zero LOO error; a
    design with no clearance touches at ~0 (the onset per clearance times its floor)."""
    from exofric.design._surrogate import CLEARANCE_FLOOR

    sur = fit_surrogate(_law_frame(32, 5))
    assert sur.loo_error_pct["max"] < 1e-6
    new = _law_frame(16, 6)
    one = new.drop_duplicates("key").assign(
        shear_modulus_mpa=lambda f: 2 * (f["c10_mpa"] + f["c01_mpa"]))
    p = np.linspace(0.02, 0.6, 30)
    inside = sur.in_domain(sweep_groups(one))
    assert inside.sum() >= 8
    one = one[inside].reset_index(drop=True)
    n, onset = sur._predict(one, p)
    np.testing.assert_allclose(onset, one["contact_onset_pressure_mpa"], rtol=1e-9, atol=1e-12)
    g = sweep_groups(one)
    q_on = (one["contact_onset_pressure_mpa"] / one["shear_modulus_mpa"]).to_numpy()[:, None]
    s = p[None, :] / one["shear_modulus_mpa"].to_numpy()[:, None] - q_on
    k = 1.0 + q_on + 0.5 * g["wire_ratio"].to_numpy()[:, None] + 0.3 * np.sqrt(np.maximum(s, 0))
    want = np.where(s > 0, k * s * (one["shear_modulus_mpa"] * one["length_mm"]
                                    * one["wire_mm"]).to_numpy()[:, None], 0.0)
    np.testing.assert_allclose(n, want, rtol=0.0, atol=1e-8 * want.max())
    assert np.all(n[s <= 0] == 0.0) and (s <= 0).any()
    touching = one.iloc[:1].assign(hole_mm=lambda f: f["tube_od_mm"] + f["wire_mm"])
    n0, on0 = sur._predict(touching, p)
    assert 0.0 < on0[0] < 10 * CLEARANCE_FLOOR * touching["shear_modulus_mpa"].iloc[0]
    assert np.all(n0 > 0)


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> tuple:
    spec = load_sweep(ROOT / "examples" / "sweep-small.toml")
    return spec, run_sweep(spec, tmp_path_factory.mktemp("small"), serial=True).frame


@pytest.mark.parametrize("target_nm", [10.0, 15.0, 17.0, 20.0])
def test_surrogate_search_finds_the_full_fe_best_on_sweep_small(
        training: pd.DataFrame, small: tuple, target_nm: float) -> None:
    """Candidates: the sweep's 8 possible designs, ranked on a surrogate trained on 32 other
    designs; the 2 best confirmed by FE. 20 Nm is reached by none: the closest must agree."""
    spec, frame = small
    full = search_designs(frame, target_nm, 0.1, 0.6)
    sur = fit_surrogate(training)
    assert sur.loo_error_pct["max"] < 5.0
    res = surrogate_search(sur, spec, target_nm, 0.1, 0.6, candidates=list(spec.runnable),
                           confirm=2)
    assert res.out_of_domain == 0 and res.candidates == len(spec.runnable)
    want = full.best or full.closest.iloc[0].to_dict()
    got = res.best or res.confirmed.closest.iloc[0].to_dict()
    for k in ("hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm"):
        assert got[k] == want[k]
    assert got["torque_at_pmax_nm"] == pytest.approx(want["torque_at_pmax_nm"], rel=1e-9)
    rel = np.abs(res.comparison["predicted_n_pmax_n"] / res.comparison["fe_n_pmax_n"] - 1)
    assert rel.max() < 0.05, res.comparison
    assert len(res.to_dict()["confirmed"]) == 2


def test_candidates_and_bad_input(training: pd.DataFrame) -> None:
    spec = load_sweep(ROOT / "examples" / "sweep-small.toml")
    c = candidate_designs(spec, 256)
    assert len(c) > len(spec.runnable)
    assert all(d.tube_od_mm + d.wire_mm <= d.hole_mm for d in c)
    with pytest.raises(InputError, match="at least 4 solved designs"):
        fit_surrogate(training[training["key"].isin(training["key"].unique()[:2])])
    with pytest.raises(InputError, match="confirm"):
        surrogate_search(fit_surrogate(training, loo=False), spec, 20.0, 0.1, 0.6, confirm=0)
    with pytest.raises(InputError, match="candidates"):
        candidate_designs(spec, -1)


def test_failed_fe_confirmation_is_a_solver_failure(training: pd.DataFrame,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """A confirmation solve that does not converge is reported as a ConvergenceError (the
    CLI's exit 3) naming the candidate, not recorded as a sweep row nor called bad input."""
    import exofric.simulate
    from exofric.errors import ConvergenceError

    def no_convergence(*args, **kwargs):  # type: ignore[no-untyped-def]
        raise ConvergenceError("squeeze did not converge at 0.45 MPa", reached=0.4)

    spec = load_sweep(ROOT / "examples" / "sweep-small.toml")
    monkeypatch.setattr(exofric.simulate, "squeeze", no_convergence)
    with pytest.raises(ConvergenceError, match="FE confirmation of .*0.45 MPa") as info:
        surrogate_search(fit_surrogate(training, loo=False), spec, 15.0, 0.1, 0.6,
                         candidates=list(spec.runnable), confirm=1)
    assert info.value.reached == 0.4


def test_cli_design_surrogate_json(cli, tmp_path: Path) -> None:
    """`exofric design ... --surrogate --json`: LOO error, confirmed designs, FE-confirmed best
    at least as good as the swept grid's (the grid's designs are candidates too)."""
    r = cli(["design", str(ROOT / "examples" / "sweep-small.toml"), "--target-torque", "15",
             "--out", str(tmp_path / "s"), "--no-plot", "--json", "--surrogate"])
    assert r.code == 0, r.err
    d = r.json()
    s = d["surrogate"]
    assert set(s["loo_error_pct"]) == {"max", "p95", "median"} and s["trained_designs"] == 8
    assert len(s["confirmed"]) == 5 and s["candidates"] >= 8
    assert s["best"]["required_pressure_mpa"] <= d["best"]["required_pressure_mpa"] + 1e-9
    for c in s["confirmed"]:
        assert {"predicted_n_pmax_n", "fe_n_pmax_n", "applicability_distance"} <= set(c)
