"""One task of a sweep: a batch of grid points solved in a worker process, returned as rows for the Parquet tables.

Run by dask workers; the caches of the package (compiled kernels, stored generic solution sets, the generic
distance solve) live in the worker process and are filled by its first task, not per task.  A point whose solve
raises is recorded with its error (the sweep goes on)."""

from __future__ import annotations

import time
import traceback

import numpy as np

from cdpr_algebra.model.pose import angles_from_matrix, matrix_from_angles

POSE_DEFAULT = {"x": 0.0, "y": 0.0, "z": 0.0, "phi_x": 0.0, "phi_y": 0.0, "phi_z": 0.0}


def _point_row(names, values, point):
    return {"point": point, **dict(zip(names, values))}


def _solve_dgp(robot, names, values, certify):
    from cdpr_algebra.dgp.solve import dgp

    rho = np.array(robot.lengths, dtype=float) if robot.lengths is not None else np.zeros(robot.n)
    for nm, v in zip(names, values):
        rho[int(nm[3:]) - 1] = v
    res = dgp(robot, rho, jobs=1, certify=certify)
    eqs = []
    for s in res.solutions:
        eqs.append({"taut": ",".join(str(c) for c in s.taut), "x": float(s.position[0]), "y": float(s.position[1]),
                    "z": float(s.position[2]), **dict(zip(("phi_x", "phi_y", "phi_z"), map(float, s.angles))),
                    **{f"tau{i + 1}": float(t) for i, t in enumerate(s.tensions)}, "stable": bool(s.stable),
                    "certified": s.certified})
    failed = sum(sub.failed_paths for sub in res.subproblems)
    return {"n_admissible": len(res.solutions), "n_stable": sum(1 for s in res.solutions if s.stable),
            "failed_paths": int(failed), "complete": bool(res.complete),
            "min_tension": min((float(np.min(s.tensions[[c - 1 for c in s.taut]])) for s in res.solutions),
                               default=None)}, eqs


def _solve_igp(robot, names, values, certify):
    from cdpr_algebra.igp.position import igp_position

    G = dict(POSE_DEFAULT)
    G.update(zip(names, values))
    res = igp_position(robot, [G["x"], G["y"], G["z"]], include_complex=False, certify=certify)
    eqs = []
    adm = [s for s in res.real_solutions if s.admissible]
    for s in adm:
        ang = angles_from_matrix(s.rotation)
        eqs.append({"taut": ",".join(str(i + 1) for i in range(robot.n)), "x": G["x"], "y": G["y"], "z": G["z"],
                    "phi_x": float(ang[0]), "phi_y": float(ang[1]), "phi_z": float(ang[2]),
                    **{f"tau{i + 1}": float(np.real(t)) for i, t in enumerate(s.tensions)},
                    "stable": bool(s.stable) if s.stable is not None else None,
                    "certified": getattr(s, "certified", None)})
    return {"n_admissible": len(adm), "n_stable": sum(1 for s in adm if s.stable),
            "failed_paths": 0, "complete": res.status == "complete",
            "min_tension": min((float(np.min(np.real(s.tensions))) for s in adm), default=None)}, eqs


def _solve_cc(robot, names, values, certify):
    from cdpr_algebra.cc.configurations import valid_configurations
    from cdpr_algebra.cc.radii import cc_radii_many

    P = dict(POSE_DEFAULT)
    P.update(zip(names, values))
    G = np.array([P["x"], P["y"], P["z"]])
    R = matrix_from_angles(P["phi_x"], P["phi_y"], P["phi_z"])
    ccs = valid_configurations(robot, G, R, sizes=[6])
    radii = cc_radii_many(robot, [(G, c.cables, R) for c in ccs], certify=certify) if ccs else []
    rmins = [r.rmin for r in radii]
    eqs = [{"taut": ",".join(str(i + 1) for i in c.cables), "x": float(G[0]), "y": float(G[1]), "z": float(G[2]),
            "phi_x": P["phi_x"], "phi_y": P["phi_y"], "phi_z": P["phi_z"],
            **{f"tau{i + 1}": (float(c.tensions[list(c.cables).index(i)]) if i in c.cables else 0.0)
               for i in range(robot.n)},
            "stable": None, "certified": bool(r.certified), "rmin": float(r.rmin)} for c, r in zip(ccs, radii)]
    failed = sum(int(getattr(r, "failed_paths", 0) or 0) for r in radii)
    return {"n_admissible": len(ccs), "n_stable": None, "failed_paths": failed, "complete": failed == 0,
            "min_tension": min((float(np.min(c.tensions)) for c in ccs), default=None),
            "rmin": max(rmins) if rmins else None}, eqs


SOLVERS = {"dgp": _solve_dgp, "igp": _solve_igp, "cc": _solve_cc}


def solve_batch(robot, kind: str, names, batch, certify: bool = True) -> tuple[list, list]:
    """Rows of ``points`` (one per (index, values) of ``batch``) and of ``equilibria`` for the Parquet tables."""
    solver = SOLVERS[kind]
    points, eqs = [], []
    for point, values in batch:
        t0 = time.perf_counter()
        row = _point_row(names, values, point)
        try:
            summary, rows = solver(robot, names, values, certify)
            row.update(summary)
            row["error"] = None
            for r in rows:
                eqs.append({**_point_row(names, values, point), **r})
        except Exception as exc:  # recorded, not dropped: the sweep goes on
            row.update({"n_admissible": None, "n_stable": None, "failed_paths": None, "complete": False,
                        "min_tension": None,
                        "error": f"{type(exc).__name__}: {exc} | {traceback.format_exc(limit=2).splitlines()[-1]}"})
        row["seconds"] = time.perf_counter() - t0
        points.append(row)
    return points, eqs
