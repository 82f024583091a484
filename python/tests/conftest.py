"""Shared fixtures: the `prismatic` binary the package is compared with, and small settings."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Small renders: the comparisons are bit for bit, not about quality.
SMALL = {"width": 48, "height": 36, "photons": 4000, "backend": "cpu"}


def flags(settings):
    """The CLI flags for keyword settings."""
    out = []
    for key, value in settings.items():
        out += [f"--{key.replace('_', '-')}", str(value)]
    return out


@pytest.fixture(scope="session")
def cli():
    """Runs the `prismatic` binary (PRISMATIC, or the workspace's release build)."""
    binary = os.path.abspath(os.environ.get("PRISMATIC", str(ROOT / "target" / "release" / "prismatic")))
    if not os.path.exists(binary):
        pytest.fail(f"no prismatic binary at {binary}: build it with `cargo build --release` or set PRISMATIC")

    def run(*args, cwd):
        done = subprocess.run([binary, *args], cwd=cwd, capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        return done

    return run
