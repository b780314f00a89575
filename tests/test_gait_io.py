"""read_gait: OpenSim storage files (.sto/.mot) and tables, written here as the real writers do.

References are the numbers written into the files (the conversion deg -> rad, ms -> s, kN m
-> N m is pint's, not the reader's own), so each check can fail independently of the code.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from exofric.errors import InputError
from exofric.io import GaitData, gait_data_path, read_gait

T = np.round(np.arange(0.0, 1.2, 0.01), 4)
FLEX_DEG = 30.0 * (1.0 - np.cos(2.0 * np.pi * T / 1.2))        # 0-60 deg, flexion positive
MOM_NM = -40.0 * np.sin(2.0 * np.pi * T / 1.2)


def _storage(path: Path, title: str, header: list[str], cols: list[np.ndarray],
             extra: tuple[str, ...]) -> Path:
    """An OpenSim 4 storage file: title, key=value lines, endheader, tab-separated table."""
    lines = [title, "version=1", f"nRows={len(cols[0])}", f"nColumns={len(cols)}", *extra,
             "endheader", "\t".join(header)]
    lines += ["\t".join(f"{c[i]:16.8f}" for c in cols) for i in range(len(cols[0]))]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_ik_mot_in_degrees_and_id_sto_merge(tmp_path: Path) -> None:
    # gait2392-style: flexion negative in the model, angle in degrees (inDegrees=yes)
    mot = _storage(tmp_path / "walk_ik.mot", "Coordinates",
                   ["time", "hip_flexion_r", "knee_angle_r", "knee_angle_l"],
                   [T, 0 * T, -FLEX_DEG, -FLEX_DEG[::-1]], ("inDegrees=yes",))
    sto = _storage(tmp_path / "walk_id.sto", "Inverse Dynamics Generalized Forces",
                   ["time", "hip_flexion_r_moment", "knee_angle_r_moment", "knee_angle_l_moment"],
                   [T, 0 * T, -MOM_NM, 0 * T], ("inDegrees=no",))
    g = read_gait(mot, moment_path=sto)
    assert isinstance(g, GaitData)
    # flexion-negative convention detected: both signals negated back
    np.testing.assert_allclose(g.knee_angle_rad, np.radians(FLEX_DEG), atol=1e-8)
    np.testing.assert_allclose(g.knee_moment_nm, MOM_NM, atol=1e-8)
    assert "negated" in g.source and "walk_id.sto" in g.source
    left = read_gait(mot, moment_path=sto, side="l", flexion_sign=-1)
    np.testing.assert_allclose(left.knee_angle_rad, np.radians(FLEX_DEG[::-1]), atol=1e-8)


def test_opensim4_path_headers_in_radians(tmp_path: Path) -> None:
    sto = _storage(tmp_path / "coordinates.sto", "Coordinates",
                   ["time", "/jointset/walker_knee_r/knee_angle_r/value",
                    "/jointset/walker_knee_r/knee_angle_r_beta/value", "knee_angle_r_moment"],
                   [T, np.radians(FLEX_DEG), 0 * T, MOM_NM], ("inDegrees=no",))
    g = read_gait(sto)
    np.testing.assert_allclose(np.degrees(g.knee_angle_rad), FLEX_DEG, atol=1e-6)
    np.testing.assert_allclose(g.knee_moment_nm, MOM_NM, atol=1e-7)


def test_csv_with_units_in_headers_converted_by_pint(tmp_path: Path) -> None:
    p = tmp_path / "lab.csv"
    rows = [f"{1000 * t:.1f};{math.radians(a):.9f};{m / 1000:.9f}"
            for t, a, m in zip(T, FLEX_DEG, MOM_NM, strict=True)]
    p.write_text("# subject S3\n# body_mass_kg: 72.5\nTime (ms);Knee angle (rad);"
                 "Knee moment [kN m]\n" + "\n".join(rows) + "\n")
    g = read_gait(p)
    np.testing.assert_allclose(g.time_s, T, atol=1e-9)
    np.testing.assert_allclose(np.degrees(g.knee_angle_rad), FLEX_DEG, atol=1e-6)
    np.testing.assert_allclose(g.knee_moment_nm, MOM_NM, atol=1e-5)
    assert g.body_mass_kg == 72.5
    assert {"time_s", "knee_angle_deg", "knee_moment_nm"} <= set(g.to_frame().columns)


def test_columns_mapping(tmp_path: Path) -> None:
    p = tmp_path / "m.csv"
    p.write_text("t_s,phi_deg,M_nm\n" + "\n".join(
        f"{t},{a},{m}" for t, a, m in zip(T, FLEX_DEG, MOM_NM, strict=True)))
    g = read_gait(p, {"time": "t_s", "knee_angle": "phi_deg", "knee_moment": "M_nm"})
    assert g.n_samples == T.size


def test_shipped_stride_reads() -> None:
    g = read_gait(gait_data_path())
    assert g.n_samples == 1144 and g.body_mass_kg == 85.27 and g.stance_fraction == 0.661
    assert 70.0 < math.degrees(float(g.knee_angle_rad.max())) < 75.0


# ---- bad input: one line naming the problem ------------------------------------------------


def _one_line(exc: pytest.ExceptionInfo[InputError]) -> str:
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


def test_no_moment_column(tmp_path: Path) -> None:
    p = tmp_path / "kin.csv"
    p.write_text("time_s,knee_angle_deg\n" + "\n".join(f"{t},{a}" for t, a in zip(T, FLEX_DEG,
                                                                                      strict=True)))
    with pytest.raises(InputError) as e:
        read_gait(p)
    assert "no knee moment column" in _one_line(e)


def test_no_angle_column(tmp_path: Path) -> None:
    p = tmp_path / "mom.csv"
    p.write_text("time_s,knee_moment_nm\n" + "\n".join(f"{t},{m}" for t, m in zip(T, MOM_NM,
                                                                                     strict=True)))
    with pytest.raises(InputError) as e:
        read_gait(p)
    assert "no knee angle column" in _one_line(e)


def test_degrees_labelled_radians(tmp_path: Path) -> None:
    p = tmp_path / "wrong.csv"
    p.write_text("time_s,knee_angle_rad,knee_moment_nm\n" + "\n".join(
        f"{t},{a},{m}" for t, a, m in zip(T, FLEX_DEG, MOM_NM, strict=True)))
    with pytest.raises(InputError) as e:
        read_gait(p)
    assert "wrong unit" in _one_line(e) and "180" in str(e.value)


def test_storage_angle_without_unit(tmp_path: Path) -> None:
    sto = _storage(tmp_path / "x.sto", "Coordinates", ["time", "knee_angle_r", "knee_moment"],
                   [T, np.radians(FLEX_DEG), MOM_NM], ())
    with pytest.raises(InputError) as e:
        read_gait(sto)
    assert "angle_unit" in _one_line(e)
    assert read_gait(sto, angle_unit="rad").n_samples == T.size


def test_time_going_back(tmp_path: Path) -> None:
    t = T.copy()
    t[50] = t[48]
    p = tmp_path / "back.csv"
    p.write_text("time_s,knee_angle_deg,knee_moment_nm\n" + "\n".join(
        f"{a},{b},{c}" for a, b, c in zip(t, FLEX_DEG, MOM_NM, strict=True)))
    with pytest.raises(InputError) as e:
        read_gait(p)
    assert "increase strictly" in _one_line(e)


def test_non_angle_unit(tmp_path: Path) -> None:
    p = tmp_path / "mm.csv"
    p.write_text("time_s,knee angle (mm),knee_moment_nm\n" + "\n".join(
        f"{a},{b},{c}" for a, b, c in zip(T, FLEX_DEG, MOM_NM, strict=True)))
    with pytest.raises(InputError) as e:
        read_gait(p)
    assert "not an angle" in _one_line(e)
