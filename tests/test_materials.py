"""Material model (paper Eqs 3-6, Table 2) against the paper's printed numbers."""

from __future__ import annotations

import math
import warnings

import pytest

from exofric import paper
from exofric.errors import InputError
from exofric.material import CORRELATIONS, MaterialRangeWarning, MooneyRivlin, shore_to_modulus


def test_eq3_at_table1_hardness_values():
    # Eq 3 evaluated by hand: (2.15 S + 15.75)/(100 - S); printed to 3-4 digits in the issue/paper.
    for s, e0 in [(60, 3.61875), (62.5, 150.125 / 37.5), (65, 155.5 / 35), (70, 166.25 / 30)]:
        assert shore_to_modulus(s) == pytest.approx(e0, rel=1e-12)


def test_eq4_to_eq6_exact_construction():
    m = MooneyRivlin.from_shore(62.5)
    # Exact arithmetic: G = E0/3, C10 = G/2/1.05, C01 = 0.05 C10, d = 0.004/(C10 + C01).
    e0 = 150.125 / 37.5
    assert m.shear_modulus == pytest.approx(e0 / 3, rel=1e-14)
    assert m.c10_mpa == pytest.approx(e0 / 6 / 1.05, rel=1e-14)
    assert m.c01_mpa == pytest.approx(0.05 * m.c10_mpa, rel=1e-14)
    assert m.d_per_mpa == pytest.approx((1 - 2 * 0.498) / (m.c10_mpa + m.c01_mpa), rel=1e-14)
    assert m.bulk_modulus == pytest.approx(2 / m.d_per_mpa, rel=1e-14)
    # Acceptance numbers of issue 2 (1e-5 absolute).
    assert m.c10_mpa == pytest.approx(0.63545, abs=1e-5)
    assert m.c01_mpa == pytest.approx(0.031772, abs=1e-5)
    assert m.d_per_mpa == pytest.approx(0.005995, abs=1e-5)
    # Eq 6 gives K = 2/d = mu/(1-2nu) = 250 mu, while isotropic elasticity has
    # K = 2mu(1+nu)/(3(1-2nu)); the Poisson ratio implied by (K, mu) is therefore
    # (3*250 - 2)/(2*(3*250 + 1)) = 748/1502 = 0.4980027, not exactly 0.498.
    assert m.poisson == pytest.approx(748 / 1502, rel=1e-12)


def test_table2_printed_values_and_c10_slip():
    t2 = paper.table2()
    m = MooneyRivlin.from_shore(t2["shore"])
    e0 = shore_to_modulus(t2["shore"])
    # E0, G and nu print correctly (4-5 significant digits).
    assert e0 == pytest.approx(t2["e0_mpa"], abs=5e-5)
    assert m.shear_modulus == pytest.approx(t2["g_mpa"], abs=5e-5)
    # The printed C10 is NOT Eq 4: it is (E0/6)/1.005, a slip for /1.05 (docs/paper-notes.md).
    assert t2["c10_mpa"] == pytest.approx(e0 / 6 / 1.005, abs=5e-5)
    assert abs(m.c10_mpa - t2["c10_mpa"]) > 0.02  # fails if someone "fixes" Eq 4 to the misprint
    assert m.c10_mpa == pytest.approx(e0 / 6 / 1.05, rel=1e-12)
    # The printed C01 is 0.05 x the printed (slipped) C10.
    assert t2["c01_mpa"] == pytest.approx(0.05 * t2["c10_mpa"], abs=5e-5)
    # The printed d follows from the slipped constants to 0.2% (0.004/0.6971 = 0.005738).
    d_from_printed = (1 - 2 * t2["poisson"]) / (t2["c10_mpa"] + t2["c01_mpa"])
    assert d_from_printed == pytest.approx(t2["d_per_mpa"], rel=3e-3)
    assert abs(m.d_per_mpa - t2["d_per_mpa"]) / t2["d_per_mpa"] > 0.04
    # The printed constants are usable directly.
    printed = MooneyRivlin(t2["c10_mpa"], t2["c01_mpa"], t2["d_per_mpa"])
    assert printed.shear_modulus == pytest.approx(2 * (0.6639 + 0.0332))


def test_gent_original_vs_rounded_paper_relation():
    # Eq 3's 2.15 and 15.75 are Gent's constants divided out and rounded:
    assert 0.0981 * 7.62336 / (0.137505 * 2.54) == pytest.approx(2.15, abs=0.01)
    assert 0.0981 * 56 / (0.137505 * 2.54) == pytest.approx(15.75, abs=0.03)
    for s in (30, 50, 62.5, 75):
        assert shore_to_modulus(s, "gent") == pytest.approx(shore_to_modulus(s, "paper"), rel=0.01)


def test_qi_and_log_linear_correlations():
    # Qi et al.: S = 100 erf(3.186e-4 sqrt(E[Pa])) -- check the inverse round-trips.
    e = shore_to_modulus(62.5, "qi")
    assert 100 * math.erf(3.186e-4 * math.sqrt(e * 1e6)) == pytest.approx(62.5, rel=1e-10)
    # log10(E) = 0.0235 S - 0.6403 (base 10, not natural log).
    assert math.log10(shore_to_modulus(50, "astm-log10")) == pytest.approx(0.0235 * 50 - 0.6403)
    assert set(CORRELATIONS) >= {"paper", "gent", "qi", "astm-log10"}
    for c in CORRELATIONS.values():
        assert c.reference and c.valid[0] < c.valid[1]


def test_monotonic_in_hardness():
    for name in CORRELATIONS:
        vals = [shore_to_modulus(s, name) for s in (25, 40, 55, 70)]
        assert all(b > a for a, b in zip(vals, vals[1:], strict=False))


@pytest.mark.parametrize("shore", [0, 100, 120, -3, float("nan"), float("inf")])
def test_bad_hardness(shore):
    with pytest.raises(InputError, match="shore"):
        shore_to_modulus(shore)


def test_out_of_validity_range_warns():
    with pytest.warns(MaterialRangeWarning, match="outside"):
        shore_to_modulus(10.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        shore_to_modulus(62.5)


@pytest.mark.parametrize(
    "kwargs,field",
    [
        ({"poisson": 0.6}, "poisson"),
        ({"poisson": 0.5}, "poisson"),
        ({"c01_ratio": -1}, "c01_ratio"),
        ({"correlation": "bogus"}, "correlation"),
    ],
)
def test_bad_parameters(kwargs, field):
    with pytest.raises(InputError, match=field):
        MooneyRivlin.from_shore(62.5, **kwargs)


def test_direct_construction_validation():
    with pytest.raises(InputError, match="d must be > 0"):
        MooneyRivlin(0.6, 0.03, 0.0)
    with pytest.raises(InputError, match="c10 \\+ c01"):
        MooneyRivlin(-1.0, 0.03, 0.006)
    m = MooneyRivlin(0.6, 0.03, 0.006)
    assert m.with_bulk_factor(1000).bulk_modulus == pytest.approx(1000 * m.bulk_modulus)
    assert m.to_dict()["k_mpa"] == pytest.approx(2 / 0.006)
