"""Sweep throughput on dask.distributed: Test 1's DGP (Berti et al. 2016) over a grid of rho_1, on 1 and 2 local
worker processes, and the per-task overhead of the cluster.

    python -m benchmarks.bench_sweep [--points 24] [--batch 8]

Throughput counts grid points solved per second once the cluster is up (its start-up is printed separately); the
first task of every worker also loads the compiled kernels and the stored generic solution sets.
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT)]

from cdpr_algebra.model.robot import load_robot  # noqa: E402
from cdpr_algebra.sweep.grid import make_grid  # noqa: E402
from cdpr_algebra.sweep.run import run_sweep  # noqa: E402
from timing import machine  # noqa: E402


def _noop(x):
    return x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=24)
    ap.add_argument("--batch", type=int, default=None, help="points per task (default: the sweep's rule)")
    a = ap.parse_args()
    print(machine())
    from dask.distributed import Client, LocalCluster

    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    grid = make_grid(robot, [f"rho1=7.5:9.5:{a.points}"])
    for workers in (1, 2):
        t0 = time.perf_counter()
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0") as cl:
            with Client(cl) as client:
                up = time.perf_counter() - t0
                client.run(lambda: __import__("cdpr_algebra.dgp.solve"))  # imports, not the kernels
                tmp = Path(tempfile.mkdtemp())
                try:
                    t1 = time.perf_counter()
                    res = run_sweep(robot, grid, tmp / "s", scheduler=cl.scheduler_address, batch=a.batch,
                                    progress=False)
                    dt = time.perf_counter() - t1
                    t2 = time.perf_counter()
                    res2 = run_sweep(robot, grid, tmp / "s2", scheduler=cl.scheduler_address, batch=a.batch,
                                     progress=False)
                    dt2 = time.perf_counter() - t2
                finally:
                    shutil.rmtree(tmp)
                n = 400
                t3 = time.perf_counter()
                client.gather(client.map(_noop, range(n), pure=False))
                per_task = (time.perf_counter() - t3) / n
        print(f"{workers} worker(s): cluster up in {up:.2f} s; {res.solved} points (certified DGP, tasks of "
              f"{a.batch or 'the default size'}) in {dt:.2f} s = {res.solved / dt:.2f} points/s on the first sweep (kernels loaded by "
              f"the first tasks), {res2.solved / dt2:.2f} points/s on a second; per-task overhead "
              f"{per_task * 1e3:.2f} ms ({n} empty tasks)")


if __name__ == "__main__":
    main()
