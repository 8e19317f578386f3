"""Conversion of result values to JSON-ready Python values (one rule for every result record)."""

import json
import math

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


def _finite_or_none(v):
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, list):
        return [_finite_or_none(x) for x in v]
    if isinstance(v, dict):
        return {k: _finite_or_none(x) for k, x in v.items()}
    return v


def json_text(v, **kwargs) -> str:
    """Strict JSON of a result record (:func:`jsonable` first): a non-finite number (an overflowed residual, an
    accuracy never measured) is null, never the ``Infinity`` / ``NaN`` that strict parsers reject."""
    return json.dumps(_finite_or_none(jsonable(v)), allow_nan=False, **kwargs)
