"""CLI contract: --help, --version, --json (one object), bad input -> one line, exit 2."""

from __future__ import annotations

import pytest

from exofric import __version__


def test_version_and_help(cli):
    r = cli(["--version"])
    assert r.code == 0 and __version__ in r.out
    r = cli(["--help"])
    assert r.code == 0 and "material" in r.out


def test_material_json_acceptance(cli):
    r = cli(["material", "--shore", "62.5", "--json"])
    assert r.code == 0
    d = r.json()
    assert set(d) == {
        "shore",
        "correlation",
        "e0_mpa",
        "g_mpa",
        "c10_mpa",
        "c01_mpa",
        "d_per_mpa",
        "k_mpa",
        "paper_table2",
        "warnings",
    }
    # the printed Table 2 beside ours at the paper's inputs (issue 20)
    assert d["paper_table2"]["c10_mpa"] == 0.6639 and d["paper_table2"]["d_per_mpa"] == 0.00575
    assert d["warnings"] == []  # every --json lists the warnings printed (none here)
    for k, v in [
        ("e0_mpa", 4.00333),
        ("g_mpa", 1.33444),
        ("c10_mpa", 0.63545),
        ("c01_mpa", 0.031772),
        ("d_per_mpa", 0.005995),
    ]:
        assert d[k] == pytest.approx(v, abs=1e-5)
    for s, e0 in [("60", 3.619), ("65", 4.443), ("70", 5.542)]:
        assert cli(["material", "--shore", s, "--json"]).json()["e0_mpa"] == pytest.approx(
            e0, abs=5e-4
        )


@pytest.mark.parametrize(
    "args,field",
    [
        (["--shore", "120"], "shore"),
        (["--shore", "nan"], "shore"),
        (["--shore", "-3"], "shore"),
        (["--shore", "62.5", "--poisson", "0.6"], "poisson"),
        (["--shore", "abc"], "--shore"),
    ],
)
def test_material_bad_input(cli, args, field):
    r = cli(["material", *args])
    assert r.code == 2
    assert r.out == ""
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and field in lines[0] and "Traceback" not in r.err


def test_material_warning_goes_to_stderr(cli):
    r = cli(["material", "--shore", "10", "--json"])
    assert r.code == 0 and "outside" in r.err
    assert r.json()["shore"] == 10.0


def test_paper_json(cli):
    r = cli(["paper", "--json"])
    assert r.code == 0
    d = r.json()
    assert d["scalars"]["gamma"] == 0.7168 and d["table2"]["c10_mpa"] == 0.6639
    r = cli(["paper"])
    assert r.code == 0 and "0.7168" in r.out


def test_bare_exofric_prints_help_without_an_empty_error_line(cli) -> None:
    r = cli([])
    assert r.code == 0, r.err
    assert "Usage" in r.out and "reduce" in r.out
    assert "error" not in r.err


def test_missing_optional_dependency_names_its_extra(monkeypatch, capsys):
    """A command that needs an extra `make demo` does not install (issue 34: `exofric sweep`
    after `make demo` said 'internal error ... please report it'): one line naming the extra,
    exit 2."""
    import typer

    import exofric.cli as cli

    class Command:
        def main(self, *_args, **_kwargs):
            raise ModuleNotFoundError("No module named 'pyarrow'", name="pyarrow")

    monkeypatch.setattr(typer.main, "get_command", lambda _app: Command())
    monkeypatch.setattr(cli, "_BUILT", [None, None])  # the click tree is built once per app
    code = cli.run(["sweep", "x.toml"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "pip install 'exofric[dask]'" in err[0] and "internal error" not in err[0]
