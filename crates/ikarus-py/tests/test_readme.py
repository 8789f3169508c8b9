"""The Python examples of the README and of every page of the book (``docs/src/**/*.md``), run as
doctests against the installed package, so that they cannot drift (as
``crates/ikarus-cli/tests/readme.rs`` runs their console examples).

The convention: every ```` ```python ```` block of a page that holds ``>>>`` lines is run,
unless the line just before it is ``<!-- readme-test: not run (REASON) -->``. Each block is one
doctest, run from the repository's root (so that ``examples/…`` paths resolve) and compared
exactly as doctest compares. An expected exception is written as Python's last line shows it
(``ValueError: …``), without the traceback header doctest wants: the header is added here.
"""

from __future__ import annotations

import doctest
import re

import pytest

from conftest import ROOT

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs" / "src").rglob("*.md"))]
NOT_RUN = "<!-- readme-test: not run ("
# The last line of a traceback: an exception's name, a colon and its message.
EXCEPTION = re.compile(r"^[A-Za-z_][\w.]*(Error|Exception|Warning|Interrupt|Exit): ")


def blocks(text: str) -> list[tuple[int, list[str]]]:
    """The Python blocks to run: (line of the block's first line, from 1; its lines)."""
    lines = text.splitlines()
    out = []
    i = 0
    while i < len(lines):
        if lines[i].rstrip() != "```python":
            i += 1
            continue
        start = end = i + 1
        while end < len(lines) and not lines[end].startswith("```"):
            end += 1
        marked = i > 0 and lines[i - 1].startswith(NOT_RUN)
        if not marked and any(line.startswith(">>> ") for line in lines[start:end]):
            out.append((start + 1, lines[start:end]))
        i = end + 1
    return out


def as_doctest(lines: list[str]) -> str:
    """The block with a traceback header before each expected exception."""
    out = []
    after_source = False
    for line in lines:
        if after_source and EXCEPTION.match(line):
            out.append("Traceback (most recent call last):")
        out.append(line)
        after_source = line.startswith((">>> ", "... "))
    return "\n".join(out) + "\n"


# (page, its path from the root, line of the block's first line, the block's lines)
BLOCKS = [
    (page, page.relative_to(ROOT).as_posix(), line, lines)
    for page in PAGES
    for line, lines in blocks(page.read_text(encoding="utf-8"))
]


def test_the_pages_have_python_examples():
    # The test below must not pass by finding nothing.
    assert BLOCKS, "no ```python block with >>> lines in README.md or the book"


def test_an_expected_exception_gets_its_header():
    text = as_doctest([">>> f()", "ValueError: x: bad", ">>> g()", "done: ValueError: not one"])
    assert text.splitlines() == [">>> f()", "Traceback (most recent call last):", "ValueError: x: bad", ">>> g()", "done: ValueError: not one"]


@pytest.mark.parametrize("page,name,line,lines", BLOCKS, ids=[f"{name}:{line}" for _, name, line, _ in BLOCKS])
def test_page_python_block(page, name, line, lines, monkeypatch):
    if any("ikarus.plot(" in l for l in lines):
        pytest.importorskip("matplotlib")
    monkeypatch.chdir(ROOT)
    test = doctest.DocTestParser().get_doctest(as_doctest(lines), {}, f"{name}:{line}", str(page), line - 1)
    report: list[str] = []
    runner = doctest.DocTestRunner(optionflags=doctest.REPORT_NDIFF)
    runner.run(test, out=report.append)
    try:
        import matplotlib.pyplot as plt

        plt.close("all")
    except ImportError:
        pass
    assert runner.failures == 0, "".join(report)
