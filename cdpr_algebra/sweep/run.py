"""Run a sweep on dask.distributed and write its results as Parquet datasets, resumably.

* Execution: a ``LocalCluster`` of worker processes on this machine (``workers``, default all cores, one thread
  each: the solvers are numeric and the GIL would serialize threads), or an existing cluster by scheduler address /
  scheduler file.  Grid points are batched into tasks (``batch`` points each; by default up to DEFAULT_BATCH, and
  at least TASKS_PER_WORKER tasks per worker; the cluster's per-task overhead is ~2-3 ms, measured by
  ``benchmarks/bench_sweep.py``); every task is submitted with retries, so a worker that dies loses no point.
* Output in ``DIR``: ``sweep.json`` (robot, grid, kind: a rerun must ask for the same sweep), ``points/part-*.parquet``
  (one row per grid point: the varied values, ``n_admissible``, ``n_stable``, ``failed_paths``, ``complete``,
  ``min_tension``, ``seconds``, ``error``) and ``equilibria/part-*.parquet`` (one row per equilibrium: the varied
  values, ``taut``, ``x``, ``y``, ``z``, angles, tensions, ``stable``, ``certified``).  Each finished task is written
  at once (an interrupted sweep keeps it), and rerunning the same command skips the points already written.
"""

from __future__ import annotations

import json
import sys
import time
import uuid
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cdpr_algebra.model.errors import CdprInputError

from .grid import Grid
from .tasks import solve_batch

WAIT_FOR_WORKERS = 60  # seconds to wait for a first worker on an existing cluster
DEFAULT_BATCH = {"dgp": 8, "igp": 32, "cc": 4}  # largest points per task by default (tasks of a few seconds)
TASKS_PER_WORKER = 4


@dataclass(frozen=True)
class SweepResult:
    """What a run did: points in the grid, done before (resumed), solved now, with errors, incomplete; the output
    directory and the time taken."""

    out: Path
    total: int
    resumed: int
    solved: int
    errors: int
    incomplete: int
    seconds: float
    workers: int
    dashboard: str | None

    @property
    def status(self) -> str:
        return "complete" if self.errors == 0 and self.incomplete == 0 else "incomplete"

    def to_dict(self) -> dict:
        return {"status": self.status, "out": str(self.out), "points": self.total, "resumed": self.resumed,
                "solved": self.solved, "errors": self.errors, "incomplete": self.incomplete,
                "seconds": self.seconds, "workers": self.workers, "dashboard": self.dashboard}


def _robot_dict(robot) -> dict:
    return {"name": robot.name, "base": robot.base.tolist(), "platform": robot.platform.tolist(),
            "com": robot.com.tolist(), "load": robot.load, "load_direction": robot.load_direction.tolist(),
            "lengths": None if robot.lengths is None else robot.lengths.tolist()}


def read_table(out, name: str):
    """A pyarrow Table of ``points`` or ``equilibria`` (all part files), or None when there is none yet."""
    import pyarrow.parquet as pq

    d = Path(out) / name
    parts = sorted(d.glob("part-*.parquet")) if d.is_dir() else []
    if not parts:
        return None
    import pyarrow as pa

    return pa.concat_tables([pq.read_table(p) for p in parts], promote_options="permissive")


def _write(out: Path, name: str, rows: list) -> None:
    if not rows:
        return
    import pyarrow as pa
    import pyarrow.parquet as pq

    d = out / name
    d.mkdir(parents=True, exist_ok=True)
    tmp = d / f".tmp-{uuid.uuid4().hex}.parquet"
    pq.write_table(pa.Table.from_pylist(rows), tmp)
    tmp.rename(d / f"part-{time.strftime('%Y%m%d%H%M%S')}-{uuid.uuid4().hex[:8]}.parquet")  # atomic


def _check_same_sweep(out: Path, header: dict) -> None:
    f = out / "sweep.json"
    if f.exists():
        old = json.loads(f.read_text(encoding="utf-8"))
        if old != header:
            raise CdprInputError("--out", f"{out} holds another sweep (robot, grid, kind or certification differ): "
                                 "use another directory")
    else:
        out.mkdir(parents=True, exist_ok=True)
        f.write_text(json.dumps(header, indent=1), encoding="utf-8")


def _client(scheduler, workers):
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            if str(scheduler).endswith(".json"):
                client = Client(scheduler_file=str(scheduler), timeout="20s")
            else:
                client = Client(str(scheduler), timeout="20s")
        except (OSError, TimeoutError, ValueError) as err:
            raise CdprInputError("--scheduler", f"cannot connect to {scheduler}: {err}") from None
        try:
            client.wait_for_workers(1, timeout=WAIT_FOR_WORKERS)
        except (TimeoutError, OSError):
            client.close()
            raise CdprInputError("--scheduler", f"no worker joined {scheduler} within {WAIT_FOR_WORKERS} s") from None
        return client, None
    import os

    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0")
    return Client(cluster), cluster


def run_sweep(robot, grid: Grid, out, scheduler=None, workers: int | None = None, batch: int | None = None,
              certify: bool = True, progress: bool = True) -> SweepResult:
    """Solve every grid point not yet in ``out`` (module doc)."""
    t0 = time.perf_counter()
    out = Path(out)
    header = {"robot": _robot_dict(robot), "grid": grid.to_dict(), "certify": bool(certify), "version": 1}
    _check_same_sweep(out, header)
    done_table = read_table(out, "points")
    done = set() if done_table is None else set(done_table.column("point").to_pylist())
    todo = [(k, v) for k, v in grid.points() if k not in done]
    if batch is not None and batch < 1:
        raise CdprInputError("--batch", f"expected >= 1 points per task, got {batch}")
    errors = incomplete = 0
    dashboard = None
    nworkers = 0
    if todo:
        client, cluster = _client(scheduler, workers)
        try:
            dashboard = client.dashboard_link
            nworkers = len(client.scheduler_info().get("workers", {}))
            # tasks of DEFAULT_BATCH points, but at least TASKS_PER_WORKER tasks per worker (load balance; the
            # per-task overhead is ~2-3 ms against ~0.4 s per DGP point, benchmarks/bench_sweep.py)
            size = batch or max(1, min(DEFAULT_BATCH[grid.kind], -(-len(todo) // (TASKS_PER_WORKER * max(nworkers, 1)))))
            batches = [todo[i:i + size] for i in range(0, len(todo), size)]
            if progress:
                print(f"cdpr sweep: {len(todo)} of {grid.size} points to solve ({len(done)} done before), "
                      f"{len(batches)} tasks on {nworkers} workers; dashboard {dashboard}", file=sys.stderr)
            from dask.distributed import as_completed

            futures = [client.submit(solve_batch, robot, grid.kind, grid.names, b, certify, retries=3, pure=False)
                       for b in batches]
            bar = None
            if progress:
                from tqdm import tqdm

                bar = tqdm(total=len(todo), unit="pt", file=sys.stderr, desc="cdpr sweep")
            for fut in as_completed(futures):
                points, eqs = fut.result()
                _write(out, "equilibria", eqs)
                _write(out, "points", points)  # after its equilibria: a point listed is a point complete on disk
                errors += sum(1 for p in points if p["error"])
                incomplete += sum(1 for p in points if not p["error"] and not p["complete"])
                if bar is not None:
                    bar.update(len(points))
            if bar is not None:
                bar.close()
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    return SweepResult(out=out, total=grid.size, resumed=len(done), solved=len(todo), errors=errors,
                       incomplete=incomplete, seconds=time.perf_counter() - t0, workers=nworkers, dashboard=dashboard)


def summary_counts(out) -> dict:
    """Counts over every point written in ``out``: points, errors, incomplete, and equilibria."""
    pts = read_table(out, "points")
    eqs = read_table(out, "equilibria")
    if pts is None:
        return {"points": 0, "errors": 0, "incomplete": 0, "equilibria": 0}
    err = np.array([e is not None for e in pts.column("error").to_pylist()])
    comp = np.array([bool(c) for c in pts.column("complete").to_pylist()])
    return {"points": pts.num_rows, "errors": int(err.sum()), "incomplete": int((~err & ~comp).sum()),
            "equilibria": 0 if eqs is None else eqs.num_rows}
