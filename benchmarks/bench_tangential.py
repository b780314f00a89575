"""Benchmark: the friction force along the wire's contact arc, exofric vs CalculiX (issue 35.3).

Run: ``python benchmarks/bench_tangential.py [--full] [--quick] [--only ccx|exofric] [--json]
[--quiet] [--out PATH]``. Without options (``make bench``): exofric's standard run against the
stored CalculiX reference, a few seconds, nothing written. ``--full``: every study of both codes,
~1 h on a shared 2-core machine (several minutes of CPU per CalculiX run on the finer meshes),
written to ``tests/data/ccx_tangential_base.json`` (or ``--out``).

Quantity (units mm, N, MPa): ``wire_tangential_force_n_per_mm`` T_wire, the friction force that
the tube exerts along the wire's contact arc, full section, N per mm of tube. In exofric it is
``2 sum_i |T_i|`` over the half model's contact nodes on the wire, ``T_i`` the nodal tangential
(friction) force of the return map (``fe/_contact.py`` ``evaluate_friction``; the node on the
symmetry line carries none), i.e. the integral over the arc of the magnitude of the shear
traction. In CalculiX it is ``2 |sum_j f_j . t_j|`` over the rigid wire's nodes (``f_j`` the
node's reaction, ``t_j`` the circumferential unit vector about the wire's centre;
``calculix_models.read_squeeze``): the integral of the signed shear traction over the half arc.
The two are the same number where the shear traction keeps one sign along the half arc (it
does in exofric at every output here: the ``sign_changes`` column).

Problem: the base group (``exofric.geometry.BASE``: hole 10, tube OD 8.3 / ID 4.97, wire 1.6
mm), Shore 62.5 through ``MooneyRivlin.from_shore`` (constants only), weightless, plane strain,
mu_wire 0.3 on the tube-wire contact, the wall frictionless (``wire_only``: the wall's friction
changes T_wire by < 6 %, ``bench_friction_ccx.py``), the pressure ramped from 0 to 0.6 MPa with
outputs every 0.05 MPa.

Studies: exofric in its tangential penalty ``friction_penalty`` (1e2 .. 1e5 N/mm^3), its largest
load sub-step (0.05 .. 0.003125 MPa) and its mesh (4 x 32 = the standard before issue 35 .. 12 x
96); CalculiX (``calculix_models.squeeze_deck``, CPE8R, node-to-surface penalty contact,
``*FRICTION`` mu 0.3 with a stick slope) in its stick slope (300 .. 1e4 MPa/mm), its largest
increment, its mesh (4, 8, 16 elements through the wall) and its contact formulation. The
CalculiX runs are stored (with the ccx version, meshes, penalties and CPU times) as the
reference of ``tests/test_tangential_reference.py``; exofric's own numbers are stored beside
them as the study's record (not a reference): ``--only exofric --out
tests/data/ccx_tangential_exofric.json``.

Measured 2026-11-27 (ccx 2.20, one thread; a 2-core machine shared by ~8 jobs, so the wall
times were 5-10x the CPU times stored in the JSON), T_wire in N/mm at 0.2 / 0.3 / 0.6 MPa:

* exofric standard 0.0165 / 0.0651 / 0.3424; penalty 1e2 .. 1e5: -17 .. +2.5 % at 0.2 MPa
  (1e3 -> 1e5 +2.5 %); steps 0.05 .. 0.00625 MPa: <= 1 %. Converged in both, not in the mesh:
  2-3 contact nodes on the half arc at 0.1-0.2 MPa.
* exofric resolved: 6 x 48 (20:1, steps 0.00625 MPa) 0.0214 / 0.0620 / 0.3408; 12 x 96 (steps
  0.003125 MPa, step-converged) 0.0191 / 0.0597 / 0.3380.
* CalculiX 4 x 60: 0.0284 / 0.0652 / 0.3250 (stick slope 300 .. 1e4: 0.0254 .. 0.0326 at 0.2
  MPa; surface-to-surface 0.0347 / 0.0715 / 0.3283); 8 x 60: 0.0231 / 0.0581 / 0.3318; 16 x 60
  (the reference, 109 s CPU): 0.0182 / 0.0577 / 0.3364.
* exofric 12 x 96 against CalculiX 16 x 60: +5.0 / +3.5 / +0.5 % (+6.7 % at 0.25 MPa, <= 2.3 %
  from 0.35 MPa); the standard 4 x 32: -9.1 / +12.8 / +1.8 %; like grids (both 4 x 60, 10:1):
  -4.6 / +3.1 / +6.5 % against each other.

See docs/formulation.md section 13 for the reading of these numbers.
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
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from exofric import defaults  # noqa: E402
from exofric.fe import MeshSpec, NewtonSettings  # noqa: E402
from exofric.geometry import BASE  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402
from exofric.simulate import squeeze  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_friction_ccx as bfc  # noqa: E402
import calculix_models as ccxm  # noqa: E402

SHORE = 62.5
MU_WIRE = 0.3
PRESSURES_MPA = np.round(np.arange(1, 13) * 0.05, 10)
SHOWN_MPA = (0.1, 0.2, 0.3, 0.6)
OUT = HERE.parent / "tests" / "data" / "ccx_tangential_base.json"

#: CalculiX runs: name -> deck options (beside COMMON). The reference is REFERENCE.
CCX_COMMON: dict[str, Any] = {"element": "CPE8R", "contact": "NODE TO SURFACE", "penalty": 1e4,
                              "mu_wall": 0.0, "mu_wire": MU_WIRE}
CCX_BASE: dict[str, Any] = {"n_radial": 4, "n_circ": 60, "rigid_elements": 64, "grading": 10.0,
                            "max_increment_mpa": 0.025, "stick_slope": 1e3}
CCX_RUNS: dict[str, dict[str, Any]] = {
    "slope_1e3": {},
    "slope_300": {"stick_slope": 300.0},
    "slope_3e3": {"stick_slope": 3e3},
    "slope_1e4": {"stick_slope": 1e4},
    "inc_0.00625": {"max_increment_mpa": 0.00625},
    "mesh_8x60": {"n_radial": 8},
    "mesh_8x60_slope_1e4": {"n_radial": 8, "stick_slope": 1e4},
    "s2s": {"contact": "SURFACE TO SURFACE"},
    "mesh_16x60": {"n_radial": 16},
}
CCX_QUICK = ("slope_1e3",)
#: The CalculiX run exofric is compared with (tests/test_tangential_reference.py)
REFERENCE = "mesh_16x60"

#: exofric runs: name -> (mesh (n_radial, n_circ, grading), friction_penalty N/mm^3 or None
#: (the default 1e3), largest load sub-step MPa)
#: ("standard": the standard accuracy's mesh before issue 35 item 1, 4 x 32 graded 6:1 toward
#: the wire over the whole half, no separate grading toward the wall.)
EXO_RUNS: dict[str, tuple[tuple[int, int, float], float | None, float]] = {
    "standard": ((4, 32, 6.0), None, 0.025),
    "standard_eps_1e2": ((4, 32, 6.0), 1e2, 0.025),
    "standard_eps_1e4": ((4, 32, 6.0), 1e4, 0.025),
    "standard_eps_1e5": ((4, 32, 6.0), 1e5, 0.025),
    "standard_step_0.05": ((4, 32, 6.0), None, 0.05),
    "standard_step_0.00625": ((4, 32, 6.0), None, 0.00625),
    "4x60_g10": ((4, 60, 10.0), None, 0.025),
    "6x32_g30_step_0.0125": ((6, 32, 30.0), None, 0.0125),
    "6x48_g20": ((6, 48, 20.0), None, 0.025),
    "6x48_g20_step_0.0125": ((6, 48, 20.0), None, 0.0125),
    "6x48_g20_step_0.00625": ((6, 48, 20.0), None, 0.00625),
    "6x48_g20_step_0.003125": ((6, 48, 20.0), None, 0.003125),
    "6x48_g20_step_0.00625_eps_1e4": ((6, 48, 20.0), 1e4, 0.00625),
    "6x48_g20_step_0.00625_eps_1e5": ((6, 48, 20.0), 1e5, 0.00625),
    "12x96_g20": ((12, 96, 20.0), None, 0.025),
    "12x96_g20_step_0.00625": ((12, 96, 20.0), None, 0.00625),
    "12x96_g20_step_0.003125": ((12, 96, 20.0), None, 0.003125),
}
EXO_QUICK = ("standard",)


def _material() -> MooneyRivlin:
    return MooneyRivlin.from_shore(SHORE)


def _list(a: Any) -> list[float]:
    return [float(v) + 0.0 for v in np.asarray(a, dtype=float)]


def run_ccx(name: str, ccx: str = "ccx") -> dict[str, Any]:
    """One CalculiX run of :data:`CCX_RUNS` ``name``: T_wire, S_wire, N (N/mm), CPU (s)."""
    opts = {**CCX_BASE, **CCX_RUNS[name]}
    deck = ccxm.squeeze_deck(PRESSURES_MPA, _material(), hole_mm=BASE.hole_mm,
                             tube_od_mm=BASE.tube_od_mm, tube_id_mm=BASE.tube_id_mm,
                             wire_mm=BASE.wire_mm, node_forces=True,
                             **{**CCX_COMMON, **opts})
    run = ccxm.run_ccx(deck, ccx=ccx, timeout_s=3600.0)
    out: dict[str, Any] = {"name": name, "options": opts, "cpu_time_s": run.cpu_time_s,
                           "equations": run.equations,
                           "incrementation": ccxm.increments(run.sta)}
    try:
        res = ccxm.read_squeeze(deck, run)
    except RuntimeError as exc:
        out["error"] = str(exc).splitlines()[0]
        return out
    ci = res.contact_integrals or {}
    # the circumferential sum is negative here (friction holds the tube's surface back
    # toward the symmetry line); its magnitude is exofric's T_wire
    out.update(tangential_n_per_mm=_list(np.abs(ci["wire"]["tangential_n_per_mm"])),
               normal_n_per_mm=_list(ci["wire"]["normal_n_per_mm"]),
               squeeze_force_n_per_mm=_list(res.squeeze_force_n_per_mm))
    return out


def run_exofric(name: str) -> dict[str, Any]:
    """One exofric run of :data:`EXO_RUNS` ``name``: T_wire, S_wire, N (N/mm), stick, time."""
    (nr, nc, grading), eps_t, step = EXO_RUNS[name]
    settings = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "max_step": step})
    t0 = time.process_time()
    r = squeeze(BASE, _material(), PRESSURES_MPA, mu_wall=0.0, mu_wire=MU_WIRE,
                gravity="none", mesh=MeshSpec(nr, nc, grading=grading), friction_penalty=eps_t,
                settings=settings)
    cpu = time.process_time() - t0
    c = r.contact
    signs = []
    for prof in c.profiles:
        s = np.sign(np.asarray(prof["wire"]["shear_mpa"]))
        s = s[s != 0]
        signs.append(int(np.count_nonzero(s[1:] != s[:-1])))
    return {"name": name, "mesh": [nr, nc], "grading": grading,
            "friction_penalty_n_per_mm3": c.friction_penalty, "max_step_mpa": step,
            "tangential_n_per_mm": _list(c.wire_tangential_force_n_per_mm),
            "normal_n_per_mm": _list(c.wire_pressure_integral_n_per_mm),
            "squeeze_force_n_per_mm": _list(r.squeeze_force_n_per_mm),
            "stick_fraction": _list(c.stick_fraction_wire),
            "contact_nodes": [len(p["wire"]["node"]) for p in c.profiles],
            "sign_changes": signs, "cpu_time_s": cpu}


def _at(values: list[float], p: float) -> float:
    return float(values[int(np.argmin(np.abs(PRESSURES_MPA - p)))])


def compare(exo: dict[str, Any], ref: dict[str, Any], p_from: float = 0.2) -> dict[str, Any]:
    """Relative difference exo / ref - 1 of T_wire per pressure (None where ref is 0) and its
    largest magnitude from ``p_from`` MPa."""
    a, b = np.asarray(exo["tangential_n_per_mm"]), np.asarray(ref["tangential_n_per_mm"])
    rel = [None if bb <= 0 else float(aa / bb - 1.0) for aa, bb in zip(a, b, strict=True)]
    k = [i for i, p in enumerate(PRESSURES_MPA) if p >= p_from - 1e-12 and rel[i] is not None]
    return {"rel": rel, f"max_abs_rel_from_{p_from:g}_mpa": max(abs(rel[i]) for i in k)}


def run(quick: bool = False, only: str | None = None, ccx: str = "ccx",
        log: Any = None, progress: Any = None, names: list[str] | None = None,
        start: dict[str, Any] | None = None) -> dict[str, Any]:
    """The CalculiX and exofric runs (``quick``: one of each); JSON-ready dict.

    ``progress(partial)`` is called after every run (the caller writes partial results);
    ``names`` restricts the runs, ``start`` holds earlier runs that are kept."""
    def note(msg: str) -> None:
        if log is not None:
            print(msg, file=log, flush=True)

    out: dict[str, Any] = {"ccx": dict((start or {}).get("ccx", {})),
                           "exofric": dict((start or {}).get("exofric", {}))}
    if only in (None, "ccx"):
        for name in (CCX_QUICK if quick else CCX_RUNS):
            if names is not None and name not in names:
                continue
            note(f"[tangential] CalculiX {name} ...")
            out["ccx"][name] = run_ccx(name, ccx)
            if progress is not None:
                progress(out)
    if only in (None, "exofric"):
        for name in (EXO_QUICK if quick else EXO_RUNS):
            if names is not None and name not in names:
                continue
            note(f"[tangential] exofric {name} ...")
            out["exofric"][name] = run_exofric(name)
            if progress is not None:
                progress(out)
    return out


def _row(label: str, values: list[float] | None, fmt: str = "{:9.4f}") -> str:
    if values is None:
        return f"{label:<40}" + "        -" * len(SHOWN_MPA)
    return f"{label:<40}" + "".join(fmt.format(_at(values, p)) for p in SHOWN_MPA)


def render(out: dict[str, Any]) -> str:
    """T_wire (N/mm) at 0.1/0.2/0.3/0.6 MPa per run, CPU times."""
    lines = [f"[tangential] base group, mu_wire {MU_WIRE:g}, wall frictionless; T_wire (N/mm)",
             f"{'P (MPa)':<40}" + "".join(f"{p:9.2f}" for p in SHOWN_MPA) + "   CPU s"]
    for code in ("ccx", "exofric"):
        for name, r in out.get(code, {}).items():
            if "error" in r:
                lines.append(f"{code + ' ' + name:<40} failed: {r['error']}")
                continue
            lines.append(_row(f"{code} {name}", r["tangential_n_per_mm"])
                         + f"  {r['cpu_time_s']:6.1f}")
    for name, cmp_ in out.get("comparison", {}).items():
        rel = cmp_["rel"]
        lines.append(f"{'rel ' + name:<40}" + "".join(
            "        -" if rel[int(np.argmin(np.abs(PRESSURES_MPA - p)))] is None else
            f"{100 * rel[int(np.argmin(np.abs(PRESSURES_MPA - p)))]:8.1f}%" for p in SHOWN_MPA))
    if out.get("written"):
        lines.append(f"wrote {out['written']}")
    return "\n".join(lines)


def _header(exe: str | None, started: datetime.datetime, argv: list[str]) -> dict[str, Any]:
    """Description, provenance, units, problem and definitions of the output JSON."""
    return {
        "description": "The friction force along the wire's contact arc, T_wire "
                       "(wire_tangential_force_n_per_mm), base group, mu_wire 0.3, wall "
                       "frictionless: CalculiX runs (the reference: stick slope, increment "
                       "and mesh studies) and exofric's own penalty, load-step and mesh "
                       "studies (a record, not a reference); issue 35 item 3",
        "provenance": {
            "command": " ".join(["python", "benchmarks/bench_tangential.py",
                                 *argv]),
            "date_utc": started.isoformat(timespec="seconds"),
            "ccx": exe, "ccx_version": bfc._ccx_version(exe) if exe else None, "threads": 1,
            "python": platform.python_version(), "machine": platform.machine()},
        "units": {"pressure": "MPa", "force": "N/mm (per mm depth, full section)",
                  "length": "mm", "penalty": "N/mm^3 = MPa/mm", "time": "s (CPU)"},
        "pressure_mpa": PRESSURES_MPA.tolist(),
        "structure": {"name": BASE.name, "hole_mm": BASE.hole_mm,
                      "tube_od_mm": BASE.tube_od_mm, "tube_id_mm": BASE.tube_id_mm,
                      "wire_mm": BASE.wire_mm},
        "material": {"shore_a": SHORE, "c10_mpa": _material().c10_mpa,
                     "c01_mpa": _material().c01_mpa, "d_per_mpa": _material().d_per_mpa,
                     "gravity": "none (weightless)"},
        "friction": {"mu_wire": MU_WIRE, "mu_wall": 0.0},
        "definition": {
            "exofric": "2 sum_i |T_i|, nodal friction forces of the half model's wire contact "
                       "nodes (SqueezeResult.contact.wire_tangential_force_n_per_mm)",
            "ccx": "2 |sum_j f_j . t_j| over the rigid wire's nodes, f_j the reaction, t_j the "
                   "circumferential unit vector about the wire's centre"},
        "ccx_model": {"deck": "benchmarks/calculix_models.py squeeze_deck",
                      "common": CCX_COMMON, "base_options": CCX_BASE},
    }


def main(argv: list[str] | None = None) -> dict[str, Any]:
    """Command-line entry point; prints the table and returns (and writes) the summary."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--full", action="store_true",
                    help="every study of both codes (~1 h); writes the reference JSON")
    ap.add_argument("--quick", action="store_true",
                    help="one CalculiX and one exofric run; writes nothing unless --out")
    ap.add_argument("--only", choices=("ccx", "exofric"), default=None,
                    help="run one code only; writes nothing unless --out")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--quiet", action="store_true", help="print nothing (return only)")
    ap.add_argument("--out", type=Path, default=None,
                    help=f"output JSON (default {OUT.relative_to(HERE.parent)}; '-' none)")
    ap.add_argument("--ccx", default="ccx", help="CalculiX executable")
    ap.add_argument("--runs", default=None,
                    help="comma-separated run names (default: all of the chosen codes)")
    ap.add_argument("--merge", action="store_true",
                    help="keep the runs already in --out and add (or replace) these")
    args = ap.parse_args(argv)
    if not (args.full or args.quick or args.only or args.runs):
        args.quick, args.only = True, "exofric"   # make bench: the stored reference, no ccx
    exe = ccxm.ccx_available(args.ccx)
    only = args.only
    if exe is None:
        if only == "ccx":
            skipped = {"skipped": f"CalculiX ({args.ccx}) not on PATH (make calculix)"}
            if not args.quiet:
                print(json.dumps(skipped) if args.json else f"[tangential] {skipped['skipped']}")
            return skipped
        only = "exofric"
    started = datetime.datetime.now(datetime.UTC)
    target = args.out if args.out is not None else (
        OUT if args.full and not (args.quick or args.only) else None)
    header = _header(exe, started, sys.argv[1:] if argv is None else list(argv))

    def progress(partial: dict[str, Any]) -> None:
        if target is not None and str(target) != "-":
            bfc._write_atomic(target, {**header, **partial, "complete": False})

    start = None
    if args.merge and target is not None and Path(target).exists():
        start = json.loads(Path(target).read_text())
    names = None if args.runs is None else [n.strip() for n in args.runs.split(",")]
    res = run(args.quick, only, exe or args.ccx,
              None if (args.quiet or args.json) else sys.stderr, progress, names, start)
    out = {**header, **res, "complete": True}
    ref = (res["ccx"] or (json.loads(OUT.read_text())["ccx"] if OUT.exists() else {})
           ).get(REFERENCE)
    if ref is not None and "error" not in ref:
        out["comparison"] = {f"{name} vs ccx {REFERENCE}": compare(r, ref)
                             for name, r in res["exofric"].items()}
    if target is not None and str(target) != "-":
        bfc._write_atomic(target, out)
        out["written"] = str(target)
    if not args.quiet:
        print(json.dumps(out) if args.json else render(out))
    return out


if __name__ == "__main__":
    main()
