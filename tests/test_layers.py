"""The package's layers (issue 16), read from the imports of every module (ast, function-level imports included):
data flows one way, the engines are generic, only the CLI imports the CLI, no import cycle, no hand-written module
over 900 lines, no private name imported from another part.  The architecture is described in the README."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "cdpr_algebra"

# rank of each part: a part imports only parts of lower rank, plus the sibling edges below
RANK = {"homotopy": 0, "intervals": 0, "generated": 0, "model": 1, "report": 2, "certificates": 3,
        "igp": 4, "dgp": 4, "bp": 4, "cc": 4, "track": 4, "sweep": 5, "comparison": 5, "cli": 6, "": 7}
# the safety of sub-configurations solves the DGP of the sub-robot; tracking starts from the DGP's stable equilibrium
# and follows the branches of its equations; the DGP does not track a taut set that the interval filter proves to hold
# no admissible equilibrium (the branch and prune stays independent of the DGP: test_bp_is_independent_of_dgp); the
# generated interval evaluators (the float ones rewritten over complex intervals) call the interval engine's
# outward-rounded operations, and the generated double-double residual the homotopy engine's double-double
# operations (the engines import nothing of the package)
SIBLINGS = {("cc", "dgp"), ("track", "dgp"), ("dgp", "bp"), ("generated", "intervals"), ("generated", "homotopy")}
MAX_LINES = 900


def _modules():
    out = {}
    for f in sorted(PACKAGE.rglob("*.py")):
        rel = f.relative_to(PACKAGE.parent).with_suffix("")
        name = ".".join(rel.parts)
        if name.endswith(".__init__"):
            name = name[: -len(".__init__")]
        out[name] = f
    return out


MODULES = _modules()


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(module: str, path: Path):
    """(imported module, names, line) for every import of a cdpr_algebra module in ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    is_package = path.name == "__init__.py"
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "cdpr_algebra":
                    yield a.name, [], node.lineno
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, is_package, node)
            if target.split(".")[0] != "cdpr_algebra":
                continue
            for a in node.names:  # "from package import module" imports the module
                sub = f"{target}.{a.name}"
                if sub in MODULES:
                    yield sub, [], node.lineno
                else:
                    yield target, [a.name], node.lineno


def _part(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in RANK else ""


EDGES = [(m, t, names, line) for m, p in MODULES.items() for t, names, line in _imports(m, p)]


def test_every_part_is_known():
    subpackages = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert subpackages <= set(RANK), subpackages - set(RANK)
    loose = {p.name for p in PACKAGE.glob("*.py")} - {"__init__.py", "__main__.py"}
    assert not loose, f"modules outside the parts: {sorted(loose)}"


def test_imports_point_down():
    bad = []
    for m, t, _, line in EDGES:
        a, b = _part(m), _part(t)
        if a == b or t == "cdpr_algebra" and a == "":
            continue
        if not (RANK[b] < RANK[a] or (a, b) in SIBLINGS):
            bad.append(f"{m}:{line} imports {t} ({a or 'top'} -> {b or 'top'})")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("engine", ["homotopy", "intervals", "generated"])
def test_engines_import_nothing_else_of_the_package(engine):
    # generated code imports nothing else of the package but the engines' operations (SIBLINGS)
    allowed = {engine} | {b for a, b in SIBLINGS if a == engine == "generated"}
    bad = [f"{m}:{line} imports {t}" for m, t, _, line in EDGES if _part(m) == engine and _part(t) not in allowed]
    assert not bad, "\n".join(bad)


def test_only_the_cli_imports_the_cli():
    bad = [f"{m}:{line} imports {t}" for m, t, _, line in EDGES
           if _part(t) == "cli" and _part(m) != "cli" and m != "cdpr_algebra.__main__"]
    assert not bad, "\n".join(bad)


def test_bp_is_independent_of_dgp():
    bad = [f"{m}:{line} imports {t}" for m, t, _, line in EDGES if _part(m) == "bp" and _part(t) == "dgp"]
    assert not bad, "\n".join(bad)


def _cycles(graph):
    state, stack, cycles = {}, [], []

    def visit(u):
        state[u] = 1
        stack.append(u)
        for v in sorted(graph.get(u, ())):
            if state.get(v) == 1:
                cycles.append(stack[stack.index(v):] + [v])
            elif v not in state:
                visit(v)
        stack.pop()
        state[u] = 2

    for u in sorted(graph):
        if u not in state:
            visit(u)
    return cycles


def test_no_import_cycle():
    graph = {}
    for m, t, _, _ in EDGES:
        if t in MODULES and t != m:
            graph.setdefault(m, set()).add(t)
    # a package's __init__ importing its own modules is not a cycle of ideas: drop edges into a module's own parents
    for m in graph:
        graph[m] = {t for t in graph[m] if not m.startswith(t + ".")}
    cycles = _cycles(graph)
    assert not cycles, "\n".join(" -> ".join(c) for c in cycles)


def test_no_private_name_imported_from_another_part():
    bad = [f"{m}:{line} imports {n} from {t}" for m, t, names, line in EDGES for n in names
           if n.startswith("_") and _part(m) != _part(t)]
    assert not bad, "\n".join(bad)


def test_no_hand_written_module_over_900_lines():
    long = {m: n for m, p in MODULES.items() if _part(m) != "generated"
            and (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
    assert not long, long


def test_the_checks_see_a_violation(tmp_path):
    """The reader sees relative, absolute and function-level imports, and the cycle finder a planted cycle (so an
    empty edge list or a blind reader cannot pass)."""
    assert len(EDGES) > 100
    src = tmp_path / "mod.py"
    src.write_text("from .x import a\nimport cdpr_algebra.cli.main\ndef f():\n    from cdpr_algebra.model import robot\n")
    found = {(t, tuple(n)) for t, n, _ in _imports("cdpr_algebra.dgp.mod", src)}
    assert found == {("cdpr_algebra.dgp.x", ("a",)), ("cdpr_algebra.cli.main", ()), ("cdpr_algebra.model.robot", ())}
    assert RANK[_part("cdpr_algebra.cli.main")] > RANK[_part("cdpr_algebra.dgp.mod")]  # dgp -> cli is upward
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]
    assert _cycles({"a": {"b"}, "b": {"c"}}) == []


def _modules_after_cli(argv: list, expect: str, select: str, timeout: int) -> str:
    """In a fresh interpreter: ``main(argv)`` of the CLI (stdout captured, containing ``expect``, exit status 0), then
    the sorted names of the loaded modules m for which the expression ``select`` holds; returns that list's text."""
    import subprocess
    import sys

    code = ("import sys, io, contextlib\nfrom cdpr_algebra.cli.main import main\n"
            "out = io.StringIO()\n"
            "with contextlib.redirect_stdout(out):\n"
            f"    try:\n        main({argv!r})\n    except SystemExit as e:\n        assert not e.code, e.code\n"
            f"assert {expect!r} in out.getvalue()\n"
            f"print(sorted(m for m in sys.modules if {select}))\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout.strip().splitlines()[-1]


def test_numeric_dgp_path_runs_without_sympy():
    """Issue 19 item 5: the numeric path (CLI dgp of a shipped robot: tracking, endgame, certificates) imports
    no sympy (symbolic work is for derivations and user expressions); checked in a fresh interpreter."""
    robot = PACKAGE.parent / "examples" / "seed000_test1.toml"
    assert _modules_after_cli(["dgp", str(robot), "--json"], '"complete": true',
                              "m == 'sympy' or m.startswith('sympy.')", 600) == "[]"


def test_numeric_igp_path_runs_without_sympy():
    """The IGP with assigned position (CLI, Table 3 of seed 004, certificates included) imports no sympy either:
    sympy is for the exact determinant and exact input only (it cost ~0.3 s of a ~1.2 s run)."""
    robot = PACKAGE.parent / "examples" / "seed004_table3.toml"
    assert _modules_after_cli(["igp", str(robot), "--position", "7", "9", "1", "--json"], '"certified": true',
                              "m == 'sympy' or m.startswith('sympy.')", 300) == "[]"


def test_help_imports_neither_numpy_nor_the_library():
    """Issue 19 item 5 (``cdpr --help`` <= 0.2 s): building the parser of every command imports no numpy (about
    60-80 ms of the 0.16 s it took) and none of the numeric layers; checked in a fresh interpreter."""
    select = ("m.split('.')[0] in ('numpy', 'sympy', 'numba', 'scipy') "
              "or (m.startswith('cdpr_algebra.') and m.split('.')[1] not in ('cli', 'model'))")
    assert _modules_after_cli(["--help"], "dgp", select, 120) == "[]"
