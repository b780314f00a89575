"""The exofric version (one place, importable from every layer).

This constant is the single source: ``pyproject.toml`` reads it (``dynamic = ["version"]``,
``[tool.setuptools.dynamic]``), so the installed metadata carries the same string and nothing
reads :mod:`importlib.metadata` at import time (it costs ~20 ms of every CLI start-up).
"""

__version__ = "0.1.0"

__all__ = ["__version__"]
