"""Material fit figure: data and fitted curves per test mode, with the residuals below.

Presentation only: the fit is read through its attributes (stretch unitless, stress MPa).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from exofric.plots._common import SMALL, finish, new_figure

if TYPE_CHECKING:
    from exofric.material import MaterialFit

__all__ = ["plot_material_fit"]

_COLOURS = {"uniaxial": "tab:blue", "biaxial": "tab:orange", "planar": "tab:green"}
_LABELS = {"uniaxial": "uniaxial", "biaxial": "equibiaxial", "planar": "planar (pure shear)"}


def plot_material_fit(fit: MaterialFit, fig: Any | None = None, title: str = "") -> Any:
    """Nominal stress (MPa) against stretch per mode: data, fitted curve, and residuals (MPa).

    Top panel: the measured points and the fitted model's curve of each mode fitted, from
    stretch 1 to the mode's largest stretch. Bottom panel: ``fitted - measured`` (MPa) per
    point. The title gives the model, its shear modulus and the stability check.

    Parameters
    ----------
    fit : MaterialFit
        From :func:`exofric.material.fit_material` (stresses in MPa).
    fig : matplotlib Figure, optional
        An empty figure to draw on (default a new one, 7 x 6.4 in).
    title : str
        Figure title (default: the model and its fit summary).

    Returns
    -------
    matplotlib Figure

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> from exofric.material import fit_material, treloar_1944
    >>> fig = plot_material_fit(fit_material("yeoh", **treloar_1944()), Figure())
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['nominal stress P (MPa)', 'residual P^ - P (MPa)']
    """
    fig, created = new_figure(fig, (7.0, 6.4))
    top, bottom = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1.3]})
    for mode, m in fit.modes.items():
        c = _COLOURS.get(mode, "k")
        lo, hi = min(1.0, float(m.stretch.min())), max(1.0, float(m.stretch.max()))
        lam = np.linspace(lo, hi, 200)
        curve = fit.model.stress_mpa(mode, lam)
        top.plot(m.stretch, m.stress_mpa, "o", color=c, ms=5, mfc="none",
                 label=f"{_LABELS.get(mode, mode)} data ({m.stress_kind})")
        top.plot(lam, curve, "-", color=c, lw=1.8,
                 label=f"fit: R$^2$ = {m.r2:.3f}, RMS = {m.rms_mpa:.3f} MPa")
        bottom.plot(m.stretch, m.residual_mpa, "o-", color=c, ms=4, lw=0.8)
    top.set_ylabel("nominal stress P (MPa)")
    top.legend(fontsize=SMALL, loc="upper left")
    top.grid(alpha=0.3)
    bottom.axhline(0.0, color="0.5", lw=0.8)
    bottom.set_ylabel("residual P^ - P (MPa)")
    bottom.set_xlabel("stretch (unitless)")
    bottom.grid(alpha=0.3)
    st = fit.stability
    stab = ("Drucker-stable" if st.stable else "UNSTABLE") + (
        f" over stretch {st.stretch_min:.3g}-{st.stretch_max:.3g}") + (
        " (constrained)" if getattr(fit, "constrained", False) else "")
    top.set_title(title or f"{fit.model.name}: mu = {fit.model.shear_modulus_mpa:.4g} MPa, "
                  f"{fit.residuals} residuals; {stab}", fontsize=SMALL + 1)
    finish(fig, created)
    return fig
