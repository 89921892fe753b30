"""JSON conversion of NumPy scalars and arrays (non-finite floats become ``null``)."""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

__all__ = [
    "dumps_jsonable",
    "to_jsonable",
]


def to_jsonable(obj: Any) -> Any:
    """Convert NumPy scalars/arrays and tuples to plain JSON types; non-finite floats -> None."""
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, float | np.floating):
        x = float(obj)
        return x if math.isfinite(x) else None
    return obj


def _json_default(obj: Any) -> Any:
    """``default`` of :func:`dumps_jsonable`: what :func:`to_jsonable` does to the types the C
    encoder does not know; a non-finite NumPy float raises, so that the caller falls back."""
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        x = float(obj)
        if math.isfinite(x):
            return x
        raise ValueError("non-finite float")
    raise TypeError(f"Object of type {type(obj).__name__} is not JSON serializable")


_CONTAINERS = (dict, list, tuple)


def _str_keys(obj: Any) -> bool:
    """Whether every dict key inside ``obj`` (through dicts, lists and tuples) is a ``str``."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            if type(k) is not str or (isinstance(v, _CONTAINERS) and not _str_keys(v)):
                return False
    elif isinstance(obj, list | tuple):
        for v in obj:
            if isinstance(v, _CONTAINERS) and not _str_keys(v):
                return False
    return True


def dumps_jsonable(obj: Any) -> str:
    """``json.dumps(to_jsonable(obj))``, the same text, mostly by the C encoder.

    The encoder handles NumPy scalars and arrays through ``default``; a non-finite float makes it
    raise (``allow_nan=False``), and dict keys other than ``str`` (which ``to_jsonable`` writes
    with ``str()``, the encoder differently for ``True``/``None``) are checked first: both cases,
    and any error, take the exact route through :func:`to_jsonable`. About 2 x faster for a
    ``SimulationResult.meta``.
    """
    if _str_keys(obj):
        try:
            return json.dumps(obj, default=_json_default, allow_nan=False)
        except (TypeError, ValueError):
            pass
    return json.dumps(to_jsonable(obj))
