"""The version comes from Cargo: the wheel's, ``ikarus.__version__`` and the workspace's agree."""

from __future__ import annotations

import importlib.metadata
import re

import ikarus
from conftest import ROOT


def cargo_version(path, table: str) -> str:
    """The ``version = "…"`` line of ``[table]`` in a Cargo.toml (no TOML parser before 3.11)."""
    text = path.read_text(encoding="utf-8")
    section = text.split(f"[{table}]\n", 1)[1].split("\n[", 1)[0]
    found = re.search(r'^version = "([^"]+)"$', section, re.M)
    assert found, f"no version in [{table}] of {path}"
    return found.group(1)


def test_the_version_is_the_workspace_version():
    workspace = cargo_version(ROOT / "Cargo.toml", "workspace.package")
    assert cargo_version(ROOT / "crates/ikarus-py/Cargo.toml", "package") == workspace
    assert ikarus.__version__ == workspace
    assert importlib.metadata.version("ikarus") == workspace


def test_pyproject_takes_the_version_from_cargo():
    text = (ROOT / "crates/ikarus-py/pyproject.toml").read_text(encoding="utf-8")
    assert 'dynamic = ["version"]' in text
    assert not re.search(r"^version\s*=", text, re.M)
