"""Third-party messages read like exofric's own (issue 38).

* npTDMS logs what it finds odd in a file on stderr through handlers of its own
  (``[nptdms.reader WARNING] Last segment of file has less data than expected...``): held
  while the file is read and said once, as one exofric warning naming the file.
* pymodbus's exception texts (``Modbus Error: [Input/Output] No response received after 0
  retries, continue with next request``) made one-line errors of 330 characters with the
  device's URL twice: now one line of at most 200 characters naming the device and the
  registers read.
"""

from __future__ import annotations

import contextlib
import io
import logging
import warnings
from pathlib import Path

import pytest

from exofric.errors import PlausibilityWarning

FORMATS = Path(__file__).resolve().parent / "data" / "formats"


def test_npTDMS_log_lines_become_one_exofric_warning(tmp_path, caplog):
    """A TDMS file cut short by 37 bytes: npTDMS logs two warnings; none reaches a logging
    handler (caplog sees what its own stderr handler would print), one PlausibilityWarning
    names the file and quotes the first."""
    pytest.importorskip("nptdms")
    from exofric.errors import InputError
    from exofric.io import read_raw_log

    data = (FORMATS / "ni.tdms").read_bytes()
    p = tmp_path / "cut.tdms"
    p.write_bytes(data[:-37])
    with warnings.catch_warnings(record=True) as w, caplog.at_level(logging.DEBUG):
        warnings.simplefilter("always")
        with pytest.raises(InputError, match=r"^cut\.tdms: channels have different lengths"):
            read_raw_log(p)
    assert not [r for r in caplog.records if r.name.startswith("nptdms")]
    mine = [str(x.message) for x in w if issubclass(x.category, PlausibilityWarning)]
    assert len(mine) == 1 and "\n" not in mine[0] and len(mine[0]) <= 300, mine
    assert mine[0].startswith("cut.tdms: the TDMS file looks truncated or damaged (nptdms: "
                              "Last segment of file has less data than expected")


def test_an_intact_TDMS_file_warns_nothing(caplog):
    pytest.importorskip("nptdms")
    from exofric.io import read_raw_log

    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        df = read_raw_log(FORMATS / "ni.tdms")
    assert len(df) > 100 and not caplog.records


@pytest.mark.parametrize("text,short", [
    ("Modbus Error: [Input/Output] No response received after 0 retries, continue with next "
     "request", "No response received after 0 retries"),
    ("Modbus Error: [Connection] ModbusTcpClient 127.0.0.1:5020: Connection unexpectedly "
     "closed 0.001 seconds into read of 8 bytes without response from slave before it closed "
     "connection", None),
    ("x" * 300, "x" * 77 + "..."),
])
def test_pymodbus_reasons_are_cut_to_their_clause(text, short):
    from exofric.hardware._modbus import _reason

    got = _reason(Exception(text))
    assert len(got) <= 80 and "Modbus Error" not in got and "[" not in got
    assert "continue with next request" not in got
    if short is not None:
        assert got == short


def test_a_mute_modbus_device_is_one_short_line(capsys, monkeypatch):
    """The server accepts the connection and answers no read: exit 2, one line of <= 200
    characters naming the device (its URL, once) and the registers read."""
    pytest.importorskip("pymodbus")
    from exofric.cli import run
    from exofric.hardware import ModbusSimServer

    monkeypatch.setattr(warnings, "showwarning", warnings.showwarning)   # run() replaces it
    with ModbusSimServer(fault="mute") as srv:
        srv.rig.freeze_after_s = 0.0       # mute from the start: the first read fails
        url = srv.url + "&timeout=0.05"
        err = io.StringIO()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            code = run(["control", "run", "--device", url, "--duration", "1"])
    lines = [ln for ln in err.getvalue().splitlines() if ln.strip()]
    assert code == 2 and len(lines) == 1, err.getvalue()
    line = lines[0]
    assert len(line) <= 200 and line.count(url) == 1, line
    assert "does not answer reads" in line and "input registers" in line
    assert "Modbus Error" not in line
