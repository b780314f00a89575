"""exofric's defaults, in one place: meshes, contact, density, Newton settings, validity limits.

The API keywords, the CLI options and the sweep specs take their defaults from here, so a change
here changes them all. Every value says its unit and where it was checked. This module imports
nothing (it sits at the bottom of the layers, and the CLI reads it at start-up): meshes and
Newton settings are the keyword arguments of :class:`exofric.fe.MeshSpec` and
:class:`exofric.fe.NewtonSettings` (``MeshSpec(**SQUEEZE_MESH)``).

Units: mm, N, MPa, s; density in t/mm^3 (consistent with N, mm, s).

Examples
--------
>>> from exofric import defaults
>>> from exofric.fe import MeshSpec
>>> MeshSpec(**defaults.SQUEEZE_MESH).n_circ, defaults.CONTACT_PENALTY_N_PER_MM3
(24, 100000.0)
"""

from types import MappingProxyType
from typing import Any, Final

__all__ = [
    "ACCURACY",
    "BLAS_THREADS",
    "CONTACT_PENALTY_N_PER_MM3",
    "FRICTION_PENALTY_REL",
    "ESTIMATE_FLOOR_PCT",
    "ESTIMATE_MIN_PATCH_NODES",
    "ESTIMATE_SAFETY_FACTOR",
    "ESTIMATE_WINDOW_MPA",
    "GRAVITY",
    "INFLATION_ACCURACY",
    "INFLATION_MESH",
    "INFLATION_NEWTON",
    "MR_STRETCH_LIMIT",
    "NEWTON",
    "REGULARISER_SPRING_REL",
    "SILICONE_DENSITY_T_PER_MM3",
    "SQUEEZE_ACCURACY",
    "SQUEEZE_MESH",
    "SQUEEZE_NEWTON",
]

#: Free-inflation mesh: quarter model, 2 x 6 quad9 (130 dofs); within 3e-5 of the 1D reference
#: for 8.3/4.97 mm up to 0.6 MPa (tests/test_fe_inflate.py, convergence study). The quarter
#: model's angles are uniform (the solution is axisymmetric): ``grading`` only applies to the
#: squeeze's half model, and is the same 6:1 as there so that ``MeshSpec(4, 48)`` means one
#: mesh whichever problem it is given to.
INFLATION_MESH: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {"n_radial": 2, "n_circ": 6, "kind": "quad9", "grading": 6.0, "formulation": "mixed"})

#: Squeeze mesh: half model, 2 x 24 quad9 graded 6:1 toward the wire (490 dofs); within 0.05%
#: of an 8 x 96 mesh at 0.6 MPa (tests/test_squeeze.py).
SQUEEZE_MESH: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {"n_radial": 2, "n_circ": 24, "kind": "quad9", "grading": 6.0, "formulation": "mixed"})

#: Accuracy levels of the squeeze (``squeeze(..., accuracy=...)``, ``--accuracy``). Each names
#: the half-tube mesh whose answer is returned and the factors (radial, circumferential) by which
#: it is coarsened into the nested mesh whose difference from it gives the error estimate (both
#: halved: the estimate sees the radial and the circumferential error). The meshes are graded
#: toward both contacts (issue 35): ``wall_elements`` of the ``n_circ`` elements over -90..0 deg
#: toward the hole wall (ratio ``wall_grading``), the rest toward the wire (``grading``).
#: Largest error from the first pressure where N >= 1% of N(0.6 MPa) against the independent
#: FElupe reference (tests/data/squeeze_reference_felupe.json, six Table 3 structures) and
#: against the independent thick-wall FElupe reference (squeeze_reference_felupe_onset.json, five
#: structures, ID/OD 0.54): "draft" 0.81% / 1.47%, "standard" 0.47% / 0.58%, "fine" 0.16% /
#: 0.59% (docs/formulation.md section 6; before issue 35 "standard" was 0.63% / 3.7%).
SQUEEZE_ACCURACY: Final[MappingProxyType[str, MappingProxyType[str, Any]]] = MappingProxyType({
    "draft": MappingProxyType({"n_radial": 2, "n_circ": 24, "grading": 6.0, "wall_elements": 8,
                               "wall_grading": 4.0, "coarsen": (2, 2)}),
    "standard": MappingProxyType({"n_radial": 4, "n_circ": 32, "grading": 6.0,
                                  "wall_elements": 10, "wall_grading": 4.0, "coarsen": (2, 2)}),
    "fine": MappingProxyType({"n_radial": 4, "n_circ": 64, "grading": 6.0, "wall_elements": 20,
                              "wall_grading": 4.0, "coarsen": (2, 2)}),
})

#: Safety factor Fs of the two-mesh error estimate, Fs |f_fine - f_coarse| / (r^p - 1) with
#: refinement ratio r = 2 and order p = 1 (nodal contact converges at order ~1, oscillating):
#: Roache's grid convergence index for two-grid studies (Fs = 3; J. Fluids Eng. 116, 1994).
ESTIMATE_SAFETY_FACTOR: Final = 3.0

#: Smallest squeeze-force error estimate claimed (% of N where N > 0). Nodal contact makes the
#: discretisation error oscillate with P (the active set moves node by node), so the two meshes'
#: difference can cross zero at any one pressure; on mesh-converged references the error of the
#: "standard" level at such crossings was up to 0.014% (test 7, 0.6 MPa, against FElupe).
ESTIMATE_FLOOR_PCT: Final = 0.1

#: Squeeze estimate: the two meshes' difference is taken at its largest over the outputs
#: within this distance (MPa) of each pressure (its sign oscillates as the contact edges
#: pass the nodes; issue 35: 3 of 167 pressures had an error above the pointwise estimate).
ESTIMATE_WINDOW_MPA: Final = 0.05

#: Squeeze estimate: reliable only where the coarse mesh's wire contact patch spans at least
#: this many outer nodes from its centre (centre included); below, the coarse mesh cannot
#: resolve the patch and the difference does not scale like the error (issue 35).
ESTIMATE_MIN_PATCH_NODES: Final = 2

#: Accuracy levels of the free inflation (quarter model; same meaning as SQUEEZE_ACCURACY).
#: "standard" is the 2 x 6 mesh above (3e-5 of the 1D reference).
INFLATION_ACCURACY: Final[MappingProxyType[str, MappingProxyType[str, Any]]] = MappingProxyType({
    "draft": MappingProxyType({"n_radial": 1, "n_circ": 4, "grading": 6.0, "coarsen": (1, 2)}),
    "standard": MappingProxyType(
        {"n_radial": 2, "n_circ": 6, "grading": 6.0, "coarsen": (2, 2)}),
    "fine": MappingProxyType({"n_radial": 4, "n_circ": 12, "grading": 6.0, "coarsen": (2, 2)}),
})

#: Accuracy level used when neither ``accuracy`` nor an explicit mesh is given.
ACCURACY: Final = "standard"

#: Orientation of gravity in the squeeze: "none" (the tube's weight is left out; the load path
#: is regularised by a body force that is taken to zero before any output is read),
#: "toward-wall" (the tube rests on the hole wall) or "toward-wire" (hangs on the wire).
GRAVITY: Final = "none"

#: gravity "none": stiffness of the spring that holds the floating tube (on the outer node at
#: the wall) before it bears on wall and wire, relative to the shear modulus (N/mm per mm
#: depth per MPa). Its force is zero at every reported state (simulate.squeeze).
REGULARISER_SPRING_REL: Final = 1.0

#: Contact penalty (N/mm^3, MPa of contact pressure per mm of penetration): penetration
#: ~3e-5 mm at 0.6 MPa for the base group; 10x stiffer changes N by 1e-5.
CONTACT_PENALTY_N_PER_MM3: Final = 1e5

#: Tangential (friction) penalty relative to the contact penalty (unitless): 1e3 N/mm^3 at
#: the default, an elastic slip before sliding of mu p / eps_t ~ 1 um at 3 MPa of contact
#: pressure. Measured on the base group (mu 0.3): 1e3 vs 1e5 changes N by 1e-5 and halves the
#: failed Newton attempts (a stiff stick spring makes the stick/slip switch abrupt); 1e2
#: changes N by 2e-4 (CalculiX's stick slope in the reference: 1e3 for a normal 1e4).
FRICTION_PENALTY_REL: Final = 0.01

#: Silicone density (t/mm^3 = 1.1 g/cm^3): the tube's weight in the squeeze (with gravity on),
#: and the magnitude of the load path's regulariser (with gravity "none").
SILICONE_DENSITY_T_PER_MM3: Final = 1.1e-9

#: Newton settings shared by every load path (tolerances relative to the problem's scales;
#: ``max_iter`` iterations per sub-step before a cut-back; ``max_step`` in MPa;
#: ``active_set_iterations`` re-solves of a direction whose step would run nodes into an
#: obstacle, see ``SqueezeProblem.refine_direction``; ``stagnation_ratio``: an attempt whose
#: last four steps were all damped and cut the residual by less than this factor over them is
#: abandoned at once; both measured on the base group, 2 x 24 to 8 x 128, issue 22;
#: ``chord_step``: steps at most this long, relative to the length scale, reuse the last
#: factorisation for the next direction, issue 37).
NEWTON: Final[MappingProxyType[str, Any]] = MappingProxyType({
    "tol_r": 1e-9, "tol_u": 1e-10, "max_iter": 15, "max_cutbacks": 12, "max_step": 0.05,
    "min_step": 1e-6, "line_search_halvings": 8, "extrapolate": True,
    "active_set_iterations": 3, "stagnation_ratio": 0.5, "chord_step": 1e-5,
})

#: Newton settings of the free inflation (largest pressure step 0.05 MPa).
INFLATION_NEWTON: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {**NEWTON, "max_step": 0.05})

#: Newton settings of the squeeze (largest pressure step 0.025 MPa; contact needs smaller steps).
SQUEEZE_NEWTON: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {**NEWTON, "max_step": 0.025})

#: Largest principal stretch for which the paper claims its two-parameter Mooney-Rivlin model
#: holds ("100-150% material deformation", §3.3); beyond it results are extrapolations.
MR_STRETCH_LIMIT: Final = 2.5

#: BLAS/OpenMP threads a Newton solve may use (``NewtonSettings.threads``; 0 leaves the thread
#: pools as they are). The banded factorisations of the tube meshes are too small to gain from
#: threads, and under CPU contention (parallel sweeps, other jobs) extra threads made refined
#: meshes 6-9x slower; one thread per solve is the fast and safe setting.
BLAS_THREADS: Final = 1

# --- Design sweeps: serial, worker processes or Dask (exofric.design, `exofric sweep`) ----------
# Block owned by the sweep scheduling (issue 22); measured 2026-11-23 on the 2-core machine
# (benchmarks/bench_sweep.py). The rule is exofric.design.plan_execution.

#: A-priori cost of one design's squeeze solve before any was timed (s): ``s_per_design +
#: s_per_dof_step x dofs x (largest pressure / max_step_mpa)``, dofs = 2 (2 n_radial + 1)
#: (2 n_circ + 1). Fitted to 1 x 12 ... 4 x 64 meshes up to 0.6 MPa in 0.025 MPa steps
#: (0.08-0.73 s CPU). A sweep replaces it by the measured time once one design is solved, so
#: a faster solver only makes this first guess pessimistic.
SWEEP_DESIGN_COST: Final[MappingProxyType[str, float]] = MappingProxyType(
    {"s_per_design": 0.02, "s_per_dof_step": 1.3e-5})

#: Start-up of k local worker processes until all solve (s) = ``fixed + per_worker x k``, by
#: start method. fork (Linux): 0.01-0.03 s for 2 (the workers inherit this process' imports);
#: forkserver / spawn: +0.7 / +1.0 s over fork for 2 workers solving 2 small designs (each
#: worker imports NumPy, SciPy, pandas and exofric). For comparison a Dask LocalCluster took
#: 0.65-0.75 s to start and 0.2-0.3 s to close.
SWEEP_POOL_START_S: Final[MappingProxyType[str, MappingProxyType[str, float]]] = \
    MappingProxyType({
        "fork": MappingProxyType({"fixed": 0.02, "per_worker": 0.01}),
        "forkserver": MappingProxyType({"fixed": 0.7, "per_worker": 0.05}),
        "spawn": MappingProxyType({"fixed": 1.0, "per_worker": 0.05}),
    })

#: Cost of handing one design to a worker and getting its result back (s): local processes
#: 0.1-0.2 ms (pickling, pipes; taken as 1 ms), Dask ~3 ms (scheduler round trip).
SWEEP_TASK_OVERHEAD_S: Final[MappingProxyType[str, float]] = MappingProxyType(
    {"processes": 1e-3, "dask": 3e-3})

#: Worker processes are started only if they are predicted to save at least this much wall
#: time (s) and at least SWEEP_MIN_GAIN_REL of the serial time (unitless fraction): a sweep of
#: a few quick designs stays in the calling process.
SWEEP_MIN_GAIN_S: Final = 0.2
#: The relative part of that rule: the least gain as a fraction of the serial time (unitless).
SWEEP_MIN_GAIN_REL: Final = 0.1

__all__ += ["SWEEP_DESIGN_COST", "SWEEP_MIN_GAIN_REL", "SWEEP_MIN_GAIN_S", "SWEEP_POOL_START_S",
            "SWEEP_TASK_OVERHEAD_S"]

# --- Input bounds (issue 21: hostile inputs are refused before any solve) ----------------------
# Block owned by the input validation of issue 21 (exofric.fe.MeshSpec, exofric.geometry).

#: Largest explicit mesh (MeshSpec; ``--n-radial``/``--n-circ``). Memory grows with the number of
#: quad9 elements, ~50 KB each plus ~0.1 GB of start-up (peak RSS of `exofric inflate` with one
#: pressure, 2 x 1024, 8 x 512 and 2 x 4096 meshes, 2026-11-23): the element cap of 8192 keeps
#: a solve near 0.5 GB, well inside a laptop, while the finest meshes of the tests and
#: benchmarks (12 x 256 = 3072 and 8 x 256 elements; mesh-convergence references of 6 x 192)
#: stay legal. n_radial / n_circ caps bound a single direction (32 elements through a 1.7 mm
#: wall, 1024 around a half tube are far past mesh convergence).
MESH_MAX_N_RADIAL: Final = 32
#: Most elements around the modelled sector (see MESH_MAX_N_RADIAL).
MESH_MAX_N_CIRC: Final = 1024
#: Most elements of one mesh, n_radial x n_circ (~0.5 GB; see MESH_MAX_N_RADIAL).
MESH_MAX_ELEMENTS: Final = 8192
#: Memory per element (bytes) of the estimate quoted when a mesh is refused (measured above).
MESH_BYTES_PER_ELEMENT: Final = 50e3
#: Fixed start-up memory (bytes) of that estimate (measured above).
MESH_BYTES_FIXED: Final = 0.1e9
#: Largest circumferential grading (largest/smallest element, unitless): the defaults use 6;
#: past ~100 the smallest elements are thousands of times thinner than thick, which only
#: degrades the conditioning.
MESH_MAX_GRADING: Final = 100.0

#: Sizes of a friction structure (hole, tube and wire diameters, tube length; mm). An exosuit
#: friction structure is worn on the body: the paper's hole is 10 mm and its tube 116 mm long, so
#: 1000 mm (1 m) is far beyond any wearable part, and 0.01 mm (10 um) below any tube or wire that
#: can be made; outside this range the FE mesh is ill-conditioned (sizes near 1e300 overflow
#: the element Jacobians) and no answer would mean anything.
SIZE_MIN_MM: Final = 0.01
#: Largest size of a friction structure (mm); see SIZE_MIN_MM.
SIZE_MAX_MM: Final = 1000.0

__all__ += ["MESH_BYTES_FIXED", "MESH_BYTES_PER_ELEMENT", "MESH_MAX_ELEMENTS", "MESH_MAX_GRADING",
            "MESH_MAX_N_CIRC", "MESH_MAX_N_RADIAL", "SIZE_MAX_MM", "SIZE_MIN_MM"]

# --- Sweep integrity and cluster options (exofric.design, `exofric sweep`; issue 21) ----------

#: How long `exofric sweep --scheduler ADDRESS` tries one TCP connection to the scheduler (s)
#: before handing the address to Dask: an address where nothing listens fails in this time
#: instead of waiting the whole ``--timeout``. A reachable scheduler on a LAN answers in ms.
SWEEP_SCHEDULER_CONNECT_S: Final = 3.0

__all__ += ["SWEEP_SCHEDULER_CONNECT_S"]

# --- Plausibility rules for data that parses (issue 21): warnings, or errors past them -------

#: Inflation tests: largest drop of the outer diameter between consecutive pressures before a
#: warning, relative to the diameter (0.5%: ~0.04 mm on an 8-10 mm tube, twice a caliper's or a
#: camera's typical scatter). A net drop from the lowest to the highest pressure larger than this
#: is impossible for an inflating tube: an error.
PLAUSIBLE_OD_DROP_REL: Final = 0.005
#: Squeeze curves N(P): largest drop between consecutive pressures before a warning, relative
#: to the curve's largest force (2%: the rig's force scatter); a net drop larger than this from
#: the first pressure with force to the last is an error (N grows with P).
PLAUSIBLE_N_DROP_REL: Final = 0.02
#: Step-response identification: R^2 below this warns that the first-order-plus-dead-time model
#: does not describe the data (pneumatic steps fit it with R^2 > 0.95; pure noise gives ~0).
PLAUSIBLE_IDENTIFY_MIN_R2: Final = 0.9
#: Materials: a small-strain Poisson ratio below this warns (silicone rubber is nearly
#: incompressible, the paper uses 0.498); <= 0 is an error, as in ``MooneyRivlin.from_shore``.
PLAUSIBLE_POISSON_MIN: Final = 0.45

__all__ += ["PLAUSIBLE_IDENTIFY_MIN_R2", "PLAUSIBLE_N_DROP_REL", "PLAUSIBLE_OD_DROP_REL",
            "PLAUSIBLE_POISSON_MIN"]

# --- Raw rig logs (exofric.io.read_raw_log; issue 14) ----------------------------------------

#: A time step longer than this multiple (unitless) of the log's median step is a gap: an error
#: naming the time range (a logger that dropped samples; reducing across it would average
#: unrelated data).
RAWLOG_MAX_GAP_FACTOR: Final = 10.0
#: Fewest samples a raw log must have.
RAWLOG_MIN_SAMPLES: Final = 20

#: A raw log whose estimated reading memory exceeds this fraction (unitless) of the machine's
#: physical memory is refused, naming the estimate (issue 38): split it and reduce the parts.
RAWLOG_MEMORY_FRACTION: Final = 0.5
#: Peak memory of reading a raw log as a multiple (unitless) of its file's size, by format:
#: text (CSV, LVM) measured at 2.95 on a 37 MB, 500,000-row CSV (rounded up); xlsx: openpyxl
#: documents about 50; TDMS (uncompressed samples): as text. Parquet is estimated from its
#: metadata (rows x columns x 8 bytes x 3), not from its compressed size.
RAWLOG_MEMORY_PER_FILE_BYTE: Final = {"text": 3.5, "xlsx": 50.0}

__all__ += ["RAWLOG_MAX_GAP_FACTOR", "RAWLOG_MEMORY_FRACTION", "RAWLOG_MEMORY_PER_FILE_BYTE",
            "RAWLOG_MIN_SAMPLES"]

# --- Plausibility of what a rig log says (exofric.io.read_raw_log; issue 31) ---------------------

#: A tube pressure above this (MPa) in a rig log is an error naming the probable unit: the
#: paper's tubes run at 0.2-0.6 MPa and burst well below 10 MPa, so 300-600 "MPa" are kPa.
RAWLOG_MAX_PRESSURE_MPA: Final = 10.0
#: A friction force above this (N) in a rig log is an error naming the probable unit (the
#: paper's forces are 10-300 N; 10 kN would tear the wire).
RAWLOG_MAX_FORCE_N: Final = 1.0e4
#: Typical levels (MPa, N) used to name the probable unit of an implausible column: the unit
#: whose reading lands closest (in log scale) to these.
RAWLOG_TYPICAL_PRESSURE_MPA: Final = 0.4
#: The typical force level (N) of the same rule.
RAWLOG_TYPICAL_FORCE_N: Final = 100.0
#: Factors between units of one quantity (MPa/kPa, bar/kPa, psi/kPa, lbf/N, kgf/N, ...): a jump of
#: the level by one of them within one sample is a unit change inside the log (an error).
RAWLOG_UNIT_JUMP_FACTORS: Final = (1.0e3, 1.0e6, 1.0e2, 6.894757, 68.94757, 145.0377, 14.50377,
                                   4.448222, 9.80665, 2.204623)
#: Relative tolerance (unitless) of a level ratio matching one of those factors.
RAWLOG_UNIT_JUMP_RTOL: Final = 0.02

__all__ += ["RAWLOG_MAX_FORCE_N", "RAWLOG_MAX_PRESSURE_MPA", "RAWLOG_TYPICAL_FORCE_N",
            "RAWLOG_TYPICAL_PRESSURE_MPA", "RAWLOG_UNIT_JUMP_FACTORS", "RAWLOG_UNIT_JUMP_RTOL"]

# --- Reducing raw rig logs (exofric.friction.reduce_log, `exofric reduce`; issue 14) ----------

#: A pressure plateau: the smoothed pressure moves less than max(abs, rel x level) over
#: REDUCE_MIN_PLATEAU_S (0.005 MPa is 5 kPa, a regulator's typical hold accuracy; 2 % keeps the
#: band proportionate at high pressure).
REDUCE_PLATEAU_TOL_MPA: Final = 0.005
#: The relative part of the plateau band (unitless fraction of the plateau's pressure).
REDUCE_PLATEAU_TOL_REL: Final = 0.02
#: Shortest pressure plateau (s).
REDUCE_MIN_PLATEAU_S: Final = 1.0
#: Moving-median window for the pressure and displacement channels (s).
REDUCE_SMOOTH_S: Final = 0.1
#: Travel (mm, with a displacement column) or time (s, without) excluded from the start of a
#: pull before the steady (kinetic) window: the stretch and the breakaway transient.
REDUCE_SKIP_MM: Final = 2.0
#: The same exclusion as time (s), for a log without a displacement column.
REDUCE_SKIP_S: Final = 1.0
#: Time excluded at the end of a pull (deceleration) (s).
REDUCE_END_TRIM_S: Final = 0.1
#: Shortest pull (s); shorter motions are listed as skipped.
REDUCE_MIN_PULL_S: Final = 0.5
#: Tare: rest windows of this length (s) before and after each pull, starting this long (s)
#: after a pull ends or before one starts (the wire relaxes).
REDUCE_TARE_S: Final = 0.5
#: The gap (s) between a pull's end or start and its tare window.
REDUCE_TARE_GAP_S: Final = 0.3
#: Moving-average window of the breakaway (static) peak (s): short against the breakaway transient,
#: whose cusp a longer average flattens (0.02 s loses ~1 % of the peak on the virtual rig; 0.005 s
#: loses ~0.3 % and halves nothing of the noise: the raw maximum is as good).
REDUCE_STATIC_WINDOW_S: Final = 0.005
#: A pull: displacement speed above this share (unitless) of the log's typical pull speed (95th
#: percentile).
REDUCE_SPEED_FRACTION: Final = 0.3
#: Without displacement: a pull is where the force leaves its rest level by more than this many
#: rest-noise standard deviations (unitless).
REDUCE_FORCE_SIGMAS: Final = 8.0
#: Warn when the force drifts by more than this share of the kinetic friction over its window (%).
REDUCE_DRIFT_WARN_PCT: Final = 5.0
#: Samples flat at the force channel's extreme that mean saturation.
REDUCE_SATURATION_SAMPLES: Final = 5

__all__ += ["REDUCE_DRIFT_WARN_PCT", "REDUCE_END_TRIM_S", "REDUCE_FORCE_SIGMAS",
            "REDUCE_MIN_PLATEAU_S", "REDUCE_MIN_PULL_S", "REDUCE_PLATEAU_TOL_MPA",
            "REDUCE_PLATEAU_TOL_REL", "REDUCE_SATURATION_SAMPLES", "REDUCE_SKIP_MM",
            "REDUCE_SKIP_S", "REDUCE_SMOOTH_S", "REDUCE_SPEED_FRACTION", "REDUCE_STATIC_WINDOW_S",
            "REDUCE_TARE_GAP_S", "REDUCE_TARE_S"]

# --- Control that meets hardware (exofric.control pneumatic plant, scheduling; exofric.hardware;
#     issue 17). Valve and volume values are typical of a 1/8" proportional regulator and 1 m of
#     4 mm hose: assumptions for the simulated plant, not measurements. -------------------------

#: Default supply pressure (gauge) in MPa: the top of the paper's tested range.
PNEU_SUPPLY_MPA: Final = 0.6
#: Default sonic conductance C of the fill and vent ports in dm^3/(s bar) (a small 1/8"
#: valve; an assumption, not a measurement).
PNEU_C_DM3_PER_S_BAR: Final = 0.05
#: Default critical pressure ratio b (unitless; typical of small valves).
PNEU_CRITICAL_RATIO: Final = 0.3
#: Pressure ratio above which the ISO 6358 subsonic law is replaced by a linear (laminar)
#: law to zero flow at ratio 1, continuous at the ratio (unitless; removes the infinite
#: slope dm/dp at equal pressures, as ISO 6358-3's laminar range; Simscape uses 0.999).
PNEU_LAMINAR_RATIO: Final = 0.999
#: Default line (hose + fittings + regulator outlet) volume in mm^3 (1 m of 4 mm ID hose).
PNEU_LINE_VOLUME_MM3: Final = 12566.0
#: Default tube cavity volume in mm^3: pi 4.97^2 / 4 x 116 mm (the base-group tube at P = 0).
PNEU_TUBE_VOLUME_MM3: Final = 2250.4
#: Default proportional band of the regulator in MPa (pressure error for a full opening).
PNEU_PROPORTIONAL_BAND_MPA: Final = 0.02
#: Relative tolerance (unitless) of the plant's ODE integrator.
PNEU_RTOL: Final = 1e-7
#: Absolute tolerance (MPa) of the plant's ODE integrator.
PNEU_ATOL_MPA: Final = 1e-8
#: Default slope floor as a fraction of the reference slope (unitless): scheduled gains are at
#: most 1/0.1 = 10 x the nominal gains (below contact onset, where dF/dP = 0).
SCHEDULE_FLOOR_RATIO: Final = 0.1
#: Default backlash half-width of the hysteretic plant in the comparison, MPa (10 kPa: the
#: up/down branches differ by about 2 x 0.01 x 471 = 9.4 N at the paper's 54.4 N target).
SCHEDULE_COMPARE_HYSTERESIS_MPA: Final = 0.01
#: Connect timeout in s for Modbus TCP (an unreachable host fails after this).
DEVICE_CONNECT_TIMEOUT_S: Final = 2.0
#: Per-request read/write timeout in s (Modbus and serial; ``?timeout=`` in the URL).
DEVICE_IO_TIMEOUT_S: Final = 0.25
#: Default serial and Modbus RTU baud rate in bit/s.
DEVICE_BAUD: Final = 115200
#: Device-side watchdog the host sets at open, in ms: the firmware vents when no command
#: arrives for this long (host crashed or unplugged).
DEVICE_WATCHDOG_MS: Final = 1000
#: Default pressure limit in MPa: commands are clipped to it.
LOOP_MAX_PRESSURE_MPA: Final = 0.6
#: Default trip pressure as a multiple (unitless) of the pressure limit (measured above it: vent,
#: stop).
LOOP_TRIP_PRESSURE_FACTOR: Final = 1.1
#: Default force limit in N (set-points above it are refused; measured above it trips).
LOOP_MAX_FORCE_N: Final = 250.0
#: Watchdog in s: a sensor that repeats its value (or fails to answer) this long vents the
#: tube and stops the loop (exit 4).
LOOP_WATCHDOG_S: Final = 0.5

__all__ += ["DEVICE_BAUD", "DEVICE_CONNECT_TIMEOUT_S", "DEVICE_IO_TIMEOUT_S",
            "DEVICE_WATCHDOG_MS", "LOOP_MAX_FORCE_N", "LOOP_MAX_PRESSURE_MPA",
            "LOOP_TRIP_PRESSURE_FACTOR", "LOOP_WATCHDOG_S", "PNEU_ATOL_MPA",
            "PNEU_CRITICAL_RATIO", "PNEU_C_DM3_PER_S_BAR", "PNEU_LAMINAR_RATIO",
            "PNEU_LINE_VOLUME_MM3", "PNEU_PROPORTIONAL_BAND_MPA", "PNEU_RTOL",
            "PNEU_SUPPLY_MPA", "PNEU_TUBE_VOLUME_MM3",
            "SCHEDULE_COMPARE_HYSTERESIS_MPA", "SCHEDULE_FLOOR_RATIO"]

# --- Off-centre wire (full squeeze model; issue 19) -------------------------------------------

#: Full model (off-centre wire): stiffness of the spring on the tube's rotation about its own
#: axis, relative to mu B^2 (unitless; N mm per mm depth per rad^2 over MPa mm^2). Its force is
#: zero without gravity; the reported forces do not depend on it (tests/test_squeeze_wire_angle).
ROTATION_SPRING_REL: Final = 1.0

__all__ += ["ROTATION_SPRING_REL"]

# --- Hyperelastic fits (exofric.material.fit_material; issue 31) -----------------------------

#: Stability margin of a fit (relative, in stretch): a fit is kept Drucker-stable (dP/dl > 0)
#: along every measured mode over that mode's data range widened by this fraction: the top
#: stretch x (1 + margin) and, with compression data, the bottom / (1 + margin). 10 % lets a
#: model be used a little past the largest measured stretch.
FIT_STABILITY_MARGIN_REL: Final = 0.10
#: Floor of the tangent dP/dl in the stability constraints, relative to the data's secant
#: modulus max|P| / max|l - 1| (unitless; 1e-3): "stable" means clearly rising, not flat.
FIT_TANGENT_FLOOR_REL: Final = 1e-3
#: Stretches per measured mode at which the stability constraints are first imposed (evenly
#: spaced over the widened range); stretches of a 401-point check that still fall below the floor
#: are added and the fit is repeated (up to 4 times).
FIT_CONSTRAINT_POINTS: Final = 41
#: Ogden fits: local fits started for 1, 2 and 3 terms, from the discrete local minima (then the
#: best points) of the variable-projection cost over a grid of exponent combinations, besides
#: the published Treloar-type starts (40 for three terms, all run at once: Ogden-3 on 1,000
#: points in < 2 s, benchmarks/bench_material_fit.py).
FIT_OGDEN_STARTS: Final[MappingProxyType[int, int]] = MappingProxyType({1: 6, 2: 10, 3: 40})
#: Ogden fits: bound on each |mu_i|, relative to the data's secant modulus max|P| / max|l - 1|
#: (unitless; 100). Larger mu_i come in cancelling pairs of nearly equal exponents: a flat,
#: ill-conditioned direction of the least squares, not a material property; a fit reaching the
#: bound is reported as constrained.
FIT_OGDEN_MU_MAX_REL: Final = 100.0

__all__ += ["FIT_CONSTRAINT_POINTS", "FIT_OGDEN_MU_MAX_REL", "FIT_OGDEN_STARTS",
            "FIT_STABILITY_MARGIN_REL", "FIT_TANGENT_FLOOR_REL"]

# --- Pull-out of the wire through the inflated tube, joint stiffness (issue 39) --------------

#: Axial stiffness EA (N) of the 1.6 mm 7x7 steel cable: an effective modulus of ~110 GPa
#: (stranded rope, below the wire's 200 GPa: the strands' helix) on its metallic area of
#: ~1.2 mm^2 (fill factor ~0.6 of the 2.0 mm^2 circle) gives ~1.3e5 N. An assumption to be
#: replaced by a measured EA of the cable used.
CABLE_EA_N: Final = 1.3e5
#: Stick penalty of the axial friction on the tube-wire and tube-wall arcs (N/mm^3: N per mm of
#: tube per mm of slip per mm of arc), augmented by a Lagrange multiplier (Uzawa) until the
#: sticking nodes' elastic slip is below PULLOUT_CREEP_TOL_MM: the answer does not depend on it.
PULLOUT_STICK_PENALTY_N_PER_MM3: Final = 1e3
#: Largest elastic slip (mm) of a sticking node accepted by the augmented Lagrangian.
PULLOUT_CREEP_TOL_MM: Final = 1e-9
#: Load steps of the per-unit-length pull (to 3x the estimated slip displacement; extended
#: until the wire slides on its whole arc).
PULLOUT_SECTION_STEPS: Final = 40
#: Linear elements of the cable along the tube in the shear lag (count; 0.5 mm over 116 mm).
PULLOUT_Z_ELEMENTS: Final = 232
#: Load steps per displacement amplitude D of the pulled end's path (count).
PULLOUT_PATH_STEPS: Final = 60
#: The wire-wall line contact (rigid steel on rigid aluminium) sticks rigidly; the along-length
#: model regularises it by a stick spring this many times the tube's initial section stiffness
#: (unitless). The reported secant stiffness converges as it grows (tests/test_pullout.py).
PULLOUT_LINE_STICK_REL: Final = 1e3

#: Held end zones (``ends="fixed"``; docs/formulation.md section 12): length of a zone (mm),
#: over which a held face's influence decays. The fittings' rod acts on the section only where
#: the tube slides on the wall, so the zone must hold the whole decay: the secant at 0.1 mm
#: (P / 0.6 MPa)^2 of the 116 mm tube, zone 5 / 10 / 16 / 20 / 24 / 36 mm: 51.25 / 53.09 /
#: 53.66 / 53.74 / 53.77 / 53.76 N/mm (base, 0.2 MPa), 54.03 / 56.69 / 57.79 / 57.99 / 58.10 /
#: 58.15 (test 3, 0.2 MPa), 97.43 / 98.23 / 98.28 / 98.22 / 98.25 / 98.20 (base, 0.6 MPa):
#: 20 mm is within 0.3 % of 36 mm. Tubes of at most two zones are solved as two zones.
PULLOUT_HELD_ZONE_MM: Final = 20.0
#: First element along z at a held face (mm) and the growth of the next ones (unitless).
#: Convergence of the held tubes' secant k1 at 0.1 mm, 0.6 MPa (first / growth 0.25 / 1.5,
#: 0.125 / 1.25, 0.0625 / 1.125, 0.03125 / 1.0625): 14.876, 14.722, 14.690, 14.676 N/mm (5 mm
#: base), 21.242, 21.003, 20.937, 20.915 (10 mm base), 17.506, 17.317, 17.273, 17.260 (5 mm
#: test 3), 37.076, 36.852, 36.786, 36.764 (30 mm base). These defaults (the second level,
#: since session 49) are +0.27 to +0.47 % above the Richardson value of the last three; the
#: first level was +0.87 to +1.61 %; 0.125 / 1.35 would be +0.5 to +0.8 %. The K(P) of the
#: 116 mm tube moves by 0.1-0.2 % and took 30-50 % more CPU (6.3-8.1 s against 4.1-6.7 s), won
#: back by the friction solve's secant predictor (4.2-6.5 s; tests/test_pullout_held_zone.py,
#: benchmarks/bench_pullout.py).
PULLOUT_HELD_DZ_MM: Final = 0.125
#: Growth of the held zone's elements along z away from the held face (unitless; see
#: PULLOUT_HELD_DZ_MM for the convergence study).
PULLOUT_HELD_DZ_GROWTH: Final = 1.25
#: The scalar zone's rod modulus along z over the shear modulus (unitless; ``held_zone=
#: "scalar"``): the laterally free, incompressible rod (E_z = 3 G; E_z = G gives a 15-18 %
#: softer secant on the held tubes).
PULLOUT_EZ_OVER_G: Final = 3.0
#: The held end zones' model (``"vector"`` or ``"scalar"``): the 3-D incremental problem
#: about the squeeze (``simulate/_vector_zone.py``; Mooney-Rivlin and neo-Hookean tubes, the
#: others fall back to the scalar zone) or the axial field alone with E_z = PULLOUT_EZ_OVER_G x G.
#: On the held annulus inflated first (CalculiX) the vector zone is within 1.6 % at every bore
#: stretch 1-1.84, the scalar one -19 to +11 % (docs/formulation.md section 12, "The vector zone").
PULLOUT_HELD_ZONE: Final = "vector"
#: Largest in-plane stretch of the squeeze state (unitless) from which a pull with held ends
#: carries a note that its end zones are stiff in the early slip. With the vector zone, against
#: CalculiX the 5-10 mm held tubes' first secant (k1) is within 3 % at stretches 1.18-1.47
#: (0.2-0.4 MPa: -2.2 to +2.3 %) and +2.3 to +5.0 % at 1.76 (0.6 MPa: +2.8 / +2.3 % on the 5 mm
#: tubes, +5.0 % on the 10 mm one, against 3-D references refined in the plane and at the held
#: faces; the second secant within 3.6 % everywhere; session 49): the note starts between them
#: (docs/formulation.md section 12).
PULLOUT_HELD_STRETCH_NOTE: Final = 1.6
#: The same for the scalar zone (``held_zone="scalar"``): k1 and k2 +0.3..+3.5 % at 1.18,
#: +3.6..+6.3 % at 1.47-1.76 (session 49).
PULLOUT_HELD_STRETCH_NOTE_SCALAR: Final = 1.3
#: The zone's law is solved at displacements PULLOUT_HELD_GRID_MM (k / m)^2 (mm), k = 0, 1, ...,
#: continued to the travel (fixed points: smooth in the coefficients for the calibration).
PULLOUT_HELD_GRID_MM: Final = 2.0

__all__ += ["CABLE_EA_N", "PULLOUT_CREEP_TOL_MM", "PULLOUT_EZ_OVER_G", "PULLOUT_HELD_DZ_GROWTH",
            "PULLOUT_HELD_DZ_MM", "PULLOUT_HELD_GRID_MM", "PULLOUT_HELD_STRETCH_NOTE",
            "PULLOUT_HELD_STRETCH_NOTE_SCALAR", "PULLOUT_HELD_ZONE",
            "PULLOUT_HELD_ZONE_MM",
            "PULLOUT_LINE_STICK_REL", "PULLOUT_PATH_STEPS", "PULLOUT_SECTION_STEPS",
            "PULLOUT_STICK_PENALTY_N_PER_MM3", "PULLOUT_Z_ELEMENTS"]


# --- The paper's two constants that serve as defaults ----------------------------------------
#: Poisson's ratio behind the compressibility d of the paper's Eq 6 (unitless): silicone as
#: nearly incompressible, d = 2 (1 - 2 nu) / mu.
POISSON: Final = 0.498
#: The paper's equivalent friction coefficient gamma (Eq 7, unitless), the default wherever a
#: gamma is needed and none is given; equal to ``exofric.paper.scalar("gamma")``
#: (tests/test_defaults_literals.py).
PAPER_GAMMA: Final = 0.7168

__all__ += ["PAPER_GAMMA", "POISSON"]
