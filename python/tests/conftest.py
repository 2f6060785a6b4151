import os
import shutil
from pathlib import Path

import pytest

import mcquad

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> str:
    """The mcquad command to compare with: $MCQUAD_CLI, the Release build, or PATH. Required under CI=true."""
    for candidate in (os.environ.get("MCQUAD_CLI"), str(REPO / "build/release/cli/mcquad"), shutil.which("mcquad")):
        if candidate and Path(candidate).is_file() and os.access(candidate, os.X_OK):
            return candidate
    if os.environ.get("CI") == "true":
        pytest.fail("no mcquad command found (set MCQUAD_CLI or run scripts/build)")
    pytest.skip("no mcquad command found (set MCQUAD_CLI or run scripts/build)")


@pytest.fixture(scope="session")
def t_shape(tmp_path_factory) -> Path:
    """A generated T (the paper's Fig. 1) written as files: t-shape.ply, t-shape.skeleton.obj."""
    directory = tmp_path_factory.mktemp("t")
    mcquad.generate("t-shape", directory, points=20000, seed=4)
    return directory
