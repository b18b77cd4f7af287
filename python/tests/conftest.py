"""Shared fixtures: the command-line binary the results are compared with."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _binary():
    given = os.environ.get("PERSSON_CHECK_BIN")
    if given:
        return pathlib.Path(given)
    for profile in ("release", "debug"):
        for target in (os.environ.get("CARGO_TARGET_DIR"), ROOT / "target"):
            if target:
                path = pathlib.Path(target) / profile / "persson-check"
                if path.is_file():
                    return path
    return None


@pytest.fixture(scope="session")
def cli():
    """Runs the persson-check binary; skips when none is built (`cargo build`)."""
    binary = _binary()
    if binary is None or not binary.is_file():
        pytest.skip("no persson-check binary (cargo build, or set PERSSON_CHECK_BIN)")

    def run(*args, check=True):
        return subprocess.run(
            [str(binary), *map(str, args)], capture_output=True, text=True, check=check
        )

    return run


def cli_error(result):
    """The command line's message, without its `error: ` prefix."""
    assert result.returncode != 0, result.stdout
    text = result.stderr.strip()
    assert text.startswith("error: "), text
    return text[len("error: "):]


@pytest.fixture
def rough():
    """A 64 x 64 surface, H = 0.8, lambda_l = 32, lambda_s = 4, seed 3."""
    import persson_check

    return persson_check.surface(64, 0.8, 32.0, 4.0, 3)


def save(path, array):
    np.save(path, np.ascontiguousarray(array, dtype=np.float64))
    return path
