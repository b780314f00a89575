"""Every shell command of README.md and examples/README.md runs as written (issues 20, 34).

The commands are extracted from every ```bash / ```sh block of both files (continuation lines
joined, comment lines dropped) and run in order in one scratch folder that sees the
repository's ``examples/`` and ``src/`` (the paths the README uses), so that a command reuses
what an earlier one wrote (``squeeze.json``, ``pulls.csv``, ``sweep-out``), as a reader's
session would (a command repeated word for word in a later section is run once). ``exofric``
commands run in process (``exofric.cli.run``: the same code as the console script, without ~0.6
s of interpreter and import start-up each), ``> file`` is written from the captured stdout.

What each command must do is read off the README itself:

* by default: exit 0 and a non-degenerate answer (something on stdout, or in the file it
  redirects to), no traceback, no error line;
* a trailing comment with ``(not shipped)`` (the reader's own files): exit 2 with one line on
  stderr naming the missing file, so the flags are checked and the failure is the documented
  one;
* a trailing comment with ``on your hardware``: not run (a device at a LAN address or a serial
  port); the test checks only that the README says so.

A few commands are run elsewhere, at their full cost, and are listed in ``ELSEWHERE`` with the
test that covers them; the test fails if one of these entries stops matching a command.
"""

from __future__ import annotations

import re
import shlex
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
READMES = (ROOT / "README.md", ROOT / "examples" / "README.md")

#: Commands run by another test (prefix -> where), not here: they would double this test's
#: time for nothing it does not already check.
ELSEWHERE = {
    "make demo": "the test environment is what it sets up (make test installs every extra)",
    "make test": "the test suite itself",
    "python examples/": "tests/test_examples.py (imports every example: the same computation)",
    ".venv/bin/pytest": "the test suite itself",
    "exofric predict --gamma 0.7168 --hole 10 --tube-od 8.3 --tube-id 4.97 --wire 1.6 "
    "--clearance-sd": "the tolerance bands (64 samples, ~45 s CPU): tests/test_tolerance.py",
}


@dataclass(frozen=True)
class Command:
    """One README command: its text, its trailing comment and the file it is in."""

    text: str
    comment: str
    source: str

    @property
    def not_shipped(self) -> bool:
        return "(not shipped)" in self.comment

    @property
    def on_hardware(self) -> bool:
        return "on your hardware" in self.comment

    @property
    def elsewhere(self) -> str | None:
        return next((why for pre, why in ELSEWHERE.items() if self.text.startswith(pre)), None)


def readme_commands() -> list[Command]:
    """Every command of the shell blocks of the READMEs, in order."""
    out: list[Command] = []
    for path in READMES:
        for block in re.findall(r"```(?:bash|sh)\n(.*?)```", path.read_text(), re.S):
            current, comment = "", ""
            for raw in block.splitlines():
                line = raw.strip()
                if not line or (line.startswith("#") and not current):
                    continue
                m = re.search(r"\s+#\s.*$", line)
                if m:
                    comment += m.group(0)
                    line = line[: m.start()]
                if line.endswith("\\"):
                    current += line[:-1].strip() + " "
                    continue
                out.append(Command((current + line).strip(), comment.strip(), path.name))
                current, comment = "", ""
    return out


def test_the_readmes_commands_are_found() -> None:
    cmds = readme_commands()
    assert len(cmds) >= 40, len(cmds)
    assert all(c.text.startswith(("exofric ", "python ", "make ", ".venv/bin/")) for c in cmds), \
        [c.text for c in cmds if not c.text.startswith(("exofric ", "python ", "make ", ".venv"))]
    for prefix in ELSEWHERE:        # every exemption still names a command of the README
        assert any(c.text.startswith(prefix) for c in cmds), prefix
    hardware = [c.text for c in cmds if c.on_hardware]
    assert len(hardware) == 2 and all("modbus-tcp://" in h or "serial://" in h for h in hardware)


def _run_exofric(cmd: Command, tmp: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from exofric.cli import run

    argv = shlex.split(cmd.text)[1:]
    redirect = argv[-1] if len(argv) > 1 and argv[-2] == ">" else None
    if redirect:
        argv = argv[:-2]
    code = run(argv)
    out, err = capsys.readouterr()
    if cmd.not_shipped:
        lines = err.strip().splitlines()
        assert code == 2 and len(lines) == 1 and "error:" in lines[0], (cmd.text, code, err)
        named = [a for a in argv if re.search(r"\.(csv|tdms|mot|json|toml)$", a)
                 and not (tmp / a).exists()]
        assert named and any(n in lines[0] for n in named), (cmd.text, err)
        return
    assert code == 0, f"{cmd.text}\n{err[-2000:]}"
    assert "Traceback" not in err and "error:" not in err, (cmd.text, err)
    if redirect:
        (tmp / redirect).write_text(out)
        assert (tmp / redirect).stat().st_size > 100, cmd.text
    else:
        assert len(out.strip()) > 50, (cmd.text, out)


def test_every_readme_command_runs_as_written(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    for name in ("examples", "src"):
        (tmp_path / name).symlink_to(ROOT / name)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("COLUMNS", "100")
    ran: set[str] = set()
    for cmd in readme_commands():
        if cmd.on_hardware or cmd.elsewhere or cmd.text in ran:   # a repeat: its output is here
            continue
        assert cmd.text.startswith("exofric "), f"{cmd.text}: not an exofric command"
        _run_exofric(cmd, tmp_path, capsys)
        ran.add(cmd.text)
    assert len(ran) >= 30
    # a few answers that must be there (non-degenerate)
    assert (tmp_path / "exofric-report" / "report.html").is_file()
    for png in ("inflate.png", "squeeze.png", "fit.png", "seg.png", "pi.png", "fig12.png",
                "k.png", "gait.png"):
        assert (tmp_path / png).stat().st_size > 10_000, png
    assert (tmp_path / "run.csv").stat().st_size > 10_000
    assert (tmp_path / "raw-log.truth.json").is_file()
