"""A solve stopped by the material's own Drucker instability says so (issue 38, item 2).

Ogden-1 with mu = 0.6 MPa, alpha = 0.55: stable at small strain (mu alpha > 0), Drucker-stable
within the FE's validated stretches 0.4-2.5 (so ``check_fe_stability`` only warns), unstable
from planar stretch l* = ((1 + alpha) / (1 - alpha))^(1 / (2 alpha)) = 3.078 and uniaxial
stretch ((1 + alpha/2) / (1 - alpha))^(2 / (3 alpha)) = 3.536 (closed forms of dP/dl = 0 for
the Ogden-1 engineering stress along those paths: the independent reference of the onset).
Squeezed in the base structure, the tube's largest principal stretch reaches ~2.9-3.3 near
0.5 MPa and Newton stops: the error must be a :class:`MaterialInstabilityError` naming the
model, its parameters and both stretches, never "try a finer mesh". Measured (draft, 2 x 24,
3 x 24 meshes): last converged stretch 3.34, 2.88, 2.89. Ogden-1 alpha = 0.85 (onset planar
4.39) stops at a similar pressure (0.54-0.66 MPa) for a reason that is not the material's (a
Drucker-stable alpha = 1.2 stops at 0.667 MPa too): its plain ConvergenceError stays.

Time: ~6 s (one squeeze through the CLI on an explicit 2 x 24 mesh, no error estimate).
"""

from __future__ import annotations

import pytest

from exofric.errors import ConvergenceError, MaterialInstabilityError
from exofric.fe import PlaneStrainMaterial
from exofric.material import material_model


def _planar_onset(alpha: float) -> float:
    return ((1.0 + alpha) / (1.0 - alpha)) ** (1.0 / (2.0 * alpha))


def test_the_onset_is_the_closed_form():
    """The planar/uniaxial onset against the closed forms (tolerance 0.2 %: the scan's grid,
    2001 stretches evenly spaced in ln l over 1-10, is 0.115 % apart)."""
    from exofric.material._hyperelastic import _tension_onset

    for alpha in (0.3, 0.55, 0.85):
        stretch, mode = _tension_onset("ogden1", (0.6, alpha))
        assert mode == "planar"
        assert stretch == pytest.approx(_planar_onset(alpha), rel=2e-3)
    assert _tension_onset("ogden1", (0.6, 1.2)) is None       # alpha >= 1: stable in tension
    assert _tension_onset("neo-hookean", (0.3,)) is None


class _Body:
    """A body at a given largest stretch (what explain_failure reads of an FE problem)."""

    def __init__(self, model, stretch: float) -> None:
        self.model = PlaneStrainMaterial(model)
        self._stretch = stretch

    def max_stretch(self, u) -> float:
        return self._stretch


def test_only_a_stretch_near_the_onset_is_blamed_on_the_material():
    """Below 90 % of the onset (3.078 for alpha 0.55) the solver's own message stays (alpha =
    0.85, onset 4.39, stops in the base squeeze near 0.54 MPa at stretch ~3 for a reason that
    is not the material's: a Drucker-stable alpha = 1.2 stops there too)."""
    from types import SimpleNamespace

    from exofric.fe._divergence import explain_failure

    plain = ConvergenceError("Newton failed at pressure 0.5 MPa. To try: a finer mesh",
                             reached=0.49)
    soft = material_model("ogden1", [0.6, 0.55])
    for stretch, blamed in [(2.5, False), (2.75, False), (2.8, True), (3.3, True)]:
        err = explain_failure(SimpleNamespace(body=_Body(soft, stretch)), [0.0], plain)
        assert isinstance(err, MaterialInstabilityError) is blamed, stretch
    err = explain_failure(SimpleNamespace(body=_Body(soft, 3.3)), [0.0], plain)
    assert (err.reached, err.stretch, err.param) == (0.49, 3.3, "params")
    assert str(err).startswith("Newton failed at pressure 0.5 MPa, largest principal "
                               "stretch 3.3: ogden1 (mu1 = 0.6 MPa, alpha1 = 0.55) is ")
    assert "finer mesh" not in str(err).split("cures")[1]
    stiff = material_model("ogden1", [0.6, 1.2])
    assert explain_failure(SimpleNamespace(body=_Body(stiff, 6.0)), [0.0], plain) is plain


def test_an_unstable_ogden1_squeeze_stops_with_a_stability_error_naming_it():
    """The real solve, through the CLI: exit 3, one line naming the model, its parameters,
    the stretch reached and the onset (3.08, the closed form's 3.078 to 3 digits)."""
    import contextlib
    import io
    import re

    from exofric.cli import run

    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = run(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
                    "--wire", "1.6", "--model", "ogden1", "--params", "0.6,0.55",
                    "--pressures", "0.3,0.45,0.6", "--n-radial", "2", "--n-circ", "24"])
    last = err.getvalue().strip().splitlines()[-1]
    assert code == 3 and last.startswith("exofric: did not converge: Newton failed at "), last
    assert "ogden1 (mu1 = 0.6 MPa, alpha1 = 0.55) is Drucker-unstable (dP/dl <= 0) from " \
           "planar stretch 3.08, a material instability no finer mesh cures. To try: " \
           "parameters stable to a larger stretch" in last
    assert f"{_planar_onset(0.55):.3g}" == "3.08"
    reached = float(re.search(r"largest principal stretch ([\d.]+):", last).group(1))
    assert 0.9 * 3.078 <= reached < 4.0
    assert "--accuracy fine" not in err.getvalue() and len(last) < 400
