"""Command line: ``cdpr`` (also ``python -m cdpr_algebra``), a thin layer over the library; one module per command.

    cdpr igp ROBOT --orientation PHI_X PHI_Y PHI_Z [--degrees] [--exact] [--json]        (igp.py)
    cdpr igp ROBOT --position X Y Z [--all] [--json]
    cdpr dgp ROBOT [--lengths L1 .. Ln] [--jobs N] [--extended-precision] [--mpmath-retry] [--settle [--settle-max-boxes N]] [--json] (dgp.py)
    cdpr plot ROBOT [--lengths L1 .. Ln] [--out FILE.png|.svg] [--jobs N] [--extended-precision]  (plot.py)
    cdpr cc ROBOT --position X Y Z [--angles ..] [--configuration ..] [--ball R] [--uncertainty DA DB DRHO] [--json]
                                                                                          (cc.py)
    cdpr crosscheck ROBOT [--lengths L1 .. Ln] [--taut C1 .. Cm] [--jobs N] [--extended-precision] [--json]  (crosscheck.py)
    cdpr track ROBOT [--lengths L1 .. Ln] (--to L1 .. Ln | --trajectory FILE) [--steps N] [--json] [--plot F]
                                                                                          (track.py)
    cdpr sweep ROBOT --vary NAME=START:STOP:NUM .. --out DIR [--kind ..] [--workers N] [--scheduler A] (sweep.py)
    cdpr plot-sweep DIR [--value NAME] [--out FILE.png]                                   (plot_sweep.py)
    cdpr export ROBOT --taut C1 .. Cm [--lengths ..] [--format minibex|phc|json]          (export.py)
    cdpr warm ROBOT [ROBOT ..]   (compile and cache the numeric kernels; pip install . runs it)   (warm.py)

Exit status: 0 on success, 2 on bad input (one line on stderr naming the field and the problem), 3 when the
result is incomplete (``dgp``: some subproblem has failed paths or regular endpoints without a Krawczyk
certificate, so equilibria may be missing there; the subproblems and why are named on stderr).
"""

from __future__ import annotations

import argparse
import atexit
import importlib
import os
import sys
import threading

from cdpr_algebra.model.errors import CdprInputError

from .common import INCOMPLETE, Parser  # noqa: F401  (INCOMPLETE: the documented exit status)

COMMANDS = ("igp", "dgp", "plot", "cc", "crosscheck", "track", "sweep", "plot-sweep", "export", "warm")  # each a module of this package with add_parser and run


def _command(name):
    return importlib.import_module(f"{__package__}.{name.replace('-', '_')}")


def build_parser() -> argparse.ArgumentParser:
    p = Parser(prog="cdpr", description="Equilibria of underconstrained cable-driven parallel robots.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=Parser)
    for name in COMMANDS:
        _command(name).add_parser(sub)
    return p


def console() -> None:
    """The ``cdpr`` console script and ``python -m cdpr_algebra``: :func:`main`, then :func:`exit_now`."""
    exit_now(main())


def exit_now(code) -> None:
    """Exit with ``code`` without the interpreter's teardown: the atexit callbacks run and stdout / stderr are
    flushed, then ``os._exit``.  The teardown only frees memory; after numba has compiled or loaded a kernel it takes
    0.2-0.3 s (numba's LLVM objects), a fifth of a small DGP's whole process (``benchmarks/bench_startup.py``).
    With other threads still running (they would be joined) or without the atexit hook, a plain ``sys.exit``."""
    run_exitfuncs = getattr(atexit, "_run_exitfuncs", None)
    if run_exitfuncs is None or threading.active_count() > 1:
        sys.exit(code)
    run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe or stream: nothing more can be written to it
            pass
    os._exit(code if isinstance(code, int) else (0 if code is None else 1))


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return _command(args.command).run(args)
    except CdprInputError as err:
        print(f"cdpr: error: {err}", file=sys.stderr)
        return 2
