"""Cross-checking another solver's results file (cdpr crosscheck --against): a file made from the published-example
solutions agrees; one wrong count and one moved box flag exactly those two subproblems (exit status 1); the text
form of interval solvers reads the same; bad files name the field."""

import json

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cli.main import main
from cdpr_algebra.comparison.external import load_results
from cdpr_algebra.dgp.solve import dgp
from cdpr_algebra.model.errors import CdprInputError

ROBOT = "examples/seed000_test1.toml"


@pytest.fixture(scope="module")
def results():
    """Results 'of another solver' for Test 1: our certified solutions boxed to +-1e-6, per subproblem."""
    robot = load_robot(ROBOT)
    res = dgp(robot)
    assert res.complete
    subs = []
    for sub in res.subproblems:
        sols = [s for s in res.solutions if s.taut == sub.taut]
        boxes = [[[float(v) - 1e-6, float(v) + 1e-6] for v in s.position] for s in sols]
        subs.append({"taut": list(sub.taut), "count": len(sols), "boxes": boxes})
    return {"solver": "test solver", "subproblems": subs}


def test_agreeing_file(results, tmp_path, capsys):
    f = tmp_path / "r.json"
    f.write_text(json.dumps(results))
    assert main(["crosscheck", ROBOT, "--against", str(f), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["summary"] == {"agree": 7, "disagree": 0, "not_compared": 0}
    assert all(s["agree"] is True for s in out["subproblems"])
    three = next(s for s in out["subproblems"] if s["taut"] == [1, 2, 3])
    assert three["ours"] == 6 and len(three["matched"]) == 6


def test_one_wrong_count_and_one_moved_box_are_flagged(results, tmp_path, capsys):
    bad = json.loads(json.dumps(results))
    by = {tuple(s["taut"]): s for s in bad["subproblems"]}
    by[(1, 2)]["count"] += 1  # a wrong count
    box = by[(1, 2, 3)]["boxes"][2]
    box[0] = [box[0][0] + 0.5, box[0][1] + 0.5]  # a moved box
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(bad))
    assert main(["crosscheck", ROBOT, "--against", str(f), "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    flagged = sorted(tuple(s["taut"]) for s in out["subproblems"] if s["agree"] is False)
    assert flagged == [(1, 2), (1, 2, 3)]
    assert all(s["agree"] is True for s in out["subproblems"] if tuple(s["taut"]) not in flagged)
    three = next(s for s in out["subproblems"] if s["taut"] == [1, 2, 3])
    assert three["unmatched_boxes"] == [2] and len(three["uncovered"]) == 1
    assert "counts differ" in next(s for s in out["subproblems"] if s["taut"] == [1, 2])["compared"]


def test_text_form(results, tmp_path, capsys):
    lines = ["# boxes as an interval solver prints them"]
    for s in results["subproblems"]:
        t = " ".join(map(str, s["taut"]))
        if not s["boxes"]:
            lines.append(f"{t} ; none")
        for b in s["boxes"]:
            lines.append(f"{t} ; " + " ".join(f"[{lo!r}, {hi!r}]" for lo, hi in b))
    f = tmp_path / "r.txt"
    f.write_text("\n".join(lines) + "\n")
    solver, subs = load_results(f, 3)
    assert len(subs) == 7 and {s.taut: s.count for s in subs}[(1, 2, 3)] == 6
    assert main(["crosscheck", ROBOT, "--against", str(f)]) == 0
    assert "7 agree, 0 disagree, 0 not compared" in capsys.readouterr().out


@pytest.mark.parametrize("content, field", [
    ('{"subproblems": [{"taut": [1, 9], "count": 1}]}', "subproblems[0]"),
    ('{"subproblems": [{"taut": [1, 2], "count": -1}]}', "subproblems[0]"),
    ('{"subproblems": [{"taut": [1, 2], "boxes": [[[0, 1], [0, 1]]]}]}', "subproblems[0].boxes[0]"),
    ('{"subproblems": [{"taut": [1, 2]}, {"taut": [2, 1]}]}', "subproblems[1]"),
    ("1 2 ; [0, 1] [0, 1]\n", "r.txt line 1"),
    ("1 2 [0, 1] [0, 1] [0, 1]\n", "r.txt line 1"),
    ('{"solver": "me", "subproblems": []}', "--against"),  # nothing to compare is no agreement
    ("1 2 ; none\n1 2 ; [0, 1] [0, 1] [0, 1]\n", "r.txt line 2"),
    ("1 2 ; [0, 1] [0, 1] [0, 1]\n1 2 ; none\n", "r.txt line 2"),
    ("1 2 ; [2, 1] [0, 1] [0, 1]\n", "r.txt line 1"),  # lo > hi: said so, not 'not a number'
    ('[{"taut": [1, 2]}]', "--against"),  # JSON, not an object
    ('{"subproblems": [{"taut": [1, 2], "cnt": 1}]}', "subproblems[0].cnt"),  # a misspelt key is not ignored
    ('{"solvr": "me", "subproblems": [{"taut": [1, 2]}]}', "solvr"),
])
def test_bad_files_name_the_field(tmp_path, content, field):
    f = tmp_path / ("r.json" if content.startswith(("{", "[{")) else "r.txt")
    f.write_text(content)
    with pytest.raises(CdprInputError) as err:
        load_results(f, 3)
    assert err.value.field == field
    assert not content.startswith("1 2 ; [2, 1]") or "lo <= hi" in str(err.value)


def test_their_lengths_must_be_ours(tmp_path):
    """A file that says which lengths it solved for is checked against ours: other lengths are an error naming
    the field, the same lengths (to rounding) are accepted."""
    f = tmp_path / "r.json"
    f.write_text(json.dumps({"lengths": [1.0, 2.0, 3.0], "subproblems": [{"taut": [1, 2], "count": 0}]}))
    with pytest.raises(CdprInputError) as err:
        load_results(f, 3, [1.0, 2.0, 3.5])
    assert err.value.field == "lengths" and "3.5" in str(err.value)
    with pytest.raises(CdprInputError) as err:
        load_results(f, 3, [1.0, 2.0, 3.0, 4.0])
    assert err.value.field == "lengths"
    _, subs = load_results(f, 3, [1.0, 2.0, 3.0 * (1 + 1e-12)])
    assert [s.taut for s in subs] == [(1, 2)]
