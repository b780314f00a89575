"""Calibration from pulls: measured against fitted force-displacement curves, and residuals."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from exofric.plots._common import SMALL, finish, new_figure

__all__ = ["plot_pullout_fit"]


def _coef_text(fit: Any) -> str:
    parts = []
    for k in fit.fitted:
        v = fit.estimate[k]
        if not math.isfinite(v):
            parts.append(f"{k} not identifiable")
        else:
            parts.append(f"{k} {v:.3g} [{fit.ci_low[k]:.3g}, {fit.ci_high[k]:.3g}]")
    return "; ".join(parts)


def plot_pullout_fit(fit: Any, fig: Any | None = None) -> Any:
    """Measured (dots) and fitted (lines) pull force against displacement, one colour per
    pressure, and the residuals (N) below.

    Parameters
    ----------
    fit : PulloutFit
        From :func:`exofric.friction.fit_pullout`.
    fig : matplotlib Figure, optional
        Empty figure to draw on (default a new one).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> x = np.linspace(0.0, 1.0, 5)
    >>> pull = {"label": 1, "pressure_mpa": 0.4, "group": 0, "displacement_mm": x,
    ...         "force_n": x, "model_n": x}
    >>> fit = SimpleNamespace(pulls=(pull,), pressures_mpa=np.array([0.4]), fitted=("mu_wire",),
    ...                       estimate={"mu_wire": 0.3}, ci_low={"mu_wire": 0.2},
    ...                       ci_high={"mu_wire": 0.4}, confidence=0.95, rmse_n=0.0)
    >>> [a.get_ylabel() for a in plot_pullout_fit(fit).axes]
    ['pull force F (N)', 'residual (N)']
    """
    fig, created = new_figure(fig, (7.0, 6.0))
    ax, axr = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    colours = {g: f"C{g % 10}" for g in range(len(fit.pressures_mpa))}
    labelled: set[int] = set()
    for p in fit.pulls:
        g = int(p["group"])
        c = colours[g]
        x = np.asarray(p["displacement_mm"])
        order = np.argsort(x, kind="stable")
        step = max(1, x.size // 150)            # at most ~150 dots per pull
        ax.plot(x[order][::step], np.asarray(p["force_n"])[order][::step], ".", ms=2.5,
                color=c, alpha=0.45)
        ax.plot(x[order], np.asarray(p["model_n"])[order], "-", lw=1.3, color=c,
                label=(f"{fit.pressures_mpa[g]:.3g} MPa" if g not in labelled else None))
        labelled.add(g)
        res = np.asarray(p["model_n"]) - np.asarray(p["force_n"])
        axr.plot(x[order][::step], res[order][::step], ".", ms=2, color=c, alpha=0.5)
    ax.set_ylabel("pull force F (N)")
    ax.set_title(f"measured (dots) and fitted (lines); {100 * fit.confidence:g} % intervals",
                 fontsize=SMALL + 1)
    ax.text(0.99, 0.03, _coef_text(fit), transform=ax.transAxes, ha="right", va="bottom",
            fontsize=SMALL, wrap=True,
            bbox={"boxstyle": "round", "fc": "white", "ec": "0.7", "alpha": 0.9})
    ax.grid(alpha=0.3)
    ax.legend(fontsize=SMALL, title="pressure", title_fontsize=SMALL, loc="upper left")
    axr.axhline(0.0, color="0.3", lw=0.8)
    axr.set_ylabel("residual (N)")
    axr.set_xlabel("wire displacement x (mm)")
    axr.grid(alpha=0.3)
    finish(fig, created)
    return fig
