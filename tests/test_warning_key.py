"""One rule for "each warning once" (issue 38, item 3): :func:`exofric.errors.warning_key`.

``exofric predict`` (cli/predict.py ``_warnings_once``) and the tolerance bands' samples
(simulate/_tolerance.py ``_warn_once``) used two rules: predict collapsed only numbers with a
point or an exponent, the tolerance bands every number. Now both use one key: measured numbers
(a point, an exponent, or a whole number followed by a unit) collapse; other whole numbers name
or count things and keep messages apart. The expected merges below are written by hand from
the messages' meaning, not from the function. Time: < 0.1 s.
"""

from __future__ import annotations

import warnings

import pytest

from exofric.errors import PlausibilityWarning, warning_key
from exofric.simulate import StretchWarning

MERGE = [   # (a, b): the same check, different measured values
    ("N = 1.23 N", "N = 1.24 N"),
    ("test 6: principal stretch 2.63 at 0.6 MPa exceeds 2.5 (150% strain)",
     "test 6: principal stretch 2.51 at 1 MPa exceeds 2.5 (150% strain)"),   # 1 MPa: a unit
    ("clearance: 12 % of the length has a clearance above 0.35 mm",
     "clearance: 3 % of the length has a clearance above 0.4 mm"),
    ("mu_wall = 1.5 is above 1.2", "mu_wall = 1.25e+00 is above 1.2"),
    ("a pull of 20 mm at 1 mm/s", "a pull of 25.5 mm at 2 mm/s"),
]
APART = [   # (a, b): different things named or counted
    ("test 6: principal stretch 2.63 at 0.6 MPa", "test 7: principal stretch 2.63 at 0.6 MPa"),
    ("only 3 of 64 samples solved", "only 5 of 64 samples solved"),
    ("structure 2 has no contact", "structure 12 has no contact"),
    ("mu_wall = 1.5 is above 1.2", "mu_wire = 1.5 is above 1.2"),
]


@pytest.mark.parametrize(("a", "b"), MERGE)
def test_the_same_check_with_other_numbers_merges(a, b):
    assert warning_key(PlausibilityWarning, a) == warning_key(PlausibilityWarning, b)


@pytest.mark.parametrize(("a", "b"), APART)
def test_other_things_named_or_counted_stay_apart(a, b):
    assert warning_key(PlausibilityWarning, a) != warning_key(PlausibilityWarning, b)


def test_the_category_keeps_messages_apart():
    assert warning_key(StretchWarning, "x 1.2") != warning_key(PlausibilityWarning, "x 1.2")


def test_both_batches_issue_each_kind_once_with_the_same_rule():
    """The tolerance samples' warnings and predict's context: the first of each kind."""
    from exofric.cli.predict import _warnings_once
    from exofric.simulate._tolerance import _Outcome, _warn_once

    msgs = [m for pair in MERGE + APART for m in pair]
    want = list(dict.fromkeys(warning_key(PlausibilityWarning, m) for m in msgs))
    outcomes = [_Outcome(None, None, None, ((PlausibilityWarning, m),)) for m in msgs]
    with warnings.catch_warnings(record=True) as got_tol:
        warnings.simplefilter("always")
        _warn_once(outcomes)
    with warnings.catch_warnings(record=True) as got_cli:
        warnings.simplefilter("always")
        with _warnings_once():
            for m in msgs:
                warnings.warn(m, PlausibilityWarning, stacklevel=1)
    for got in (got_tol, got_cli):
        keys = [warning_key(w.category, str(w.message)) for w in got]
        assert keys == want
        assert len(got) == len(MERGE) + 2 * len(APART) - 1   # one APART pair shares a MERGE text


def test_implausible_input_warning_names_the_users_line() -> None:
    """A warning raised deep inside a checked public call (dataclass ``__init__``, the
    argument-checking wrapper, ``__post_init__``) points at the caller's line, not at
    exofric's wrapper (``_validate.py``), as ``skip_file_prefixes`` does on Python 3.12."""
    import inspect
    import warnings

    import exofric.material as m

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1   # type: ignore[union-attr]
        m.HyperelasticModel("mooney-rivlin", (0.6, 0.03), d_per_mpa=0.9)
    [w] = [w for w in caught if "Poisson ratio" in str(w.message)]
    assert (w.filename, w.lineno) == (__file__, line)
