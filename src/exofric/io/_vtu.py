"""Export of deformed meshes with fields (VTU via meshio) for ParaView."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exofric.io._files import atomic_path

__all__ = ["write_vtu", "QUAD9_TO_VTK"]

#: exofric's quad9 local order (a = 3 j + i) to VTK's biquadratic quad order.
QUAD9_TO_VTK = np.array([0, 2, 8, 6, 1, 5, 7, 3, 4])
QUAD4_TO_VTK = np.array([0, 1, 3, 2])


def write_vtu(
    path: str | Path,
    nodes: np.ndarray,
    elements: np.ndarray,
    displacement: np.ndarray,
    cell_fields: dict[str, np.ndarray] | None = None,
    point_fields: dict[str, np.ndarray] | None = None,
) -> Path:
    """Write the deformed mesh (mm) with point displacement and cell fields to ``path``.

    The format follows the suffix as in :func:`meshio.write` (VTU XML for ``.vtu`` and for an
    unknown suffix); the file is written atomically (see :func:`~exofric.io.atomic_path`).

    Parameters
    ----------
    path : str or Path
        Output file (parent directories are created).
    nodes : numpy.ndarray
        Undeformed node coordinates, shape (n, 2), in mm.
    elements : numpy.ndarray
        Connectivity, shape (m, 9) for quad9 (exofric's local order) or (m, 4) for quad4.
    displacement : numpy.ndarray
        Node displacements, shape (n, 2), in mm; written as ``displacement_mm``.
    cell_fields : dict of str to numpy.ndarray, optional
        Per-element values (name them with their unit, e.g. ``von_mises_mpa``).
    point_fields : dict of str to numpy.ndarray, optional
        Per-node values, shape (n,) (e.g. ``contact_pressure_wire_mpa``).

    Examples
    --------
    >>> import numpy as np, tempfile, os
    >>> from exofric.fe import polar_mesh
    >>> m = polar_mesh(1.0, 2.0, 1, 2)
    >>> p = write_vtu(os.path.join(tempfile.mkdtemp(), "t.vtu"), m.nodes, m.elements,
    ...               np.zeros_like(m.nodes))
    >>> p.suffix
    '.vtu'
    """
    import meshio

    kind = "quad9" if elements.shape[1] == 9 else "quad"
    perm = QUAD9_TO_VTK if kind == "quad9" else QUAD4_TO_VTK
    pts = np.column_stack([nodes + displacement, np.zeros(len(nodes))])
    disp3 = np.column_stack([displacement, np.zeros(len(nodes))])
    cd = {k: [np.asarray(v)] for k, v in (cell_fields or {}).items()}
    pd = {"displacement_mm": disp3, **{k: np.asarray(v, dtype=float)
                                        for k, v in (point_fields or {}).items()}}
    mesh = meshio.Mesh(pts, [(kind, elements[:, perm])], point_data=pd, cell_data=cd)
    p = Path(path)
    fmt = meshio.extension_to_filetypes.get(p.suffix.lower(), ["vtu"])[0]
    with atomic_path(p) as tmp:
        mesh.write(tmp, file_format=fmt)
    return p
