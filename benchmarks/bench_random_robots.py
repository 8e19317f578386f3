"""The whole DGP on random robots: how often is it complete, how long does it take.  Run by hand:

    python -m benchmarks.bench_random_robots --seeds 0 40 [--jobs 1] [--json] [--designed] [--write DIR]

Robot ``seed``: 3..6 cables (numpy's ``default_rng(seed)``); three kinds of frames in turn (seed mod 3: exit points at
a height of 4.5-5.5 m over a 10 m square, anywhere in an 8 m cube, on a circle of radius 4 m at heights 3-5 m),
platform anchors in a 1 x 1 x 0.5 m box, the centre of mass near the platform's origin, load along -z; cable lengths
those of a random pose (position within 1 m, rotation vector ~ 0.3 rad), half of them lengthened by up to 8 % (slack
cables).  None of these robots is in the tests' or examples' tuning: they are the robots nobody chose.  One line per
robot (complete or not, outcomes, admissible equilibria, incomplete sets, seconds), then a summary.

``--designed``: the robots people draw instead (:func:`designed_robot`): a regular polygon of exit points and a
platform polygon, similar to it or not, G on the axis or off it, every coordinate printed to 6 decimals as a robot
file would hold it.  Symmetry and similarity make taut sets special members of their families (limits at infinity,
huge roots); this is where the DGP is weakest (README, "Known limit").

``--write DIR``: write the robots as robot files (``DIR/random<seed>.json``, ``DIR/designed<seed>.json``) for
``cdpr`` and stop, e.g. ``cdpr dgp DIR/designed1.json --settle``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from cdpr_algebra import Robot, solve_dgp  # noqa: E402


def pose_lengths(rng, base, platform, spin: float, slack: float) -> np.ndarray:
    """Cable lengths of a random pose (position within 1 m of the origin, 0 to 2 m up; rotation vector ~ ``spin``
    rad), half of the cables lengthened by up to ``slack`` (slack cables)."""
    from scipy.spatial.transform import Rotation

    n = len(base)
    position = np.r_[rng.uniform(-1, 1, 2), rng.uniform(0, 2)]
    R = Rotation.from_rotvec(rng.normal(size=3) * spin).as_matrix()
    d = np.linalg.norm(base - (position + platform @ R.T), axis=1)
    return d * (1 + rng.uniform(0, slack, n) * (rng.uniform(size=n) < 0.5))


def random_robot(seed: int) -> Robot:
    """The robot ``seed`` of the module doc."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 7))
    kind = seed % 3
    if kind == 0:
        base = np.c_[rng.uniform(-5, 5, (n, 2)), rng.uniform(4.5, 5.5, n)]
    elif kind == 1:
        base = rng.uniform(-4, 4, (n, 3))
        base[:, 2] += 4
    else:
        a = np.sort(rng.uniform(0, 2 * np.pi, n))
        base = np.c_[4 * np.cos(a), 4 * np.sin(a), rng.uniform(3, 5, n)]
    platform = rng.uniform(-0.5, 0.5, (n, 3)) * [1, 1, 0.5]
    com = rng.uniform(-0.2, 0.2, 3) - [0, 0, 0.3 * rng.uniform()]
    lengths = pose_lengths(rng, base, platform, 0.3, 0.08)
    return Robot(base=base, platform=platform, com=com, load=1.0, lengths=lengths, name=f"random{seed}")


DESIGNS = ("similar", "similar, turned 0.3 rad", "stretched 1.2 along x", "similar, G off the axis")


def designed_robot(seed: int) -> Robot:
    """The designed robot ``seed`` (module doc): k = 3 + seed % 4 cables on a regular k-gon of radius 5 m at a height
    of 5 m; the platform a k-gon of radius 0.5 m, ``DESIGNS[(seed // 4) % 4]``; G 0.3 m below the platform (on its
    axis except in the last design); lengths those of a random pose (``default_rng(seed)``), some cables slack by up
    to 5 %; every number rounded to 6 decimals."""
    rng = np.random.default_rng(seed)
    k = 3 + seed % 4
    design = (seed // 4) % 4
    a = np.arange(k) * 2 * np.pi / k + np.pi / k
    base = np.c_[5 * np.cos(a), 5 * np.sin(a), np.full(k, 5.0)]
    turn = 0.3 if design == 1 else 0.0
    platform = np.c_[0.5 * np.cos(a + turn), 0.5 * np.sin(a + turn), np.zeros(k)]
    if design == 2:
        platform[:, 0] *= 1.2
    com = np.array([0.05, -0.03, -0.3]) if design == 3 else np.array([0.0, 0.0, -0.3])
    base, platform = base.round(6), platform.round(6)
    lengths = pose_lengths(rng, base, platform, 0.2, 0.05).round(6)
    return Robot(base=base, platform=platform, com=com, load=1.0, lengths=lengths,
                 name=f"designed{seed} ({k} cables, {DESIGNS[design]})")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, nargs=2, default=(0, 40), metavar=("FIRST", "STOP"))
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--json", action="store_true", help="one JSON object per robot")
    ap.add_argument("--designed", action="store_true", help="the designed robots (designed_robot) instead")
    ap.add_argument("--write", type=Path, default=None, metavar="DIR", help="write the robot files to DIR and stop")
    args = ap.parse_args(argv)
    if args.write is not None:
        args.write.mkdir(parents=True, exist_ok=True)
        for seed in range(*args.seeds):
            robot = designed_robot(seed) if args.designed else random_robot(seed)
            path = args.write / f"{'designed' if args.designed else 'random'}{seed}.json"
            path.write_text(json.dumps(robot.to_dict(), indent=1) + "\n")
            print(path)
        return 0
    times, incomplete = [], []
    for seed in range(*args.seeds):
        robot = designed_robot(seed) if args.designed else random_robot(seed)
        t0 = time.perf_counter()
        res = solve_dgp(robot, jobs=args.jobs)
        dt = time.perf_counter() - t0
        times.append(dt)
        line = dict(seed=seed, cables=robot.n, complete=res.complete, outcomes=res.outcomes(),
                    admissible=len(res.solutions), incomplete=[list(s.taut) for s in res.incomplete],
                    seconds=round(dt, 2))
        if not res.complete:
            incomplete.append(seed)
        print(json.dumps(line) if args.json else
              f"seed {seed}{' (' + DESIGNS[(seed // 4) % 4] + ')' if args.designed else ''}: {robot.n} cables, {res.status}, {res.outcomes()}, {len(res.solutions)} admissible, "
              f"incomplete sets {line['incomplete']}, {dt:.2f} s", flush=True)
    print(f"{len(times)} robots: {len(times) - len(incomplete)} complete, incomplete: seeds {incomplete}; "
          f"median {np.median(times):.2f} s, max {np.max(times):.2f} s, total {np.sum(times):.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
