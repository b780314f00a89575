"""Input sizes a user can give have a bounded memory path or a clear refusal (issue 38).

A raw rig log is read whole (reading, checking and reducing it holds 3-4 copies of its
samples): a file whose estimated reading memory exceeds ``RAWLOG_MEMORY_FRACTION`` of the
machine's physical memory is refused before anything is read, naming the estimate. The tests
allocate nothing: a sparse file of 1 TiB (its size without its bytes), or this machine's memory
taken as a few kilobytes. The other user-sized inputs are bounded where they are parsed and
tested there: meshes (MESH_MAX_ELEMENTS, the GiB estimate: tests/test_input_properties.py),
tolerance samples (8-4096), sweep designs (MAX_DESIGNS), control durations and gait strides
(tests/test_cli_hostile.py: 1e300 and huge integers are refused with their range).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from exofric import defaults as D
from exofric.errors import InputError
from exofric.io import read_raw_log, write_raw_log


def _sparse(path: Path, size: int) -> Path:
    with open(path, "wb") as f:
        f.truncate(size)
    return path


def test_a_one_tebibyte_log_is_refused_with_the_estimate_and_nothing_read(tmp_path):
    """3.5 x 1 TiB = 3584 GiB estimated (the measured text factor), more than half of any
    machine's memory this runs on."""
    p = _sparse(tmp_path / "huge.csv", 2**40)
    with pytest.raises(InputError) as exc:
        read_raw_log(p)
    msg = str(exc.value)
    assert msg.startswith("huge.csv: too large to read: about 3584.0 GiB of memory for this "
                          "1024.00 GiB file"), msg
    assert "split the log" in msg and "\n" not in msg


def _small_machine(monkeypatch, ram_bytes: int) -> None:
    from exofric.io import _rawlog

    monkeypatch.setattr(_rawlog, "_physical_memory", lambda: ram_bytes)


def _log(n: int) -> pd.DataFrame:
    t = np.arange(n) * 0.01
    return pd.DataFrame({"time_s": t, "pressure_mpa": 0.3 + 0.0 * t, "force_n": 50.0 + t})


def test_the_limit_is_the_fraction_of_physical_memory(tmp_path, monkeypatch):
    """The same CSV reads on a machine with room for its estimate and is refused on one with
    less: the estimate is size x RAWLOG_MEMORY_PER_FILE_BYTE['text'] bytes, compared with
    RAWLOG_MEMORY_FRACTION x the physical memory."""
    p = write_raw_log(tmp_path / "run.csv", _log(200))
    need = os.path.getsize(p) * D.RAWLOG_MEMORY_PER_FILE_BYTE["text"]
    _small_machine(monkeypatch, int(need / D.RAWLOG_MEMORY_FRACTION) + 4)
    assert len(read_raw_log(p)) == 200
    _small_machine(monkeypatch, int(need / D.RAWLOG_MEMORY_FRACTION) - 4)
    with pytest.raises(InputError, match=r"^run\.csv: too large to read"):
        read_raw_log(p)


def test_parquet_is_estimated_from_its_rows_not_its_compressed_size(tmp_path, monkeypatch):
    """A constant-valued Parquet log compresses to a few kB; its estimate is rows x columns x
    8 B x 3 from the metadata (200,000 rows x 3 columns -> 14.4 MB)."""
    pytest.importorskip("pyarrow")
    from exofric.io._rawlog import _memory_estimate

    df = _log(200_000)
    df["force_n"] = 50.0
    p = write_raw_log(tmp_path / "run.parquet", df)
    assert os.path.getsize(p) < 2e6
    assert _memory_estimate(p) == 200_000 * 3 * 8 * 3


def test_xlsx_uses_openpyxls_factor(tmp_path, monkeypatch):
    """openpyxl documents ~50x the file's size; the check runs before the file is opened (a
    file of zeros is refused for its size, not parsed)."""
    p = tmp_path / "run.xlsx"
    p.write_bytes(b"\0" * 10_000)
    _small_machine(monkeypatch, int(2 * 50 * 10_000 * 0.9))
    with pytest.raises(InputError, match=r"^run\.xlsx: too large to read: about 0\.0 GiB"):
        read_raw_log(p)
