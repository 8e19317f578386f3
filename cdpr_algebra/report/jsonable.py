"""Conversion of result values to JSON-ready Python values (one rule for every result record)."""

import numpy as np


def jsonable(v):
    """numpy scalars -> Python numbers, arrays/tuples -> lists, complex -> [re, im], dicts recursively."""
    if isinstance(v, np.ndarray):
        return [jsonable(x) for x in v]
    if isinstance(v, (list, tuple)):
        return [jsonable(x) for x in v]
    if isinstance(v, (complex, np.complexfloating)):
        return [float(v.real), float(v.imag)]
    if isinstance(v, np.floating):
        return float(v)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.bool_):
        return bool(v)
    if isinstance(v, dict):
        return {k: jsonable(x) for k, x in v.items()}
    return v
