"""``cdpr plot ROBOT [--lengths L1 .. Ln] [--out FILE.png|.svg] [--jobs N]``: run the DGP and draw its admissible
equilibria (:func:`cdpr_algebra.report.plot.plot_equilibria`), one panel per equilibrium, into a PNG or SVG file.

The table of ``cdpr dgp`` goes to stdout, then the file written; progress to stderr.  Default output file:
``<robot file stem>_equilibria.png`` in the current directory.
"""

from __future__ import annotations

import sys
from pathlib import Path

from cdpr_algebra.model.errors import CdprInputError

from .common import INCOMPLETE, dgp_lengths, finite, output_file, print_incomplete

SUFFIXES = (".png", ".svg")


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("plot", help="run the DGP and draw its admissible equilibria (PNG or SVG)")
    p.add_argument("robot", help="robot file (.json or .toml)")
    p.add_argument("--lengths", nargs="+", type=finite("--lengths"), metavar="L",
                   help="cable lengths rho_1 .. rho_n (default: the robot file's)")
    p.add_argument("--out", default=None, metavar="FILE",
                   help="output file, .png or .svg (default: <robot file stem>_equilibria.png)")
    p.add_argument("--jobs", type=int, default=None, help="parallel threads (default: all cores)")
    p.add_argument("--extended-precision", action="store_true",
                   help="the DGP with Newton residuals in double-double where double precision stalls (as cdpr dgp "
                        "--extended-precision)")


def output_path(out: str | None, robot_file: str) -> Path:
    """The file to write: ``out`` checked (suffix .png / .svg, existing directory), or the default name."""
    return output_file(out if out is not None else f"{Path(robot_file).stem}_equilibria.png", "--out", SUFFIXES)


def run(args) -> int:
    from cdpr_algebra.dgp.solve import default_options, dgp, dgp_table
    from cdpr_algebra.report.plot import plot_equilibria
    from cdpr_algebra.model.robot import load_robot

    out = output_path(args.out, args.robot)
    robot = load_robot(args.robot)
    lengths = dgp_lengths(args, robot)
    if args.jobs is not None and args.jobs < 1:
        raise CdprInputError("--jobs", f"expected a number >= 1, got {args.jobs}")

    def progress(sub, done, total):
        what = f"skipped ({sub.skipped})" if sub.skipped else f"{sub.admissible} admissible"
        print(f"[{done}/{total}] taut {list(sub.taut)}: {what}, {sub.seconds:.2f} s", file=sys.stderr, flush=True)

    options = default_options(extended=True) if args.extended_precision else None
    result = dgp(robot, lengths, jobs=args.jobs, progress=progress, options=options)
    print(f"{robot.name}: DGP, lengths {', '.join(f'{v:g}' for v in lengths)}")
    print(dgp_table(result, robot.n))
    fig = plot_equilibria(robot, result.solutions)
    try:
        fig.savefig(out, dpi=110)
    except OSError as err:
        raise CdprInputError("--out", f"cannot write {str(out)!r}: {err.strerror or err}") from None
    print(f"wrote {out} ({len(result.solutions)} panel(s))")
    if not result.complete:  # as cdpr dgp: the picture may miss equilibria of these taut sets
        print_incomplete(result, "from the picture")
        return INCOMPLETE
    return 0
