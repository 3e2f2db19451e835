"""Shared fixtures: the suite's scenes, and the `strata` command line to compare against.

The command line is the binary `cargo build --release -p render` makes (`target/release/strata`
in the repository), or the one `STRATA_BIN` names. Tests that compare against it fail, rather
than skip, when it is missing.
"""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
SCENES = ROOT / "scenes"


@pytest.fixture(scope="session")
def strata_bin():
    path = pathlib.Path(os.environ.get("STRATA_BIN", ROOT / "target" / "release" / "strata"))
    if not path.is_file():
        pytest.fail(f"no strata binary at {path}: run `cargo build --release -p render` or set "
                    f"STRATA_BIN")
    return path


@pytest.fixture(scope="session")
def cli(strata_bin):
    """Runs `strata ARGS...`; returns its completed process, failing the test unless it exits 0."""

    def run(*args):
        done = subprocess.run([str(strata_bin), *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, f"strata {' '.join(map(str, args))}: {done.stderr}"
        return done

    return run


@pytest.fixture(scope="session")
def cli_render(cli, tmp_path_factory):
    """Renders with `strata render SCENE FLAGS... -q`; returns (EXR path, stats dict)."""
    directory = tmp_path_factory.mktemp("cli")
    counter = iter(range(10**6))

    def render(scene, *flags):
        n = next(counter)
        out, stats = directory / f"cli-{n}.exr", directory / f"cli-{n}.json"
        cli("render", scene, "-q", "-o", out, "--stats", stats, *flags)
        return out, json.loads(stats.read_text())

    return render


def bits(array):
    """The float32 array's bit patterns, for comparisons that tell -0 from 0 and NaN from NaN."""
    import numpy as np

    return np.ascontiguousarray(array, dtype=np.float32).view(np.uint32)
