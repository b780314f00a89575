"""CSV validation: every bad file gets one clear line naming the problem."""

from __future__ import annotations

import pytest

from exofric.errors import InputError
from exofric.io import jsonable, read_table

REQ = ["pressure_mpa", "outer_diameter_mm"]


def _write(tmp_path, text, name="d.csv"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_good_file_any_order_extra_columns_comments(tmp_path):
    p = _write(
        tmp_path, "# rig 3\nnote,outer_diameter_mm,pressure_mpa\na,8.5,0.1\nb,8.8,0.2 # hi\n"
    )
    df = read_table(p, REQ, unique_within=("pressure_mpa", None))
    assert list(df.columns) == REQ
    assert df["pressure_mpa"].tolist() == [0.1, 0.2]


@pytest.mark.parametrize(
    "text,match",
    [
        ("pressure_mpa,diameter_mm\n0.1,8\n0.2,9\n", "missing column 'outer_diameter_mm'"),
        ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n0.2,abc\n", "data row 2.*not a number"),
        ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n-0.2,8.7\n", "data row 2.*must be >= 0"),
        ("pressure_mpa,outer_diameter_mm\n0.1,nan\n0.2,8.7\n", "data row 1.*NaN"),
        ("pressure_mpa,outer_diameter_mm\n0.1,\n0.2,8.7\n", "data row 1.*empty"),
        ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n0.1,8.7\n", "duplicate pressure_mpa 0.1"),
        ("pressure_mpa,outer_diameter_mm\n0.1,8.5\n", "at least 2 data rows"),
        ("pressure_kpa,outer_diameter_mm\n100,8.5\n200,8.7\n", "wrong unit.*pressure_mpa"),
        ("", "no header"),
        ('pressure_mpa,outer_diameter_mm\n0.1,8.5,3,4\n0.2,"8.7\n', "malformed CSV"),
    ],
)
def test_bad_files(tmp_path, text, match):
    p = _write(tmp_path, text)
    with pytest.raises(InputError, match=match) as exc:
        read_table(p, REQ, unique_within=("pressure_mpa", None))
    assert "\n" not in str(exc.value)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        read_table(tmp_path / "none.csv", REQ)


def test_groups(tmp_path):
    p = _write(tmp_path, "test,pressure_mpa,friction_n\nA,0.1,5\nA,0.2,9\nB,0.1,4\nB,0.2,8\n")
    df = read_table(
        p,
        ["pressure_mpa", "friction_n"],
        ["test"],
        text_columns=["test"],
        unique_within=("pressure_mpa", "test"),
    )
    assert sorted(set(df["test"])) == ["A", "B"]
    p = _write(tmp_path, "test,pressure_mpa,friction_n\nA,0.1,5\nA,0.1,9\nB,0.1,4\nB,0.2,8\n")
    with pytest.raises(InputError, match="in test 'A'"):
        read_table(
            p,
            ["pressure_mpa", "friction_n"],
            ["test"],
            text_columns=["test"],
            unique_within=("pressure_mpa", "test"),
        )


def test_jsonable():
    import numpy as np

    assert jsonable(
        {"a": np.float64(1.5), "b": np.array([1, 2]), "c": float("nan"), "d": (1,)}
    ) == {"a": 1.5, "b": [1, 2], "c": None, "d": [1]}
