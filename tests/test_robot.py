"""Robot files and bad input: one clear error naming the field, exit status 2 in the CLI."""

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cdpr_algebra import CdprInputError, Robot, load_robot
from cdpr_algebra.cli.main import main

GOOD = {
    "name": "t",
    "base": [[0, 0, 0], [10, 0, 0], [0, 12, 0]],
    "platform": [[0.6, 0.1, -0.8], [-0.4, -0.9, -0.3], [-0.7, 0.5, -0.5]],
    "com": [0, 0, 0],
    "load": 10,
    "load_direction": [0, 0, 1],
}


def _write(tmp_path, data, name="r.json"):
    p = tmp_path / name
    p.write_text(json.dumps(data) if isinstance(data, dict) else data)
    return p


def test_json_and_toml_agree(tmp_path):
    toml = """name = "t"
base = [[0, 0, 0], [10, 0, 0], [0, 12, 0]]
platform = [[0.6, 0.1, -0.8], [-0.4, -0.9, -0.3], [-0.7, 0.5, -0.5]]
com = [0, 0, 0]
load = 10
load_direction = [0, 0, 1]
"""
    a = load_robot(_write(tmp_path, GOOD))
    b = load_robot(_write(tmp_path, toml, "r.toml"))
    assert a.to_dict() == b.to_dict()
    assert Robot.from_dict(a.to_dict()).to_dict() == a.to_dict()


@pytest.mark.parametrize(
    "change, field, words",
    [
        ({"base": [[0, 0, 0], [10, 0], [0, 12, 0]]}, "base[1]", "expected 3 numbers"),
        ({"platform": [[0, 0, 0]]}, "platform", "expected 3 points"),
        ({"base": [[0, 0, 0], [10, 0, float("nan")], [0, 12, 0]]}, "base[1][2]", "finite"),
        ({"load": 0}, "load", "> 0"),
        ({"load": -3}, "load", "> 0"),
        ({"load_direction": [0, 0, 0]}, "load_direction", "zero vector"),
        ({"lengths": [1, -2, 3]}, "lengths[1]", "> 0"),
        ({"lengths": [1, 2]}, "lengths", "expected 3 numbers"),
        ({"base": [[0, 0, 0], [0, 0, 0], [0, 12, 0]]}, "base", "coincide"),
        ({"platform": [[1, 0, 0], [0, 1, 0], [1, 0, 0]]}, "platform", "coincide"),
        ({"bases": [[0, 0, 0]]}, "bases", "unknown key"),
        ({"com": "middle"}, "com", "expected a list"),
        ({"load": "heavy"}, "load", "expected a number"),
        ({"load": 1e300}, "load", "overflow double precision"),
        ({"load": 1e-300}, "load", "underflow double precision"),
        ({"lengths": [1, 1e308, 3]}, "lengths[1]", "overflow double precision"),
        ({"base": [[0, 0, 0], [1e101, 0, 0], [0, 12, 0]]}, "base[1][0]", "beyond 1e+100"),
    ],
)
def test_bad_input_names_field(tmp_path, change, field, words, capsys):
    data = dict(GOOD) | change
    path = _write(tmp_path, data)
    with pytest.raises(CdprInputError) as err:
        load_robot(path)
    assert err.value.field == field and words in str(err.value)
    assert main(["igp", str(path), "--orientation", "0", "0", "0"]) == 2
    line = capsys.readouterr().err
    assert line.count("\n") == 1 and f"'{field}'" in line and "Traceback" not in line


def test_missing_key_and_unreadable_files(tmp_path, capsys):
    data = dict(GOOD)
    del data["com"]
    with pytest.raises(CdprInputError, match="'com': required key is missing"):
        load_robot(_write(tmp_path, data))
    with pytest.raises(CdprInputError, match="no such file"):
        load_robot(tmp_path / "nope.json")
    with pytest.raises(CdprInputError, match="not valid JSON"):
        load_robot(_write(tmp_path, "{base: ", "bad.json"))
    with pytest.raises(CdprInputError, match="not valid TOML"):
        load_robot(_write(tmp_path, "base = [", "bad.toml"))
    with pytest.raises(CdprInputError, match="expected .json or .toml"):
        load_robot(_write(tmp_path, "x", "r.yaml"))
    assert main(["igp", str(tmp_path / "nope.json"), "--position", "1", "2", "3"]) == 2
    assert "no such file" in capsys.readouterr().err


def test_cli_argument_errors(capsys):
    with pytest.raises(SystemExit) as e:
        main(["igp", "examples/seed004_table1.toml", "--orientation", "0", "zero", "0"])
    assert e.value.code == 2
    assert "expected a number" in capsys.readouterr().err


def test_cli_numbers_beyond_1e100_are_refused(capsys):
    with pytest.raises(SystemExit) as e:
        main(["igp", "examples/seed004_table1.toml", "--position", "1e200", "0", "0"])
    assert e.value.code == 2 and "beyond 1e+100" in capsys.readouterr().err


def test_json_of_results_is_strict_json():
    """A non-finite number in a result (an overflowed residual, an accuracy never measured) prints as null."""
    from cdpr_algebra.report.jsonable import json_text

    text = json_text({"residual": np.float64("inf"), "x": [1.0, float("nan")], "z": complex(1, float("inf"))})
    assert json.loads(text) == {"residual": None, "x": [1.0, None], "z": [1.0, None]}
    assert "Infinity" not in text and "NaN" not in text


def test_load_direction_normalized():
    r = Robot.from_dict(dict(GOOD) | {"load_direction": [0, 0, 5]})
    assert np.allclose(r.load_direction, [0, 0, 1])


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from(["base", "platform", "com", "load", "load_direction", "lengths", "name", "extra"]),
                       st.one_of(st.none(), st.integers(-3, 3), st.floats(allow_nan=True), st.text(max_size=3),
                                 st.lists(st.one_of(st.floats(), st.lists(st.floats(), max_size=4)), max_size=4)),
                       max_size=8))
def test_arbitrary_input_never_crashes_deep(data):
    """Whatever the mapping, the result is a Robot or a CdprInputError (never a numpy traceback)."""
    try:
        Robot.from_dict(data)
    except CdprInputError as err:
        assert err.field


def test_unknown_keys_are_named_alike_everywhere(tmp_path):
    """A robot file, the exact IGP's data dict and a ``crosscheck --against`` file reject misspelt keys the same
    way (model.errors.reject_unknown_keys): the field is the path of the first unknown key, the message lists every
    unknown key and the allowed ones."""
    from cdpr_algebra.comparison.external import load_results
    from cdpr_algebra.igp.position import dialytic_determinant

    data = dict(GOOD) | {"bases": [[0, 0, 0]], "lenghts": [1, 2, 3]}
    with pytest.raises(CdprInputError) as err:
        load_robot(_write(tmp_path, data))
    assert err.value.field == "bases"
    assert "'bases', 'lenghts'" in err.value.problem and "allowed keys: name, base" in err.value.problem
    with pytest.raises(CdprInputError) as err:
        dialytic_determinant({"base": GOOD["base"], "platform": GOOD["platform"], "plataform": 1}, [0, 0, 1])
    assert err.value.field == "plataform" and "allowed keys: base, platform, com, load_direction" in str(err.value)
    f = tmp_path / "theirs.json"
    f.write_text('{"solver": "x", "subproblems": [{"taut": [1, 2], "count": 0}, {"taut": [1], "cnt": 2}]}')
    with pytest.raises(CdprInputError) as err:
        load_results(f, 3)
    assert err.value.field == "subproblems[1].cnt" and "unknown key 'cnt' (allowed keys: taut, count, boxes)" in str(
        err.value)
