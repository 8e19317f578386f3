"""Per-update time of the equilibrium tracking (cdpr_algebra.track) and a whole tracking run.

    python -m benchmarks.bench_track [--updates 200] [--repeat 3]

* Real time: on Berti et al. 2016 Test 3 (MARIONET-VR, 6 cables), from its stable equilibrium of lowest potential,
  one update = new lengths (a small change of every cable) -> the updated equilibrium by the tracker's step
  (linear predictor, Newton on the taut set's equations) with its stability check (lowest eigenvalue of the reduced
  Hessian; empty for six independent taut cables) and event functions.  Issue goal: <= 50 microseconds per update
  between events.  Also Test 1 (3 taut cables, a 3 x 3 reduced Hessian).
* Whole run: Test 1's robot paying out cable 1 from 7.5 to 14 and back (one slack and one taut event, 21 samples).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT)]

import numpy as np  # noqa: E402

from cdpr_algebra.model.robot import load_robot  # noqa: E402
from cdpr_algebra.track import follow  # noqa: E402
from cdpr_algebra.track.trajectory import LengthTrajectory  # noqa: E402
from timing import machine, run_times, spread  # noqa: E402


def updates(robot, n_updates: int):
    rho0 = robot.lengths.copy()
    st = follow._start_state(robot, rho0, 0.0, None)
    rng = np.random.default_rng(1)
    direction = rng.normal(size=robot.n)
    direction *= 1e-3 * robot.size / np.abs(direction).max()  # 0.1 % of the robot's size over the whole run
    traj = LengthTrajectory(np.array([0.0, 1.0]), np.array([rho0, rho0 + direction]))
    ts = np.linspace(0, 1, n_updates + 1)[1:]
    per = []
    cur = st
    for t in ts:
        t0 = time.perf_counter()
        r = follow._step(robot, traj, cur, float(t))
        if r is None:
            raise RuntimeError("a step failed: the benchmark's trajectory is meant to have no event")
        nxt = r[0]
        follow._crossed(robot, cur, nxt)
        per.append(time.perf_counter() - t0)
        cur = nxt
    return per, st


def update_medians(robot, n_updates: int, repeat: int):
    """The median time of one update in each of ``repeat`` runs (after a warm-up run for the compiled kernels)."""
    updates(robot, 10)
    meds = []
    for _ in range(repeat):
        per, st = updates(robot, n_updates)
        meds.append(statistics.median(per))
    return meds, st


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--updates", type=int, default=200)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    print(machine())
    robot = load_robot(ROOT / "examples" / "seed000_test3.toml")
    meds, st = update_medians(robot, a.updates, a.repeat)
    print(f"Test 3 (MARIONET-VR), taut set {list(st.taut)}: one update (predictor, Newton, stability, events): "
          f"{spread(meds, 'us', 1e6)} of the per-update medians over {a.updates} updates; goal <= 50 us")
    r1 = load_robot(ROOT / "examples" / "seed000_test1.toml")
    meds1, st1 = update_medians(r1, a.updates, a.repeat)
    print(f"Test 1 (3 cables), taut set {list(st1.taut)}: one update, the reduced Hessian's eigenvalues included: "
          f"{spread(meds1, 'us', 1e6)}")
    rho0 = r1.lengths.copy()
    rho1 = rho0.copy()
    rho1[0] = 14.0
    traj = LengthTrajectory(np.array([0.0, 1.0, 2.0]), np.array([rho0, rho1, rho0]))
    start = follow._start_state(r1, rho0, 0.0, None)
    times = run_times(lambda: follow.track(r1, traj, np.linspace(0, 2, 21), start=start), a.repeat)
    res = follow.track(r1, traj, np.linspace(0, 2, 21), start=start)
    print(f"Test 1 pay out cable 1 to 14 and back (21 samples, events {[e.kind for e in res.events]}, "
          f"{res.newton_steps} Newton iterations): {spread(times)}")


if __name__ == "__main__":
    main()
