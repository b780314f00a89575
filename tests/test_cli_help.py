"""Every command's --help reads at 80 columns (issue 34).

In process (``exofric.cli.run``; rich takes the width from ``COLUMNS``): flags show no
``<bool>`` metavar (they take no value), every line fits in 80 columns, and prose is wrapped
by the terminal, not by the docstring's line breaks: no line of a help paragraph stops short
of the width while the sentence goes on on the next line.
"""

from __future__ import annotations

import re

import pytest
import typer

from exofric.cli import app, run


def _commands() -> list[list[str]]:
    out: list[list[str]] = [[]]

    def walk(cmd: object, path: list[str]) -> None:
        for name, sub in sorted(getattr(cmd, "commands", {}).items()):
            out.append([*path, name])
            walk(sub, [*path, name])

    walk(typer.main.get_command(app), [])
    return out


def _ragged(lines: list[str]) -> list[str]:
    """Lines of a wrapped paragraph that end far short of the width although the sentence
    continues on the next line (lower-case start, inside the same box or description)."""
    bad = []
    for a, b in zip(lines, lines[1:], strict=False):
        ta, tb = a.strip(" │"), b.strip(" │")
        if not ta or not re.match(r"^[a-z]", tb) or tb.startswith(("-", "[")) \
                or re.match(r"^[a-z][\w-]*\s{2,}", tb):           # a new row: a command
            continue
        end = len(a.rstrip(" │"))                       # where line a's text stops
        room = len(a.rstrip()) - 2 if a.rstrip().endswith("│") else 80
        if end + 1 + len(tb.split()[0]) < room:         # the next word would have fitted
            bad.append(f"{a!r} / {b!r}")
    return bad


@pytest.mark.parametrize("path", _commands(), ids=lambda p: " ".join(p) or "exofric")
def test_help_at_80_columns(path: list[str], capsys: pytest.CaptureFixture[str],
                            monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "80")
    assert run([*path, "--help"]) == 0
    out = capsys.readouterr().out
    lines = out.splitlines()
    assert "<bool>" not in out
    assert all(len(ln) <= 80 for ln in lines), [ln for ln in lines if len(ln) > 80][:2]
    assert not _ragged(lines), _ragged(lines)[:3]
