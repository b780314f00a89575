"""Shared plumbing of the figures: new Axes/Figure on demand, and :func:`save`.

No backend is selected here (library code never calls ``matplotlib.use``): matplotlib picks
its default, and the CLI sets ``MPLBACKEND=Agg`` once at start-up.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["new_axes", "new_figure", "finish", "save", "SMALL", "is_synthetic"]

# Smallest text (pt) in a figure: the report shows figures in a ~1100 px column, at most ~20 %
# below their natural size (130 dpi, <= ~1400 px wide), so 9 pt stays >= ~12 CSS px there.
SMALL = 9.0


def is_synthetic(title: str) -> bool:
    """Whether a figure title says its data are SYNTHETIC (virtual rig), for default labels."""
    return "synthetic" in title.lower()


def new_axes(ax: Any | None, figsize: tuple[float, float]) -> tuple[Any, bool]:
    """``(ax, created)``: ``ax`` itself, or the single Axes of a new pyplot figure (inches)."""
    if ax is not None:
        return ax, False
    import matplotlib.pyplot as plt

    _, new = plt.subplots(figsize=figsize)
    return new, True


def new_figure(fig: Any | None, figsize: tuple[float, float]) -> tuple[Any, bool]:
    """``(fig, created)``: ``fig`` itself (should be empty), or a new pyplot figure (inches)."""
    if fig is not None:
        return fig, False
    import matplotlib.pyplot as plt

    return plt.figure(figsize=figsize), True


def finish(fig: Any, created: bool) -> None:
    """Lay out a figure this package created (a caller's figure is left as it is)."""
    if created:
        fig.tight_layout()


def save(fig: Any, path: str | Path, *, dpi: int = 130, close: bool = True) -> Path:
    """Write a figure (or the figure of an Axes) to ``path`` and return the path.

    The format follows the suffix (``.png``, ``.svg``, ``.pdf``); a path without a suffix gets
    ``.png`` appended, and the path returned is the one written. The image is written
    atomically (a temporary file in the same directory, then renamed): a failed write leaves no
    partial file, and its :class:`OSError` names ``path``. Only the image file is written: the
    parent directory must exist. The figure is closed afterwards unless ``close=False``.

    Parameters
    ----------
    fig : matplotlib Figure or Axes
        What to write (an Axes writes its whole figure).
    path : str or Path
        Output file; its directory must exist.
    dpi : int
        Resolution in dots per inch (raster formats).
    close : bool
        Close the figure after writing (frees it from pyplot).

    Returns
    -------
    Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import matplotlib.pyplot as plt
    >>> from exofric.plots import save
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0.0, 0.6], [0.0, 268.55])
    >>> out = save(fig, pathlib.Path(tempfile.mkdtemp()) / "n.png")
    >>> out.stat().st_size > 0
    True
    """
    import os
    import uuid

    from matplotlib.axes import Axes

    figure: Any = fig.figure if isinstance(fig, Axes) else fig
    figure = getattr(figure, "figure", figure)  # the root figure of a SubFigure
    p = Path(path)
    if not p.suffix:  # matplotlib would write "out.png" for "out": name the file it writes
        p = p.with_name(p.name + ".png")
    fmt = p.suffix[1:].lower()
    # atomic: a full disk or a killed process leaves a hidden temporary file, never a partial
    # image under the requested name
    tmp = p.parent / f".{p.name}.{uuid.uuid4().hex}.tmp"
    try:
        figure.savefig(tmp, dpi=dpi, bbox_inches="tight", format=fmt)
        os.replace(tmp, p)
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        raise OSError(exc.errno, f"cannot write the figure ({exc.strerror or exc})",
                      str(p)) from None
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    finally:
        if close:
            import matplotlib.pyplot as plt

            plt.close(figure)
    return p
