"""Uniaxial tensile curves of soft-robotics silicones, shipped as package data with provenance.

Extracts of the Soft Robotics Materials Database (Marechal et al., Soft Robotics 8(3) 2021,
doi:10.1089/soro.2019.0115; github.com/LucMarechal/Soft-Robotics-Materials-Database),
licensed under the Open Database License 1.0 with contents under the Database Contents
License 1.0: ASTM D412 die C dumbbells (3 mm x 6 mm, gauge length 33 mm) pulled to failure
at 450 mm/min, strain from the crosshead. Each CSV's header states the source file, the
commit, the licence and which rows were kept (values unchanged). The files are package
resources read as text (file-format code lives in :mod:`exofric.io`).
"""

from __future__ import annotations

from importlib.resources import files
from typing import TYPE_CHECKING

from exofric.errors import InputError

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

__all__ = ["SILICONES", "SILICONE_SOURCE", "silicone_uniaxial"]

#: Shipped silicones: key -> (product, file stem).
SILICONES: dict[str, str] = {
    "ecoflex-00-30": "srmd_ecoflex0030",
    "dragon-skin-20": "srmd_dragonskin20",
    "rtv615": "srmd_rtv615",
}

#: Where the shipped silicone curves come from (database, paper, licence, commit).
SILICONE_SOURCE = (
    "Soft Robotics Materials Database, Marechal, Balland, Lindenroth, Petrou, Kontovounisios & "
    "Bello, Soft Robotics 8(3) (2021) 284-297, doi:10.1089/soro.2019.0115; "
    "github.com/LucMarechal/Soft-Robotics-Materials-Database Tensile-Tests-Data/*.csv @ "
    "1049b050a0f54bb7ab3e05487fe45416de287d50; ODbL 1.0 (contents DbCL 1.0); engineering strain "
    "and stress (MPa), rows subsampled, values unchanged"
)


def silicone_uniaxial(name: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A shipped silicone's uniaxial tensile curve: stretch and nominal stress (MPa).

    Parameters
    ----------
    name : {'ecoflex-00-30', 'dragon-skin-20', 'rtv615'}
        The silicone (see :data:`SILICONES`): Smooth-On Ecoflex 00-30 (102 points, stretch
        1.07-17.1), Dragon Skin 20 (102 points, 1.04-10.2) or Momentive RTV615 (84 points,
        1.04-2.93).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        Stretch (unitless, ``1 + engineering strain``) and engineering (nominal) stress in
        MPa; ready for ``fit_material(model, uniaxial=...)``.

    Examples
    --------
    >>> stretch, stress_mpa = silicone_uniaxial("rtv615")
    >>> len(stretch), round(float(stretch[-1]), 4), float(stress_mpa[-1])
    (84, 2.9318, 2.50748)
    """
    import numpy as np

    key = name.strip().lower() if isinstance(name, str) else name
    if key not in SILICONES:
        raise InputError(f"name must be one of {', '.join(SILICONES)}, got {name!r}",
                         param="name")
    stem = SILICONES[key]
    text = (files("exofric.material") / "data" / f"{stem}_uniaxial.csv").read_text("utf-8")
    rows = [ln for ln in text.splitlines() if ln.strip() and not ln.startswith("#")]
    assert rows[0] == "strain,stress_mpa", rows[0]
    a = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return 1.0 + a[:, 0], a[:, 1]
