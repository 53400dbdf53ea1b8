"""Shared fixtures: the repository, and the `hcm` command the API is compared with."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def target_dir() -> Path:
    return Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))


@pytest.fixture(scope="session")
def root() -> Path:
    """The repository's root (scenarios/, examples/, data/)."""
    return ROOT


@pytest.fixture(scope="session")
def hcm_bin() -> Path:
    """The `hcm` command of this clone: $HCM_BIN, else built by Cargo (the whole
    workspace's features, as the Rust tests build it, so their build serves)."""
    if "HCM_BIN" in os.environ:
        return Path(os.environ["HCM_BIN"])
    subprocess.run(
        ["cargo", "build", "-q", "--workspace", "--bin", "hcm"], cwd=ROOT, check=True
    )
    return target_dir() / "debug" / "hcm"


class Cli:
    """Runs `hcm` in the repository's root."""

    def __init__(self, binary: Path) -> None:
        self.binary = binary

    def __call__(self, *args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
        return subprocess.run(
            [str(self.binary), *map(str, args)], cwd=cwd, capture_output=True, text=True
        )

    def ok(self, *args: str, cwd: Path = ROOT) -> str:
        """Standard output of a run that must succeed."""
        done = self(*args, cwd=cwd)
        assert done.returncode == 0, f"hcm {' '.join(map(str, args))} failed:\n{done.stderr}"
        return done.stdout

    def refusal(self, *args: str, cwd: Path = ROOT) -> str:
        """The message of a run that must fail: its standard error after `error: `."""
        done = self(*args, cwd=cwd)
        assert done.returncode != 0, f"hcm {' '.join(map(str, args))} succeeded"
        text = done.stderr.strip()
        assert text.startswith("error: "), text
        return text[len("error: "):]


@pytest.fixture(scope="session")
def cli(hcm_bin: Path) -> Cli:
    return Cli(hcm_bin)
