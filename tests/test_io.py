"""exofric.io: every bad file gets one clear line; every write is atomic; the Parquet store."""

from __future__ import annotations

import os
from pathlib import Path

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
        ("pressure_mpa (kPa),outer_diameter_mm\n100,8.5\n200,8.7\n", "no unit|missing"),
        ("pressure_s,outer_diameter_mm\n100,8.5\n200,8.7\n", "not convertible to MPa"),
        ("", "no header"),
        ('pressure_mpa,outer_diameter_mm\n0.1,8.5,3,4\n0.2,"8.7\n', "malformed CSV"),
    ],
)
def test_bad_files(tmp_path, text, match):
    p = _write(tmp_path, text)
    with pytest.raises(InputError, match=match) as exc:
        read_table(p, REQ, unique_within=("pressure_mpa", None))
    assert "\n" not in str(exc.value)


def test_other_units_are_converted_not_refused(tmp_path):
    # issue 31: a column in another unit is converted (pint), never refused or misread.
    # Reference: SI definitions, 1 kPa = 1e-3 MPa and 1 cm = 10 mm (exact; tolerance 1e-12
    # relative for float round-off).
    p = _write(tmp_path, "pressure_kpa,Outer diameter (cm)\n100,0.85\n200,0.87\n")
    df = read_table(p, REQ, unique_within=("pressure_mpa", None))
    assert df["pressure_mpa"].tolist() == pytest.approx([0.1, 0.2], rel=1e-12)
    assert df["outer_diameter_mm"].tolist() == pytest.approx([8.5, 8.7], rel=1e-12)
    assert df.attrs["units"] == {"pressure_mpa": "kpa", "outer_diameter_mm": "cm"}


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


# --- TOML and JSON readers ------------------------------------------------------------------


def test_read_toml_round_trip_and_syntax_errors_name_file_and_line(tmp_path):
    from exofric.io import read_toml

    good = _write(tmp_path, "[plant]\ntau_s = 0.5\n", "good.toml")
    assert read_toml(good) == {"plant": {"tau_s": 0.5}}
    bad = _write(tmp_path, "[plant]\ntau_s = 0.5\ntau_s = 0.6\n", "bad.toml")
    with pytest.raises(InputError, match=r"bad\.toml: not valid TOML.*line 3, column") as exc:
        read_toml(bad)
    assert "\n" not in str(exc.value)
    # tomllib reports "at end of document" without a line: we add it
    unclosed = _write(tmp_path, "a = 1\nb = [1,\n", "unclosed.toml")
    with pytest.raises(InputError, match=r"unclosed\.toml: .*end of document, line 3, column 1"):
        read_toml(unclosed)


def test_read_toml_missing_file_is_oserror_and_bad_bytes_input_error(tmp_path):
    from exofric.io import read_toml

    with pytest.raises(FileNotFoundError):
        read_toml(tmp_path / "none.toml")
    latin = tmp_path / "latin.toml"
    latin.write_bytes(b"name = '\xe9'\n")
    with pytest.raises(InputError, match="latin.toml: cannot read as UTF-8"):
        read_toml(latin)


def test_cli_missing_toml_exits_2_with_one_line(tmp_path, capsys):
    from exofric.cli import run

    code = run(["sweep", str(tmp_path / "none.toml"), "--out", str(tmp_path / "o"), "--json"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "none.toml" in err


def test_read_json_errors_name_line(tmp_path):
    from exofric.io import read_json

    bad = _write(tmp_path, '{"a": 1,\n "b": }\n', "bad.json")
    with pytest.raises(InputError, match=r"bad\.json: not valid JSON .*line 2, column 7"):
        read_json(bad)
    with pytest.raises(FileNotFoundError):
        read_json(tmp_path / "none.json")


# --- rig and curve readers ------------------------------------------------------------------


def test_read_squeeze_curve_json_and_csv_agree(tmp_path):
    import json

    from exofric.io import read_squeeze_curve

    j = _write(tmp_path, json.dumps({"pressure_mpa": [0.4, 0.2], "squeeze_force_n": [60, 20],
                                     "dofs": 10}), "n.json")
    c = _write(tmp_path, "squeeze_force_n,pressure_mpa\n20,0.2\n60,0.4\n", "n.csv")
    a, b = read_squeeze_curve(j), read_squeeze_curve(c)
    assert a.equals(b) and a["pressure_mpa"].tolist() == [0.2, 0.4]
    assert (a.attrs["source"], b.attrs["source"]) == ("n.json", "n.csv")
    dup = _write(tmp_path, json.dumps({"pressure_mpa": [0.2, 0.2], "squeeze_force_n": [1, 2]}),
                 "d.json")
    with pytest.raises(InputError, match="d.json: duplicate pressure_mpa 0.2"):
        read_squeeze_curve(dup)
    with pytest.raises(InputError, match="file not found"):
        read_squeeze_curve(tmp_path / "none.json")


def test_read_friction_table_labels_and_synthetic_flag(tmp_path):
    from exofric.io import read_friction_table

    f = _write(tmp_path, "pressure_mpa,friction_n\n0.3,20\n0.4,40\n", "f.csv")
    df = read_friction_table(f)
    assert df["test"].tolist() == ["", ""] and df.attrs["synthetic"] is False
    g = _write(tmp_path, "# Synthetic rig data\ntest,pressure_mpa,friction_n\n1,0.3,20\n"
               "1,0.4,40\n2,0.3,21\n2,0.4,41\n", "g.csv")
    df = read_friction_table(g)
    assert df["test"].tolist() == ["1", "1", "2", "2"] and df.attrs["synthetic"] is True


def test_read_step_response_and_inflation_table(tmp_path):
    from exofric.calibration import InflationData
    from exofric.io import read_inflation_table, read_step_response

    rows = "\n".join(f"{0.1 * i:.1f},{min(i, 5) * 0.05:.2f},0.25" for i in range(10))
    df = read_step_response(_write(tmp_path, "time_s,pressure_mpa,command_mpa\n" + rows))
    assert list(df.columns) == ["time_s", "pressure_mpa", "command_mpa"] and len(df) == 10
    with pytest.raises(InputError, match="at least 10 data rows"):
        read_step_response(_write(tmp_path, "time_s,pressure_mpa\n0,0\n1,1\n", "short.csv"))
    f = _write(tmp_path, "shore,pressure_mpa,outer_diameter_mm\n60,0.2,8.8\n60,0.1,8.5\n"
               "65,0.1,8.4\n65,0.2,8.7\n", "inf.csv")
    d = InflationData.from_frame(read_inflation_table(f))
    assert d.source == "inf.csv" and d.shore.tolist() == [60.0, 60.0, 65.0, 65.0]
    assert d.pressure_mpa.tolist() == [0.1, 0.2, 0.1, 0.2]


# --- atomic writes --------------------------------------------------------------------------


def _half_then_fail(monkeypatch, target, attr):
    """Make ``target.attr(path, ...)`` write a partial file at ``path`` and then fail."""

    def broken(*args, **kwargs):
        path = next(a for a in args if isinstance(a, str | os.PathLike))
        Path(path).write_bytes(b"partial")
        raise OSError("disk full (simulated)")

    monkeypatch.setattr(target, attr, broken)


def test_write_json_is_atomic(tmp_path, monkeypatch):
    from exofric.io import read_json, write_json, write_text

    p = write_json({"a": float("nan"), "b": [1, 2]}, tmp_path / "sub" / "r.json")
    assert read_json(p) == {"a": None, "b": [1, 2]}
    assert sorted(x.name for x in p.parent.iterdir()) == ["r.json"]
    # a failure in the middle of the write leaves the previous complete file, no temp file
    import pathlib

    real = pathlib.Path.write_text

    def broken(self, data, *args, **kwargs):
        real(self, data[: len(data) // 2], *args, **kwargs)
        raise OSError("disk full (simulated)")

    monkeypatch.setattr(pathlib.Path, "write_text", broken)
    with pytest.raises(OSError, match="simulated"):
        write_json({"a": 2.0, "c": "x" * 1000}, p)
    with pytest.raises(OSError, match="simulated"):
        write_text(tmp_path / "sub" / "new.csv", "pressure_mpa\n0.1\n")
    monkeypatch.undo()
    assert read_json(p) == {"a": None, "b": [1, 2]}
    assert sorted(x.name for x in p.parent.iterdir()) == ["r.json"]


def test_atomic_path_cleans_up_on_error(tmp_path):
    from exofric.io import atomic_path

    target = tmp_path / "x.bin"
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_bytes(b"half")
        assert tmp.parent == target.parent and tmp.name.startswith(".x.bin.")
        raise RuntimeError("killed")
    assert list(tmp_path.iterdir()) == []


def test_write_vtu_is_atomic(tmp_path, monkeypatch):
    import meshio
    import numpy as np

    from exofric.fe import polar_mesh
    from exofric.io import write_vtu

    m = polar_mesh(1.0, 2.0, 1, 2)
    p = write_vtu(tmp_path / "t.vtu", m.nodes, m.elements, np.zeros_like(m.nodes))
    assert meshio.read(p).points.shape == (len(m.nodes), 3)
    _half_then_fail(monkeypatch, meshio.Mesh, "write")
    with pytest.raises(OSError, match="simulated"):
        write_vtu(tmp_path / "u.vtu", m.nodes, m.elements, np.zeros_like(m.nodes))
    assert sorted(x.name for x in tmp_path.iterdir()) == ["t.vtu"]


# --- the Parquet store ----------------------------------------------------------------------


def _store(tmp_path):
    import pyarrow as pa

    from exofric.io import ParquetStore

    schema = pa.schema([("key", pa.string()), ("pressure_mpa", pa.float64()),
                        ("dofs", pa.int64())])
    return ParquetStore(tmp_path / "out", schema, tags=("ok", "failed", "skipped"),
                        prefix="design", manifest="_sweep.json")


def _rows(key, p):
    import pandas as pd

    return pd.DataFrame({"dofs": [7] * len(p), "pressure_mpa": p, "key": key, "extra": 1})


def test_store_round_trip(tmp_path):
    import pandas as pd

    store = _store(tmp_path)
    assert store.finished() == {} and store.read().empty
    assert list(store.read().columns) == ["key", "pressure_mpa", "dofs"]
    store.write("b2", "ok", _rows("b2", [0.3, 0.6]))
    store.write("a1", "failed", _rows("a1", [float("nan")]))
    store.write("c3", "skipped", _rows("c3", [float("nan")]))
    assert store.finished() == {"a1": "failed", "b2": "ok", "c3": "skipped"}
    df = store.read(["c3", "b2", "zz"])              # requested order, unknown keys skipped
    assert df["key"].tolist() == ["c3", "b2", "b2"] and df["dofs"].dtype == "int64"
    assert df["pressure_mpa"].tolist()[1:] == [0.3, 0.6]
    # a retried design replaces its failed file
    store.write("a1", "ok", _rows("a1", [0.3]))
    assert store.finished()["a1"] == "ok"
    assert not store.path("a1", "failed").exists()
    # pandas reads the directory as one dataset (manifest and temp files ignored)
    store.write_manifest({"name": "t", "pressures_mpa": (0.3, 0.6), "nan": float("nan")})
    assert store.read_manifest() == {"name": "t", "pressures_mpa": [0.3, 0.6], "nan": None}
    assert len(pd.read_parquet(store.out)) == 4
    with pytest.raises(InputError, match="tag must be one of"):
        store.write("a1", "done", _rows("a1", [0.3]))


def test_store_priority_stale_temp_files_and_failed_writes(tmp_path, monkeypatch):
    import pyarrow.parquet as pq

    store = _store(tmp_path)
    store.write("k", "ok", _rows("k", [0.1]))
    store.path("k", "failed").write_bytes(store.path("k", "ok").read_bytes())
    assert store.finished() == {"k": "ok"}          # ok wins over failed
    (store.out / ".design-k-ok.parquet.abc.tmp").write_bytes(b"half")
    (store.out / "._sweep.json.abc.tmp").write_text("{")
    assert store.remove_temporary() == 2
    # a writer killed mid-file never leaves a partial design file
    _half_then_fail(monkeypatch, pq, "write_table")
    with pytest.raises(OSError, match="simulated"):
        store.write("m", "ok", _rows("m", [0.2]))
    names = sorted(x.name for x in store.out.iterdir())
    assert names == ["design-k-failed.parquet", "design-k-ok.parquet"]
    assert store.read_manifest() is None
    (tmp_path / "file").write_text("")
    with pytest.raises(InputError, match="not a directory"):
        type(store)(tmp_path / "file", store.schema)
