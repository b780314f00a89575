"""FElupe 3-D check of the vector held zone on the squeezed tube (issue 39, session 47).

The vector held zone (``src/exofric/simulate/_vector_zone.py``) is the linearised 3-D problem
about the squeeze state. Its tests check it on a free and an inflated annulus (closed-form
states, CalculiX); this script checks it on the squeezed tube itself, with its contact arcs,
its non-circular bore and the squeeze's own mixed pressure, against a 3-D model that shares
nothing with it but the input: FElupe (GPL-3, benchmarks and tests only), tri-quadratic
27-node hexahedra with FElupe's three-field (u, p, J) formulation and the Mooney-Rivlin law of
``felupe_models.py``, solved in full nonlinearity.

**The problem** (half model, x >= 0; a zone of length ``lz`` next to a held end face):

1. *The squeezed state.* exofric's 2-D squeeze mesh is extruded along z. Its contact nodes
   (tube-wire and tube-wall arcs, all z) are moved in the plane to where exofric's squeeze put
   them (Dirichlet), the bore carries the follower pressure P (FElupe's
   ``SolidBodyPressure``), x = 0 is a symmetry plane, both end faces have u_z = 0. FElupe's
   Newton starts from exofric's displacement and finds its own equilibrium (z-invariant).
2. *The pull, with every contact stuck.* The contact nodes keep their in-plane position; the
   wire-arc nodes move along z by ``delta f(z)`` (f = 0 on the held face z = 0), the wall-arc
   nodes stay; u_z = 0 on the held face; the far face z = lz keeps its in-plane position and
   is free along z under the state's axial stress (the middle of a tube held at both ends,
   where the pull's increment of u_z is even and that of u_x, u_y odd). ``delta`` = 1e-4 mm
   (linear: 2 delta changes the stiffness by < 1e-4); on ``NONLINEAR_CASES`` also +-0.05 and
   +-0.1 mm, the size of the held tubes' secant displacement at 0.6 MPa (the pull's geometric
   nonlinearity, which the vector zone neglects). A tube held at both ends pulls one face's
   zone by +delta and, mirrored, the other's by -delta: the held tube's stiffness is the mean
   of the two signs.

Measured: the energy stiffness K_f = sum r_z f / delta (N/mm, half model) over the wire-arc
nodes, r_z their axial reactions, for the profiles f(z) = sin(pi z / 2 lz) and 1 - exp(-z /
0.25 mm). exofric's vector zone gives the same quantity as w^T C w with C its condensed
contact stiffness (stations x contact nodes) and w = f at its stations on the wire arc
(``tests/test_vector_zone.py``).

Run (adds the cases of ``CASES`` not yet in ``tests/data/felupe_vector_zone.json``; 1-2 min
per case on the draft mesh, 5-10 on the standard one, on one core; ``--redo``: all)::

    python benchmarks/felupe_vector_zone.py

Units: mm, N, MPa.
"""

from __future__ import annotations

import argparse
import datetime
import json
import platform
import sys
import time
from pathlib import Path
from typing import Any

import felupe as fem
import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from felupe_models import mooney_rivlin_umat  # noqa: E402

OUT = HERE.parent / "tests" / "data" / "felupe_vector_zone.json"

#: the cases: (structure of bench_pullout_ccx, pressure MPa, exofric accuracy)
CASES: tuple[tuple[str, float, str], ...] = (("test 1", 0.2, "draft"), ("test 1", 0.6, "draft"),
                                             ("test 3", 0.6, "draft"),
                                             ("test 1", 0.6, "standard"),
                                             ("test 3", 0.6, "standard"))
#: the zone's length (mm): half of the 5 mm tubes of the CalculiX comparison
ZONE_MM = 2.5
#: FElupe's elements along z: first element (mm) at the held face, growth; and the refined
#: grid of the convergence check (8 and 12 elements over 2.5 mm)
Z_FIRST_MM, Z_GROWTH = 0.1, 1.35
Z_FINE = (0.05, 1.25)
#: the exponential profile's length (mm)
EXP_MM = 0.25
DELTA_MM = 1e-4
#: the pull's geometric nonlinearity: the same at delta = +-0.05 and +-0.1 mm (the secant k1 of
#: the held tubes is read at 0.1 mm at 0.6 MPa), on the cases listed
LARGE_DELTA_MM = 0.05
NONLINEAR_CASES: tuple[tuple[str, float, str], ...] = (("test 1", 0.6, "draft"),)



def profiles(z: np.ndarray, lz: float = ZONE_MM) -> dict[str, np.ndarray]:
    """The prescribed axial profiles of the wire arc, f(z) (unitless, 0 at the held face)."""
    z = np.asarray(z, float)
    return {"sine": np.sin(0.5 * np.pi * z / lz), "exp": 1.0 - np.exp(-z / EXP_MM)}


def z_grid(lz: float = ZONE_MM, first: float = Z_FIRST_MM, growth: float = Z_GROWTH
           ) -> np.ndarray:
    """Element edges along z (mm), graded from the held face z = 0."""
    sizes = first * growth ** np.arange(64)
    n = int(np.searchsorted(np.cumsum(sizes), lz - 1e-12)) + 1
    sizes = sizes[:n] * (lz / sizes[:n].sum())
    return np.r_[0.0, np.cumsum(sizes)]


def squeeze_state(name: str, pressure: float, accuracy: str) -> dict[str, Any]:
    """exofric's squeeze at ``pressure`` (the input of both models): mesh, displacement,
    contact nodes, material constants."""
    import bench_pullout_ccx as bpc

    from exofric.simulate import squeeze

    mat = bpc.material()
    res = squeeze(bpc.structure(name), mat, [pressure], gravity="none", keep_fields=True,
                  accuracy=accuracy)
    prof = res.contact.profiles[0]
    return {"res": res, "nodes": np.asarray(res.nodes), "elements": np.asarray(res.elements),
            "u": np.asarray(res.displacements[0]),
            "wire": np.asarray(prof["wire"]["node"], int),
            "wall": np.asarray(prof["wall"]["node"], int),
            "c10": mat.c10_mpa, "c01": mat.c01_mpa, "d": mat.d_per_mpa}


def extrude(nodes: np.ndarray, elements: np.ndarray, zedges: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(points (n3, 3), hex27 cells in FElupe's order, z of each level): quad9 (exofric's
    local order a = 3 j + i) extruded with quadratic elements along z."""
    zl = np.empty(2 * len(zedges) - 1)
    zl[0::2] = zedges
    zl[1::2] = 0.5 * (zedges[:-1] + zedges[1:])
    n2 = len(nodes)
    pts = np.hstack([np.tile(nodes, (len(zl), 1)), np.repeat(zl, n2)[:, None]])
    ref = fem.TriQuadraticHexahedron().points.astype(int) + 1  # (27, 3) in {0, 1, 2}
    a2 = 3 * ref[:, 1] + ref[:, 0]
    cells = []
    for m in range(len(zedges) - 1):
        lev = 2 * m + ref[:, 2]
        cells.append(lev[None, :] * n2 + elements[:, a2])
    return pts, np.vstack(cells), zl


def felupe_zone(state: dict[str, Any], pressure: float, lz: float = ZONE_MM,
                zedges: np.ndarray | None = None, delta: float = DELTA_MM) -> dict[str, Any]:
    """The FElupe model of the module docstring: K_f (N/mm, half model) per profile, at
    ``delta`` and 2 ``delta`` (mm; ``linearity``: the relative change)."""
    t0 = time.perf_counter()
    zedges = z_grid(lz) if zedges is None else zedges
    nodes, elements, u2 = state["nodes"], state["elements"], state["u"]
    pts, cells, zl = extrude(nodes, elements, zedges)
    n2 = len(nodes)
    mesh = fem.Mesh(pts, cells, "hexahedron27")
    region = fem.RegionTriQuadraticHexahedron(mesh)
    fields = fem.FieldsMixed(region, n=3)
    u = fields[0]
    u.values[:, :2] = np.tile(u2, (len(zl), 1))  # start from exofric's squeeze
    solid = fem.SolidBody(mooney_rivlin_umat(state["c10"], state["c01"], state["d"]), fields)
    # the bore: the reference mesh's inner ring (radius ID / 2 about the tube's centre)
    st = state["res"].structure
    r = np.hypot(*(nodes - np.asarray(st.tube_center_mm)).T)
    bore2 = np.abs(r - 0.5 * st.tube_id_mm) < 1e-6
    bmask = np.tile(bore2, len(zl))
    boundary = fem.RegionTriQuadraticHexahedronBoundary(mesh, mask=bmask)
    pfield = fem.FieldContainer([fem.Field(boundary, dim=3)])
    bore = fem.SolidBodyPressure(pfield, pressure=pressure)
    level = np.repeat(np.arange(len(zl)), n2)
    node2 = np.tile(np.arange(n2), len(zl))
    contact2 = np.zeros(n2, bool)
    contact2[state["wire"]] = contact2[state["wall"]] = True
    on_contact = contact2[node2]
    wire = np.isin(node2, state["wire"])
    sym = np.abs(pts[:, 0]) < 1e-9
    face0, face1 = level == 0, level == len(zl) - 1

    def bc(mask: np.ndarray, skip: tuple[int, int, int], value: Any = 0.0) -> fem.Boundary:
        return fem.Boundary(u, mask=mask, skip=skip, value=value)

    inplane = bc(on_contact, (0, 0, 1))
    assert np.array_equal(inplane.dof, (3 * inplane.points[:, None] + np.arange(2)).ravel())
    inplane.update(u.values[inplane.points, :2].ravel())
    bcs = {"symmetry": bc(sym, (0, 1, 1)), "inplane": inplane,
           "ends": bc(face0 | face1, (1, 1, 0)), "contact_z": bc(on_contact, (1, 1, 0))}

    def solve(b: dict[str, fem.Boundary], loads: tuple[Any, ...] = ()) -> Any:
        dof0, dof1 = fem.dof.partition(fields, b)
        ext0 = fem.dof.apply(fields, b, dof0)
        return fem.newtonraphson(items=[solid, bore, *loads], x0=fields, dof1=dof1, dof0=dof0,
                                 ext0=ext0, tol=1e-10, verbose=0, maxiter=30)

    first = solve(bcs)
    t_state = time.perf_counter() - t0

    def reactions() -> np.ndarray:
        n = u.values.size
        v = np.asarray(solid.assemble.vector(fields).todense()).ravel()[:n]
        v = v + np.asarray(bore.assemble.vector(pfield).todense()).ravel()[:n]
        return v.reshape(-1, 3)

    r0 = reactions()
    base = u.values.copy()
    # how far FElupe's own equilibrium moved from exofric's squeeze (the contact nodes held)
    moved = np.hypot(*(u.values[:, :2] - np.tile(u2, (len(zl), 1))).T)
    out: dict[str, Any] = {"points": int(mesh.npoints), "cells": int(mesh.ncells),
                           "dofs": int(sum(fields.fieldsizes)), "z_edges_mm": zedges.tolist(),
                           "state_iterations": int(first.iterations),
                           "state_moved_max_mm": float(moved.max()),
                           "squeeze_displacement_max_mm": float(np.hypot(*u2.T).max())}
    far_inplane = bc(face1, (0, 0, 1))
    far_inplane.update(base[far_inplane.points, :2].ravel())
    # the far face is free along z under the state's axial stress (the plane-strain state's
    # sigma_zz, even about the middle of the tube; the pull's increment of sigma_zz is odd
    # about it, so zero there)
    far = np.flatnonzero(face1)
    keep_state = fem.PointLoad(fields, far, values=np.c_[0 * far, 0 * far, r0[far, 2]])
    for name, f in profiles(zl, lz).items():
        ks = []
        for scale in (1.0, 2.0):
            u.values[:] = base
            d = scale * delta
            wz = np.where(wire, d * f[level], 0.0)
            cz = bc(on_contact & ~face0, (1, 1, 0))
            cz.update(wz[cz.points])
            b = {"symmetry": bcs["symmetry"], "inplane": inplane, "held": bc(face0, (1, 1, 0)),
                 "far": far_inplane, "contact_z": cz}
            solve(b, (keep_state,))
            rz = reactions()[:, 2] - r0[:, 2]
            ks.append(float((rz * wz)[wire].sum() / d ** 2))
        out[name] = {"k_n_per_mm": ks[0], "linearity": ks[1] / ks[0] - 1.0}
    u.values[:] = base
    out["wall_time_s"] = time.perf_counter() - t0
    out["state_wall_time_s"] = t_state
    return out


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="the first case only, not stored")
    ap.add_argument("--redo", action="store_true",
                    help="run every case (default: only those not yet stored)")
    args = ap.parse_args(argv)
    old = json.loads(OUT.read_text()) if OUT.exists() and not args.redo else {"runs": []}
    have = {(r["structure"], r["pressure_mpa"], r["accuracy"]): r for r in old["runs"]}
    rows = []
    for name, p, acc in CASES[:1] if args.quick else CASES:
        large = (name, p, acc) in NONLINEAR_CASES
        if (name, p, acc) in have and not args.quick and (
                not large or {"large_delta", "large_delta_negative"} <= set(have[name, p, acc])):
            rows.append(have[name, p, acc])
            continue
        st = squeeze_state(name, p, acc)
        if (name, p, acc) in have:
            r = have[name, p, acc]
        else:
            r = felupe_zone(st, p)
            fine = felupe_zone(st, p, zedges=z_grid(ZONE_MM, *Z_FINE))
            r["z_refined"] = {k: fine[k] for k in ("z_edges_mm", "sine", "exp", "wall_time_s")}
            r = {"structure": name, "pressure_mpa": p, "accuracy": acc, **r}
        for key, d in (("large_delta", LARGE_DELTA_MM),
                       ("large_delta_negative", -LARGE_DELTA_MM)):
            if large and key not in r:
                big = felupe_zone(st, p, delta=d)
                r[key] = {"delta_mm": d, **{k: big[k] for k in ("sine", "exp", "wall_time_s")}}
        rows.append(r)
        print(json.dumps(rows[-1]), flush=True)
    data = {"description": __doc__.split("\n\n")[0], "zone_mm": ZONE_MM, "exp_mm": EXP_MM,
            "delta_mm": DELTA_MM, "units": {"k_n_per_mm": "N/mm, half model"}, "runs": rows,
            "provenance": {"created_utc": datetime.datetime.now(datetime.UTC).isoformat(
                timespec="seconds"), "script": "benchmarks/felupe_vector_zone.py",
                "felupe_version": fem.__version__, "platform": platform.platform(),
                "python": platform.python_version()}}
    if not args.quick:
        tmp = OUT.with_suffix(".tmp")
        tmp.write_text(json.dumps(data, indent=1) + "\n")
        tmp.replace(OUT)
    return data


if __name__ == "__main__":
    main()
