"""Where along z the held tube's excess stiffness sits: the wire's axial friction force and
normal force per slice of a held 5 mm tube, CalculiX against exofric's held zone (issue 39).

The 5 mm base tube of ``bench_pullout_ccx.py`` (Shore 62.5, mu_wire 0.3, mu_wall 0.5, 2 x 20
in the plane, ``n_z`` C3D20R elements along z, ends held axially) is pulled to 4 d1 (d1 =
0.1 mm (P / 0.6 MPa)^2, the k1 secant's displacement). From the rigid wire's nodal reactions
(``*NODE PRINT`` of NWIRE, every output) the axial and the radial (normal) force are summed
per element of the wire's own mesh along z (a 20-node element's three planes: the middle one
and half of each end plane, which keeps a uniform traction's total per element), after the
inflation and at every output of the pull. exofric's side: the held zone of the same tube
(``pullout(..., ends="fixed")``; the zone of half the tube, held face to the symmetric
middle): the friction force per station (the condensed stiffness times the contact nodes'
axial displacements, both arcs' wire nodes, x 2 for the half model) over its tributary
length, plus the held face's rigid-plastic end row. Both are integrated over the same bins:
next to a held face (0 to the wire element's edge at ~0.58 mm) and the zone's interior
(from there to the middle, 2.5 mm); the 3-D tube's two halves each (the faces are not alike in
3-D: the contact pressure rises next to one and falls next to the other during the pull) and
their mean.

Run: ``python benchmarks/calculix_zprofile.py [--pressures 0.2,0.6] [--n-z 10] [--out PATH]``
(3-4 min of CalculiX CPU per pressure on one thread). Stored:
``tests/data/ccx_pullout_zprofile.json``. Units: mm, N, MPa.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import re
import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_pullout_ccx as bpc  # noqa: E402
import calculix_models as ccxm  # noqa: E402
import calculix_pullout as ccxp  # noqa: E402


def _per_element(planes: np.ndarray) -> np.ndarray:
    """Per-element sums of plane values of 20-node elements along z (planes 0, 1, 2 | 2, 3,
    4 | ...): the middle plane and half of each shared end plane (the outer ends whole)."""
    v = np.asarray(planes, float)
    n = (len(v) - 1) // 2
    return np.array([(0.5 * v[2 * k] if k else v[0]) + v[2 * k + 1]
                     + (0.5 * v[2 * k + 2] if k < n - 1 else v[-1]) for k in range(n)])


def ccx_profile(pressure: float, n_z: int = 10) -> dict[str, Any]:
    """The 3-D run: wire element edges along z (mm), normal force per element after the
    inflation (N), and axial and normal force per element at every output (N)."""
    st = bpc.structure("test 1")
    geo = (st.hole_mm, st.tube_od_mm, st.tube_id_mm, st.wire_mm)
    opts = {**bpc.TUBE, **bpc.MESHES[bpc.TUBE_MESH], "depth_mm": 5.0, "n_z": n_z,
            "delta_max_mm": bpc.secant_travel_mm(pressure),
            "max_increment_mm": bpc.MAX_INCREMENT_MM, "stick_slope": bpc.STICK_SLOPE}
    deck = ccxp.pullout_deck(geo, bpc.material(), pressure, bpc.MU_WIRE, bpc.MU_WALL, **opts)
    block = re.search(r"\*NODE[^\n]*\n(.*?)\n\*", deck.text, re.S)
    assert block is not None
    z = {int(r.split(",")[0]): float(r.split(",")[3]) for r in block.group(1).splitlines()}
    run = ccxm.run_ccx(deck.text, timeout_s=3600.0)
    if run.returncode != 0 or not run.dat:
        raise RuntimeError(run.stdout[-2000:])
    tab = ccxm.parse_dat(run.dat)
    times = sorted({t for (q, s, t) in tab if q == "forces" and s == "NWIRE"})
    wire, centre = deck.rigid_xy["wire"], np.asarray(deck.wire_center)
    keys = sorted({round(z[n], 6) for n in wire})

    def planes(rows: dict[Any, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        ax, nr = dict.fromkeys(keys, 0.0), dict.fromkeys(keys, 0.0)
        for n, v in rows.items():
            if isinstance(n, int) and n in wire:
                er = np.asarray(wire[n]) - centre
                nr[round(z[n], 6)] += 2.0 * float(v[:2] @ er) / float(np.linalg.norm(er))
                ax[round(z[n], 6)] += 2.0 * float(v[2])   # x 2: the half model
        return (_per_element(np.array([ax[k] for k in keys])),
                _per_element(np.array([nr[k] for k in keys])))

    out: dict[str, Any] = {"pressure_mpa": pressure, "n_z": n_z,
                           "edges_mm": list(keys[::2]),
                           "normal_inflated_n": planes(tab[("forces", "NWIRE", 1.0)])[1].tolist(),
                           "delta_mm": [], "axial_n": [], "normal_n": [],
                           "cpu_time_s": run.cpu_time_s}
    for d in deck.deltas_mm:
        t = 1.0 + float(d)
        k = min(times, key=lambda v: abs(v - t))
        if abs(k - t) <= 2e-6 * t:
            a, nr = planes(tab[("forces", "NWIRE", k)])
            out["delta_mm"].append(float(d))
            out["axial_n"].append(a.tolist())
            out["normal_n"].append(nr.tolist())
    return out


def exofric_profile(pressure: float, deltas: np.ndarray) -> dict[str, Any]:
    """exofric's held zone of the same tube: station positions (mm from the held face),
    tributary lengths (mm), friction force per station on the wire (N, whole section) and the
    end row's force (N) at each displacement (mm)."""
    from exofric.geometry import BASE
    from exofric.simulate import PulloutSetup, section_pullout
    from exofric.simulate._antiplane import solve_friction_steps
    from exofric.simulate._shear_lag import _z_modes, z_elements, zone_stiffness

    setup = PulloutSetup(dataclasses.replace(BASE, length_mm=5.0), bpc.material(),
                         mu_wire=bpc.MU_WIRE, mu_wall=bpc.MU_WALL, mu_wire_wall=0.0,
                         ends="fixed", cable_ea_n=bpc.CABLE_EA_N)
    he = section_pullout(setup, pressure).held_ends
    assert he is not None
    h = z_elements(2.5)
    zs = zone_stiffness(he, h, (True, False))
    _, _, trib = _z_modes(h, (True, False))
    out = solve_friction_steps(zs, np.asarray(deltas, float), he.penalty, he.creep_tol_mm)
    nc, on = len(he.contact), he.section.on_wire
    force = [[float((t[a * nc:(a + 1) * nc] * on).sum() * he.fac) for a in range(len(trib))]
             for t in (zs.K @ w for w in out["w"])]
    end = 0.5 * h[0] * float(he.section.capacity[on].sum()) * he.fac
    return {"z_mm": np.cumsum(h).tolist(), "trib_mm": trib.tolist(), "station_force_n": force,
            "end_row_n": end}


def _bins(edge: float) -> tuple[tuple[float, float], tuple[float, float]]:
    return (0.0, edge), (edge, 2.5)


def compare(c: dict[str, Any], e: dict[str, Any], d: float) -> dict[str, float]:
    """Forces (N) next to the front held face and in the zone's interior at displacement
    ``d`` (mm), 3-D and exofric (exofric's stations as piecewise-constant densities)."""
    k = int(np.argmin(np.abs(np.array(c["delta_mm"]) - d)))
    edges = np.array(c["edges_mm"])
    edge = float(edges[edges > 0.3][0])          # first wire element edge inside the tube
    ax = np.array(c["axial_n"][k])
    lo, hi = edges[:-1], edges[1:]
    z = np.array(e["z_mm"])
    a = np.r_[0.5 * (z[0] + 0.0), 0.5 * (z[:-1] + z[1:])]   # station tributary limits
    b = np.r_[0.5 * (z[:-1] + z[1:]), z[-1]]
    f = np.array(e["station_force_n"][k]) / (b - a)
    out: dict[str, float] = {"delta_mm": float(c["delta_mm"][k])}
    length = 5.0
    for name, (z0, z1) in zip(("face", "interior"), _bins(edge), strict=True):
        halves = []
        for y0, y1 in ((z0, z1), (length - z1, length - z0)):   # front half, back half
            w3 = np.clip(np.minimum(hi, y1) - np.maximum(lo, y0), 0, None) / (hi - lo)
            if name == "face":  # the elements at and beyond a face: wholly the face's
                w3 = np.where((lo < 0.0) if y0 == 0.0 else (hi > length), 1.0, w3)
            halves.append(float((ax * w3).sum()))
        we = np.clip(np.minimum(b, z1) - np.maximum(a, z0), 0, None)
        out[f"{name}_3d_front_n"], out[f"{name}_3d_back_n"] = halves
        out[f"{name}_3d_n"] = 0.5 * (halves[0] + halves[1])
        out[f"{name}_exofric_n"] = float((f * we).sum()) + (e["end_row_n"] if name == "face"
                                                            else 0.0)
    out["edge_mm"] = edge
    return out


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pressures", default="0.2,0.6")
    ap.add_argument("--n-z", type=int, default=10)
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    res: dict[str, Any] = {"description": __doc__.splitlines()[0], "units": "mm, N, MPa",
                           "runs": []}
    for p in (float(v) for v in args.pressures.split(",")):
        c = ccx_profile(p, args.n_z)
        e = exofric_profile(p, np.array(c["delta_mm"]))
        d1 = 0.1 * (p / 0.6) ** 2
        row = {"ccx": c, "exofric": e, "compare": [compare(c, e, d) for d in (d1, 2 * d1)]}
        res["runs"].append(row)
        for cmp_ in row["compare"]:
            print(f"P {p:g} MPa, d {cmp_['delta_mm']:.4f} mm: next to a face (0-"
                  f"{cmp_['edge_mm']:.2f} mm) 3-D {cmp_['face_3d_n']:.4f} N (halves "
                  f"{cmp_['face_3d_front_n']:.4f} / {cmp_['face_3d_back_n']:.4f}), exofric "
                  f"{cmp_['face_exofric_n']:.4f} N; interior 3-D {cmp_['interior_3d_n']:.4f} N "
                  f"({cmp_['interior_3d_front_n']:.4f} / {cmp_['interior_3d_back_n']:.4f}), "
                  f"exofric {cmp_['interior_exofric_n']:.4f} N")
        if args.out is not None:
            tmp = args.out.with_suffix(".tmp")
            tmp.write_text(json.dumps(res, indent=1))
            tmp.replace(args.out)
    return res


if __name__ == "__main__":
    main()
