"""exofric: friction modelling, prediction and control for friction-based
variable-stiffness structures (Ma et al., Actuators 2021).

Units everywhere: mm, N, MPa, s (Nm for torque).
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("exofric")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]
