"""A small design sweep and the search for a structure that reaches a target torque.

Which hole, tube and wire reach a given joint torque at an allowed pressure? A sweep solves
the squeeze problem for every combination of a few diameters and stores N(P) per design;
:func:`exofric.search_designs` then ranks the designs against the target. This script sweeps
four designs in a plain serial loop (no Dask), with a coarse mesh, into a temporary directory.
For real sweeps, write the same table to a TOML file (see ``sweep-small.toml``) and run
``exofric sweep FILE --out DIR``, which spreads the designs over all CPUs and caches them.

Run it from the repository root::

    python examples/small_sweep.py           # writes small_sweep.png here

Units: mm, MPa, N, Nm; arm radius in m.
"""

# %%
# The sweep definition
# --------------------
#
# ``ef.parse_sweep`` takes the same table as a sweep TOML file. ``[grid]`` is a Cartesian
# product over hole D, tube outer diameter d1 and wire d2 (mm); sizes left out take the base
# group's, and the tube ID keeps the base wall-to-diameter ratio (ID = 4.97 d1 / 8.3 mm). The
# ``[solver]`` mesh of 1 x 12 elements (instead of the default 2 x 24) keeps the example fast;
# it changes N at 0.6 MPa by about 0.1 % for the base group. gamma = 0.7168 (unitless) and the
# arm radius R = 0.10 m turn N into friction F = gamma N (N) and torque T = F R (Nm).

import tempfile

import exofric as ef

sweep_table = {
    "name": "example",
    "pressures_mpa": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
    "gamma": 0.7168,
    "arm_radius_m": 0.10,
    "grid": {"hole_mm": [10.0], "tube_od_mm": [8.3, 8.8], "wire_mm": [1.1, 1.6]},
    "solver": {"n_radial": 1, "n_circ": 12},
}
spec = ef.parse_sweep(sweep_table)

# %%
# Impossible designs are kept, not solved
# ---------------------------------------
#
# An 8.8 mm tube and a 1.6 mm wire do not fit in a 10 mm hole (8.8 + 1.6 > 10). The spec keeps
# that design with the reason, so the results say why it is missing.

skipped = {d.name: d.skip_reason for d in spec.designs if d.skipped}

# %%
# Running the sweep
# -----------------
#
# ``ef.run_sweep(spec, out, serial=True)`` solves the designs one after another in this
# process and writes one Parquet file per design into ``out`` (here a temporary directory,
# removed afterwards); running it again on the same directory reuses the finished designs.
# ``run.frame`` is a pandas DataFrame with one row per design and pressure: the sizes, N(P) in
# ``squeeze_force_n`` (N), friction (N), torque (Nm), the deviation from the base (%) and the
# solver's diagnostics.

with tempfile.TemporaryDirectory(prefix="exofric-sweep-") as out_dir:
    run = ef.run_sweep(spec, out_dir, serial=True)
frame = run.frame
solved = frame[frame["status"] == "ok"]
n_at_0_6_mpa_n = {
    name: float(rows.loc[rows["pressure_mpa"] == 0.6, "squeeze_force_n"].iloc[0])
    for name, rows in solved.groupby("name")
}

# %%
# Searching the designs
# ---------------------
#
# A target of 15 Nm on R = 0.10 m needs F = 150 N, i.e. N = 150 / 0.7168 = 209 N.
# ``search_designs`` finds, for each design, the pressure at which N(P) (interpolated
# monotonically between the swept pressures) reaches it, keeps those that do by
# ``pmax_mpa`` = 0.6 MPa and ranks them by least required pressure. The wide tube with the thin
# wire needs the least pressure but is 54 % away from a proportional resize of the base,
# outside the region where the paper validated the model; ``validated_only=True`` restricts
# the ranking to validated designs and returns the base group itself.

target_torque_nm = 15.0
search = ef.search_designs(frame, target_torque_nm, 0.10, 0.6)
best = search.best
best_validated = ef.search_designs(frame, target_torque_nm, 0.10, 0.6, validated_only=True).best
required_pressure_mpa = {
    r["name"]: r["required_pressure_mpa"] for r in search.table.to_dict("records")
}

print(f"{run.summary.computed} designs solved, {run.summary.skipped} skipped in "
      f"{run.summary.wall_time_s:.1f} s")
for name, reason in skipped.items():
    print(f"  skipped {name}: {reason}")
for name, n in n_at_0_6_mpa_n.items():
    print(f"  {name}: N(0.6 MPa) = {n:6.1f} N, T(0.6 MPa) = {0.1 * 0.7168 * n:5.2f} Nm")
if best:
    print(f"target {target_torque_nm:g} Nm: best {best['name']} at "
          f"{best['required_pressure_mpa']:.3f} MPa")
if best_validated:
    print(f"best validated: {best_validated['name']} at "
          f"{best_validated['required_pressure_mpa']:.3f} MPa")

# %%
# Figure
# ------
#
# ``exofric.plots.plot_design_map`` draws the torque at 0.6 MPa over the two varying design
# dimensions (red edge: outside the validated region; cross: impossible; star: best design).

if __name__ == "__main__":
    from exofric.plots import plot_design_map, save

    ax = plot_design_map(search, skipped=frame[frame["status"] == "skipped"])  # titled by it
    print("wrote", save(ax, "small_sweep.png"))
