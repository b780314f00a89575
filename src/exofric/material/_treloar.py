"""Treloar's (1944) natural-rubber data, shipped as package data with its provenance.

L. R. G. Treloar, "Stress-strain data for vulcanised rubber under various types of
deformation", Trans. Faraday Soc. 40 (1944) 59-70. Tabulated in N/mm^2 (= MPa, Treloar's
kgf/cm^2 x 0.0981) by github.com/Chongran-Zhao/Hyperelastic-fitting (MIT), files
``Treloar_1944/{UT,ET,PS}/stress_stretch.txt`` at commit
2e9f227cd03779934932b106f365ef08831863a9; each CSV's header says so. The files are package
resources read as text (no file-format code here: that lives in :mod:`exofric.io`).
"""

from __future__ import annotations

from importlib.resources import files
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

__all__ = ["TRELOAR_SOURCE", "treloar_1944"]

#: Where the shipped Treloar data come from (paper, tabulation, commit).
TRELOAR_SOURCE = (
    "Treloar, L.R.G. (1944) Trans. Faraday Soc. 40, 59-70 (doi:10.1039/TF9444000059); "
    "tabulation github.com/Chongran-Zhao/Hyperelastic-fitting (MIT) "
    "Treloar_1944/{UT,ET,PS}/stress_stretch.txt @ 2e9f227cd03779934932b106f365ef08831863a9; "
    "nominal stress in MPa (kgf/cm^2 x 0.0981)"
)


def _load(mode: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    import numpy as np

    text = (files("exofric.material") / "data" / f"treloar1944_{mode}.csv").read_text("utf-8")
    rows = [ln for ln in text.splitlines() if ln.strip() and not ln.startswith("#")]
    assert rows[0] == "stretch,stress_mpa", rows[0]
    a = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return a[:, 0], a[:, 1]


def treloar_1944() -> dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """Treloar's 1944 natural rubber data: stretch and nominal stress (MPa) per test mode.

    Uniaxial tension (24 points, stretch 1.02-7.6), equibiaxial tension (16 points,
    1.03-4.45) and pure shear (13 points, 1.03-4.97); provenance in :data:`TRELOAR_SOURCE`
    and each CSV's header.

    Returns
    -------
    dict
        ``{"uniaxial": (stretch, stress_mpa), "biaxial": ..., "planar": ...}``: stretch
        unitless, engineering (nominal) stress in MPa; ready for
        ``fit_material(model, **treloar_1944())``.

    Examples
    --------
    >>> data = treloar_1944()
    >>> stretch, stress_mpa = data["uniaxial"]
    >>> len(stretch), float(stretch[-1]), float(stress_mpa[-1])
    (24, 7.6, 6.3176)
    """
    return {mode: _load(mode) for mode in ("uniaxial", "biaxial", "planar")}
