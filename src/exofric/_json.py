"""JSON-ready values: one converter for every layer (a value conversion, not file I/O).

Its public home is :func:`exofric.io.jsonable`; result classes of the computing stages use it in
their ``to_dict()`` without importing :mod:`exofric.io`.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

__all__ = ["jsonable"]


def jsonable(obj: Any) -> Any:
    """Convert NumPy scalars/arrays, tuples and non-finite floats to JSON-ready values.

    NaN and infinities become ``None`` (JSON has no NaN); paths become strings.

    Parameters
    ----------
    obj : Any
        A value, possibly nested in dicts, lists and tuples.

    Returns
    -------
    Any
        The same structure built of dicts (string keys), lists, plain numbers and strings.

    Examples
    --------
    >>> import numpy as np
    >>> jsonable({"gamma": np.float64(0.7168), "p_mpa": np.array([0.2, np.nan])})
    {'gamma': 0.7168, 'p_mpa': [0.2, None]}
    """
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [jsonable(v) for v in obj]
    # NumPy only if loaded: no value can be a NumPy one otherwise (start-up without NumPy)
    np = sys.modules.get("numpy")
    if np is not None and isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if np is not None and isinstance(obj, np.generic):
        return jsonable(obj.item())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, Path):
        return str(obj)
    return obj
