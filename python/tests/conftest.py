"""Fixtures of the raceway package's tests: the repository and the `raceway` command line
(the serial reference the package must agree with)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli():
    """Run the `raceway` program (RACEWAY_BIN, else target/debug or target/release);
    returns its standard output."""
    candidates = [os.environ.get("RACEWAY_BIN")] + [
        str(ROOT / "target" / p / "raceway") for p in ("debug", "release")
    ]
    exe = next((c for c in candidates if c and os.path.exists(c)), None)
    if exe is None:
        raise RuntimeError("no raceway binary: run `cargo build` or set RACEWAY_BIN")

    def run(*args: str, check: bool = True) -> str:
        p = subprocess.run([exe, *args], capture_output=True, text=True, cwd=ROOT)
        if check and p.returncode != 0:
            raise RuntimeError(f"raceway {' '.join(args)} failed: {p.stderr}")
        return p.stdout

    run.json = lambda *a: json.loads(run(*a))
    return run
