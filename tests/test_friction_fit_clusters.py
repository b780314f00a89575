"""gamma with replicate pulls: cluster-robust CIs (CR1, CR2, CR3), lack of fit, ODR, files.

Every number is checked against an independent code path: statsmodels OLS with
``cov_type="cluster"`` (CR1), a dense textbook CR2 / Bell-McCaffrey written here with n x n
matrices (SciPy's ``sqrtm`` for (I - H_gg)^(1/2), eigenvalues of G'WG for the dof) and the
closed form for the mean of balanced clusters (CR2), an explicit leave-one-cluster-out refit
loop with statsmodels (CR3), statsmodels ``anova_lm`` against a cluster-dummy model (lack of
fit), SciPy's (deprecated) ``scipy.odr`` and the weighted least-squares closed form (ODR).
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.linalg
import statsmodels.api as sm
import statsmodels.formula.api as smf
from scipy import stats
from statsmodels.stats.anova import anova_lm

from exofric import paper
from exofric.errors import InputError
from exofric.friction import CubicFit, SqueezeCurve, fit_gamma
from exofric.friction import _fit as fit_module
from exofric.io import read_friction_table

GAMMA = 0.7168
EQ8 = CubicFit(paper.eq8(), 0.2, 0.6)
CURVE_P = np.linspace(0.2, 0.6, 41)
CURVE_N = EQ8(CURVE_P)
SET_P = np.round(np.arange(0.2, 0.6001, 0.05), 3)        # 9 pressure plateaus


def _replicates(seed: int, pulls: int = 5, between_n: float = 3.0, within_n: float = 1.0,
                drag_n: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pulls at each set pressure with a random plateau effect (N) shared by its pulls."""
    rng = np.random.default_rng(seed)
    p = np.repeat(SET_P, pulls)
    code = np.repeat(np.arange(SET_P.size), pulls)
    f = (GAMMA * EQ8(p) + drag_n + rng.normal(0, between_n, SET_P.size)[code]
         + rng.normal(0, within_n, p.size))
    return p, f, code


def _half_width_se(ci: tuple[float, float], dof: int) -> float:
    return (ci[1] - ci[0]) / 2 / float(stats.t.ppf(0.975, dof))


@pytest.mark.parametrize("model", ["proportional", "affine"])
def test_cr1_matches_statsmodels_cluster(monkeypatch: pytest.MonkeyPatch, model: str) -> None:
    # statsmodels' cov_type="cluster" is CR1 (G/(G-1) x (n-1)/(n-k)); the CI is t(G-1) x bse.
    monkeypatch.setattr(fit_module, "_CLUSTER_VARIANT", "cr1")
    p, f, code = _replicates(1, drag_n=4.0 if model == "affine" else 0.0)
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, model=model, ci="cluster")
    n = EQ8(p)
    x = n[:, None] if model == "proportional" else np.column_stack([n, np.ones_like(n)])
    ref = sm.OLS(f, x).fit(cov_type="cluster", cov_kwds={"groups": code})
    g = SET_P.size
    assert fit.ci_method == "cluster" and fit.n_clusters == g
    assert fit.gamma == pytest.approx(ref.params[0], rel=1e-12)
    assert _half_width_se(fit.gamma_ci95, g - 1) == pytest.approx(ref.bse[0], rel=1e-10)
    if model == "affine":
        assert fit.f0_ci95_n is not None
        assert _half_width_se(fit.f0_ci95_n, g - 1) == pytest.approx(ref.bse[1], rel=1e-10)
    # the private covariance directly, full matrix
    cov = fit_module._cluster_covariance(x, f, ref.params, code, g, "cr1")
    np.testing.assert_allclose(cov, ref.cov_params(), rtol=1e-10)
    assert "CR1" in fit.ci_note and f"{g} pressure clusters" in fit.ci_note


@pytest.mark.parametrize("model", ["proportional", "affine"])
def test_cr3_matches_leave_one_cluster_out_refits(model: str, monkeypatch) -> None:
    # CR3 (MacKinnon-Nielsen-Webb 2023): (G-1)/G sum_g (b_(g) - b)(b_(g) - b)^T from G explicit
    # statsmodels refits without cluster g; fit_gamma uses per-cluster sums instead.
    monkeypatch.setattr(fit_module, "_CLUSTER_VARIANT", "cr3")
    p, f, code = _replicates(2, pulls=4, drag_n=4.0 if model == "affine" else 0.0)
    # unbalanced: drop three pulls of the first plateau
    p, f, code = p[3:], f[3:], code[3:]
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, model=model, ci="cluster")
    n = EQ8(p)
    x = n[:, None] if model == "proportional" else np.column_stack([n, np.ones_like(n)])
    b = sm.OLS(f, x).fit().params
    g = SET_P.size
    d = np.array([sm.OLS(f[code != c], x[code != c]).fit().params - b for c in range(g)])
    cov_ref = (g - 1) / g * d.T @ d
    assert _half_width_se(fit.gamma_ci95, g - 1) == pytest.approx(np.sqrt(cov_ref[0, 0]),
                                                                  rel=1e-10)
    if model == "affine":
        assert fit.f0_ci95_n is not None
        assert _half_width_se(fit.f0_ci95_n, g - 1) == pytest.approx(np.sqrt(cov_ref[1, 1]),
                                                                     rel=1e-10)
    np.testing.assert_allclose(fit_module._cluster_covariance(x, f, b, code, g, "cr3"), cov_ref,
                               rtol=1e-10)
    assert "CR3 jackknife" in fit.ci_note and f"t with {g - 1} dof" in fit.ci_note


@pytest.mark.parametrize("model", ["proportional", "affine"])
def test_lack_of_fit_matches_anova_lm(model: str) -> None:
    # Reference: statsmodels anova_lm(reduced, full), full = OLS on cluster dummies.
    p, f, code = _replicates(3, drag_n=4.0)       # a drag the proportional model misses
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, model=model)
    df = pd.DataFrame({"f": f, "n": EQ8(p), "group": code})
    reduced = smf.ols("f ~ n - 1" if model == "proportional" else "f ~ n", df).fit()
    full = smf.ols("f ~ C(group) - 1", df).fit()
    table = anova_lm(reduced, full)
    lof = fit.lack_of_fit
    assert lof is not None
    assert lof.f_stat == pytest.approx(table["F"].iloc[1], rel=1e-10)
    assert lof.p_value == pytest.approx(table["Pr(>F)"].iloc[1], rel=1e-10, abs=1e-300)
    assert lof.ss_pure_error == pytest.approx(full.ssr, rel=1e-10)
    assert lof.df_pure_error == p.size - SET_P.size
    assert lof.df_lack_of_fit == SET_P.size - (1 if model == "proportional" else 2)
    assert isinstance(lof.significant, bool) and "dof" in lof.verdict
    assert fit.to_dict()["lack_of_fit"]["df_pure_error"] == lof.df_pure_error


def test_lack_of_fit_flags_missing_drag_only() -> None:
    # Between-plateau effects off: the proportional model with a 6 N drag planted fails the
    # F test, the affine model does not (seed fixed; p values far from 0.05 either way).
    p, f, _ = _replicates(4, between_n=0.0, within_n=1.0, drag_n=6.0)
    prop = fit_gamma(p, f, CURVE_P, CURVE_N)
    aff = fit_gamma(p, f, CURVE_P, CURVE_N, model="affine")
    assert prop.lack_of_fit is not None and prop.lack_of_fit.significant
    assert prop.lack_of_fit.p_value < 1e-6
    assert aff.lack_of_fit is not None and not aff.lack_of_fit.significant
    assert "significant lack of fit" in prop.lack_of_fit.verdict


def test_replicate_csv_fits(tmp_path: Path) -> None:
    # A friction CSV with five pulls per pressure (repeated pressure_mpa within one test) is
    # read and fitted without error; the ANOVA uses the replicates: df_pure_error = n - G.
    p, f, _ = _replicates(5)
    path = tmp_path / "pulls.csv"
    path.write_text("pressure_mpa,friction_n\n"
                    + "\n".join(f"{a:.3f},{b:.6f}" for a, b in zip(p, f, strict=True)) + "\n")
    df = read_friction_table(path)
    assert len(df) == 45 and df.attrs["kind"] == "points"
    fit = fit_gamma(df["pressure_mpa"], df["friction_n"], CURVE_P, CURVE_N,
                    groups=df["group"].to_numpy())
    assert fit.ci_method == "cluster" and fit.n_clusters == 9 and fit.n_points == 45
    assert fit.lack_of_fit is not None and fit.lack_of_fit.df_pure_error == 45 - 9
    assert fit.gamma_ci95[0] < fit.gamma < fit.gamma_ci95[1]
    # same clusters by default (equal pressures) as by the file's group labels
    same = fit_gamma(df["pressure_mpa"], df["friction_n"], CURVE_P, CURVE_N)
    assert same.gamma_ci95 == fit.gamma_ci95
    assert fit.to_frame()["group"].nunique() == 9


def test_reduce_pull_table_with_plateaus(tmp_path: Path) -> None:
    # The per-pull table of `exofric reduce`: kinetic_n is the friction, plateau the cluster
    # (pressures jitter within a plateau, so clustering by exact pressure would not work).
    p, f, code = _replicates(6)
    rng = np.random.default_rng(0)
    pj = p + rng.normal(0, 0.0005, p.size)
    rows = [f"{c + 1},{i % 5 + 1},{'out' if i % 2 else 'in'},up,{a:.5f},{b + 2:.5f},{b:.5f}"
            for i, (c, a, b) in enumerate(zip(code, pj, f, strict=True))]
    path = tmp_path / "reduced.csv"
    path.write_text("plateau,pull,direction,branch,pressure_mpa,static_n,kinetic_n\n"
                    + "\n".join(rows) + "\n")
    df = read_friction_table(path)
    assert df.attrs["kind"] == "pulls" and list(df.columns) == [
        "pressure_mpa", "friction_n", "test", "group", "branch"]
    assert df["group"].iloc[0] == "plateau 1" and df["branch"].iloc[0] == "up"
    np.testing.assert_allclose(df["friction_n"], np.round(f, 5))
    fit = fit_gamma(df["pressure_mpa"], df["friction_n"], CURVE_P, CURVE_N,
                    groups=df["group"].to_numpy())
    assert fit.n_clusters == 9 and fit.ci_method == "cluster"
    assert fit.lack_of_fit is not None and fit.lack_of_fit.df_pure_error == 36
    by_pressure = fit_gamma(df["pressure_mpa"], df["friction_n"], CURVE_P, CURVE_N)
    assert by_pressure.n_clusters == 45 and by_pressure.ci_method == "analytic"


def test_auto_is_analytic_without_replicates_and_cluster_with() -> None:
    rng = np.random.default_rng(7)
    f = GAMMA * EQ8(SET_P) + rng.normal(0, 2, SET_P.size)
    auto = fit_gamma(SET_P, f, CURVE_P, CURVE_N)
    hc3 = fit_gamma(SET_P, f, CURVE_P, CURVE_N, ci="analytic")
    assert auto.ci_method == "analytic" and auto.gamma_ci95 == hc3.gamma_ci95
    assert auto.lack_of_fit is None and auto.n_clusters == SET_P.size
    assert "HC3" in auto.ci_note
    d = auto.to_dict()
    assert d["n_clusters"] == 9 and d["lack_of_fit"] is None and d["ci_method"] == "analytic"
    p, f2, _ = _replicates(8)
    assert fit_gamma(p, f2, CURVE_P, CURVE_N).ci_method == "cluster"
    # replicates at one pressure only: too few clusters for a cluster CI, auto says so
    one = fit_gamma([0.4] * 5, [50.0, 51, 52, 49, 50], CURVE_P, CURVE_N)
    assert one.ci_method == "analytic" and "only 1 pressure clusters" in one.ci_note


def test_cluster_ci_wider_than_naive_with_cluster_effect() -> None:
    # Coverage smoke: with a plateau effect (3 N) larger than the pull scatter (1 N), the
    # points are not independent and the naive intervals are too narrow; the cluster-robust
    # one is wider on every seed, and over 100 seeds it covers the planted gamma much more
    # often than the naive OLS interval does.
    hits = {"cluster": 0, "ols": 0}
    for seed in range(100):
        p, f, _ = _replicates(100 + seed)
        cl = fit_gamma(p, f, CURVE_P, CURVE_N, ci="cluster")
        ols = fit_gamma(p, f, CURVE_P, CURVE_N, ci="ols")
        if seed < 5:
            assert np.ptp(cl.gamma_ci95) > 1.5 * np.ptp(ols.gamma_ci95)
        hits["cluster"] += cl.gamma_ci95[0] <= GAMMA <= cl.gamma_ci95[1]
        hits["ols"] += ols.gamma_ci95[0] <= GAMMA <= ols.gamma_ci95[1]
    assert hits["cluster"] >= 85 and hits["ols"] <= 80, hits


def _scipy_odr(p: np.ndarray, f: np.ndarray, sx: np.ndarray | float, sy: np.ndarray | float,
               affine: bool, beta0: list[float]) -> tuple[np.ndarray, np.ndarray]:
    curve = SqueezeCurve(CURVE_P, CURVE_N)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from scipy import odr

        def fcn(b: np.ndarray, x: np.ndarray) -> np.ndarray:
            x = np.clip(x, 0.195, 0.605)
            return b[0] * curve(x, edge_tol_mpa=0.005) + (b[1] if affine else 0.0)

        def fjacb(b: np.ndarray, x: np.ndarray) -> np.ndarray:
            nx = curve(np.clip(x, 0.195, 0.605), edge_tol_mpa=0.005)
            return np.vstack([nx, np.ones_like(nx)]) if affine else nx[None, :]

        def fjacd(b: np.ndarray, x: np.ndarray) -> np.ndarray:
            return b[0] * curve.slope(np.clip(x, 0.195, 0.605), edge_tol_mpa=0.005)

        run = odr.ODR(odr.RealData(p, f, sx=sx, sy=sy),
                      odr.Model(fcn, fjacb=fjacb, fjacd=fjacd), beta0=beta0)
        run.set_job(fit_type=0, deriv=3)
        out = run.run()
    return np.asarray(out.beta), np.asarray(out.sd_beta)


@pytest.mark.parametrize("model", ["proportional", "affine"])
def test_odr_matches_scipy_odr(model: str) -> None:
    # Pressure read with 0.01 MPa noise: the errors-in-variables estimate and its sd agree
    # with scipy.odr (the original ODRPACK; odrpack wraps ODRPACK95) on the same problem.
    rng = np.random.default_rng(9)
    p_true = np.repeat(SET_P[1:-1], 3)
    p = p_true + rng.normal(0, 0.01, p_true.size)
    f = GAMMA * EQ8(p_true) + (4.0 if model == "affine" else 0.0) + rng.normal(0, 1.0, p.size)
    sf = np.full(p.size, 1.0)
    sf[::2] = 1.5
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, model=model, ci="odr",
                    pressure_sd_mpa=0.01, friction_sd_n=sf)
    ols = fit_gamma(p, f, CURVE_P, CURVE_N, model=model, ci="ols")
    affine = model == "affine"
    order = np.argsort(p, kind="stable")
    beta, sd = _scipy_odr(p[order], f[order], 0.01, sf[order], affine,
                          [ols.gamma, ols.model.f0_n] if affine else [ols.gamma])
    assert fit.ci_method == "odr" and fit.gamma != ols.gamma
    assert fit.gamma == pytest.approx(beta[0], rel=1e-6)
    k = 2 if affine else 1
    assert _half_width_se(fit.gamma_ci95, p.size - k) == pytest.approx(sd[0], rel=1e-6)
    if affine:
        assert fit.model.f0_n == pytest.approx(beta[1], rel=1e-6)
        assert fit.f0_ci95_n is not None
        assert _half_width_se(fit.f0_ci95_n, p.size - k) == pytest.approx(sd[1], rel=1e-6)
    assert "ODR" in fit.ci_note and "residual variance" in fit.ci_note


def test_odr_tiny_pressure_sd_is_weighted_least_squares() -> None:
    # sd_P -> 0: no room to move the pressures, so gamma -> sum(w N F) / sum(w N^2),
    # w = 1 / sd_F^2.
    rng = np.random.default_rng(11)
    p = np.repeat(SET_P, 2)
    sf = np.where(p > 0.4, 3.0, 0.5)
    f = GAMMA * EQ8(p) + rng.normal(0, 1, p.size) * sf
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, ci="odr", pressure_sd_mpa=1e-9, friction_sd_n=sf)
    n, w = EQ8(p), 1 / sf**2
    assert fit.gamma == pytest.approx(np.sum(w * n * f) / np.sum(w * n * n), rel=1e-6)


def test_cluster_and_odr_input_errors() -> None:
    p, f, _ = _replicates(12)
    with pytest.raises(InputError, match="at least 2 clusters.*got 1"):
        fit_gamma([0.4] * 5, [50.0, 51, 52, 49, 50], CURVE_P, CURVE_N, ci="cluster")
    with pytest.raises(InputError, match="at least 3 clusters.*got 2"):
        fit_gamma([0.3] * 3 + [0.5] * 3, [30.0, 31, 32, 60, 61, 62], CURVE_P, CURVE_N,
                  model="affine", ci="cluster")
    with pytest.raises(InputError, match="groups has 3 labels"):
        fit_gamma(p, f, CURVE_P, CURVE_N, groups=["a", "b", "c"])
    with pytest.raises(InputError, match="pressure_sd_mpa is required"):
        fit_gamma(p, f, CURVE_P, CURVE_N, ci="odr", friction_sd_n=1.0)
    with pytest.raises(InputError, match="friction_sd_n is required"):
        fit_gamma(p, f, CURVE_P, CURVE_N, ci="odr", pressure_sd_mpa=0.01)
    with pytest.raises(InputError, match="friction_sd_n must be finite and > 0 N"):
        fit_gamma(p, f, CURVE_P, CURVE_N, ci="odr", pressure_sd_mpa=0.01, friction_sd_n=0.0)
    with pytest.raises(InputError, match="one value per friction point"):
        fit_gamma(p, f, CURVE_P, CURVE_N, ci="odr", pressure_sd_mpa=[0.01, 0.02],
                  friction_sd_n=1.0)
    with pytest.raises(InputError, match="only used with ci='odr'"):
        fit_gamma(p, f, CURVE_P, CURVE_N, ci="cluster", pressure_sd_mpa=0.01)
    with pytest.raises(InputError, match="ci must be one of"):
        fit_gamma(p, f, CURVE_P, CURVE_N, ci="jackknife")


def test_groups_any_hashable_labels() -> None:
    # Tuples (test, plateau) as labels: factorised by hashing, same clusters as integers.
    p, f, code = _replicates(13)
    a = fit_gamma(p, f, CURVE_P, CURVE_N, groups=[("t1", int(c)) for c in code])
    b = fit_gamma(p, f, CURVE_P, CURVE_N, groups=code)
    assert a.n_clusters == b.n_clusters == 9 and a.gamma_ci95 == pytest.approx(b.gamma_ci95,
                                                                               rel=1e-14)
    assert a.to_frame()["group"].iloc[0] == ("t1", 0)


# ----------------------------------------------------------------- CR2 in linear memory (issue 31)


def _dense_cr2_bm(x: np.ndarray, f: np.ndarray, codes: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Textbook CR2 and Bell-McCaffrey dof with n x n matrices (small n only): beta, cov, dof.

    A_g = (I - H_gg)^(-1/2) by scipy.linalg.sqrtm and an inverse; the dof from the
    eigenvalues of G'WG, G_g = (I - H)_(:,g) A_g X_g (X'X)^-1 l, W = diag(|X beta|).
    """
    m, k = x.shape
    beta = np.linalg.lstsq(x, f, rcond=None)[0]
    e = f - x @ beta
    xtx_inv = np.linalg.inv(x.T @ x)
    h = x @ xtx_inv @ x.T
    w = np.abs(x @ beta)
    blocks = []
    meat = np.zeros((k, k))
    for c in np.unique(codes):
        idx = np.flatnonzero(codes == c)
        a_g = np.linalg.inv(scipy.linalg.sqrtm(np.eye(idx.size) - h[np.ix_(idx, idx)]).real)
        s = x[idx].T @ a_g @ e[idx]
        meat += np.outer(s, s)
        blocks.append((idx, a_g))
    cov = xtx_inv @ meat @ xtx_inv
    dof = []
    for j in range(k):
        gm = np.column_stack([(np.eye(m) - h)[:, idx] @ (a_g @ x[idx] @ xtx_inv[:, j])
                              for idx, a_g in blocks])
        lam = np.linalg.eigvalsh(gm.T @ (w[:, None] * gm))
        dof.append(lam.sum() ** 2 / (lam @ lam))
    return beta, cov, np.array(dof)


def _random_design(rng: np.random.Generator, k: int) -> tuple[np.ndarray, np.ndarray,
                                                             np.ndarray, int]:
    """Squeeze-force-like design (N 5-300 N) with k columns, G clusters of 1-7 points."""
    g = int(rng.integers(k + 2, 12))
    codes = np.repeat(np.arange(g), rng.integers(1, 8, g))
    rng.shuffle(codes)
    m = codes.size
    n = rng.uniform(5.0, 300.0, m)
    cols = [n] + ([rng.uniform(0.0, 50.0, m)] if k == 3 else []) + ([np.ones(m)] if k >= 2
                                                                      else [])
    x = np.column_stack(cols)
    f = x @ rng.uniform(0.2, 1.0, k) + rng.normal(0.0, 3.0, m)
    return x, f, codes, g


@pytest.mark.parametrize("k", [1, 2, 3], ids=["no intercept", "intercept", "interfaces+F0"])
def test_cr2_bm_matches_dense_textbook(k: int) -> None:
    # 40 random designs with unequal clusters (1-7 points, so some leverages near 1): the
    # per-cluster k x k algebra agrees with the dense n x n textbook form to rounding. The
    # tolerance 1e-10 is ~1e5 eps; measured <= 4e-14 (cov) and 4e-15 (dof) over 400 designs.
    rng = np.random.default_rng(31 + k)
    for _ in range(40):
        x, f, codes, g = _random_design(rng, k)
        beta, cov_ref, dof_ref = _dense_cr2_bm(x, f, codes)
        cov, dof = fit_module._cr2_bm(x, f, beta, codes, g)
        scale = np.sqrt(np.outer(np.diag(cov_ref), np.diag(cov_ref)))
        np.testing.assert_array_less(np.abs(cov - cov_ref) / scale, 1e-10)
        np.testing.assert_allclose(dof, dof_ref, rtol=1e-10)


def test_cr2_bm_balanced_mean_closed_form() -> None:
    # Intercept-only model with G balanced clusters of n_g points: H_gg = J / n has the single
    # eigenvalue 1/G, so X_g'A_g e_g = s_g / sqrt(1 - 1/G) with s_g the cluster's residual sum:
    # var = G / (G - 1) sum s_g^2 / n^2, and the Bell-McCaffrey dof are exactly G - 1.
    rng = np.random.default_rng(5)
    g, n_g = 7, 6
    codes = np.repeat(np.arange(g), n_g)
    f = 50.0 + rng.normal(0, 3, g)[codes] + rng.normal(0, 1, codes.size)
    x = np.ones((codes.size, 1))
    cov, dof = fit_module._cr2_bm(x, f, np.array([f.mean()]), codes, g)
    s = np.bincount(codes, weights=f - f.mean())
    assert cov[0, 0] == pytest.approx(g / (g - 1) * np.sum(s**2) / codes.size**2, rel=1e-12)
    assert dof[0] == pytest.approx(g - 1, rel=1e-12)


@pytest.mark.parametrize("model", ["proportional", "affine"])
def test_cr2_interval_matches_dense_textbook(model: str) -> None:
    # fit_gamma's default cluster interval (CR2 + Bell-McCaffrey) on unbalanced replicates:
    # half-width = t(dof) x se with dof and se from the dense textbook form (rel 1e-10).
    assert fit_module._CLUSTER_VARIANT == "cr2bm"
    p, f, code = _replicates(21, pulls=4, drag_n=4.0 if model == "affine" else 0.0)
    keep = np.ones(p.size, bool)
    keep[[0, 1, 2, 9, 30]] = False                     # clusters of 1, 3 and 4 pulls
    p, f, code = p[keep], f[keep], code[keep]
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, model=model, groups=code)
    n = EQ8(p)
    x = n[:, None] if model == "proportional" else np.column_stack([n, np.ones_like(n)])
    _, cov, dof = _dense_cr2_bm(x, f, code)
    assert fit.ci_method == "cluster" and "Bell-McCaffrey" in fit.ci_note
    half = (fit.gamma_ci95[1] - fit.gamma_ci95[0]) / 2
    assert half == pytest.approx(stats.t.ppf(0.975, dof[0]) * np.sqrt(cov[0, 0]), rel=1e-10)
    if model == "affine":
        assert fit.f0_ci95_n is not None
        half0 = (fit.f0_ci95_n[1] - fit.f0_ci95_n[0]) / 2
        assert half0 == pytest.approx(stats.t.ppf(0.975, dof[1]) * np.sqrt(cov[1, 1]),
                                      rel=1e-10)


@pytest.mark.parametrize("k", [1, 2], ids=["no intercept", "intercept"])
def test_cr1_matches_statsmodels_unbalanced_random(k: int) -> None:
    # statsmodels cov_type="cluster" (CR1) on 20 random designs with unequal clusters.
    rng = np.random.default_rng(77 + k)
    for _ in range(20):
        x, f, codes, g = _random_design(rng, k)
        ref = sm.OLS(f, x).fit(cov_type="cluster", cov_kwds={"groups": codes})
        cov = fit_module._cluster_covariance(x, f, ref.params, codes, g, "cr1")
        np.testing.assert_allclose(cov, ref.cov_params(), rtol=1e-10)


@pytest.mark.parametrize("model", ["proportional", "affine"])
def test_bootstrap_in_blocks_matches_one_draw(monkeypatch: pytest.MonkeyPatch,
                                              model: str) -> None:
    # The resamples are drawn in blocks of rows (bounded memory); the reference draws all
    # n_boot x m indices at once, as before issue 31, and solves each resample by numpy's
    # lstsq: the same seeded stream, so the same percentile interval (rel 1e-12).
    monkeypatch.setattr(fit_module, "_BOOT_BLOCK", 100)       # blocks of 2 resamples
    p, f, _ = _replicates(22, drag_n=4.0 if model == "affine" else 0.0)
    fit = fit_gamma(p, f, CURVE_P, CURVE_N, model=model, ci="bootstrap", n_boot=301, seed=4)
    n, fs = np.asarray(fit.squeeze_force_n), np.asarray(fit.friction_n)   # the points used
    idx = np.random.default_rng(4).integers(0, p.size, size=(301, p.size))
    cols = (lambda i: n[i][:, None]) if model == "proportional" else (
        lambda i: np.column_stack([n[i], np.ones(i.size)]))
    est = np.array([np.linalg.lstsq(cols(i), fs[i], rcond=None)[0][0] for i in idx])
    lo, hi = np.percentile(est, [2.5, 97.5])
    assert fit.gamma_ci95 == pytest.approx((lo, hi), rel=1e-12)
