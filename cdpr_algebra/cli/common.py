"""Helpers shared by the command modules: the parser class (one-line errors, exit status 2), number arguments,
the DGP's cable lengths, and the exit status of an incomplete result."""

from __future__ import annotations

import argparse
import math

from cdpr_algebra.model.errors import CdprInputError, check_magnitude

__all__ = ["INCOMPLETE", "Parser", "finite", "dgp_lengths", "as_flags", "print_incomplete", "output_file",
           "json_text", "FIGURE_SUFFIXES"]

FIGURE_SUFFIXES = (".png", ".svg", ".pdf")  # pictures saved by matplotlib (Agg and its vector backends)
INCOMPLETE = 3  # exit status: a result not proven complete (failed paths, uncertified endpoints), said on stderr


def print_incomplete(result, where: str = "there") -> None:
    """On stderr: the DGP ``result``'s subproblems not proven complete, each with its reason (equilibria may be
    missing ``where``), before a command returns :data:`INCOMPLETE`."""
    import sys

    from cdpr_algebra.dgp.solve import incompleteness

    print(f"cdpr: incomplete: {len(result.incomplete)} subproblem(s) not proven complete, so equilibria may be "
          f"missing {where} (exit status 3):", file=sys.stderr)
    for s in result.incomplete:
        print(f"  {list(s.taut)}: {incompleteness(s)}", file=sys.stderr)


def json_text(v, **kwargs) -> str:
    """Strict JSON of a result record (:func:`cdpr_algebra.report.jsonable.json_text`; imported here on first use:
    ``cdpr --help`` imports every command's module, and that one imports numpy)."""
    from cdpr_algebra.report.jsonable import json_text as text

    return text(v, **kwargs)


def output_file(path, option: str, suffixes: tuple = ()):
    """The file an option names for writing, checked before any work is done: its suffix one of ``suffixes`` (any
    when empty), its directory existing, and not itself a directory (else a :class:`CdprInputError` naming
    ``option``)."""
    from pathlib import Path

    out = Path(path)
    if suffixes and out.suffix.lower() not in suffixes:
        raise CdprInputError(option, f"expected a file name ending in {' or '.join(suffixes)}, got {str(out)!r}")
    if out.is_dir():
        raise CdprInputError(option, f"{str(out)!r} is a directory, not a file name")
    if not out.parent.is_dir():
        raise CdprInputError(option, f"directory {str(out.parent)!r} does not exist")
    return out


class Parser(argparse.ArgumentParser):
    """argparse with a one-line error message and exit status 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message}\n")


def finite(name):
    """argparse type: a finite float; the error names the flag ``name``."""
    def conv(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name}: expected a number, got {text!r}") from None
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"{name}: expected a finite number, got {text!r}")
        try:
            check_magnitude(v, name)
        except CdprInputError as err:
            raise argparse.ArgumentTypeError(f"{name}: {err.problem}") from None
        return v
    return conv


def dgp_lengths(args, robot):
    """The DGP's cable lengths (numpy array): ``--lengths`` (checked) or the robot file's (used by dgp, plot and
    crosscheck).  numpy is imported here, not with the module: ``cdpr --help`` needs none of it."""
    import numpy as np

    if args.lengths is not None:
        if len(args.lengths) != robot.n:
            raise CdprInputError("--lengths", f"expected {robot.n} cable lengths, got {len(args.lengths)}")
        if any(v <= 0 for v in args.lengths):
            raise CdprInputError("--lengths", "cable lengths must be > 0")
        return np.array(args.lengths)
    if robot.lengths is not None:
        return robot.lengths
    raise CdprInputError("--lengths", "no cable lengths: the robot file has none and --lengths is not given")


class as_flags:
    """Context manager: a library input error about ``field`` is re-raised naming the command-line flag that gave
    it (``flags``: {library field: flag}); the library describes problems in its own terms."""

    def __init__(self, flags: dict):
        self.flags = flags

    def __enter__(self):
        return self

    def __exit__(self, kind, err, tb):
        if isinstance(err, CdprInputError) and err.field in self.flags:
            raise CdprInputError(self.flags[err.field], err.problem, err.source) from None
        return False
