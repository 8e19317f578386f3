"""Issue 15: four taut cables whose exit points and platform anchors are two parallelograms with the same diagonals,
the anchors' centred on G (a rectangular frame and a flat rectangular plate with G at its centre), are tracked from
the generic solution set of that subfamily (:mod:`cdpr_algebra.dgp.parallelogram`): 152 paths, none of them into
the solutions at infinity that the generic route could not decide (40 failed paths on the flat plate).

Independent checks: the stored subfamily set solves its equations, lies exactly in the subfamily and carries a trace
test that passed inside it, with its separation (recorded by derivations/solve_generic_parallelogram.py); the generic
route's certified roots of the same taut set are the subfamily route's; the admissible equilibria agree with the
interval branch and prune's proven ones; a taut set listed in another order is the same robot.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.dgp.parallelogram import (fixed_parameters, parallelogram_kind, parallelogram_order,
                                            parallelogram_path, parallelogram_relations, zero_parameters)
from cdpr_algebra.dgp.solve import _solve_taut_set, _with_endpoint_certificates, dgp, solve_taut_set
from cdpr_algebra.model.robot import Robot, load_robot

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ("centred", "off_centre", "squares")  # squares_axis: its trace test did not decide (README)


def meta_kind(data) -> str:
    """The kind a stored set's record names (the centred set was stored before kinds were recorded)."""
    return data["meta"].get("kind", "centred")


def _flat():
    """examples/flat_plate_4cables.toml: examples/symmetric_4cables.toml with G at the plate's centre."""
    flat = load_robot(ROOT / "examples" / "flat_plate_4cables.toml")
    sym = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    assert np.array_equal(flat.base, sym.base) and np.array_equal(flat.platform, sym.platform)
    return flat


def _solved(robot, cables, **kw):
    rho = np.asarray(robot.lengths)
    sub, sols, Z = _solve_taut_set(robot, rho, cables, exclude=False, **kw)
    (sub,) = _with_endpoint_certificates(robot, rho, [(cables, sub, Z)])
    return sub, sols, Z


def _parallelograms(perm=(0, 1, 2, 3)):
    """A robot whose exit points are a (non-rectangular, tilted) parallelogram and whose plate is a skew
    parallelogram centred on G, cables listed in the order ``perm`` of the diagonals 1, 3 and 2, 4."""
    A = np.array([[-6.0, -4.5, 5.2], [-5.0, 4.0, 5.6], [6.4, 4.7, 5.8], [5.4, -3.8, 5.4]])
    b = np.array([[-0.5, -0.3, -0.1], [-0.4, 0.25, 0.05], [0.5, 0.3, 0.1], [0.4, -0.25, -0.05]])
    p = np.array([0.3, 0.2, 1.0])
    rho = np.linalg.norm(A - (p + b), axis=1) * np.array([1.001, 1.003, 1.002, 1.004])
    idx = list(perm)
    return Robot(A[idx], b[idx], np.zeros(3), 1.0, np.array([0.0, 0.0, -1.0]), rho[idx], name="parallelograms")


@pytest.mark.parametrize("kind", SHIPPED)
def test_stored_subfamily_set_solves_its_equations_and_passed_the_trace_test(kind):
    from cdpr_algebra.dgp.taut_system import fast_family
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.model.taut_equations import taut_family

    p, X, data = load_instance(parallelogram_path(kind), taut_family(4))  # hash of the sympy system checked
    for rel in parallelogram_relations(kind=kind):  # exactly in the subfamily
        assert sum(c * p[i] for i, c in rel) == 0
    # 0 (the squares' planes: within 1e-15, the rounding of the monodromy's projections onto the subfamily)
    assert np.max(np.abs(p[list(zero_parameters(kind=kind))]), initial=0) <= 1e-15
    assert kind == "centred" or np.any(p[28:31] != 0)
    assert meta_kind(data) == kind and set(fixed_parameters(kind=kind)) >= set(zero_parameters(kind=kind))
    if kind.startswith("squares"):  # the load fixed along -z: the exit points' plane normal to it
        assert np.max(np.abs(p[31:34] - [0, 0, -1])) <= 1e-15
    F, J = fast_family(4).evaluate_and_jacobian(X, p)
    assert np.max(np.abs(F)) <= 1e-8 * (1 + np.max(np.abs(X)))
    assert np.max(np.linalg.cond(J)) < 1e10
    d = np.max(np.abs(X[:, None, :] - X[None, :, :]), axis=2) + np.eye(len(X))
    assert np.min(d) > 1e-6  # distinct
    meta = data["meta"]
    assert meta["check"]["new_solutions"] == 0 and meta["monodromy"]["stopped_by"] == "no_progress"
    trace = meta["trace_test"]
    assert trace["status"] == "passed" and trace["count"] == len(X)
    tr = trace["trace"]
    assert tr["relative"] <= tr["tol"] and tr["detection"] >= 100 * tr["relative"]
    assert tr["points"] == len(X) + trace["W10_count"]
    # PHCpack's blackbox on another random member of the subfamily (a polyhedral homotopy, independent of the
    # monodromy): its regular solutions with every lam_i nonzero are the stored set moved there, matched both ways
    phc = meta["phc"]
    assert phc["status"] == "finished" and phc["regular"] <= phc["mixed_volume"]
    assert phc["phc_distinct"] == phc["phc_matched"] == phc["stored_matched"] == phc["stored_moved_distinct"] == len(X)
    # fewer than the generic family's 216: the others leave to infinity in the subfamily (the off-centre count is
    # also the generic route's certified roots of examples/symmetric_4cables.toml, tests/test_dgp_symmetric.py)
    assert len(X) == {"centred": 152, "off_centre": 184, "squares": 168}[kind] < len(load_instance(
        ROOT / "cdpr_algebra" / "data" / "dgp_generic_m4.json", taut_family(4), check_hash=False)[1])


def test_which_taut_sets_are_parallelograms_and_of_which_kind():
    flat = _flat()
    assert parallelogram_order(flat, (0, 1, 2, 3)) == (0, 1, 2, 3)
    assert parallelogram_kind(flat, (0, 1, 2, 3)) == "centred"
    skew = _parallelograms((0, 2, 1, 3))
    assert parallelogram_order(skew, (0, 1, 2, 3)) == (0, 2, 1, 3)  # diagonals 1, 2 and 3, 4
    assert parallelogram_kind(skew, (0, 2, 1, 3)) == "centred"
    assert parallelogram_order(flat, (0, 1, 2)) is None  # three cables
    # G off the plate's centre (the file's, 0.2 below it; or moved in the plate by 1e-12): the off-centre kind
    sym = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    assert parallelogram_order(sym, (0, 1, 2, 3)) == (0, 1, 2, 3)
    assert parallelogram_kind(sym, (0, 1, 2, 3)) == "off_centre"
    moved = replace(flat, com=np.array([1e-12, 0.0, 0.0]))
    assert parallelogram_kind(moved, parallelogram_order(moved, (0, 1, 2, 3))) == "off_centre"
    # one platform anchor off the parallelogram by 1e-12: not one
    off = replace(flat, platform=flat.platform + np.array([[0.0, 0.0, 0.0]] * 3 + [[0.0, 1e-12, 0.0]]))
    assert parallelogram_order(off, (0, 1, 2, 3)) is None
    # nearly parallelograms (seed 002's {1, 3, 5, 7}: B7 = -B3 within 5e-3, A a parallelogram within 1e-2): no
    assert parallelogram_order(load_robot(ROOT / "examples" / "seed002_8cables.toml"), (0, 2, 4, 6)) is None


@pytest.mark.slow
def test_flat_plate_complete_with_the_generic_routes_roots_and_the_interval_searchs_equilibria():
    """The flat plate's {1, 2, 3, 4}: every one of the 152 paths regular and certified, complete.  The generic route
    (``rods=False``) leaves paths failed there, but its certified roots are the same 152 points, and the interval
    branch and prune proves the same admissible equilibria."""
    from cdpr_algebra.comparison.compare import compare_taut_set

    flat = _flat()
    sub, sols, Z = _solved(flat, (0, 1, 2, 3))
    assert sub.parallelogram == (1, 2, 3, 4) and sub.generic_count == sub.paths == 152
    assert sub.outcomes["regular"] == 152 and sub.certified == 152 and sub.complete
    gen, _, Zg = _solved(flat, (0, 1, 2, 3), rods=False)
    assert gen.parallelogram is None and gen.paths == 216 and not gen.complete
    assert gen.certified == gen.outcomes["regular"] == 152  # the same finite roots, reached by the other route
    d = np.max(np.abs(Zg[:, None, :] - Z[None, :, :]), axis=2)
    assert np.all(np.min(d, axis=1) <= 1e-8 * (1 + np.max(np.abs(Z))))
    cmp = compare_taut_set(flat, flat.lengths, (0, 1, 2, 3), homotopy_result=(sub, sols))
    assert cmp.status == "agree" and cmp.homotopy == cmp.interval == sub.admissible == 2, cmp.to_dict()


def test_cables_in_another_order_are_the_same_robot():
    """A skew plate: the taut set listed with the diagonals 1, 2 and 3, 4 gives the same certified account and the
    same equilibria as the robot listed in the diagonals' order (the tensions put back in the order of the cables)."""
    ra, rb = _parallelograms(), _parallelograms((0, 2, 1, 3))
    a, sa = solve_taut_set(ra, ra.lengths, (0, 1, 2, 3), exclude=False)
    b, sb = solve_taut_set(rb, rb.lengths, (0, 1, 2, 3), exclude=False)
    assert a.complete and b.complete and a.certified == b.certified == 152
    assert b.parallelogram == (1, 3, 2, 4)
    assert len(sa) == len(sb) >= 1
    for x, y in zip(sorted(sa, key=lambda s: s.position[2]), sorted(sb, key=lambda s: s.position[2])):
        assert np.allclose(x.position, y.position, atol=1e-9) and np.allclose(x.rotation, y.rotation, atol=1e-9)
        assert np.allclose(x.tensions, y.tensions[[0, 2, 1, 3]], atol=1e-9)  # cable k of b is cable perm[k] of a
        assert x.certified and y.certified


def test_the_flat_plates_whole_dgp_is_complete():
    res = dgp(_flat(), jobs=1)
    assert res.complete and all(s.complete for s in res.subproblems)
    (sub,) = [s for s in res.subproblems if s.taut == (1, 2, 3, 4)]
    assert sub.to_dict()["parallelogram"] == {"start": "parallelogram_generic", "kind": "centred",
                                              "diagonals": [[1, 3], [2, 4]]}
    from cdpr_algebra.dgp.solve import dgp_table

    assert "[1, 2, 3, 4]: exit points and platform anchors two parallelograms (diagonals 1-3 and 2-4)" in dgp_table(res, 4)
