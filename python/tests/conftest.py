"""What the tests share: the `condt` binary, run on points written as `.npy`, and the shipped data.

The binary is `$CONDT_BIN`, or `target/debug/condt` at the workspace root (`cargo build -p
condt-cli` makes it; CI's `cargo test` does). Tests that compare with it are skipped without
it, unless `CONDT_REQUIRE_BIN=1` (CI) makes its absence a failure.
"""

import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "data"


def condt_bin():
    path = os.environ.get("CONDT_BIN") or str(ROOT / "target" / "debug" / "condt")
    if os.path.exists(path):
        return path
    if os.environ.get("CONDT_REQUIRE_BIN") == "1":
        pytest.fail(f"the condt binary is not at {path} (build it: cargo build -p condt-cli)")
    pytest.skip(f"the condt binary is not at {path} (cargo build -p condt-cli, or CONDT_BIN)")


class Cli:
    """Runs `condt` on points (saved as `.npy`) and reads its `.npy` or text output."""

    def __init__(self, binary, tmp):
        self.binary = binary
        self.tmp = tmp
        self.count = 0

    def _input(self, points):
        self.count += 1
        path = self.tmp / f"points{self.count}.npy"
        np.save(path, np.asarray(points, dtype=np.float64).reshape(-1, 2))
        return path

    def run(self, *args):
        done = subprocess.run(
            [self.binary, *map(str, args)], capture_output=True, text=True, check=False
        )
        if done.returncode != 0:
            raise AssertionError(f"condt {' '.join(map(str, args))}: {done.stderr}")
        return done

    def reconstruct_edges(self, points, *options):
        """The edges `condt reconstruct -o X.npy` writes, as an int64 (m, 2) array."""
        out = self.tmp / f"edges{self.count}.npy"
        self.run("reconstruct", self._input(points), "-o", out, "-q", *options)
        return np.load(out).astype(np.int64).reshape(-1, 2)

    def reconstruct_text(self, points, fmt, *options):
        """What `condt reconstruct --format FMT` writes on standard output."""
        return self.run(
            "reconstruct", self._input(points), "--format", fmt, "-q", *options
        ).stdout

    def triangles(self, points):
        out = self.tmp / f"triangles{self.count}.npy"
        self.run("triangulate", self._input(points), "-o", out, "-q")
        return np.load(out).astype(np.int64).reshape(-1, 3)

    def triangulation_edges(self, points):
        out = self.tmp / f"tedges{self.count}.npy"
        self.run("triangulate", self._input(points), "--edges", "-o", out, "-q")
        return np.load(out).astype(np.int64).reshape(-1, 2)


@pytest.fixture(scope="session")
def cli(tmp_path_factory):
    return Cli(condt_bin(), tmp_path_factory.mktemp("cli"))


def shipped_point_files():
    """Every point file shipped in data/ (the command line's formats)."""
    suffixes = {".txt", ".npy", ".csv", ".geojson", ".json", ".node"}
    return sorted(p for p in DATA.iterdir() if p.suffix.lower() in suffixes)


def pytest_collection_modifyitems(items):
    """Tests marked ``first`` go first, the rest in their order: pytest-xdist hands tests out in
    this order, so on CI's two processes the 1M-point Dask test starts at once and runs beside
    the others instead of alone at the end."""
    items.sort(key=lambda item: item.get_closest_marker("first") is None)
