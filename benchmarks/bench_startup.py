"""Where the whole ``cdpr dgp`` process of a robot spends its time (issue 19, item 5: Test 1's process, goal 0.5 s).

    python -m benchmarks.bench_startup [--robot examples/seed000_test1.toml] [--runs 5]

Each run is a fresh interpreter (as ``python -m cdpr_algebra dgp ROBOT``, no shell or pyenv shim in front, ending as
the console script does, :func:`cdpr_algebra.cli.main.exit_now`; ``--plain-exit``: with the interpreter's teardown)
that records the wall time of: the interpreter's start up to our first line, ``import numpy``, ``import numba``, the
command-line module, the DGP's kernel module (which loads the compiled kernels that carry a signature), and the
command itself (the solve, the loading of the other kernels on first use, the report). numba's loads of cached
kernels are counted apart (``numba.core.caching.Cache.load_overload``): the first of them also initializes numba's
CPU target (and imports scipy.linalg for numba's linear algebra), a cost paid once per process whatever is loaded.
Printed: the median of each part over ``--runs`` runs, and the median whole-process time measured from outside.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks")]

from timing import machine  # noqa: E402

# the child: times each part, writes one JSON line on stderr (stdout is the command's)
CHILD = r"""
import time, sys, json
marks = {}
t = time.perf_counter(); import numpy; marks['numpy'] = time.perf_counter() - t
t = time.perf_counter(); import numba.core.caching as _c; marks['numba'] = time.perf_counter() - t
loads = []
_orig = _c.Cache.load_overload
def _load(self, sig, ctx):
    t = time.perf_counter()
    r = _orig(self, sig, ctx)
    loads.append(time.perf_counter() - t)
    return r
_c.Cache.load_overload = _load
t = time.perf_counter(); import cdpr_algebra.cli.main as M; marks['command-line module'] = time.perf_counter() - t
n0 = len(loads)
t = time.perf_counter(); import cdpr_algebra.dgp.kernels; marks['kernel module'] = time.perf_counter() - t
n1 = len(loads)
t = time.perf_counter()
try:
    code = M.main(sys.argv[1:])
except SystemExit as e:
    code = e.code
marks['command'] = time.perf_counter() - t
marks['first kernel load (numba start)'] = loads[0] if loads else 0.0
marks['other kernel loads'] = sum(loads[1:])
marks['kernels loaded'] = len(loads)
marks['exit status'] = code
sys.stderr.write('BENCH ' + json.dumps(marks) + '\n')
if hasattr(M, 'exit_now') and EXIT_NOW:
    M.exit_now(code)  # as the console script ends (cli.main.console)
"""


def one_run(robot: str, plain_exit: bool = False) -> tuple[float, dict]:
    t = time.perf_counter()
    child = CHILD.replace("EXIT_NOW", str(not plain_exit))
    out = subprocess.run([sys.executable, "-c", child, "dgp", robot], capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - t
    line = [x for x in out.stderr.splitlines() if x.startswith("BENCH ")]
    if not line:
        raise SystemExit(f"bench_startup: the child failed (exit {out.returncode}):\n{out.stderr[-2000:]}")
    return wall, json.loads(line[-1][6:])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--robot", default="examples/seed000_test1.toml")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--plain-exit", action="store_true",
                    help="end the child with the interpreter's teardown (sys.exit), not as the console script does")
    a = ap.parse_args(argv)
    print(machine())
    one_run(a.robot)  # warm: the first run after an edit may compile
    runs = [one_run(a.robot, a.plain_exit) for _ in range(a.runs)]
    walls = [w for w, _ in runs]
    print(f"{a.robot}: whole process median {statistics.median(walls):.3f} s (min {min(walls):.3f}, max "
          f"{max(walls):.3f}, {len(walls)} runs; `python -m cdpr_algebra dgp`, no shim); parts, medians:")
    keys = ["numpy", "numba", "command-line module", "kernel module", "command", "first kernel load (numba start)",
            "other kernel loads"]
    for k in keys:
        print(f"  {k:34s} {statistics.median(m[k] for _, m in runs):.3f} s")
    inside = statistics.median(sum(m[k] for k in keys[:5]) for _, m in runs)
    print(f"  {'interpreter start and exit':34s} {statistics.median(walls) - inside:.3f} s (the rest)")
    print(f"  kernels loaded from numba's cache: {runs[0][1]['kernels loaded']} (their loads are inside the kernel "
          f"module and the command); exit status {runs[0][1]['exit status']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
