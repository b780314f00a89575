"""Make the weightless FElupe reference of the squeeze force N(P) (issue 18).

Writes ``tests/data/squeeze_reference_felupe.json``: N (N/mm, full section) at
P = 0.05, 0.10, ..., 0.60 MPa for several hole-tube-wire structures, computed with the
independent FElupe model of ``benchmarks/felupe_models.py`` (GPL-3, benchmarks and
tests only) on fine meshes graded toward the wire contact, frictionless, practically
without weight (density 1.1e-13 t/mm^3, see :meth:`SqueezeSetup.from_structure`),
with its provenance and the studies that justify it:

* mesh study: every structure on the reference mesh and on a finer one;
* density study (weightless limit) and penalty study on one structure;
* the coarse mesh that ``tests/test_squeeze_reference.py`` re-runs, so that the
  stored file cannot silently rot.

Run (about half an hour on 2 cores; the OpenBLAS "illegal value" lines come from
FElupe's linear solves of failed, cut-back attempts and are harmless)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/make_squeeze_reference.py --jobs 2

Issue 35's thick walls (``--set onset``, ``tests/data/squeeze_reference_felupe_onset.json``):
the five :data:`ONSET_STRUCTURES` on the reference mesh at every output pressure and on the
finer mesh up to :data:`ONSET_STUDY_SPAN_MPA` past each 1D onset (the first three significant
outputs of each). Run 2026-11-27 in one process, about 16 min on a shared 2-core machine (per
structure 100-169 s + 55-82 s)::

    OPENBLAS_NUM_THREADS=1 nice .venv/bin/python benchmarks/make_squeeze_reference.py \
        --set onset --jobs 1 --cache /tmp/onset.jsonl

Measured: changes to the finer mesh <= 0.037 % where N >= 1 % of N(0.6 MPa); against exofric's
own 8 x 192 convergence study (``--set onset-convergence``) <= 0.131 %.

Units: mm, N, MPa, s; forces per unit depth in N/mm, full section (2 x half model).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import felupe
import numpy as np
import scipy
from scipy.optimize import brentq

sys.path.insert(0, str(Path(__file__).resolve().parent))

from felupe_models import (  # noqa: E402
    WEIGHTLESS_DENSITY,
    SqueezeSetup,
    felupe_squeeze_model,
)

from exofric.friction import paper_structures  # noqa: E402
from exofric.geometry import Structure  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import compressible_inflation  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "data" / "squeeze_reference_felupe.json"
#: Second file (issue 35): thick walls (ID/OD ~0.54), small and large clearances, wires of
#: 1.1-2 mm, where the contact patch is born between two output pressures.
OUT_ONSET = ROOT / "tests" / "data" / "squeeze_reference_felupe_onset.json"

#: Output pressures (MPa): 0.05, 0.10, ..., 0.60.
PRESSURES_MPA = np.round(0.05 * np.arange(1, 13), 2)
#: Shore A hardness of the tube (paper); Mooney-Rivlin constants from it.
SHORE_A = 62.5
#: FElupe node-to-surface penalty (N/mm per mm of penetration, per node). Its error is
#: ~1/penalty: 1e4 changes N by < 1e-4 relative (penalty study), and convergence at 3e3
#: needs ~4x fewer Newton iterations than at 1e4 (fewer contact-status flips).
PENALTY = 3e3
#: Largest load increment (MPa); the frictionless result is path-independent (0.025
#: gives the same N to 1e-6).
MAX_INCREMENT_MPA = 0.05
#: Reference mesh (half tube): elements through the wall (radial_grading: thickest
#: inner / thinnest outer layer) and over the half circumference, of which n_circ_wall
#: are refined toward the hole wall (largest/smallest wall_grading) and the others toward
#: the wire (grading). Both contact patches are resolved: the wire patch (half-width
#: ~0.05 mm just after onset) by elements of ~0.01 mm, the wall patch by ~0.06 mm.
REFERENCE_MESH: dict[str, Any] = {"n_radial": 8, "n_circ": 160, "grading": 30.0,
                                  "radial_grading": 3.0, "n_circ_wall": 60,
                                  "wall_grading": 5.0}
#: The next finer mesh of the mesh study (1.5 x the elements in each direction).
FINER_MESH: dict[str, Any] = {**REFERENCE_MESH, "n_radial": 12, "n_circ": 240,
                              "n_circ_wall": 90}
#: Coarse mesh (half the elements in each direction) re-run by the slow test.
COARSE_MESH: dict[str, Any] = {**REFERENCE_MESH, "n_radial": 4, "n_circ": 80,
                               "n_circ_wall": 30}
COARSE_CHECK_STRUCTURE = "test 1"
#: 1D onset (MPa) aimed at by the variant structure: just above the 0.10 MPa output.
VARIANT_ONSET_MPA = 0.1015
#: Structure of the density and penalty studies, and the stiffer penalty of the latter.
STUDY_STRUCTURE = "test 1"
STUDY_PENALTY = 1e4


def material() -> MooneyRivlin:
    """The paper's tube material (Shore 62.5 Mooney-Rivlin)."""
    return MooneyRivlin.from_shore(SHORE_A)


def onset_1d_mpa(structure: Structure, mat: MooneyRivlin) -> float | None:
    """Weightless frictionless contact onset (MPa): free OD (1D solution) = D - d2."""
    def gap(p: float) -> float:
        od = compressible_inflation(structure.tube_od_mm, structure.tube_id_mm, mat, [p])
        return float(od.outer_diameter_mm[0]) - (structure.hole_mm - structure.wire_mm)

    try:
        return float(brentq(gap, 1e-6, 0.6, xtol=1e-10, rtol=1e-12))
    except ValueError:  # no sign change: touching at rest, or no contact up to 0.6 MPa
        return None


def structures(mat: MooneyRivlin) -> dict[str, Structure]:
    """Tests 1, 2, 3, 5, 7 of Table 3 and test 5 with D moved to put the onset at 0.1015."""
    table = {s.name: s for s in paper_structures()}
    out = {name: table[name] for name in ("test 1", "test 5", "test 7", "test 2", "test 3")}
    t5 = table["test 5"]
    od = compressible_inflation(t5.tube_od_mm, t5.tube_id_mm, mat, [VARIANT_ONSET_MPA])
    hole = round(float(od.outer_diameter_mm[0]) + t5.wire_mm, 3)  # 1 um: readable
    name = f"test 5, D = {hole:.3f} mm"
    out[name] = Structure(hole, t5.tube_od_mm, t5.tube_id_mm, t5.wire_mm, t5.length_mm, name)
    return out


#: Issue 35's structures (hole, OD, ID, wire in mm): the Table 3 family with thick walls
#: (ID/OD 0.54-0.55; onsets from 0.07 to 0.32 MPa), larger clearances and wires of 1.1-2 mm.
ONSET_STRUCTURES: dict[str, tuple[float, float, float, float]] = {
    "thick, d2 = 1.6": (10.0, 8.3, 4.5, 1.6),
    "thick, d2 = 1.1": (10.0, 8.3, 4.5, 1.1),
    "thick, D = 10.2": (10.2, 8.3, 4.6, 1.6),
    "thick test 3, D = 12.6": (12.6, 10.2, 5.5, 2.0),
    "thick test 2": (7.5, 6.2, 3.35, 1.1),
}
#: Onset set: the finer mesh of the mesh study is run only up to this far above the 1D
#: onset (MPa): the first outputs after the onset are where the mesh error is largest (the
#: first file's mesh study: <= 0.05% from 0.3 MPa) and the cost is in the later pressures.
ONSET_STUDY_SPAN_MPA = 0.16


#: Onset set without FElupe (``--set onset-convergence``): exofric's own mesh convergence
#: study, meshes far finer than any accuracy level (two-sided grading as the FElupe reference
#: mesh: elements of ~0.01 mm at the wire, ~0.05 mm at the wall) and the same with half the
#: elements in both directions; |N_fine - N_half| bounds the fine mesh's error where the
#: convergence is monotone of order >= 1 (order ~1.2 measured, docs/formulation.md section 6).
CONVERGENCE_MESHES: dict[str, dict[str, Any]] = {
    "reference": {"n_radial": 8, "n_circ": 192, "grading": 30.0, "wall_elements": 72,
                  "wall_grading": 5.0},
    "half": {"n_radial": 4, "n_circ": 96, "grading": 30.0 ** (2 * 59 / 119),
             "wall_elements": 36, "wall_grading": 5.0 ** (2 * 35 / 71)},
}
OUT_CONVERGENCE = ROOT / "tests" / "data" / "squeeze_reference_onset_convergence.json"


def _structure_entry(s: Structure, mat: MooneyRivlin, nref: np.ndarray) -> dict[str, Any]:
    """A structure's sizes (mm), 1D onset (MPa) and reference curve (N/mm): every set's keys."""
    return {"hole_mm": s.hole_mm, "tube_od_mm": s.tube_od_mm, "tube_id_mm": s.tube_id_mm,
            "wire_mm": s.wire_mm, "length_mm": s.length_mm,
            "onset_1d_mpa": onset_1d_mpa(s, mat),
            "squeeze_force_n_per_mm": nref.tolist(),
            "first_significant_pressure_mpa": first_significant_mpa(nref)}


def convergence_reference(structs: dict[str, Structure], mat: MooneyRivlin,
                          argv: list[str]) -> dict[str, Any]:
    """exofric's mesh-convergence reference of the onset structures (N/mm, full section)."""
    from exofric.fe import MeshSpec
    from exofric.simulate import squeeze

    doc = _header(mat, argv)
    doc["description"] = ("Weightless, frictionless squeeze force N(P) (plane strain, full "
                          "section, N per mm depth) of issue 35's thick-wall structures: "
                          "exofric on a mesh far finer than its accuracy levels, with the "
                          "nested mesh of half the elements as its mesh study.")
    doc["model"] = {"code": "exofric.simulate.squeeze, explicit meshes, gravity 'none'",
                    "meshes": CONVERGENCE_MESHES}
    for n, s in structs.items():
        out = {}
        for key, m in CONVERGENCE_MESHES.items():
            t0 = time.process_time()
            r = squeeze(s, mat, PRESSURES_MPA, gravity="none", keep_fields=False,
                        mesh=MeshSpec(**m))
            out[key] = (r.squeeze_force_n_per_mm, time.process_time() - t0)
            print(f"{n}|{key}: {out[key][1]:.0f} s", flush=True)
        nref, nhalf = out["reference"][0], out["half"][0]
        doc["structures"][n] = {
            **_structure_entry(s, mat, nref),
            "mesh_study": {"half_squeeze_force_n_per_mm": nhalf.tolist(),
                           "change_to_half_pct": _rel_pct(nhalf, nref)},
            "cpu_time_s": out["reference"][1],
        }
    return doc


def onset_structures() -> dict[str, Structure]:
    """Issue 35's thick-wall structures (:data:`ONSET_STRUCTURES`), 116 mm long."""
    return {n: Structure(*dims, 116.0, n) for n, dims in ONSET_STRUCTURES.items()}


def solve(task: dict[str, Any]) -> dict[str, Any]:
    """Run one FElupe squeeze (a task dict of structure + setup fields) -> results."""
    s: Structure = task["structure"]
    settings = {k: v for k, v in task.items() if k not in ("structure", "label", "pressures")}
    setup = SqueezeSetup.from_structure(s, material(), **settings)
    t0 = time.perf_counter()
    r = felupe_squeeze_model(task.get("pressures", PRESSURES_MPA), setup)
    print(f"{task['label']}: {time.perf_counter() - t0:.0f} s", flush=True)
    return {
        "label": task["label"],
        "squeeze_force_n_per_mm": np.maximum(r.squeeze_force_n_per_mm, 0.0).tolist(),
        "wall_force_n_per_mm": r.wall_force_n_per_mm.tolist(),
        "equilibrium_n_per_mm": r.equilibrium_n_per_mm.tolist(),
        "max_penetration_mm": r.max_penetration_mm.tolist(),
        "newton_iterations": r.newton_iterations.tolist(),
        "dofs": r.dofs,
        "solve_time_s": r.solve_time_s,
        "setup": setup.to_dict(),
    }


def onset_tasks(structs: dict[str, Structure], mat: MooneyRivlin) -> list[dict[str, Any]]:
    """Onset set: reference mesh at every pressure, finer mesh near the onset only."""
    base = {"penalty": PENALTY, "max_increment_mpa": MAX_INCREMENT_MPA,
            "density_t_per_mm3": WEIGHTLESS_DENSITY}
    out = []
    for n, s in structs.items():
        onset = onset_1d_mpa(s, mat) or 0.0
        near = PRESSURES_MPA[PRESSURES_MPA <= onset + ONSET_STUDY_SPAN_MPA]
        out.append({"label": f"{n}|reference", "structure": s, **base, **REFERENCE_MESH})
        out.append({"label": f"{n}|finer", "structure": s, **base, **FINER_MESH,
                    "pressures": near})
    return out


def assemble_onset(results: dict[str, dict[str, Any]], structs: dict[str, Structure],
                   mat: MooneyRivlin, argv: list[str]) -> dict[str, Any]:
    """The onset set's JSON document: curves, mesh study near the onset, provenance."""
    doc = _header(mat, argv)
    doc["description"] = doc["description"].replace(
        "(issue 18 reference)", "(issue 35 reference: thick walls, contact onset)")
    doc["finer_mesh_pressures"] = (f"outputs up to {ONSET_STUDY_SPAN_MPA} MPa above the 1D "
                                   "onset; later ones are null in the mesh study")
    for n, s in structs.items():
        ref, fin = results[f"{n}|reference"], results[f"{n}|finer"]
        nref = np.array(ref["squeeze_force_n_per_mm"])
        nfin = np.full(nref.size, np.nan)
        nfin[:len(fin["squeeze_force_n_per_mm"])] = fin["squeeze_force_n_per_mm"]
        change = _rel_pct(nref, nfin)
        doc["structures"][n] = {
            **_structure_entry(s, mat, nref),
            "mesh_study": {
                "finer_squeeze_force_n_per_mm": [None if np.isnan(x) else float(x)
                                                 for x in nfin],
                "change_to_finer_pct": [None if c is None or np.isnan(c) else c
                                        for c in change],
                "finer_dofs": fin["dofs"], "finer_solve_time_s": fin["solve_time_s"],
            },
            "wall_force_n_per_mm": ref["wall_force_n_per_mm"],
            "max_penetration_mm": ref["max_penetration_mm"],
            "dofs": ref["dofs"], "solve_time_s": ref["solve_time_s"],
        }
    return doc


def _rel_pct(a: np.ndarray, ref: np.ndarray) -> list[float | None]:
    """|a / ref - 1| in % where ref > 0, else None."""
    out: list[float | None] = []
    for x, y in zip(a, ref, strict=True):
        out.append(None if y <= 0 else float(100.0 * abs(x / y - 1.0)))
    return out


def first_significant_mpa(n: np.ndarray, fraction: float = 0.01) -> float:
    """First output pressure (MPa) with N >= fraction x N(0.6 MPa)."""
    return float(PRESSURES_MPA[np.flatnonzero(n >= fraction * n[-1])[0]])


def tasks(names: list[str], structs: dict[str, Structure]) -> list[dict[str, Any]]:
    """All FElupe runs: reference + finer mesh per structure, studies, coarse check."""
    base = {"penalty": PENALTY, "max_increment_mpa": MAX_INCREMENT_MPA,
            "density_t_per_mm3": WEIGHTLESS_DENSITY}
    out = []
    for n in names:
        out.append({"label": f"{n}|finer", "structure": structs[n], **base, **FINER_MESH})
        out.append({"label": f"{n}|reference", "structure": structs[n], **base, **REFERENCE_MESH})
    st = structs[STUDY_STRUCTURE]
    for rho in (1e-1 * WEIGHTLESS_DENSITY, 10.0 * WEIGHTLESS_DENSITY):
        out.append({"label": f"density|{rho:.1e}", "structure": st, **base, **REFERENCE_MESH,
                    "density_t_per_mm3": rho})
    out.append({"label": "penalty", "structure": st, **base, **REFERENCE_MESH,
                "penalty": STUDY_PENALTY})
    out.append({"label": "coarse", "structure": structs[COARSE_CHECK_STRUCTURE], **base,
                **COARSE_MESH})
    return out


def _header(mat: MooneyRivlin, argv: list[str]) -> dict[str, Any]:
    """The JSON document's description, provenance, model and material (no curves yet)."""
    return {
        "description": (
            "Weightless, frictionless squeeze force N(P) of the tube-wire-hole problem "
            "(plane strain, full section, N per mm depth) from the independent FElupe model "
            "benchmarks/felupe_models.py on mesh-converged meshes (issue 18 reference)."),
        "units": {"pressure": "MPa", "force_per_depth": "N/mm (full section)",
                  "length": "mm", "density": "t/mm^3", "time": "s"},
        "provenance": {
            "script": "benchmarks/make_squeeze_reference.py",
            "command": " ".join(["python", "benchmarks/make_squeeze_reference.py", *argv]),
            "date_utc": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
            "felupe_version": felupe.__version__,
            "numpy_version": np.__version__,
            "scipy_version": scipy.__version__,
            "python_version": platform.python_version(),
        },
        "model": {
            "code": "FElupe (GPL-3), benchmarks/felupe_models.py:felupe_squeeze_model",
            "elements": "quad9 displacement, three-field (u, p, J) NearlyIncompressible, "
                        "plane strain, half model x >= 0",
            "contact": "frictionless node-to-surface penalty, two ContactRigidCylinder "
                       "(hole from inside, wire from outside), all outer nodes",
            "weight": "self-weight toward the wall with a vanishing density (keeps the "
                      "floating tube on the wall before it touches the wire)",
            "penalty_n_per_mm2": PENALTY,
            "density_t_per_mm3": WEIGHTLESS_DENSITY,
            "max_increment_mpa": MAX_INCREMENT_MPA,
            "newton_tol": SqueezeSetup().newton_tol,
        },
        "material": {"shore_a": SHORE_A, "c10_mpa": mat.c10_mpa, "c01_mpa": mat.c01_mpa,
                     "d_per_mpa": mat.d_per_mpa},
        "pressure_mpa": PRESSURES_MPA.tolist(),
        "reference_mesh": REFERENCE_MESH,
        "finer_mesh": FINER_MESH,
        "significance_fraction": 0.01,
        "structures": {},
    }


def assemble(results: dict[str, dict[str, Any]], structs: dict[str, Structure],
             names: list[str], mat: MooneyRivlin, argv: list[str]) -> dict[str, Any]:
    """The JSON document: reference curves, studies and provenance."""
    doc = _header(mat, argv)
    for n in names:
        s = structs[n]
        ref, fin = results[f"{n}|reference"], results[f"{n}|finer"]
        nref = np.array(ref["squeeze_force_n_per_mm"])
        nfin = np.array(fin["squeeze_force_n_per_mm"])
        doc["structures"][n] = {
            **_structure_entry(s, mat, nref),
            "mesh_study": {
                "finer_squeeze_force_n_per_mm": nfin.tolist(),
                "change_to_finer_pct": _rel_pct(nref, nfin),
                "finer_dofs": fin["dofs"], "finer_solve_time_s": fin["solve_time_s"],
            },
            "wall_force_n_per_mm": ref["wall_force_n_per_mm"],
            "equilibrium_n_per_mm": ref["equilibrium_n_per_mm"],
            "max_penetration_mm": ref["max_penetration_mm"],
            "newton_iterations": ref["newton_iterations"],
            "dofs": ref["dofs"], "solve_time_s": ref["solve_time_s"],
        }
    st = doc["structures"][STUDY_STRUCTURE]["squeeze_force_n_per_mm"]
    dens = {k.split("|")[1]: v for k, v in results.items() if k.startswith("density|")}
    doc["density_study"] = {
        "structure": STUDY_STRUCTURE,
        "note": "N is linear in the weight; change of N (N/mm) from the reference density",
        "change_n_per_mm": {rho: (np.array(v["squeeze_force_n_per_mm"]) - st).tolist()
                            for rho, v in dens.items()},
    }
    pen = results["penalty"]
    doc["penalty_study"] = {
        "structure": STUDY_STRUCTURE, "penalty_n_per_mm2": STUDY_PENALTY,
        "change_pct": _rel_pct(np.array(pen["squeeze_force_n_per_mm"]), np.array(st)),
        "max_penetration_mm": pen["max_penetration_mm"],
    }
    co = results["coarse"]
    cref = doc["structures"][COARSE_CHECK_STRUCTURE]["squeeze_force_n_per_mm"]
    doc["coarse_check"] = {
        "structure": COARSE_CHECK_STRUCTURE, "mesh": COARSE_MESH,
        "squeeze_force_n_per_mm": co["squeeze_force_n_per_mm"],
        "deviation_from_reference_pct": _rel_pct(np.array(co["squeeze_force_n_per_mm"]),
                                                 np.array(cref)),
        "solve_time_s": co["solve_time_s"],
    }
    return doc


def main(argv: list[str] | None = None) -> None:
    """Command line: run every FElupe case (in parallel) and write the JSON."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=2, help="parallel processes")
    ap.add_argument("--out", type=Path, default=OUT, help="JSON file to write")
    ap.add_argument("--structures", nargs="*", default=None, help="names (default: all)")
    ap.add_argument("--cache", type=Path, default=None,
                    help="JSON-lines file of finished runs (reused, appended)")
    args_list = sys.argv[1:] if argv is None else argv
    ap.add_argument("--set", choices=("table3", "onset", "onset-convergence"),
                    default="table3",
                    help="table3: the first file; onset: issue 35's thick walls "
                         f"({OUT_ONSET.name})")
    args = ap.parse_args(args_list)
    mat = material()
    onset_set = args.set != "table3"
    structs = onset_structures() if onset_set else structures(mat)
    names = args.structures or list(structs)
    if args.set == "onset-convergence":
        out = OUT_CONVERGENCE if args.out == OUT else args.out
        doc = convergence_reference({n: structs[n] for n in names}, mat, args_list)
        out.write_text(json.dumps(doc, indent=1) + "\n")
        print(f"wrote {out}")
        return
    if onset_set:  # a subset: e.g. the finished ones of a cached run
        structs = {n: structs[n] for n in names}
    todo = onset_tasks(structs, mat) if onset_set else tasks(names, structs)
    done: dict[str, dict[str, Any]] = {}
    if args.cache is not None and args.cache.exists():
        for line in args.cache.read_text().splitlines():
            r = json.loads(line)
            done[r["label"]] = r
    todo = [t for t in todo if t["label"] not in done]
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for r in pool.map(solve, todo):
            done[r["label"]] = r
            if args.cache is not None:
                with args.cache.open("a") as f:
                    f.write(json.dumps(r) + "\n")
    doc = (assemble_onset(done, structs, mat, args_list) if onset_set
           else assemble(done, structs, names, mat, args_list))
    out = OUT_ONSET if onset_set and args.out == OUT else args.out
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
