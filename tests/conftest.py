"""Tests run from the repository root, so example paths like ``examples/seed004_table1.toml`` resolve.

The tests import the package from this tree, whose numba kernels would compile on first use (about a minute of
the suite on a clean checkout) although ``pip install .`` has just compiled them into the installed copy
(``setup.py``): :func:`_reuse_installed_kernel_caches` copies that copy's cache files next to identical sources here
first, and gives those sources the installed copies' modification times: numba checks a cache against its source's
(mtime, size) (and its own version and the CPU), so a file edited since the install simply compiles again.
"""

import os
import shutil
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _reuse_installed_kernel_caches():
    """Copy the numba caches (``__pycache__/*.nbi``, ``*.nbc``) of an installed cdpr_algebra into this tree, next to
    each module whose source is byte for byte the installed one (giving it the installed file's modification time);
    files already here are kept unless that time changed."""
    from importlib.metadata import distributions

    tree = (ROOT / "cdpr_algebra").resolve()
    # every distribution of that name: pip's build leaves cdpr_algebra.egg-info in this tree, and from the repository
    # root (on sys.path) that one is found first and locates the package here (measured, eighteenth session: in a
    # fresh clone nothing was ever copied, and every kernel compiled again in each xdist worker)
    found = [Path(d.locate_file("cdpr_algebra")).resolve() for d in distributions(name="cdpr_algebra")]
    installed = next((p for p in found if p != tree and p.is_dir()), None)
    if installed is None:
        return
    same = {}
    for index in installed.rglob("__pycache__/*.nbi"):
        pkg = index.parent.parent
        module = index.name.split(".", 1)[0] + ".py"
        here = tree / pkg.relative_to(installed)
        key = (here, module)
        if key not in same:  # (same bytes, restamped: then this tree's own caches of the module are stale)
            mine, theirs = here / module, pkg / module
            ok = mine.is_file() and theirs.is_file() and mine.read_bytes() == theirs.read_bytes()
            same[key] = (ok, ok and _same_stamp(mine, theirs))
        ok, restamped = same[key]
        if not ok:
            continue
        target = here / "__pycache__"
        target.mkdir(exist_ok=True)
        stem = index.name[: -len(".nbi")]
        for f in [*index.parent.glob(stem + ".*.nbc"), index]:  # the index last: it names the data files
            if restamped or not (target / f.name).exists():
                fd, tmp = tempfile.mkstemp(dir=target)  # copy, then rename: the xdist workers do this at once
                os.close(fd)
                shutil.copyfile(f, tmp)
                os.replace(tmp, target / f.name)


def _same_stamp(mine: Path, theirs: Path) -> bool:
    """Give ``mine`` the modification time of ``theirs`` (the two files have the same bytes).  numba's cache index
    records its source's (mtime, size) and is ignored when they differ: a clone's files are older than the copies pip
    installed, so without this every kernel compiled again in every xdist worker of the first run (measured,
    eighteenth session: 9 min 19 s for the suite in a fresh clone, 39 s of system time, against 6 min 15 s and 7 s
    for the second run in the same clone).  True when the time was changed."""
    st = theirs.stat()
    if mine.stat().st_mtime_ns == st.st_mtime_ns:
        return False
    os.utime(mine, ns=(st.st_atime_ns, st.st_mtime_ns))
    return True


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
