"""The public API of ``cdpr_algebra/__init__.py`` (issue 16): every name resolves to the library object it names,
``import cdpr_algebra`` loads none of the numeric stack, and a name loads only its own part."""

import subprocess
import sys
from pathlib import Path

import cdpr_algebra

ROOT = Path(__file__).resolve().parents[1]

EXPECTED = {  # public name -> the object's own module and name
    "load_robot": ("cdpr_algebra.model.robot", "load_robot"),
    "solve_igp_orientation": ("cdpr_algebra.igp.orientation", "igp_orientation"),
    "solve_igp_position": ("cdpr_algebra.igp.position", "igp_position"),
    "solve_dgp": ("cdpr_algebra.dgp.solve", "dgp"),
    "certify": ("cdpr_algebra.certificates.equilibria", "certify_taut_root"),
    "crosscheck": ("cdpr_algebra.comparison.compare", "crosscheck"),
    "settle_incomplete": ("cdpr_algebra.comparison.settle", "settle_incomplete"),
    "cable_configurations": ("cdpr_algebra.cc.configurations", "valid_configurations"),
    "robustness_radius": ("cdpr_algebra.cc.radii", "cc_radii"),
    "plot_equilibrium": ("cdpr_algebra.report.plot", "plot_equilibria"),
    "track_equilibrium": ("cdpr_algebra.track.follow", "track"),
}


def test_public_names_resolve_to_the_library_objects():
    assert set(EXPECTED) <= set(cdpr_algebra.__all__)
    for name, (module, attr) in EXPECTED.items():
        obj = getattr(cdpr_algebra, name)
        assert obj.__module__ == module and obj.__name__ == attr, name
    for name in cdpr_algebra.__all__:
        assert callable(getattr(cdpr_algebra, name)), name


def test_unknown_name_is_an_attribute_error():
    try:
        cdpr_algebra.no_such_thing  # noqa: B018
    except AttributeError as err:
        assert "no_such_thing" in str(err)
    else:
        raise AssertionError("expected AttributeError")


def _loaded_after(code):
    out = subprocess.run([sys.executable, "-c", code + "\nimport sys\nprint(' '.join(sorted(sys.modules)))"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    return set(out)


def test_import_is_lazy():
    mods = _loaded_after("import cdpr_algebra")
    assert not {"numpy", "sympy", "numba", "scipy", "flint", "matplotlib"} & mods
    assert not any(m.startswith("cdpr_algebra.") for m in mods)


def test_a_name_loads_only_its_part():
    mods = _loaded_after("from cdpr_algebra import load_robot")
    assert "cdpr_algebra.model.robot" in mods
    assert not {"sympy", "numba", "matplotlib"} & mods
    assert not any(m.startswith(("cdpr_algebra.dgp", "cdpr_algebra.homotopy", "cdpr_algebra.bp")) for m in mods)


def test_api_solves_a_published_example():
    """Seed 000 Test 1 through the public names: the DGP's admissible equilibria include Table 1's row 1 pose, and
    ``certify`` proves it (the public names reach the same solvers as the CLI)."""
    robot = cdpr_algebra.load_robot(ROOT / "examples" / "seed000_test1.toml")
    result = cdpr_algebra.solve_dgp(robot)
    assert result.complete and len(result.solutions) >= 1
    s = result.solutions[0]
    cert = cdpr_algebra.certify(robot, robot.lengths, [c - 1 for c in s.taut], s.position, s.rotation, s.tensions)
    assert cert.certified and cert.reason is None


def test_every_result_states_its_status():
    """One vocabulary: every solver's result has ``status``, ``seconds`` and ``to_dict()`` with "status" (values
    computed on the shipped examples, each checked against what the result proves)."""
    import numpy as np

    robot1 = cdpr_algebra.load_robot(ROOT / "examples" / "seed000_test1.toml")
    dgp = cdpr_algebra.solve_dgp(robot1)
    assert dgp.status == dgp.to_dict()["status"] == "complete"
    assert {s.to_dict()["status"] for s in dgp.subproblems} == {"complete"}
    igp = cdpr_algebra.solve_igp_orientation(cdpr_algebra.load_robot(ROOT / "examples" / "seed004_table1.toml"),
                                             np.eye(3))
    assert igp.status == igp.to_dict()["status"] == "complete" and all(s.certified for s in igp.real_solutions)
    robot8 = cdpr_algebra.load_robot(ROOT / "examples" / "seed002_8cables.toml")
    r = cdpr_algebra.robustness_radius(robot8, (0, 1, 2), [1, 2, 3, 4, 5, 6], certify=True)
    assert r.status == r.to_dict()["status"] and r.status == ("certified" if r.certified else r.status)
    assert r.to_dict()["seed"] == 0 and cdpr_algebra.robustness_radius(robot8, (0, 1, 2), [1, 2, 3, 4, 5, 6],
                                                                        seed=5).to_dict()["seed"] == 5
    from cdpr_algebra.bp.search import solve_taut_set_interval

    sub = solve_taut_set_interval(robot1, robot1.lengths, (0, 1, 2))
    assert sub.status == sub.to_dict()["status"] == ("complete" if not sub.undecided else "undecided")
    traj = cdpr_algebra.LengthTrajectory(np.array([0.0, 1.0]), np.array([robot1.lengths, [14.0, 10.0, 9.5]]))
    tr = cdpr_algebra.track_equilibrium(robot1, traj, np.linspace(0, 1, 3))
    assert tr.status == tr.to_dict()["status"] == "complete" and [e.kind for e in tr.events] == ["slack"]
    for res in (dgp, igp, r, sub, tr):
        assert res.seconds >= 0
