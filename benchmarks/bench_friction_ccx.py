"""Benchmark: CalculiX reference of the base-group squeeze with Coulomb friction (issue 15).

Run: ``python benchmarks/bench_friction_ccx.py [--quick] [--json] [--quiet] [--out PATH]``.
Writes ``tests/data/ccx_friction_base.json`` (not with ``--quick``, unless ``--out`` is given).

Problem (units mm, N, MPa, s): the base-group squeeze (``exofric.geometry.BASE``: hole D 10,
tube OD 8.3 / ID 4.97, wire d2 1.6 mm; Shore 62.5 through ``MooneyRivlin.from_shore`` for the
constants C10, C01, d only; weightless; plane strain, half model), pressure ramped from 0 to
0.6 MPa with outputs at 0.05, 0.1, ..., 0.6 MPa, in four cases: frictionless; mu_wall = mu_wire
= 0.3; mu_wall = 0.3 only (tube-hole wall); mu_wire = 0.3 only (tube-wire). Outputs per case:
the squeeze force N (2 x the y-reaction of the wire nodes, N/mm), the wall's y-force (= N by
equilibrium), the per-interface normal and tangential contact force integrals (signed sums of
the radial and circumferential parts of the rigid nodes' reactions, full section; see
``calculix_models.CalculixSqueeze.contact_integrals``) and the change of N vs frictionless (%).

Model: ``calculix_models.squeeze_deck`` (CalculiX 2.20, independent of exofric's solver): CPE8R
quads, NLGEOM, rigid immobile hole and wire, node-to-surface penalty contact (linear
pressure-overclosure, 1e4 MPa/mm), one ``*SURFACE INTERACTION`` per contact pair with
``*FRICTION`` = ``mu, stick slope`` on a pair with mu > 0. CalculiX's node-to-surface friction
(``springforc_n2f``) is a tangential penalty (stick slope x the slave node's area) with a
Coulomb return map on the tangential slip accumulated from increment to increment (state
variables), so the result depends on the load path: the pressure ramps monotonically from 0
in one ``*STATIC`` step with at most ``MAX_INCREMENT_MPA`` per increment (CalculiX cuts it
further where contact changes; the increments used are reported). With friction the
stiffness matrix is unsymmetric: ccx switches to its unsymmetric SPOOLES solver by itself.

Choices and their checks (measured 2026-11-23 on a shared 2-core x86_64, one thread; the
full run repeats them and stores them in the JSON under ``convergence``; "change" = max
|N / N_ref - 1| for P >= 0.2 MPa):

* stick slope 1e3 MPa/mm, a tenth of the normal penalty: the elastic slip before sliding,
  mu p / slope, is at most ~1e-3 mm at the contact pressures here (up to 3.2 MPa, ``CSTR``
  at 0.6 MPa) against tangential motions of 0.1-1 mm. 300 and 3e3 MPa/mm change N by
  0.014 % and 0.013 % (2 x 30; 100 MPa/mm: 0.04 %); 1e4 (= the normal penalty) did not
  converge.
* increments: the reference allows at most 0.025 MPa per increment (ccx cuts down to
  ~1e-4 MPa where contact changes: ~100 increments, ~17 cutbacks with friction); 0.05 and
  0.0125 MPa change N by 0.007 % and 0.017 % (4 x 60, mu 0.3 on both), far below 0.1 %.
* mesh: reference 4 x 60 (rigid faces 64 elements); 2 x 30 (32) changes N by 0.24-0.32 %
  over the four cases, 3 x 45 (48) by 0.07 % (mu 0.3 on both); the 4 x 60 frictionless N is
  within 0.077 % of the stored converged FElupe reference (8 x 160) from 0.2 MPa (0.23 % at
  0.1 MPa).
* contact formulation: surface-to-surface penalty contact changes N by 0.27 % frictionless
  and 0.20 % with mu 0.3 on both (2 x 30): CalculiX's two friction implementations agree.

Results (4 x 60; N in N/mm; change vs frictionless):

==========  ======  ======  ======  ======  =========================
P (MPa)      0.2     0.3     0.4     0.6    N(0.6 MPa), CPU (s)
==========  ======  ======  ======  ======  =========================
both         -1.1%   -2.2%   -4.7%   -9.0%  1.8866, 31
wall only    -1.1%   -2.2%   -4.6%   -8.7%  1.8922, 29
wire only    -0.03%  -0.10%  -0.20%  -0.30% 2.0670, 9
==========  ======  ======  ======  ======  =========================

(frictionless N(0.6 MPa) = 2.0731 N/mm, 7 s). Friction lowers N, almost all of it through the
wall: the inflating tube slides up along the hole wall toward the wire and wall friction
holds it back; friction at the wire barely changes N (< 0.3 %, below the issue's 1 %
tolerance: the wire-only case tests an implementation through the wire's tangential force
integral, -0.325 N/mm at 0.6 MPa against a normal integral of 2.067, rather than through N).
The wall's tangential integral reaches -1.07 N/mm against a normal one of 4.23 (mu 0.3 on
both), i.e. partly stuck, partly sliding (ratio 0.25 < mu). CalculiX's ``*CONTACT PRINT``
could not give these integrals for node-to-surface contact (its ``CF`` statistics are zero
there and ccx 2.20 crashed after four outputs; ``CSTR`` has stresses without areas), hence
the split of the rigid nodes' reactions.

One thread (``OMP_NUM_THREADS=1`` etc.); CPU time = the ``ccx`` process's.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"
os.environ.setdefault("CCX_NPROC_EQUATION_SOLVER", "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import re  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric.geometry import BASE  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import calculix_models as ccxm  # noqa: E402

SHORE = 62.5
PRESSURES_MPA = np.round(np.linspace(0.05, 0.6, 12), 10)
OUT = HERE.parent / "tests" / "data" / "ccx_friction_base.json"
FELUPE_REFERENCE = HERE.parent / "tests" / "data" / "squeeze_reference_felupe.json"
MU = 0.3
#: case -> (mu_wall, mu_wire)
CASES: dict[str, tuple[float, float]] = {"frictionless": (0.0, 0.0), "both": (MU, MU),
                                         "wall_only": (MU, 0.0), "wire_only": (0.0, MU)}
#: deck options common to every run (see calculix_models.squeeze_deck)
COMMON: dict[str, Any] = {"element": "CPE8R", "contact": "NODE TO SURFACE", "penalty": 1e4,
                          "grading": 10.0}
MESHES: dict[str, dict[str, int]] = {
    "2x30": {"n_radial": 2, "n_circ": 30, "rigid_elements": 32},
    "4x60": {"n_radial": 4, "n_circ": 60, "rigid_elements": 64},
}
REFERENCE_MESH, COARSE_MESH = "4x60", "2x30"
MAX_INCREMENT_MPA = 0.025
STICK_SLOPE = ccxm.STICK_SLOPE  # MPa/mm
STICK_SLOPE_STUDY = (300.0, 1e3, 3e3)
FROM_MPA = 0.2  # the agreement range: from 0.2 MPa
CONVERGED = 1e-3  # halve the increment until N changes by less than 0.1 %


# ------------------------------------------------------------------------------ helpers
def _material() -> MooneyRivlin:
    return MooneyRivlin.from_shore(SHORE)


def _ccx_version(ccx: str) -> str | None:
    try:
        out = subprocess.run([ccx, "-v"], capture_output=True, text=True, timeout=30,
                             check=False).stdout
    except OSError:
        return None
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else None


def solve(case: str, mesh: str = REFERENCE_MESH, *, max_increment_mpa: float = MAX_INCREMENT_MPA,
          stick_slope: float = STICK_SLOPE, contact: str | None = None,
          ccx: str = "ccx") -> dict[str, Any]:
    """Run one case; return N, wall force, contact integrals (N/mm), times (s), increments."""
    mu_wall, mu_wire = CASES[case]
    setup = {**COMMON, **MESHES[mesh], "max_increment_mpa": max_increment_mpa,
             "mu_wall": mu_wall, "mu_wire": mu_wire, "stick_slope": stick_slope,
             "node_forces": True}
    if contact is not None:
        setup["contact"] = contact
    deck = ccxm.squeeze_deck(PRESSURES_MPA, _material(), hole_mm=BASE.hole_mm,
                             tube_od_mm=BASE.tube_od_mm, tube_id_mm=BASE.tube_id_mm,
                             wire_mm=BASE.wire_mm, **setup)
    run = ccxm.run_ccx(deck, ccx=ccx)
    res = ccxm.read_squeeze(deck, run)
    ci = res.contact_integrals or {}
    out = {
        "case": case, "mesh": mesh, "mu_wall": mu_wall, "mu_wire": mu_wire,
        "contact": setup["contact"], "max_increment_mpa": max_increment_mpa,
        "stick_slope_mpa_per_mm": stick_slope if (mu_wall or mu_wire) else None,
        # (+ 0.0: no -0.0 before the wire is touched)
        "squeeze_force_n_per_mm": (res.squeeze_force_n_per_mm + 0.0).tolist(),
        "wall_force_n_per_mm": (res.wall_force_n_per_mm + 0.0).tolist(),
        "cpu_time_s": run.cpu_time_s, "wall_time_s": run.wall_time_s,
        "equations": run.equations, "incrementation": ccxm.increments(run.sta),
    }
    for name in ("wire", "wall"):
        for part in ("normal", "tangential"):
            key = f"{part}_n_per_mm"
            out[f"{name}_{key}"] = (ci[name][key] + 0.0).tolist() if name in ci else None
    return out


def _rel(a: list[float], b: list[float], p_from: float = FROM_MPA) -> float:
    """max |a / b - 1| over the pressures >= p_from where b > 0."""
    a_, b_ = np.asarray(a), np.asarray(b)
    m = (PRESSURES_MPA >= p_from - 1e-12) & (b_ > 0)
    return float(np.max(np.abs(a_[m] / b_[m] - 1.0)))


def _change_pct(n: list[float], n0: list[float]) -> list[float | None]:
    return [None if b <= 0 else 100.0 * (a / b - 1.0) for a, b in zip(n, n0, strict=True)]


def _felupe() -> np.ndarray | None:
    if not FELUPE_REFERENCE.exists():
        return None
    data = json.loads(FELUPE_REFERENCE.read_text())
    if not np.allclose(data["pressure_mpa"], PRESSURES_MPA):
        return None
    for s in data["structures"].values():
        geo = (s["hole_mm"], s["tube_od_mm"], s["tube_id_mm"], s["wire_mm"])
        if np.allclose(geo, (BASE.hole_mm, BASE.tube_od_mm, BASE.tube_id_mm, BASE.wire_mm)):
            return np.asarray(s["squeeze_force_n_per_mm"], dtype=float)
    return None


# ---------------------------------------------------------------------------------- run
def run(quick: bool = False, ccx: str = "ccx", log: Any = None) -> dict[str, Any]:
    """The four cases (and, unless ``quick``, the convergence studies); JSON-ready dict."""
    def note(msg: str) -> None:
        if log is not None:
            print(msg, file=log, flush=True)

    mesh = COARSE_MESH if quick else REFERENCE_MESH
    mat = _material()
    cases: dict[str, dict[str, Any]] = {}
    for case in CASES:
        note(f"[friction-ccx] {case} on {mesh} ...")
        cases[case] = solve(case, mesh, ccx=ccx)
    n0 = cases["frictionless"]["squeeze_force_n_per_mm"]
    for r in cases.values():
        r["change_vs_frictionless_pct"] = _change_pct(r["squeeze_force_n_per_mm"], n0)
    out: dict[str, Any] = {
        "description": "CalculiX reference of the base-group squeeze with Coulomb friction "
                       "(issue 15): N(P) and per-interface contact force integrals for "
                       "frictionless, mu 0.3 on both interfaces, on the wall only and on the "
                       "wire only",
        "units": {"pressure": "MPa", "force": "N/mm (per mm depth, full section)",
                  "length": "mm", "stick_slope": "MPa/mm", "time": "s"},
        "pressure_mpa": PRESSURES_MPA.tolist(),
        "structure": {"name": BASE.name, "hole_mm": BASE.hole_mm,
                      "tube_od_mm": BASE.tube_od_mm, "tube_id_mm": BASE.tube_id_mm,
                      "wire_mm": BASE.wire_mm},
        "material": {"shore_a": SHORE, "c10_mpa": mat.c10_mpa, "c01_mpa": mat.c01_mpa,
                     "d_per_mpa": mat.d_per_mpa, "gravity": "none (weightless)"},
        "model": {
            "code": "CalculiX ccx (benchmarks/calculix_models.py squeeze_deck)",
            "summary": "plane strain (CPE8R, NLGEOM), half model x >= 0, rigid immobile hole "
                       "and wire, node-to-surface penalty contact (linear pressure-overclosure), "
                       "one *SURFACE INTERACTION per pair with *FRICTION (mu, stick slope) where "
                       "mu > 0; pressure ramped monotonically from 0 in one *STATIC step "
                       "(automatic increments up to max_increment_mpa); tube's bottom outer "
                       "node u_y = 0 on the symmetry line",
            "deck_options": {**COMMON, **MESHES[mesh], "max_increment_mpa": MAX_INCREMENT_MPA,
                             "stick_slope_mpa_per_mm": STICK_SLOPE},
            "mesh": mesh,
            "squeeze_force": "N = 2 x the y-reaction of the wire nodes",
            "contact_integrals": "signed sums over the rigid circle's nodes of the radial "
                                 "(normal, pressing: > 0) and circumferential (tangential, > 0 "
                                 "counter-clockwise about the circle's centre) parts of its "
                                 "force on the tube, x 2 (full section); wall normal includes "
                                 "the bottom node's support",
        },
        "cases": cases,
        "quick": quick,
    }
    ref = _felupe()
    if ref is not None:
        out["frictionless_vs_felupe"] = {
            "reference": "tests/data/squeeze_reference_felupe.json (FElupe 8 x 160)",
            "max_rel_from_0.2_mpa": _rel(n0, ref.tolist()),
            "max_rel_from_0.1_mpa": _rel(n0, ref.tolist(), 0.1),
        }
    if not quick:
        out["convergence"] = _studies(cases, ccx, note)
    return out


def _studies(cases: dict[str, dict[str, Any]], ccx: str, note: Any) -> dict[str, Any]:
    """Increment (reference mesh, both mu), mesh (all cases), stick slope and contact
    formulation (coarse mesh, both mu) studies; changes are max |N / N_ref - 1| from 0.2 MPa."""
    both = cases["both"]["squeeze_force_n_per_mm"]
    conv: dict[str, Any] = {"measure": "max |N / N_ref - 1| for P >= 0.2 MPa"}
    # increments: twice and half the reference's largest increment
    rows = []
    for inc in (2.0 * MAX_INCREMENT_MPA, 0.5 * MAX_INCREMENT_MPA):
        note(f"[friction-ccx] increment study: max increment {inc:g} MPa ...")
        r = solve("both", REFERENCE_MESH, max_increment_mpa=inc, ccx=ccx)
        rows.append({"max_increment_mpa": inc, "mesh": REFERENCE_MESH,
                     "squeeze_force_n_per_mm": r["squeeze_force_n_per_mm"],
                     "rel_change_vs_reference": _rel(r["squeeze_force_n_per_mm"], both),
                     "rel_change_vs_reference_from_0.1_mpa":
                         _rel(r["squeeze_force_n_per_mm"], both, 0.1),
                     "cpu_time_s": r["cpu_time_s"], "incrementation": r["incrementation"]})
    conv["increment"] = {"case": "both", "reference_max_increment_mpa": MAX_INCREMENT_MPA,
                         "runs": rows,
                         "converged": rows[1]["rel_change_vs_reference"] < CONVERGED}
    # mesh: every case on the coarse mesh
    rows = []
    for case in CASES:
        note(f"[friction-ccx] mesh study: {case} on {COARSE_MESH} ...")
        r = solve(case, COARSE_MESH, ccx=ccx)
        fine = cases[case]["squeeze_force_n_per_mm"]
        rows.append({"case": case, "mesh": COARSE_MESH,
                     "squeeze_force_n_per_mm": r["squeeze_force_n_per_mm"],
                     "rel_change_vs_reference": _rel(r["squeeze_force_n_per_mm"], fine),
                     "cpu_time_s": r["cpu_time_s"], "incrementation": r["incrementation"],
                     "change_vs_frictionless_pct": None})
    n0c = rows[0]["squeeze_force_n_per_mm"]
    for row in rows:
        row["change_vs_frictionless_pct"] = _change_pct(row["squeeze_force_n_per_mm"], n0c)
    conv["mesh"] = {"reference_mesh": REFERENCE_MESH, "meshes": MESHES, "runs": rows}
    coarse_both = rows[1]
    # stick slope (coarse mesh, both mu 0.3), relative to the chosen slope
    rows = []
    for slope in STICK_SLOPE_STUDY:
        if slope == STICK_SLOPE:
            n = coarse_both["squeeze_force_n_per_mm"]
            cpu = coarse_both["cpu_time_s"]
        else:
            note(f"[friction-ccx] stick slope study: {slope:g} MPa/mm ...")
            r = solve("both", COARSE_MESH, stick_slope=slope, ccx=ccx)
            n, cpu = r["squeeze_force_n_per_mm"], r["cpu_time_s"]
        rows.append({"stick_slope_mpa_per_mm": slope, "squeeze_force_n_per_mm": n,
                     "rel_change_vs_chosen": _rel(n, coarse_both["squeeze_force_n_per_mm"]),
                     "cpu_time_s": cpu, "reused": slope == STICK_SLOPE})
    conv["stick_slope"] = {"case": "both", "mesh": COARSE_MESH, "chosen": STICK_SLOPE,
                           "runs": rows,
                           "note": "1e4 MPa/mm (= the normal penalty) did not converge "
                                   "(2 x 30, measured while choosing)"}
    # contact formulation: surface to surface on the coarse mesh
    rows = []
    for case in ("frictionless", "both"):
        note(f"[friction-ccx] contact formulation: {case}, surface to surface ...")
        r = solve(case, COARSE_MESH, contact="SURFACE TO SURFACE", ccx=ccx)
        n2s = next(x for x in conv["mesh"]["runs"] if x["case"] == case)
        rows.append({"case": case, "squeeze_force_n_per_mm": r["squeeze_force_n_per_mm"],
                     "rel_change_vs_node_to_surface":
                         _rel(r["squeeze_force_n_per_mm"], n2s["squeeze_force_n_per_mm"]),
                     "cpu_time_s": r["cpu_time_s"]})
    conv["contact_formulation"] = {"mesh": COARSE_MESH, "contact": "SURFACE TO SURFACE",
                                   "runs": rows}
    return conv


# ------------------------------------------------------------------------------- output
def _fmt(values: list[float | None], fmt: str = "{:8.4f}") -> str:
    # (+ 0.0 and rounding first: no "-0.0000")
    return "".join("       -" if v is None else fmt.format(float(fmt.format(v)) + 0.0)
                   for v in values)


def render(out: dict[str, Any]) -> str:
    """Tables: N(P) per case, % change vs frictionless, contact integrals, studies."""
    p = out["pressure_mpa"]
    lines = [f"[friction-ccx] CalculiX {out['provenance'].get('ccx_version') or '?'}, base group, "
             f"mesh {out['model']['mesh']}, max increment "
             f"{out['model']['deck_options']['max_increment_mpa']:g} MPa, stick slope "
             f"{out['model']['deck_options']['stick_slope_mpa_per_mm']:g} MPa/mm, 1 thread",
             f"{'P (MPa)':<30}" + "".join(f"{v:8.2f}" for v in p)]
    for name, r in out["cases"].items():
        lines.append(f"{'N ' + name:<30}" + _fmt(r["squeeze_force_n_per_mm"]))
    for name, r in out["cases"].items():
        if name != "frictionless":
            lines.append(f"{'% vs frictionless ' + name:<30}"
                         + _fmt(r["change_vs_frictionless_pct"], "{:8.2f}"))
    for name, r in out["cases"].items():
        for part in ("wire_normal", "wire_tangential", "wall_normal", "wall_tangential"):
            v = r.get(f"{part}_n_per_mm")
            if v is not None:
                lines.append(f"{part.replace('_', ' ') + ' ' + name:<30}" + _fmt(v))
    lines.append("CPU s: " + ", ".join(
        f"{k} {r['cpu_time_s']:.1f} ({r['incrementation']['increments']} increments, "
        f"{r['incrementation']['cutbacks']} cutbacks)" for k, r in out["cases"].items()))
    fel = out.get("frictionless_vs_felupe")
    if fel:
        a, b = 100 * fel["max_rel_from_0.2_mpa"], 100 * fel["max_rel_from_0.1_mpa"]
        lines.append(f"frictionless vs FElupe reference: max {a:.3f} % from 0.2 MPa "
                     f"({b:.3f} % from 0.1)")
    conv = out.get("convergence")
    if conv:
        lines.append("convergence (" + conv["measure"] + "):")
        for r in conv["increment"]["runs"]:
            lines.append(f"  max increment {r['max_increment_mpa']:g} MPa vs "
                         f"{conv['increment']['reference_max_increment_mpa']:g}: "
                         f"{100 * r['rel_change_vs_reference']:.4f} %  (CPU {r['cpu_time_s']:.1f}"
                         f" s, {r['incrementation']['increments']} increments)")
        for r in conv["mesh"]["runs"]:
            lines.append(f"  mesh {r['mesh']} vs {conv['mesh']['reference_mesh']}, {r['case']}: "
                         f"{100 * r['rel_change_vs_reference']:.3f} %  (CPU {r['cpu_time_s']:.1f}"
                         " s)")
        for r in conv["stick_slope"]["runs"]:
            lines.append(f"  stick slope {r['stick_slope_mpa_per_mm']:g} vs "
                         f"{conv['stick_slope']['chosen']:g} MPa/mm ({conv['stick_slope']['mesh']}"
                         f"): {100 * r['rel_change_vs_chosen']:.4f} %")
        cf = conv["contact_formulation"]
        for r in cf["runs"]:
            lines.append(f"  surface-to-surface vs node-to-surface ({cf['mesh']}), {r['case']}: "
                         f"{100 * r['rel_change_vs_node_to_surface']:.3f} %  "
                         f"(CPU {r['cpu_time_s']:.1f} s)")
    if out.get("written"):
        lines.append(f"wrote {out['written']}")
    return "\n".join(lines)


def _write_atomic(path: Path, data: dict[str, Any]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            json.dump(data, fh, indent=1)
            fh.write("\n")
        os.chmod(tmp, 0o644)  # mkstemp makes it private; a data file is world-readable
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Command-line entry point; prints the tables and returns (and writes) the summary."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--quick", action="store_true",
                    help=f"the four cases on the {COARSE_MESH} mesh only, no studies; writes "
                         "nothing unless --out is given")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--quiet", action="store_true", help="print nothing (return only)")
    ap.add_argument("--out", type=Path, default=None,
                    help=f"output JSON (default {OUT.relative_to(HERE.parent)}; "
                         "'-' writes nothing)")
    ap.add_argument("--ccx", default="ccx", help="CalculiX executable")
    args = ap.parse_args(argv)
    exe = ccxm.ccx_available(args.ccx)
    if exe is None:  # skipped, not failed (benchmarks/run.py runs every bench_*.py)
        skipped = {"skipped": f"CalculiX ({args.ccx}) not on PATH (make calculix)"}
        if not args.quiet:
            print(json.dumps(skipped) if args.json else f"[friction-ccx] {skipped['skipped']}")
        return skipped
    started = datetime.datetime.now(datetime.UTC)
    out = run(args.quick, exe, None if (args.quiet or args.json) else sys.stderr)
    argv_used = sys.argv[1:] if argv is None else list(argv)
    out["provenance"] = {
        "command": " ".join(["python", "benchmarks/bench_friction_ccx.py", *argv_used]),
        "date_utc": started.isoformat(timespec="seconds"),
        "ccx": exe, "ccx_version": _ccx_version(exe), "threads": 1,
        "python": platform.python_version(), "machine": platform.machine(),
        "total_cpu_time_s": None,
    }
    runs = list(out["cases"].values())
    conv = out.get("convergence") or {}
    for key in ("increment", "mesh", "stick_slope", "contact_formulation"):
        runs += [r for r in conv.get(key, {}).get("runs", []) if not r.get("reused")]
    out["provenance"]["total_cpu_time_s"] = float(sum(r["cpu_time_s"] for r in runs))
    first = ("description", "provenance")
    out = {**{k: out[k] for k in first}, **{k: v for k, v in out.items() if k not in first}}
    target = args.out if args.out is not None else (None if args.quick else OUT)
    if target is not None and str(target) != "-":
        _write_atomic(target, out)
        out["written"] = str(target)
    if not args.quiet:
        print(json.dumps(out) if args.json else render(out))
    return out


if __name__ == "__main__":
    main()
