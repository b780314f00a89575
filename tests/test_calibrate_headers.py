"""Test files that carry their own sizes: ``# width_mm: 5`` in a ring CSV, ``# tube_od_mm:`` in an
inflation CSV, so that ``exofric calibrate --data inflation.csv --tensile uniaxial.csv --ring
ring.csv --model yeoh`` (the issue's command) runs as written.

The calibrated values are checked against the planted truth the files were made from (a
recovery, not a value pin): the same forward code made and fits the data.
"""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import numpy as np
import pytest

from exofric.errors import InputError
from exofric.io import RING_HEADER_KEYS, read_header_sizes


def _cli(args: list[str]) -> tuple[int, str, str]:
    from exofric.cli import run

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = run(args)
    return code, out.getvalue(), err.getvalue()


def test_header_sizes_parsed(tmp_path: Path) -> None:
    p = tmp_path / "ring.csv"
    p.write_text("# a ring from the tube\n# width_mm: 5\n#PIN_MM=3.0\n# note: width_mm: 9\n"
                 "displacement_mm,force_n\n# width_mm: 7\n1,1\n")
    # the header's keys only (case-insensitive, ':' or '='); a comment after the header row
    # does not count
    assert read_header_sizes(p, RING_HEADER_KEYS) == {"width_mm": 5.0, "pin_mm": 3.0}
    assert read_header_sizes(p, ("tube_od_mm",)) == {}


@pytest.mark.parametrize("value", ["-1", "0", "abc", "nan", ""])
def test_header_size_must_be_positive(tmp_path: Path, value: str) -> None:
    p = tmp_path / "ring.csv"
    p.write_text(f"# pin_mm: {value}\ndisplacement_mm,force_n\n1,1\n")
    with pytest.raises(InputError, match=r"ring.csv: header '# pin_mm:' must be a positive"):
        read_header_sizes(p, RING_HEADER_KEYS)


def test_missing_ring_size_names_option_and_header_line(tmp_path: Path) -> None:
    p = tmp_path / "ring.csv"
    p.write_text("# width_mm: 5\ndisplacement_mm,force_n\n0.5,0.4\n1,1.2\n")
    code, _, err = _cli(["calibrate", "--model", "neo-hookean", "--ring", str(p),
                         "--tube-od", "8.3"])
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "--pin" in err and "'pin_mm: ...' (after '#')" in err


def test_issue_command_runs_with_sizes_in_the_files(tmp_path: Path) -> None:
    """``calibrate --data --tensile --ring --model`` with every size from the files' headers:
    the planted neo-Hookean modulus (1.2 MPa) and tube ID (4.97 mm) come back (0.5 %,
    0.01 mm; noise-free data, the FE meshes' own differences are ~1e-4)."""
    from exofric.fe import MeshSpec
    from exofric.material import material_model
    from exofric.simulate import inflate, ring_test

    m = material_model("neo-hookean", [0.6])
    p = [0.1, 0.2, 0.3]
    od = inflate(8.3, 4.97, m, p, keep_fields=False).outer_diameter_mm
    (tmp_path / "inflation.csv").write_text(
        "# tube_od_mm: 8.3\npressure_mpa,outer_diameter_mm\n"
        + "".join(f"{a},{b:.6f}\n" for a, b in zip(p, od, strict=True)))
    lam = np.linspace(1.1, 1.8, 6)
    (tmp_path / "uniaxial.csv").write_text(
        "stretch,stress_mpa\n" + "".join(f"{a:.4f},{b:.6f}\n" for a, b in
                                         zip(lam, m.uniaxial_stress_mpa(lam), strict=True)))
    d = [1.0, 2.0, 3.0]
    f = ring_test(8.3, 4.97, 5.0, 3.0, d, m, mesh=MeshSpec(4, 32, grading=4.0)).force_n
    (tmp_path / "ring.csv").write_text(
        "# width_mm: 5\n# pin_mm: 3\ndisplacement_mm,force_n\n"
        + "".join(f"{a},{b:.6f}\n" for a, b in zip(d, f, strict=True)))
    code, out, err = _cli(["calibrate", "--data", str(tmp_path / "inflation.csv"),
                           "--tensile", str(tmp_path / "uniaxial.csv"),
                           "--ring", str(tmp_path / "ring.csv"), "--model", "neo-hookean",
                           "--json"])
    assert code == 0, err
    obj = json.loads(out)
    assert obj["shear_modulus_mpa"] == pytest.approx(1.2, rel=5e-3)
    assert obj["tube_id_mm"] == pytest.approx(4.97, abs=0.01)
