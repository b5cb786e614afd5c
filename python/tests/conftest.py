"""Shared fixtures: the `sctl` command-line program (the oracle the package is
compared with), synthetic scenes it writes, and the shared test data."""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
# In CI the repository sits beside `shared/`.
SHARED = REPO.parent / "shared"


def _sctl_binary():
    """SCTL_BIN, else the newest of target/release/sctl and target/debug/sctl."""
    if os.environ.get("SCTL_BIN"):
        return Path(os.environ["SCTL_BIN"])
    built = [p for p in (REPO / "target/release/sctl", REPO / "target/debug/sctl") if p.is_file()]
    return max(built, key=lambda p: p.stat().st_mtime) if built else None


@pytest.fixture(scope="session")
def cli():
    """Runs `sctl ARGS...` and returns its stdout; a failure fails the test."""
    binary = _sctl_binary()
    if binary is None or not binary.is_file():
        pytest.fail(
            "the sctl program is needed to compare answers with: build it with "
            "`cargo build --release -p sctl` or set SCTL_BIN"
        )

    def run(*args):
        proc = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True)
        if proc.returncode != 0:
            raise AssertionError(f"sctl {' '.join(map(str, args))} failed:\n{proc.stderr}")
        return proc.stdout

    return run


@pytest.fixture(scope="session")
def synthetic(cli, tmp_path_factory):
    """The scene folders of `sctl synth --preset quick --seed 7` (HOPE-F layout)."""
    out = tmp_path_factory.mktemp("synth") / "quick"
    cli("synth", "--preset", "quick", "--out", out, "--seed", 7)
    scenes = sorted(p.parent for p in out.glob("*/*/features_and_ground_truth.npz"))
    assert scenes, f"sctl synth wrote no scene under {out}"
    return scenes


def shared_path(*parts):
    """A path under shared/, or a skip saying it is missing."""
    path = SHARED.joinpath(*parts)
    if not path.exists():
        pytest.skip(f"{path} is missing (the repository is expected beside shared/)")
    return path


def write_csv(path, header, rows):
    """A CSV file whose numbers read back as the same float64 values."""
    lines = [",".join(header)]
    lines += [",".join(repr(float(v)) for v in row) for row in np.asarray(rows)]
    path.write_text("\n".join(lines) + "\n")
    return path
