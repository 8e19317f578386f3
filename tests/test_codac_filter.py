"""The filter operator on Codac 2's contractors (issue 20 item 2, cdpr_algebra.bp.codac_filter): sound (never loses a
proven solution, contracts the initial domain) and, inside the branch and prune, the same equilibria as our
compiled filter -- the two 6-cable equilibria of seed 000 Test 2 (Sec. 5.2's count)."""

import importlib.util
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

# not pytest.importorskip("codac"): importing codac directly leaves the rounding mode upward for the whole worker
if importlib.util.find_spec("codac") is None:
    pytest.skip("codac not installed", allow_module_level=True)

from cdpr_algebra.bp.codac_filter import CodacFilter, _codac, codac_rounding  # noqa: E402
from cdpr_algebra.bp.contractors import contract  # noqa: E402
from cdpr_algebra.bp.results import BPOptions  # noqa: E402
from cdpr_algebra.bp.search import build_model, solve_taut_set_interval  # noqa: E402
from cdpr_algebra.model.robot import load_robot  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def test_rounding_mode_is_ours_outside_and_codacs_inside():
    """Codac's import switches to upward rounding; the engine puts round-to-nearest back, and Codac's arithmetic
    (which needs upward rounding) runs inside codac_rounding, where its 1 / 3 encloses 1 / 3."""
    codac = _codac()
    nearest = float.fromhex("0x1.5555555555555p-2")  # 1 / 3 rounded to nearest (upward: ...556p-2)
    assert Fraction(nearest) < Fraction(1, 3) < Fraction(float.fromhex("0x1.5555555555556p-2"))
    third = np.float64(1.0) / np.float64(3.0)
    assert float(third) == nearest
    with codac_rounding():
        y = codac.Interval(1.0, 1.0) / codac.Interval(3.0, 3.0)
        lo, hi = y.lb(), y.ub()
    assert Fraction(lo) < Fraction(1, 3) < Fraction(hi)
    assert float(np.float64(1.0) / np.float64(3.0)) == nearest  # restored


def test_codac_filter_keeps_every_solution_and_contracts_the_domain():
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    sub = solve_taut_set_interval(robot, robot.lengths, (0, 1, 2))
    assert sub.admissible == 6 and sub.complete  # Table 1 of seed 000
    model = build_model(robot, robot.lengths, (0, 1, 2))
    filt = CodacFilter(model, BPOptions())
    lo0, hi0 = model.initial_box()
    lo, hi = lo0.copy(), hi0.copy()
    assert filt.contract(lo, hi).all()
    core = model.core_cols
    w0, w1 = (hi0 - lo0)[0, core], (hi - lo)[0, core]
    assert np.all(w1 <= w0) and np.any(w1 < 0.9 * w0)
    rng = np.random.default_rng(1)
    for s in sub.solutions:
        for _ in range(5):  # random boxes around the proven enclosure: never excluded, the enclosure kept
            blo, bhi = lo.copy(), hi.copy()
            rad = rng.uniform(1e-6, 0.3, len(core)) * model.core_scale
            blo[0, core] = np.maximum(lo[0, core], s.enclosure_lo - rad)
            bhi[0, core] = np.minimum(hi[0, core], s.enclosure_hi + rad)
            assert filt.contract(blo, bhi).all()
            assert np.all(blo[0, core] <= s.enclosure_lo) and np.all(s.enclosure_hi <= bhi[0, core])
    # a box away from every solution: the anchor B_1 moved 10 robot sizes off is excluded
    far_lo, far_hi = lo0.copy(), hi0.copy()
    far_lo[0, 0] = far_hi[0, 0] - 1e-3 * robot.size
    far_lo[0, 0:3] += 10 * robot.size
    far_hi[0, 0:3] += 10 * robot.size
    assert not filt.contract(far_lo, far_hi).any()


def test_codac_engine_same_equilibria_as_the_compiled_one():
    robot = load_robot(ROOT / "examples" / "seed000_test2.toml")
    cables = tuple(range(6))
    ours = solve_taut_set_interval(robot, robot.lengths, cables)
    theirs = solve_taut_set_interval(robot, robot.lengths, cables, BPOptions(kernels="codac"))
    assert ours.complete and theirs.complete
    assert ours.admissible == theirs.admissible == 2  # Sec. 5.2: two equilibria with six taut cables
    for a, b in zip(ours.solutions, theirs.solutions):  # both sorted by position
        assert np.all(a.enclosure_lo <= b.enclosure_hi) and np.all(b.enclosure_lo <= a.enclosure_hi)
        assert np.max(np.abs(a.position - b.position)) <= 1e-9 * robot.size


def test_contract_dispatches_to_codac():
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    model = build_model(robot, robot.lengths, (0, 1, 2))
    lo, hi = model.initial_box()
    l1, h1 = contract(model, lo.copy(), hi.copy(), BPOptions(kernels="codac"))
    assert len(l1) == 1 and getattr(model, "_codac_filter", None) is not None
