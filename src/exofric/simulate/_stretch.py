"""The validity check every FE result runs: the largest principal stretch vs the paper's range."""

from __future__ import annotations

import warnings

import numpy as np

from exofric.defaults import MR_STRETCH_LIMIT

__all__ = ["StretchWarning", "check_stretch"]


class StretchWarning(UserWarning):
    """The tube is stretched beyond the validated range of the Mooney-Rivlin model.

    Examples
    --------
    >>> import warnings
    >>> import numpy as np
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_stretch(np.array([3.0]), np.array([1.0]), "inflate")
    >>> caught[0].category.__name__
    'StretchWarning'
    """


def check_stretch(max_stretch: np.ndarray, pressures: np.ndarray, what: str) -> None:
    """Warn (:class:`StretchWarning`) if a principal stretch exceeds the validated limit.

    The limit is :data:`exofric.defaults.MR_STRETCH_LIMIT` (2.5, the paper's 150% strain).

    Parameters
    ----------
    max_stretch : ndarray
        Largest principal stretch (unitless) at each pressure.
    pressures : ndarray
        The matching pressures (MPa), same length, for the message.
    what : str
        Which computation is checked (``"inflate"``, ``"squeeze"``), for the message.

    Examples
    --------
    >>> import numpy as np
    >>> check_stretch(np.array([1.2, 1.4]), np.array([0.2, 0.4]), "inflate")  # no warning
    """
    bad = np.flatnonzero(max_stretch > MR_STRETCH_LIMIT)
    if bad.size:
        k = int(bad[0])
        warnings.warn(
            f"{what}: principal stretch {max_stretch[k]:.2f} at {pressures[k]:g} MPa exceeds "
            f"{MR_STRETCH_LIMIT:g} (150% strain), the range the paper validates Mooney-Rivlin for",
            StretchWarning,
            stacklevel=3,
        )
