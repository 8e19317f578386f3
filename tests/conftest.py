"""Tests run from the repository root, so example paths like ``examples/seed004_table1.toml`` resolve."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


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
