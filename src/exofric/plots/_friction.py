"""Figures for the friction model (matplotlib, Agg): gamma fit with residuals, predictions.

Presentation only: each function takes computed results and returns a matplotlib Figure
(save it with :func:`exofric.plots.save`). Units: MPa, N, %.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from exofric.friction import GammaFit, Prediction

__all__ = ["plot_gamma_fit", "plot_predictions"]


def _plt() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_gamma_fit(fit: GammaFit, title: str = "") -> Any:
    """Measured vs fitted friction (left), residuals in N and % (right).

    Parameters
    ----------
    fit : GammaFit
        Result of :func:`exofric.friction.fit_gamma`.
    title : str
        Figure title (e.g. ``"SYNTHETIC rig data"``).
    """
    plt = _plt()
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(13, 4))
    p = np.asarray(fit.pressure_mpa)
    a1.plot(p, fit.friction_n, "o", color="tab:red", label="measured F")
    lab = f"gamma N (gamma = {fit.gamma:.4f})"
    if fit.kind == "affine":
        lab = f"gamma N + F0 (gamma = {fit.gamma:.4f}, F0 = {fit.model.f0_n:.2f} N)"
    o = np.argsort(p)
    a1.plot(p[o], np.asarray(fit.predicted_friction_n)[o], "-", color="k", label=lab)
    a1.set_ylabel("friction F (N)")
    a1.legend(fontsize=8)
    lo, hi = fit.gamma_ci95
    a1.set_title(f"95% CI [{lo:.4f}, {hi:.4f}] ({fit.ci_method})", fontsize=9)
    a2.plot(p, fit.residual_n, "o", color="tab:blue")
    a2.set_ylabel("residual F^ - F (N)")
    a2.set_title(f"n = {fit.n_points} points", fontsize=9)
    a3.plot(p, fit.point_relative_error_pct, "s", color="tab:orange")
    a3.set_ylabel("relative error (F^ - F)/F (%)")
    a3.set_title(f"mean |rel. error| = {fit.relative_error_pct:.2f}%", fontsize=9)
    for ax in (a1, a2, a3):
        ax.set_xlabel("pressure P (MPa)")
        ax.grid(alpha=0.3)
    for ax in (a2, a3):
        ax.axhline(0.0, color="0.5", lw=0.8)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def plot_predictions(preds: Sequence[Prediction], title: str = "") -> Any:
    """Per structure: predicted (black) vs tested (red) friction and the relative error curve."""
    plt = _plt()
    k = max(len(preds), 1)
    fig, axes = plt.subplots(k, 2, figsize=(10, 3.2 * k), squeeze=False)
    for (a1, a2), pr in zip(axes, preds, strict=False):
        a1.plot(pr.pressure_mpa, pr.predicted_friction_n, "-", color="k", label="predicted")
        if pr.measured is not None:
            a1.plot(pr.measured.pressure_mpa, pr.measured.friction_n, "o-", color="tab:red",
                    label="tested")
            a2.plot(pr.measured.pressure_mpa, pr.relative_error_pct, "o-", color="tab:blue")
            m = pr.max_relative_error_pct
            a2.set_title(f"max relative error {m:.2f}%" if m is not None else "", fontsize=9)
        else:
            a2.text(0.5, 0.5, "no measured curve", ha="center", va="center",
                    transform=a2.transAxes)
        dev = pr.deviation
        flag = "" if dev.in_validated_region else " (outside validated region)"
        a1.set_title(f"{pr.structure.name}: deviation {dev.deviation_pct:.1f}%{flag}", fontsize=9)
        a1.set_xlabel("pressure P (MPa)")
        a1.set_ylabel("friction F (N)")
        a1.legend(fontsize=8)
        a1.grid(alpha=0.3)
        a2.axhline(0.0, color="0.5", lw=0.8)
        a2.set_xlabel("pressure P (MPa)")
        a2.set_ylabel("relative error (%)")
        a2.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig
