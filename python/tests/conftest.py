import os
import shutil
import subprocess
from pathlib import Path

import pytest

SAMPLES = Path(os.environ.get("TEXPROC_SAMPLES", Path(__file__).resolve().parents[2] / "samples"))


@pytest.fixture
def samples():
    return SAMPLES


@pytest.fixture
def cli():
    """Runs the texproc CLI (TEXPROC_CLI, else texproc on PATH); skips when there is none."""
    exe = os.environ.get("TEXPROC_CLI") or shutil.which("texproc")
    if not exe:
        pytest.skip("no texproc CLI (set TEXPROC_CLI)")

    def run(*args):
        subprocess.run([exe, *map(str, args), "-q"], check=True)

    return run
