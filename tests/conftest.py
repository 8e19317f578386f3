"""Tests run from the repository root, so example paths like ``examples/seed004_table1.toml`` resolve.

The tests import the package from this tree, whose numba kernels would compile on first use (about a minute of
the suite on a clean checkout) although ``pip install .`` has just compiled them into the installed copy
(``setup.py``): :func:`_reuse_installed_kernel_caches` copies that copy's cache files next to identical sources here
first.  numba checks every cache against the source's contents (and its own version and the CPU), so a file edited
since the install simply compiles again.
"""

import os
import shutil
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _reuse_installed_kernel_caches():
    """Copy the numba caches (``__pycache__/*.nbi``, ``*.nbc``) of an installed cdpr_algebra into this tree, next to
    each module whose source is byte for byte the installed one; files already here are kept."""
    from importlib.metadata import PackageNotFoundError, distribution

    try:
        installed = Path(distribution("cdpr_algebra").locate_file("cdpr_algebra")).resolve()
    except (PackageNotFoundError, OSError):
        return
    tree = (ROOT / "cdpr_algebra").resolve()
    if not installed.is_dir() or installed == tree:
        return
    same = {}
    for index in installed.rglob("__pycache__/*.nbi"):
        pkg = index.parent.parent
        module = index.name.split(".", 1)[0] + ".py"
        here = tree / pkg.relative_to(installed)
        key = (here, module)
        if key not in same:
            mine, theirs = here / module, pkg / module
            same[key] = mine.is_file() and theirs.is_file() and mine.read_bytes() == theirs.read_bytes()
        if not same[key]:
            continue
        target = here / "__pycache__"
        target.mkdir(exist_ok=True)
        stem = index.name[: -len(".nbi")]
        for f in [*index.parent.glob(stem + ".*.nbc"), index]:  # the index last: it names the data files
            if not (target / f.name).exists():
                fd, tmp = tempfile.mkstemp(dir=target)  # copy, then rename: the xdist workers do this at once
                os.close(fd)
                shutil.copyfile(f, tmp)
                os.replace(tmp, target / f.name)


def pytest_configure(config):
    _reuse_installed_kernel_caches()


@pytest.fixture(autouse=True)
def _run_from_repo_root(monkeypatch):
    monkeypatch.chdir(ROOT)


@pytest.fixture(scope="session")
def table3():
    """Seed 004 Table 3: (robot, IGP with assigned position G = (7, 9, 1)), solved once for the session."""
    from cdpr_algebra.igp.position import igp_position
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed004_table3.toml")
    return robot, igp_position(robot, [7, 9, 1])
