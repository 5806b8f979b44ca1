"""What the tests of the Python package share: the command line's binaries (to compare
with), the repository's scenarios, and a fresh folder per test."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def binary(name: str) -> Path:
    """A binary of the workspace's release build (`TOUCHDOWN_BIN_DIR` or target/release)."""
    folder = Path(os.environ.get("TOUCHDOWN_BIN_DIR", ROOT / "target" / "release"))
    path = folder / name
    if not path.exists():
        pytest.fail(f"{path} is not built: run `cargo build --release` (or cargo test) first")
    return path


@pytest.fixture(scope="session")
def cli() -> Path:
    """The `touchdown` command line."""
    return binary("touchdown")


def run(program, *args, check=True):
    """Runs a binary; its completed process (stdout and stderr as text)."""
    done = subprocess.run([str(program), *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"{program} {' '.join(map(str, args))}: exit {done.returncode}\n{done.stderr}")
    return done


@pytest.fixture
def root() -> Path:
    return ROOT
