"""Benchmark: the friction force along the wire's contact arc, exofric vs CalculiX (issue 35.3).

Run: ``python benchmarks/bench_tangential.py [--full] [--quick] [--converge] [--only
ccx|exofric] [--json] [--quiet] [--out PATH]``. ``--converge``: both codes refined near the wire
to convergence at 0.2-0.3 MPa (three meshes each, Richardson-extrapolated; ~21 min CPU), written
to ``tests/data/ccx_tangential_converged.json``: exofric -3.7 / -1.7 / -1.4 % against CalculiX
at 0.2 / 0.25 / 0.3 MPa (docs/formulation.md section 13.1). Without options (``make
bench``): exofric's standard run against the stored CalculiX reference, a few seconds, nothing
written. ``--full``: every study of both codes,
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
SHOWN_MPA = (0.1, 0.2, 0.25, 0.3, 0.6)
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
#: The accuracy levels as they are now (two-sided graded meshes, issue 35), with T_wire's own
#: two-mesh error estimate (``estimate.wire_tangential_pct``, %): run name "level_<level>".
EXO_LEVELS = ("level_standard", "level_fine")
EXO_QUICK = ("standard", "level_standard")

#: The convergence study of both codes (``--converge``, issue 35 item 3 revisited): pressures to
#: 0.3 MPa only (the ramp ends there: half the cost), each code refined near the wire by doubling
#: its element counts through the wall and around the half at fixed gradings (every element
#: about halves), then its penalty and load steps at the finest mesh.
CONV_PRESSURES_MPA = np.round(np.arange(1, 7) * 0.05, 10)
CONV_OUT = HERE.parent / "tests" / "data" / "ccx_tangential_converged.json"
#: CalculiX: rings graded 6:1 toward the outer surface, angles 20:1 toward the wire, the rigid
#: wire and hole in 128 elements over their half circles (facets no coarser than the tube's).
CCX_CONV_BASE: dict[str, Any] = {"rigid_elements": 128, "grading": 20.0, "radial_grading": 6.0,
                                 "max_increment_mpa": 0.025, "stick_slope": 1e3}
CCX_CONV: dict[str, dict[str, Any]] = {
    "4x40": {"n_radial": 4, "n_circ": 40},
    "8x80": {"n_radial": 8, "n_circ": 80},
    "16x160": {"n_radial": 16, "n_circ": 160},
    "16x160_slope_1e4": {"n_radial": 16, "n_circ": 160, "stick_slope": 1e4},
    "16x160_inc_0.0125": {"n_radial": 16, "n_circ": 160, "max_increment_mpa": 0.0125},
}
#: exofric: uniform rings (MeshSpec has no radial grading), angles 20:1 toward the wire.
EXO_CONV: dict[str, tuple[tuple[int, int, float], float | None, float]] = {
    "6x48": ((6, 48, 20.0), None, 0.00625),
    "12x96": ((12, 96, 20.0), None, 0.00625),
    "24x192": ((24, 192, 20.0), None, 0.00625),
    "24x192_step_0.003125": ((24, 192, 20.0), None, 0.003125),
    "24x192_eps_1e4": ((24, 192, 20.0), 1e4, 0.00625),
    "24x192_eps_1e5": ((24, 192, 20.0), 1e5, 0.00625),
    "6x48_step_0.003125": ((6, 48, 20.0), None, 0.003125),
    "12x96_step_0.003125": ((12, 96, 20.0), None, 0.003125),
    "24x192_step_0.0015625": ((24, 192, 20.0), None, 0.0015625),
}


def _material() -> MooneyRivlin:
    return MooneyRivlin.from_shore(SHORE)


def _list(a: Any) -> list[float]:
    return [float(v) + 0.0 for v in np.asarray(a, dtype=float)]


def run_ccx(name: str, ccx: str = "ccx", converge: bool = False) -> dict[str, Any]:
    """One CalculiX run of :data:`CCX_RUNS` (``converge``: :data:`CCX_CONV`) ``name``: T_wire,
    S_wire, N (N/mm), CPU (s)."""
    opts = ({**CCX_CONV_BASE, **CCX_CONV[name]} if converge
            else {**CCX_BASE, **CCX_RUNS[name]})
    pressures = CONV_PRESSURES_MPA if converge else PRESSURES_MPA
    deck = ccxm.squeeze_deck(pressures, _material(), hole_mm=BASE.hole_mm,
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


def run_exofric(name: str, converge: bool = False) -> dict[str, Any]:
    """One exofric run of :data:`EXO_RUNS` or :data:`EXO_LEVELS` (``converge``:
    :data:`EXO_CONV`) ``name``: T_wire, S_wire, N (N/mm), stick, time; for a level also
    T_wire's error estimate (%) and its flags."""
    t0 = time.process_time()
    pressures = CONV_PRESSURES_MPA if converge else PRESSURES_MPA
    if converge:
        (nr, nc, grading), eps_t, step = EXO_CONV[name]
        settings = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "max_step": step})
        r = squeeze(BASE, _material(), pressures, mu_wall=0.0, mu_wire=MU_WIRE,
                    gravity="none", mesh=MeshSpec(nr, nc, grading=grading),
                    friction_penalty=eps_t, settings=settings, keep_fields=False)
    elif name in EXO_LEVELS:
        r = squeeze(BASE, _material(), PRESSURES_MPA, mu_wall=0.0, mu_wire=MU_WIRE,
                    gravity="none", accuracy=name.split("_", 1)[1])
        nr, nc, grading, step = r.mesh.n_radial, r.mesh.n_circ, r.mesh.grading, None
    else:
        (nr, nc, grading), eps_t, step = EXO_RUNS[name]
        settings = NewtonSettings(**{**defaults.SQUEEZE_NEWTON, "max_step": step})
        r = squeeze(BASE, _material(), PRESSURES_MPA, mu_wall=0.0, mu_wire=MU_WIRE,
                    gravity="none", mesh=MeshSpec(nr, nc, grading=grading),
                    friction_penalty=eps_t, settings=settings)
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
            "sign_changes": signs, "cpu_time_s": cpu,
            **({} if r.estimate.wire_tangential_pct is None else {
                "tangential_error_estimate_pct": _list(r.estimate.wire_tangential_pct),
                "estimate_reliable": [bool(v) for v in r.estimate.reliable]})}


def _at(values: list[float], p: float) -> float:
    """``values`` at ``p`` MPa (the full or the convergence study's pressures; nan beyond)."""
    ps = PRESSURES_MPA if len(values) == PRESSURES_MPA.size else CONV_PRESSURES_MPA
    if p > ps[-1] + 1e-12:
        return float("nan")
    return float(values[int(np.argmin(np.abs(ps - p)))])


def richardson(f1: float, f2: float, f3: float, r: float = 2.0) -> dict[str, Any]:
    """Richardson extrapolation of three meshes (``f1`` coarsest .. ``f3`` finest, every
    element about halved between them: ratio ``r``) with the observed order.

    ``order`` p = ln((f2 - f1) / (f3 - f2)) / ln r where the changes keep their sign and shrink
    (otherwise None, and ``extrapolated`` is the finest value); ``extrapolated`` f3 + (f3 -
    f2) / (r^p - 1); ``gci_pct`` Roache's grid convergence index of the finest mesh (safety
    factor 1.25 with three meshes, %); ``last_change_pct`` 100 (f3 / f2 - 1)."""
    d1, d2 = f2 - f1, f3 - f2
    out: dict[str, Any] = {"last_change_pct": 100.0 * (f3 / f2 - 1.0), "order": None,
                           "extrapolated": f3, "gci_pct": None}
    if d1 * d2 > 0.0 and abs(d2) < abs(d1):
        order = float(np.log(d1 / d2) / np.log(r))
        ext = f3 + d2 / (r**order - 1.0)
        out.update(order=order, extrapolated=ext,
                   gci_pct=100.0 * 1.25 * abs(d2 / f3) / (r**order - 1.0))
    return out


def converged(out: dict[str, Any], code: str, names: tuple[str, str, str],
              from_mpa: float = 0.2) -> dict[str, Any]:
    """Per pressure from ``from_mpa``: the three-mesh Richardson extrapolation of ``code``'s
    runs ``names`` (coarsest first), see :func:`richardson`."""
    t = [np.asarray(out[code][n]["tangential_n_per_mm"]) for n in names]
    k = [i for i, p in enumerate(CONV_PRESSURES_MPA) if p >= from_mpa - 1e-12]
    return {"meshes": list(names), "pressure_mpa": [float(CONV_PRESSURES_MPA[i]) for i in k],
            "per_pressure": [richardson(float(t[0][i]), float(t[1][i]), float(t[2][i]))
                             for i in k]}


#: The mesh sequences of the convergence study (coarsest first; exofric's at the load sub-step
#: that halving changes by <= 0.4 % on its finest mesh)
CONV_MESHES = {"ccx": ("4x40", "8x80", "16x160"),
               "exofric": ("6x48_step_0.003125", "12x96_step_0.003125", "24x192_step_0.003125")}


def summarise(out: dict[str, Any]) -> dict[str, Any]:
    """Both codes' extrapolated T_wire (where their three meshes ran) and exofric's minus
    CalculiX's, relative to CalculiX's (%)."""
    res = {code: converged(out, code, names) for code, names in CONV_MESHES.items()
           if all(n in out.get(code, {}) and "error" not in out[code][n] for n in names)}
    if len(res) == 2:
        res["exofric_vs_ccx_pct"] = [
            100.0 * (a["extrapolated"] / b["extrapolated"] - 1.0) for a, b in
            zip(res["exofric"]["per_pressure"], res["ccx"]["per_pressure"], strict=True)]
    return res


def compare(exo: dict[str, Any], ref: dict[str, Any], p_from: float = 0.2) -> dict[str, Any]:
    """Relative difference exo / ref - 1 of T_wire per pressure (None where ref is 0) and its
    largest magnitude from ``p_from`` MPa."""
    a, b = np.asarray(exo["tangential_n_per_mm"]), np.asarray(ref["tangential_n_per_mm"])
    rel = [None if bb <= 0 else float(aa / bb - 1.0) for aa, bb in zip(a, b, strict=True)]
    k = [i for i, p in enumerate(PRESSURES_MPA) if p >= p_from - 1e-12 and rel[i] is not None]
    return {"rel": rel, f"max_abs_rel_from_{p_from:g}_mpa": max(abs(rel[i]) for i in k)}


def run(quick: bool = False, only: str | None = None, ccx: str = "ccx",
        log: Any = None, progress: Any = None, names: list[str] | None = None,
        start: dict[str, Any] | None = None, converge: bool = False) -> dict[str, Any]:
    """The CalculiX and exofric runs (``quick``: one of each; ``converge``: the convergence
    study :data:`CCX_CONV`, :data:`EXO_CONV`); JSON-ready dict.

    ``progress(partial)`` is called after every run (the caller writes partial results);
    ``names`` restricts the runs, ``start`` holds earlier runs that are kept."""
    def note(msg: str) -> None:
        if log is not None:
            print(msg, file=log, flush=True)

    out: dict[str, Any] = {"ccx": dict((start or {}).get("ccx", {})),
                           "exofric": dict((start or {}).get("exofric", {}))}
    if only in (None, "ccx"):
        for name in (CCX_CONV if converge else CCX_QUICK if quick else CCX_RUNS):
            if names is not None and name not in names:
                continue
            note(f"[tangential] CalculiX {name} ...")
            out["ccx"][name] = run_ccx(name, ccx, converge)
            if progress is not None:
                progress(out)
    if only in (None, "exofric"):
        for name in (EXO_CONV if converge else EXO_QUICK if quick
                     else (*EXO_RUNS, *EXO_LEVELS)):
            if names is not None and name not in names:
                continue
            note(f"[tangential] exofric {name} ...")
            out["exofric"][name] = run_exofric(name, converge)
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
            if "tangential_error_estimate_pct" in r:
                lines.append(_row("  its T_wire error estimate (%)",
                                  r["tangential_error_estimate_pct"], "{:8.1f}%"))
    for name, cmp_ in out.get("comparison", {}).items():
        rel = cmp_["rel"]
        lines.append(f"{'rel ' + name:<40}" + "".join(
            "        -" if rel[int(np.argmin(np.abs(PRESSURES_MPA - p)))] is None else
            f"{100 * rel[int(np.argmin(np.abs(PRESSURES_MPA - p)))]:8.1f}%" for p in SHOWN_MPA))
    conv = out.get("converged", {})
    for code in ("ccx", "exofric"):
        if code in conv:
            c = conv[code]
            lines.append(f"{code} {' -> '.join(c['meshes'])}: extrapolated at "
                         + ", ".join(f"{p:g}" for p in c["pressure_mpa"]) + " MPa: "
                         + ", ".join(f"{q['extrapolated']:.5f} (order "
                                     + ("-" if q["order"] is None else f"{q['order']:.2f}")
                                     + f", last change {q['last_change_pct']:+.1f} %)"
                                     for q in c["per_pressure"]))
    if "exofric_vs_ccx_pct" in conv:
        lines.append("exofric vs ccx, extrapolated: "
                     + ", ".join(f"{v:+.1f} %" for v in conv["exofric_vs_ccx_pct"]))
    if out.get("written"):
        lines.append(f"wrote {out['written']}")
    return "\n".join(lines)


def _header(exe: str | None, started: datetime.datetime, argv: list[str],
            converge: bool = False) -> dict[str, Any]:
    """Description, provenance, units, problem and definitions of the output JSON."""
    study = ("mesh convergence studies of both codes to 0.3 MPa (each refined near the wire "
             "by doubling its element counts at fixed gradings), then the penalty, stick slope "
             "and steps at the finest meshes" if converge else
             "CalculiX runs (the reference: stick slope, increment and mesh studies) and "
             "exofric's own penalty, load-step and mesh studies (a record, not a reference)")
    return {
        "description": "The friction force along the wire's contact arc, T_wire "
                       "(wire_tangential_force_n_per_mm), base group, mu_wire 0.3, wall "
                       f"frictionless: {study}; issue 35 item 3",
        "provenance": {
            "command": " ".join(["python", "benchmarks/bench_tangential.py",
                                 *argv]),
            "date_utc": started.isoformat(timespec="seconds"),
            "ccx": exe, "ccx_version": bfc._ccx_version(exe) if exe else None, "threads": 1,
            "python": platform.python_version(), "machine": platform.machine()},
        "units": {"pressure": "MPa", "force": "N/mm (per mm depth, full section)",
                  "length": "mm", "penalty": "N/mm^3 = MPa/mm", "time": "s (CPU)"},
        "pressure_mpa": (CONV_PRESSURES_MPA if converge else PRESSURES_MPA).tolist(),
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
                      "common": CCX_COMMON,
                      "base_options": CCX_CONV_BASE if converge else CCX_BASE},
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
    ap.add_argument("--converge", action="store_true",
                    help="the convergence study of both codes to 0.3 MPa (~30 min CPU); writes "
                         f"{CONV_OUT.relative_to(HERE.parent)} (or --out)")
    ap.add_argument("--merge", action="store_true",
                    help="keep the runs already in --out and add (or replace) these")
    args = ap.parse_args(argv)
    if not (args.full or args.quick or args.only or args.runs or args.converge):
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
        CONV_OUT if args.converge else
        OUT if args.full and not (args.quick or args.only) else None)
    header = _header(exe, started, sys.argv[1:] if argv is None else list(argv),
                     args.converge)

    def progress(partial: dict[str, Any]) -> None:
        if target is not None and str(target) != "-":
            bfc._write_atomic(target, {**header, **partial, "complete": False})

    start = None
    if args.merge and target is not None and Path(target).exists():
        start = json.loads(Path(target).read_text())
    names = None if args.runs is None else [n.strip() for n in args.runs.split(",")]
    res = run(args.quick, only, exe or args.ccx,
              None if (args.quiet or args.json) else sys.stderr, progress, names, start,
              args.converge)
    out = {**header, **res, "complete": True}
    ref = (res["ccx"] or (json.loads(OUT.read_text())["ccx"] if OUT.exists() else {})
           ).get(REFERENCE)
    if args.converge:
        out["converged"] = summarise(out)
    if ref is not None and "error" not in ref and not args.converge:
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
