"""``cdpr plot-sweep``: a picture of a sweep's results (:mod:`cdpr_algebra.sweep.pictures`).

    cdpr plot-sweep DIR [--value n_stable|n_admissible|min_tension|rmin] [--out FILE.png]

One varied name: the value against it; two: a heat map; x, y, z of a pose sweep: the workspace (the points in space,
coloured by the value).  Points with an error or incomplete are marked.
"""

from __future__ import annotations


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("plot-sweep", help="picture of a sweep's results (line or heat map)")
    p.add_argument("dir", help="the sweep's output directory")
    p.add_argument("--value", default="n_stable", help="n_stable (default), n_admissible, min_tension or rmin")
    p.add_argument("--out", default="sweep.png", metavar="FILE", help="picture file (default sweep.png)")


def run(args) -> int:
    from cdpr_algebra.sweep.pictures import save_sweep_figure

    from .common import FIGURE_SUFFIXES, output_file

    output_file(args.out, "--out", FIGURE_SUFFIXES)

    save_sweep_figure(args.dir, args.out, args.value)
    print(f"wrote {args.out}")
    return 0
