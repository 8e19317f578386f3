"""Whole-robot runs that several test modules check, computed once per test process.

The seed 000 Test 2 and Test 3 DGPs take about a minute each; the tests that use them carry the
``xdist_group`` mark of their robot, so that ``pytest -n auto`` (``--dist loadgroup``, pyproject) sends them
to one worker, where this cache serves the second module."""

from functools import lru_cache
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


@lru_cache(maxsize=None)
def dgp_run(name: str):
    """(robot, DGPResult) of ``examples/{name}.toml`` at its stored lengths (two threads)."""
    from cdpr_algebra.dgp.solve import dgp
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / f"{name}.toml")
    return robot, dgp(robot, jobs=2)
