"""Shared fixtures: the repository (for the Rust references the tests compare against) and
`cargo run` of its binaries and examples.

The parity tests need the repository and cargo. Without them (the wheel installed elsewhere)
they are skipped, except under CI (`CI` set), where a missing reference is a failure.
"""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SHARED = Path(os.environ.get("OSRL_SHARED", REPO.parent / "shared"))
SARCOS = SHARED / "data" / "sarcos"


def _need(ok: bool, why: str) -> None:
    if not ok:
        if os.environ.get("CI"):
            pytest.fail(f"{why} (required under CI)")
        pytest.skip(why)


@pytest.fixture(scope="session")
def cargo():
    """`cargo(*args)` runs `cargo run --release -q ARGS` in the repository; returns stdout."""
    _need((REPO / "Cargo.toml").is_file() and (REPO / "crates" / "lwpr").is_dir(),
          f"the osrl repository is not at {REPO}")
    _need(shutil.which("cargo") is not None, "cargo is not on PATH")

    def run(*args: str) -> str:
        p = subprocess.run(["cargo", "run", "--release", "-q", *args], cwd=REPO,
                           capture_output=True, text=True)
        if p.returncode != 0:
            raise AssertionError(f"cargo run {' '.join(args)} failed:\n{p.stderr}")
        return p.stdout

    return run


@pytest.fixture(scope="session")
def sarcos():
    """The SARCOS split (`shared/data/sarcos`) as (train, test) float arrays."""
    import numpy as np

    _need((SARCOS / "parity_train.csv").is_file(), f"no SARCOS data at {SARCOS}")
    load = lambda f: np.loadtxt(SARCOS / f, delimiter=",", skiprows=1)
    return load("parity_train.csv"), load("parity_test.csv")
