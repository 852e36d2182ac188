"""Shared fixtures: the `surfgrav` command-line tool, to compare the package with it."""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


def _find_cli():
    """SURFGRAV_CLI if set (it must then exist), else a built binary of this clone."""
    given = os.environ.get("SURFGRAV_CLI")
    if given:
        path = pathlib.Path(given)
        if not path.is_file():
            raise RuntimeError(f"SURFGRAV_CLI={given} does not exist")
        return path
    for profile in ("release", "debug"):
        path = ROOT / "target" / profile / "surfgrav"
        if path.is_file():
            return path
    found = shutil.which("surfgrav")
    return pathlib.Path(found) if found else None


class Cli:
    """Runs the command-line tool and returns its parsed output or its error line."""

    def __init__(self, path):
        self.path = path

    def run(self, *args, cwd=None):
        return subprocess.run(
            [str(self.path), *map(str, args)],
            capture_output=True,
            text=True,
            cwd=cwd,
            timeout=600,
        )

    def json(self, *args):
        done = self.run(*args)
        assert done.returncode == 0, done.stderr
        return json.loads(done.stdout)

    def error(self, *args):
        """The one-line message of a command that must fail with exit code 2."""
        done = self.run(*args)
        assert done.returncode == 2, (done.returncode, done.stdout, done.stderr)
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error: "), done.stderr
        return lines[0][len("error: ") :]


@pytest.fixture(scope="session")
def cli():
    path = _find_cli()
    if path is None:
        pytest.skip("no surfgrav binary: build it (cargo build --release) or set SURFGRAV_CLI")
    return Cli(path)


def vec(v):
    """X,Y,Z for the command line, each number in its shortest round-trip form."""
    return ",".join(repr(float(x)) for x in v)
