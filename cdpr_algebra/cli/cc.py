"""``cdpr cc``: cable configurations of a suspended robot with more than 6 cables (Merlet).

    cdpr cc ROBOT --position X Y Z [--angles PX PY PZ [--degrees]] [--configuration C1 .. C6]
                  [--ball R] [--uncertainty DA DB DRHO] [--json]
    cdpr cc ROBOT --trajectory EX EY EZ --range T0 T1 [--angles ..] [--configuration ..] [--json]
    cdpr cc ROBOT --surface EX EY EZ --range U0 U1 --range V0 V1 [--angles ..] [--configuration ..] [--json]

At a pose (position of the centre of mass G, orientation R = Rz Ry Rx of ``--angles``): every valid cable
configuration (:mod:`cdpr_algebra.cc.configurations`), and for those with 6 cables the radii of the first criterion
(:mod:`cdpr_algebra.cc.radii`: r_min's critical point certified by Krawczyk and its nearest-ness proven by interval exclusion,
each reported separately in ``radius_certificate``), the second criterion within ``--ball R`` (:mod:`cdpr_algebra.cc.safety`:
``safe_nearby`` true only from the interval exclusion proof, false only with a verified counterexample, null when
only the homotopy search ran; ``second_criterion.method`` and ``status`` say which) and the uncertainty
criterion for +-DA on the exit points, +-DB on the platform anchors and +-DRHO on the cable lengths
(:mod:`cdpr_algebra.cc.uncertainty`).  Along a trajectory (expressions of t) or over a surface (of u, v): the 6-cable
configurations valid over the whole path with their index (:mod:`cdpr_algebra.cc.paths`).  An expression that starts with '-'
must be written with a leading space or in parentheses (argparse would take it for an option).

JSON: ``{"robot", "mode", "position", "angles", "configurations": [{"cables", "tensions", "valid", "radii":
{"<cable number>": r, ..., "singular": r}, "rmin", "limiting", "certified", "radius_certificate", "safe_nearby",
"second_criterion", "nearest_sub_configuration", "robust_to_uncertainty", "counterexample", "tension_bounds"}],
"seconds"}``; ``null`` where a criterion was not asked for or does not apply (configurations with fewer than 6
cables).  ``certified`` (r_min) is true only when both parts of ``radius_certificate`` are proven:
``{"critical_point": "certified" | "not certified", "nearest": "proven" | "float search", "proven_interval": [lo,
hi] | null, ...}``; the per-cable ``radii`` other than the limiting one are floating-point values; ``failed_paths``:
homotopy paths of the radii (or of the path index) that failed.

Exit status 3 (named on stderr) when any configuration has failed paths: critical points of its radii may be
missing (its r_min stays proven when ``certified``); 2 on bad input.
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace

from cdpr_algebra.model.errors import CdprInputError

from .common import INCOMPLETE, as_flags, finite, json_text


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("cc", help="cable configurations of a suspended robot with > 6 cables (Merlet)")
    p.add_argument("robot", help="robot file (.json or .toml)")
    p.add_argument("--position", nargs=3, type=finite("--position"), metavar=("X", "Y", "Z"),
                   help="position of the centre of mass G (world frame)")
    p.add_argument("--angles", nargs=3, type=finite("--angles"), metavar=("PHI_X", "PHI_Y", "PHI_Z"),
                   help="orientation R = Rz(phi_z) Ry(phi_y) Rx(phi_x), radians unless --degrees (default 0 0 0)")
    p.add_argument("--degrees", action="store_true", help="--angles in degrees")
    p.add_argument("--configuration", nargs="+", metavar="C", help="only this configuration (cable numbers)")
    p.add_argument("--trajectory", nargs=3, metavar=("EX", "EY", "EZ"),
                   help="position of G as expressions of t (polynomials in t, or in cos(t), sin(t))")
    p.add_argument("--surface", nargs=3, metavar=("EX", "EY", "EZ"), help="position of G as expressions of u, v")
    p.add_argument("--range", nargs=2, action="append", metavar=("LO", "HI"),
                   help="range of t (trajectory) or of u then v (surface, given twice); numbers or constant "
                        "expressions as in the path (0 pi/2)")
    p.add_argument("--ball", type=finite("--ball"), metavar="R",
                   help="second criterion: no sub-configuration equilibrium within this radius (pose only)")
    p.add_argument("--uncertainty", nargs=3, type=finite("--uncertainty"), metavar=("DA", "DB", "DRHO"),
                   help="uncertainty criterion: +-DA on A, +-DB on b', +-DRHO on the lengths (pose only)")
    p.add_argument("--proof-boxes", type=int, default=None, metavar="N",
                   help="boxes per cubic before the interval proof that r_min is the nearest critical point gives "
                        "up, leaving nearest-ness a floating-point search (default 200000)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")


def _rotation(args) -> tuple:
    import numpy as np  # here, not with the module: ``cdpr --help`` imports every command's module
    from cdpr_algebra.model.pose import matrix_from_angles

    angles = [0.0, 0.0, 0.0] if args.angles is None else list(args.angles)
    rad = np.radians(angles) if args.degrees else np.array(angles)
    return matrix_from_angles(*rad), [float(a) for a in rad]


def _configuration_numbers(args):
    if args.configuration is None:
        return None
    try:
        return [int(c) for c in args.configuration]
    except ValueError:
        raise CdprInputError("--configuration", f"expected cable numbers, got {args.configuration}") from None


def _entry(cc, radii=None, safety=None, unc=None) -> dict:
    """One configuration of the JSON contract."""
    d = {"cables": cc.numbers, "tensions": cc.tensions, "valid": cc.valid, "radii": {}, "rmin": None,
         "limiting": None, "certified": None, "safe_nearby": None, "nearest_sub_configuration": None,
         "robust_to_uncertainty": None, "counterexample": None, "tension_bounds": None}
    if radii is not None:
        d["radii"] = radii.radii_by_number()
        d["rmin"] = float(radii.rmin) if cc.valid else 0.0
        d["limiting"] = radii.limiting + 1 if not isinstance(radii.limiting, str) else radii.limiting
        # an invalid configuration has r_min = 0 by definition: the certificate is of the distance to the nearest
        # critical point, not of that 0
        d["certified"] = radii.certified if cc.valid else None
        d["radius_certificate"] = radii.radius_certificate
        d["nearest_point"] = radii.nearest
        d["failed_paths"] = int(radii.failed_paths)
    if safety is not None:
        d["safe_nearby"] = safety.safe
        d["nearest_sub_configuration"] = safety.nearest
        d["second_criterion"] = {"radius": safety.radius, "method": safety.method, "proven": safety.proven,
                                 "status": safety.status, "counterexample_verified": safety.counterexample_verified,
                                 "boxes": safety.boxes, "failed_paths": safety.failed_paths}
    if unc is not None:
        d["robust_to_uncertainty"] = unc.robust
        d["counterexample"] = unc.counterexample
        d["tension_bounds"] = unc.tension_bounds
        d["uncertainty"] = {"tolerances": unc.tolerances, "equilibrium_region": unc.equilibrium_box,
                            "boxes": unc.boxes, "reason": unc.reason}
    return d


def _pose(args, robot, R) -> tuple[list, dict]:
    import numpy as np  # here, not with the module: ``cdpr --help`` imports every command's module
    from cdpr_algebra.cc.radii import cc_radii_many
    from cdpr_algebra.cc.configurations import configuration_tensions, parse_cables, rank_configurations, valid_configurations

    G = np.array(args.position, dtype=float)
    if args.ball is not None and not args.ball > 0:
        raise CdprInputError("--ball", f"expected a radius > 0, got {args.ball}")
    if args.uncertainty is not None and min(args.uncertainty) < 0:
        raise CdprInputError("--uncertainty", f"expected DA DB DRHO >= 0, got {args.uncertainty}")
    if args.proof_boxes is not None and args.proof_boxes < 1:
        raise CdprInputError("--proof-boxes", f"expected a number >= 1, got {args.proof_boxes}")
    numbers = _configuration_numbers(args)
    if numbers is not None:
        ccs = [configuration_tensions(robot, G, parse_cables(robot, numbers, "--configuration"), R)]
    else:
        ccs = valid_configurations(robot, G, R)
    six = [c for c in ccs if len(c.cables) == 6]
    extra = {} if args.proof_boxes is None else {"nearest_max_boxes": args.proof_boxes}
    radii = dict(zip([c.cables for c in six], cc_radii_many(robot, [(G, c.cables, R) for c in six], certify=True,
                                                            **extra))) if six else {}
    ccs = [replace(c, rmin=(radii[c.cables].rmin if c.valid else 0.0)) if c.cables in radii else c for c in ccs]
    ccs = rank_configurations(ccs) if numbers is None else ccs
    safety, unc = {}, {}
    if args.ball is not None:
        from cdpr_algebra.cc.safety import safety as second

        for c in six:
            if c.valid:
                safety[c.cables] = second(robot, G, c.cables, R, args.ball)
    if args.uncertainty is not None:
        from cdpr_algebra.cc.uncertainty import uncertainty_check

        dA, dB, drho = args.uncertainty
        for c in six:
            if c.valid:
                unc[c.cables] = uncertainty_check(robot, G, c.cables, R, dA, dB, drho)
    entries = [_entry(c, radii.get(c.cables), safety.get(c.cables), unc.get(c.cables)) for c in ccs]
    return entries, {"mode": "pose", "position": G.tolist()}


def _path(args, robot, R) -> tuple[list, dict]:
    from cdpr_algebra.cc.paths import parse_path, path_configurations

    surface = args.surface is not None
    option = "--surface" if surface else "--trajectory"
    exprs = args.surface if surface else args.trajectory
    ranges = args.range or []
    if len(ranges) != (2 if surface else 1):
        raise CdprInputError("--range", f"{option} needs {'two --range (u then v)' if surface else 'one --range'}, "
                             f"got {len(ranges)}")
    if args.position is not None:
        raise CdprInputError("--position", f"give either a pose (--position) or a path ({option}), not both")
    for opt, val in (("--ball", args.ball), ("--uncertainty", args.uncertainty)):
        if val is not None:
            raise CdprInputError(opt, f"{opt} is implemented for a pose, not along a path")
    spec = parse_path(exprs, ranges, option)
    res = path_configurations(robot, spec, R, cables=_configuration_numbers(args))
    entries = []
    for pr in res:
        d = {"cables": [c + 1 for c in pr.cables], "tensions": pr.tensions_start, "valid": pr.valid,
             "radii": pr.radii_by_number() if pr.valid else {}, "rmin": pr.index,
             "limiting": pr.limiting + 1 if not isinstance(pr.limiting, str) else pr.limiting, "certified": None,
             "safe_nearby": None, "nearest_sub_configuration": None, "robust_to_uncertainty": None,
             "counterexample": None, "tension_bounds": None, "where": pr.where, "crossings": list(pr.crossings),
             "failed_paths": pr.failed_paths}
        entries.append(d)
    return entries, {"mode": "surface" if surface else "trajectory", "path": spec.to_dict()}


def _radius_cell(e) -> str:
    """'yes' (critical point certified and nearest proven), 'critical point' (certified, nearest-ness a float
    search), 'no', or '-'."""
    rc = e.get("radius_certificate")
    if rc is None or not e["valid"]:
        return "-"
    if e["certified"]:
        return "yes"
    return "critical point" if rc["critical_point"] == "certified" else "no"


def _safe_cell(e) -> str:
    sc = e.get("second_criterion")
    if sc is None:
        return "-"
    if e["safe_nearby"] is True:
        return "yes (proof)"
    if e["safe_nearby"] is False:
        return "no (verified)"
    return "not proven"


def _table(entries, head) -> str:
    import numpy as np  # here, not with the module: ``cdpr --help`` imports every command's module
    from cdpr_algebra.report.tables import format_table

    def fmt(v):
        return "-" if v is None else ("yes" if v is True else "no" if v is False else str(v))

    rows = []
    for k, e in enumerate(entries):
        rmin = "-" if e["rmin"] is None else f"{e['rmin']:.10g}" + (f" ({e['limiting']})" if e["limiting"] else "")
        rows.append([str(k + 1), str(e["cables"]), "(" + ", ".join(f"{t:.4f}" for t in e["tensions"]) + ")",
                     "yes" if e["valid"] else "no", rmin, _radius_cell(e), _safe_cell(e),
                     fmt(e["robust_to_uncertainty"])])
    headers = ["#", "cables", "tensions" + (" (start)" if head["mode"] != "pose" else ""), "valid",
               "r_min (limiting)" if head["mode"] == "pose" else "index (limiting)", "r_min certified", "safe nearby",
               "robust"]
    lines = [format_table(headers, rows)] if rows else ["no valid cable configuration"]
    for k, e in enumerate(entries):
        rc = e.get("radius_certificate")
        if rc is not None:
            cp = ("critical point certified (Krawczyk), distance in [{:.12g}, {:.12g}]".format(*rc["radius_enclosure"])
                  if rc["critical_point"] == "certified" else "critical point not certified")
            near = (f"nearest proven (interval exclusion: no point of the 7 surfaces within {rc['proven_lower_bound']:.12g})"
                    if rc["nearest"] == "proven" else "nearest by a floating-point search (homotopy), not proven")
            what = "r_min" if e["valid"] else "not valid at the pose (r_min 0); the nearest critical point"
            lines.append(f"#{k + 1} {what}: {cp}; {near}")
        if e["radii"]:
            lines.append(f"#{k + 1} radii{' (floating point)' if rc is not None else ''}: "
                         + ", ".join(f"{c}: {r:.10g}" for c, r in e["radii"].items()))
        sc = e.get("second_criterion")
        if sc is not None:
            lines.append(f"#{k + 1} second criterion within {sc['radius']:g}: {sc['status']}")
        if e.get("nearest_sub_configuration"):
            n = e["nearest_sub_configuration"]
            lines.append(f"#{k + 1} nearest sub-configuration equilibrium: cables {n['cables']} at distance "
                         f"{n['distance']:.4g}")
        if e.get("counterexample"):
            cx = e["counterexample"]
            lines.append(f"#{k + 1} counterexample: cable {cx['cable']} tension {min(cx['tensions']):.4g} at G = "
                         f"{np.round(cx['position'], 4).tolist()}")
        if e.get("crossings"):
            lines.append(f"#{k + 1} not valid along the path: {e['crossings']}")
    return "\n".join(lines)


FLAGS = {"ranges": "--range", "cables": "--configuration", "radius": "--ball", "tolerances": "--uncertainty",
         "position": "--position"}  # library field -> the flag that gave it


def run(args) -> int:
    with as_flags(FLAGS):
        return _run(args)


def _run(args) -> int:
    from cdpr_algebra.model.robot import load_robot
    from cdpr_algebra.report.jsonable import jsonable  # here, not with the module: it imports numpy

    t0 = time.perf_counter()
    robot = load_robot(args.robot)
    R, angles = _rotation(args)
    if args.trajectory is not None and args.surface is not None:
        raise CdprInputError("--surface", "give either --trajectory or --surface, not both")
    if args.trajectory is None and args.surface is None:
        if args.position is None:
            raise CdprInputError("--position", "required (or a path: --trajectory / --surface)")
        if args.range:
            raise CdprInputError("--range", "--range goes with --trajectory or --surface")
        entries, head = _pose(args, robot, R)
    else:
        entries, head = _path(args, robot, R)
    out = {"robot": robot.name, **head, "angles": angles, "configurations": entries,
           "seconds": time.perf_counter() - t0}
    if args.json:
        print(json_text(out, indent=2))
    else:
        where = f"pose G = {head['position']}" if head["mode"] == "pose" else \
            f"{head['mode']} {head['path']['expressions']} over {head['path']['ranges']}"
        print(f"{robot.name}: cable configurations, {where}, angles {angles}")
        print(_table(jsonable(entries), head))
    failed = [e for e in entries if e.get("failed_paths")]
    if failed:
        print(f"cdpr: incomplete: homotopy paths failed for {len(failed)} configuration(s), so critical points of "
              f"their radii may be missing (exit status 3); an r_min marked certified is proven all the same:",
              file=sys.stderr)
        for e in failed:
            print(f"  {e['cables']}: {e['failed_paths']} failed path(s)", file=sys.stderr)
        return INCOMPLETE
    return 0
