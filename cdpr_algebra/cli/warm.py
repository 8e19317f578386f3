"""``cdpr warm``: compile and cache the numeric kernels now (issue 19 item 5, cold start).

    cdpr warm ROBOT [ROBOT ...]

numba compiles the kernels (tracker, DGP evaluators, interval contractors, equilibrium tracking) on first use and
caches them next to the package's sources, keyed by the sources' contents, the numba version and the CPU; a first
run would otherwise spend 10-15 s compiling.  This command solves each robot once -- the homotopy DGP, the interval
branch and prune (cables m <= 3) and a short equilibrium tracking -- and loads the kernel of the IGP's
certificates, so that every later run loads the kernels.
``pip install .`` runs it at build time on ``examples/seed000_test1.toml`` (``setup.py``); run it yourself where the
package was built on another machine (a wheel from elsewhere: another CPU means other machine code) or in an image.
"""

from __future__ import annotations

import time

from cdpr_algebra.model.errors import CdprInputError


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("warm", help="compile and cache the numeric kernels by solving the given robots once")
    p.add_argument("robots", nargs="+", metavar="ROBOT", help="robot files (.json or .toml) to solve")


def warm_kernels(robot) -> dict:
    """Solve ``robot`` once by every numeric path that has compiled kernels; seconds per path."""
    import numpy as np

    from cdpr_algebra.bp.search import interval_dgp
    from cdpr_algebra.dgp.solve import dgp
    from cdpr_algebra.dgp.study_retrack import warm_study_kernels
    from cdpr_algebra.dgp.taut_system import fast_family
    from cdpr_algebra.track.follow import track
    from cdpr_algebra.track.trajectory import straight

    if robot.lengths is None:
        raise CdprInputError("lengths", "the robot file needs cable lengths to be solved")
    seconds = {}
    t0 = time.perf_counter()
    dgp(robot, jobs=1)
    warm_study_kernels()  # the re-tracking of failed paths, which a robot without them never reaches
    import cdpr_algebra.generated.taut_equations_dd  # noqa: F401  dgp.taut_extended's evaluator (compiled when imported)
    import cdpr_algebra.intervals.real_kernels  # noqa: F401  the IGP's certificates (compiled when imported)
    import cdpr_algebra.igp.polish_kernel  # noqa: F401  the IGP's Gauss-Newton polish (compiled when imported)
    fam = fast_family(2)  # dF/dp of the taut family (monodromy, trace tests), which the DGP's compiled tracker skips
    fam.evaluate_all(np.ones(fam.n, dtype=complex), np.ones(fam.m, dtype=complex))
    seconds["dgp"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    interval_dgp(robot, max_m=3)
    seconds["interval"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    rho = np.asarray(robot.lengths, dtype=float)
    track(robot, straight(rho, 1.001 * rho, robot.n))
    seconds["track"] = time.perf_counter() - t0
    return seconds


def run(args) -> int:
    from cdpr_algebra.model.robot import load_robot

    for path in args.robots:
        robot = load_robot(path)
        seconds = warm_kernels(robot)
        print(f"{path}: " + ", ".join(f"{k} {v:.1f} s" for k, v in seconds.items()))
    return 0
