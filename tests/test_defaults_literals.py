"""The paper's constants that serve as defaults live in one place (issue 32).

nu = 0.498 (Eq 6) and gamma = 0.7168 (Eq 7) used to be literals in seven and three signatures;
now every default takes them from :mod:`exofric.defaults`, whose values equal the paper's
printed numbers (:mod:`exofric.paper`). The scan reads code, not text: docstrings, doctests and
comments may quote the numbers.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import exofric
from exofric import defaults, paper

SRC = Path(exofric.__file__).parent
#: value -> where it may be written as a number
OWNERS = {0.498: "defaults.POISSON", 0.7168: "defaults.PAPER_GAMMA"}


def _numbers(path: Path) -> list[tuple[int, float]]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return [(n.lineno, n.value) for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, float)
            and n.value in OWNERS]


def test_no_copies_of_the_papers_defaults_in_code() -> None:
    found = [f"{f.relative_to(SRC)}:{line}: {value} (use {OWNERS[value]})"
             for f in sorted(SRC.rglob("*.py"))
             if f.name != "defaults.py" and "paper" not in f.relative_to(SRC).parts
             for line, value in _numbers(f)]
    assert not found, "literal copies of a default:\n" + "\n".join(found)


def test_the_defaults_are_the_papers_numbers() -> None:
    assert defaults.PAPER_GAMMA == pytest.approx(paper.scalar("gamma"), abs=0.0)
    assert defaults.POISSON == 0.498      # Sec. 3.1, Eq 6 (printed; not in the paper's tables)
