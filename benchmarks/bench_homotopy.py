"""Benchmark of the homotopy engine (issue #3): paths, solutions, wall time, paths per second.

    python -m benchmarks.bench_homotopy [--runs 5] [--phc] [--regenerate]

Systems: Katsura-5 and -6 (total degree), cyclic-5 (total degree, 50 paths at infinity), and the
3-cable DGP of seed 000 Test 1 (12 quadrics, 156 generic solutions) by a parameter homotopy from
the stored generic complex instance ``cdpr_algebra/data/dgp3_generic.json`` to the robot data of
``examples/seed000_test1.toml``; its 6 real solutions with non-negative tensions are checked against
Table 1 (``tests/data/seed000_tables.json``, with the erratum x_O' = 2.751 of configuration 1).
Times are median, min and max of ``--runs`` runs (compilation excluded: systems are compiled once).

``--phc`` also runs PHCpack's blackbox (``phc -b``) on every system if ``phc`` is installed (Debian package
``phcpack``); ``--bertini PYTHON`` runs Bertini 2 (PyPI package ``bertini``, total-degree start, Cauchy
endgame, double precision) with that interpreter (e.g. a venv with ``pip install bertini``) on every system;
``--peer-dgp`` includes the DGP for the peers (slow: PHCpack tracks 1984 paths, Bertini 4096). Peer endpoints
are counted only after our own evaluation of the equations confirms them (residual <= 1e-8 relative):
Bertini's parser is known to misread a leading "- " (../shared/PEERS.md), so equations are written with
every term in parentheses. ``--regenerate`` runs derivations/solve_generic_dgp3.py (monodromy, about 1.5
minutes) and rewrites the data file.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "derivations"))
sys.path.insert(0, str(ROOT / "benchmarks"))

from cdpr_algebra.model.robot import load_robot  # noqa: E402
from cdpr_algebra.homotopy import SolveOptions, TrackerOptions, solve, solve_parameter_homotopy  # noqa: E402
from timing import machine  # noqa: E402
from cdpr_algebra.dgp.anchor_points import dgp3_family, dgp3_parameters, dgp3_poses  # noqa: E402
from cdpr_algebra.homotopy.families import cyclic, katsura  # noqa: E402
from cdpr_algebra.homotopy.monodromy import load_instance  # noqa: E402

DATA = ROOT / "cdpr_algebra" / "data" / "dgp3_generic.json"
ROBOT = ROOT / "examples" / "seed000_test1.toml"
# Parameter homotopies from a generic instance: every target path is nonsingular, so a looser
# predictor tolerance is safe (the path-jumping check re-tracks any duplicate endpoint).
FAST = SolveOptions(tracker=TrackerOptions(predictor_tol=1e-4))


def dgp_family():
    return dgp3_family()


def timed(fn, runs):
    ts, out = [], None
    for _ in range(runs):
        t = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts), out, ts


def table1_check(robot, result):
    rows = json.loads((ROOT / "tests/data/seed000_tables.json").read_text())["tables"]["1"]["rows"]
    X = np.array([s.x for s in result.solutions if s.is_real(1e-8) and not s.singular]).real
    adm = X[np.all(X[:, 9:] >= 0, axis=1)] if len(X) else X
    poses = dgp3_poses(robot, adm)
    matched = 0
    for row in rows:
        d = [np.max(np.abs(p["position"] - np.array(row["position"]))) for p in poses]
        matched += bool(d) and min(d) <= 5e-3
    return len(X), len(adm), matched, len(rows)


def phc_run(S, p, timeout=600):
    phc = shutil.which("phc")
    if not phc:
        return None
    _, eqs = _peer_equations(S, p)
    lines = [f"{S.neq} {S.n}"] + [e + ";" for e in eqs]
    with tempfile.TemporaryDirectory() as d:
        inp, outp = Path(d) / "in.phc", Path(d) / "out.phc"
        inp.write_text("\n".join(lines) + "\n")
        t = time.perf_counter()
        try:
            subprocess.run([phc, "-b", str(inp), str(outp)], cwd=d, capture_output=True, timeout=timeout, check=False)
        except subprocess.TimeoutExpired:
            return {"wall": time.perf_counter() - t, "paths": None, "regular": None, "real": None, "timeout": True}
        wall = time.perf_counter() - t
        text = outp.read_text(errors="replace") if outp.exists() else ""
    m = re.search(r"mixed volume\s*:\s*(\d+)", text)
    paths = int(m.group(1)) if m else None
    return {"wall": wall, "paths": paths, "regular": len(re.findall(r"regular ==", text)),
            "real": len(re.findall(r"real regular ==", text)), "timeout": False,
            "solutions": phc_regular_solutions(text, S.n)}


def phc_regular_solutions(text, n):
    """The regular solutions of a ``phc -b`` output file, as rows (x1 .. xn) of a complex array."""
    rows = []
    for block in re.split(r"\nsolution \d+ :", text):
        if not re.search(r"= (real|complex) regular ==", block):
            continue
        vals = {k: complex(float(a), float(b)) for k, a, b in re.findall(r"\n (x\d+) :\s+(\S+)\s+(\S+)", block)}
        if len(vals) == n:
            rows.append([vals[f"x{i + 1}"] for i in range(n)])
    return np.array(rows, dtype=complex).reshape(-1, n)


def _peer_equations(S, p, power="^"):
    """Equations with parameters substituted, every term in parentheses (no leading unary minus)."""
    names = [sp.Symbol(f"x{i + 1}") for i in range(S.n)]
    sub = dict(zip(S.variables, names))
    sub.update({s: sp.Float(float(np.real(v)), 17) for s, v in zip(S.parameters, p)})
    out = []
    for e in S.equations:
        terms = sp.Add.make_args(sp.expand(e.xreplace(sub)))
        out.append(" + ".join("(" + str(t).replace("**", power) + ")" for t in terms))
    return [str(n) for n in names], out


_BERTINI_SCRIPT = r"""
import json, sys, time
import re
import bertini
d = json.load(sys.stdin)
# Bertini 2's parser stops at multi-digit names (x10, f10: "more than one affine variable group"): letters only
def letters(k):
    s = ""
    while True:
        s = chr(97 + k % 26) + s
        k = k // 26 - 1
        if k < 0:
            return s
vs = ["v" + letters(i) for i in range(len(d["vars"]))]
fs = ["f" + letters(i) for i in range(len(d["eqs"]))]
idx = {v: i for i, v in enumerate(d["vars"])}
eqs = [re.sub(r"\b[A-Za-z_]\w*\b", lambda m: vs[idx[m.group(0)]] if m.group(0) in idx else m.group(0), e) for e in d["eqs"]]
text = "variable_group " + ", ".join(vs) + "; function " + ", ".join(fs) + "; "
text += " ".join(f"{f} = {e};" for f, e in zip(fs, eqs))
t = time.perf_counter()
alg = bertini.nag_algorithm.ZeroDimCauchyDoublePrecisionTotalDegree(bertini.parse.system(text))
alg.solve()
wall = time.perf_counter() - t
sols = [[[complex(z).real, complex(z).imag] for z in (s[i] for i in range(len(d["vars"]) + 1))] for s in alg.solutions()]
print(json.dumps({"wall": wall, "solutions": sols}))
"""


def bertini_run(S, p, python, timeout=1800):
    """Bertini 2 on F(x; p) = 0 in another interpreter; finite endpoints verified with our evaluator."""
    names, eqs = _peer_equations(S, p)
    try:
        proc = subprocess.run([python, "-c", _BERTINI_SCRIPT], input=json.dumps({"vars": names, "eqs": eqs}),
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"wall": timeout, "paths": None, "finite": None, "timeout": True}
    if proc.returncode != 0:
        return {"error": proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "failed"}
    out = json.loads(proc.stdout)
    Y = np.array([[complex(a, b) for a, b in s] for s in out["solutions"]])
    finite = np.abs(Y[:, 0]) > 1e-8 * np.abs(Y).max(axis=1)
    X = Y[finite, 1:] / Y[finite, :1]
    F = S.evaluate(X, np.asarray(p, dtype=complex)) if len(X) else np.zeros((0, S.neq))
    ok = np.max(np.abs(F), axis=1) <= 1e-8 * (1 + np.max(np.abs(X), axis=1)) if len(X) else np.zeros(0, bool)
    distinct = 0
    kept = []
    for x in X[ok]:
        if not any(np.max(np.abs(x - k)) <= 1e-6 * (1 + np.max(np.abs(x))) for k in kept):
            kept.append(x)
            distinct += 1
    return {"wall": out["wall"], "paths": len(Y), "finite": distinct, "timeout": False}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--phc", action="store_true", help="also run PHCpack's blackbox (phc -b) on the systems")
    ap.add_argument("--bertini", metavar="PYTHON", help="also run Bertini 2 with this interpreter (has 'bertini')")
    ap.add_argument("--peer-dgp", action="store_true", help="include the DGP for the peers (minutes)")
    ap.add_argument("--regenerate", action="store_true", help="recompute the generic DGP instance by monodromy")
    args = ap.parse_args(argv)
    if args.regenerate or not DATA.exists():
        from solve_generic_dgp3 import regenerate  # derivations/

        regenerate()
    rows = []
    peer_systems = []
    for name, S in (("katsura5", katsura(5)), ("katsura6", katsura(6)), ("cyclic5", cyclic(5))):
        solve(S, seed=0)  # compile
        wall, r, ts = timed(lambda: solve(S, seed=0), args.runs)
        s = r.summary()
        rows.append((name, "total degree", s.paths, f"{len(r.nonsingular)} (+{s.at_infinity} at inf)", wall, ts))
        peer_systems.append((name, S, np.zeros(0)))
    S = dgp3_family()
    p1, X1, _ = load_instance(DATA, S)
    robot = load_robot(ROBOT)
    p0 = dgp3_parameters(robot)
    solve_parameter_homotopy(S, p1, X1[:2], p0)  # compile
    wall, r, ts = timed(lambda: solve_parameter_homotopy(S, p1, X1, p0, seed=0, options=FAST), args.runs)
    s = r.summary()
    rows.append(("DGP seed000 Test 1", "parameter (stored generic)", s.paths, f"{len(r.nonsingular)} ({s.failed} failed)",
                 wall, ts))
    if args.peer_dgp:
        peer_systems.append(("DGP seed000 Test 1", S, p0))
    nreal, nadm, matched, nrows = table1_check(robot, r)
    print(machine())
    print(f"{'system':<20} {'homotopy':<28} {'paths':>6} {'solutions':>22} {'median s':>9} {'min s':>7} {'max s':>7} "
          f"{'paths/s':>9}")
    for name, kind, paths, sols, w, ts in rows:
        print(f"{name:<20} {kind:<28} {paths:>6} {sols:>22} {w:>9.3f} {min(ts):>7.3f} {max(ts):>7.3f} {paths / w:>9.0f}")
    print(f"DGP: {nreal} real, {nadm} with tensions >= 0; Table 1 poses matched: {matched}/{nrows}; "
          f"median of {args.runs} runs; target <= 0.5 s: {'met' if rows[-1][4] <= 0.5 else 'NOT met'}")
    for name, S, p in peer_systems if (args.phc or args.bertini) else ():
        if args.phc:
            res = phc_run(S, p)
            if res is None:
                print(f"{name:<20} phc: not installed (apt-get install -y phcpack); skipped")
            else:
                print(f"{name:<20} phc -b (PHCpack blackbox): mixed volume {res['paths']}, regular {res['regular']}, "
                      f"real regular {res['real']}, wall {res['wall']:.1f} s{' (TIMEOUT)' if res['timeout'] else ''}")
        if args.bertini:
            res = bertini_run(S, p, args.bertini)
            if "error" in res:
                print(f"{name:<20} Bertini 2: {res['error']}")
            else:
                print(f"{name:<20} Bertini 2 (total degree, double precision): paths {res['paths']}, distinct finite "
                      f"verified {res['finite']}, wall {res['wall']:.1f} s{' (TIMEOUT)' if res['timeout'] else ''}")


if __name__ == "__main__":
    main()
