"""Shared helpers: the native `ikarus` binary the results are compared against.

`IKARUS_BIN` names it (the gate script builds it); by default the repository's
target/debug/ikarus or target/release/ikarus, whichever exists.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def _binary() -> str:
    if os.environ.get("IKARUS_BIN"):
        return os.environ["IKARUS_BIN"]
    for profile in ("debug", "release"):
        path = ROOT / "target" / profile / "ikarus"
        if path.exists():
            return str(path)
    pytest.skip("no ikarus binary: set IKARUS_BIN or cargo build -p ikarus-cli")


def run_cli(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    """Runs the CLI from the repository's root (so that examples/… paths resolve)."""
    result = subprocess.run([_binary(), *args], cwd=ROOT, capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"ikarus {' '.join(args)} failed ({result.returncode}): {result.stderr}")
    return result


def cli_json(*args: str):
    return json.loads(run_cli(*args, "--format", "json").stdout)


def cli_error(*args: str) -> str:
    """The CLI's one-line error for bad input (exit 2), without its `ikarus: ` prefix."""
    result = run_cli(*args, check=False)
    assert result.returncode == 2, (args, result.returncode, result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("ikarus: "), lines
    return lines[0][len("ikarus: "):]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT
