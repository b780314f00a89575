"""Sweep definitions: a parsed TOML table -> a validated :class:`SweepSpec` and its designs.

Units: mm (sizes), MPa (pressures), Shore A (hardness), m (arm radius), N, Nm.

A sweep lists designs in three ways, combined in one file (see ``examples/sweep-*.toml``):

* ``[grid]`` / ``[[grid]]``: the Cartesian product of lists over ``hole_mm`` (D),
  ``tube_od_mm`` (d1), ``tube_id_mm`` *or* ``wall_mm`` (tube wall thickness), ``wire_mm``
  (d2), ``shore`` and ``length_mm``; a key left out takes the base value. Without
  ``tube_id_mm``/``wall_mm`` the inner diameter keeps the base wall-to-diameter ratio,
  ID = ID_base d1 / d1_base (as for the paper's Table 3 in :mod:`exofric.friction`).
* ``[[family]]``: a proportional family scaled from the base: ``scale`` factors multiply the
  diameters listed in ``scaled`` (default all four); ``wire_choices_mm`` snaps d2 to the
  nearest available steel cable, as the paper had to (Sec. 4, first group).
* ``[[design]]``: explicit designs (listed first, so their names win over duplicates).

A design that cannot exist (tube and wire do not fit in the hole, ID >= OD, a hardness
outside the correlation's range) is kept with ``skip_reason`` (the :class:`InputError`
message naming the dimensions) and is never solved. Identical designs are kept once.

Each design carries ``key``: a SHA-256 of its solve inputs (sizes, Shore, material options,
pressures, solver settings, exofric version). Gamma, F0 and the arm radius only post-process
N(P), so changing them reuses cached solves.
"""

from __future__ import annotations

import hashlib
import itertools
import json
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np

from exofric import defaults
from exofric._validate import checked_init
from exofric._version import __version__
from exofric.errors import InputError, check_positive, check_pressures, check_range
from exofric.fe import MeshSpec, NewtonSettings
from exofric.geometry import BASE, Structure
from exofric.material import MooneyRivlin

__all__ = ["SolverSpec", "MaterialSpec", "Design", "SweepSpec", "parse_sweep", "design_key"]

#: Largest number of designs one sweep file may expand to.
MAX_DESIGNS = 100_000
#: Designs sizes are rounded to this many decimals of a mm (1 nm) so keys are stable.
SIZE_DECIMALS = 6
_DIMS = ("hole_mm", "tube_od_mm", "tube_id_mm", "wire_mm")
_AXES = ("hole_mm", "tube_od_mm", "tube_id_mm", "wall_mm", "wire_mm", "shore", "length_mm")
_SHORT = {"hole_mm": "D", "tube_od_mm": "d1", "tube_id_mm": "ID", "wall_mm": "t", "wire_mm": "d2",
          "shore": "S", "length_mm": "L"}


@checked_init
@dataclass(frozen=True)
class SolverSpec:
    """Squeeze solver settings for every design (see :func:`exofric.simulate.squeeze`).

    Mesh ``n_radial`` x ``n_circ`` quad9 graded ``grading``:1 toward the wire; contact
    penalty (N/mm^3); tube density of the self-weight regulariser (t/mm^3); largest pressure
    sub-step (MPa); Newton iterations per sub-step before a cut-back.

    Attributes
    ----------
    n_radial, n_circ : int
        Elements through the wall and around the half tube.
    grading : float
        Ratio of the largest to the smallest circumferential element, finest toward the
        wire (unitless, >= 1).
    penalty_n_per_mm3 : float
        Contact penalty stiffness (N/mm^3).
    density_t_per_mm3 : float
        Tube density of the self-weight regulariser (t/mm^3).
    max_step_mpa : float
        Largest pressure sub-step of the load path (MPa).
    max_iter : int
        Newton iterations per sub-step before the step is cut back.
    gravity : {'none', 'toward-wall', 'toward-wire'}
        The tube's weight (see :func:`exofric.simulate.squeeze`); default none.

    Examples
    --------
    >>> s = SolverSpec(n_radial=1, n_circ=12, grading=6.0)     # a coarse mesh for a quick look
    >>> s.mesh().n_circ, s.to_dict()["max_step_mpa"] == s.newton().max_step
    (12, True)
    """

    n_radial: int = defaults.SQUEEZE_MESH["n_radial"]
    n_circ: int = defaults.SQUEEZE_MESH["n_circ"]
    grading: float = defaults.SQUEEZE_MESH["grading"]
    penalty_n_per_mm3: float = defaults.CONTACT_PENALTY_N_PER_MM3
    density_t_per_mm3: float = defaults.SILICONE_DENSITY_T_PER_MM3
    max_step_mpa: float = defaults.SQUEEZE_NEWTON["max_step"]
    max_iter: int = defaults.SQUEEZE_NEWTON["max_iter"]
    gravity: str = defaults.GRAVITY

    def mesh(self) -> MeshSpec:
        """The :class:`MeshSpec` of the half tube."""
        return MeshSpec(self.n_radial, self.n_circ, grading=self.grading)

    def newton(self) -> NewtonSettings:
        """The :class:`NewtonSettings` of the load path."""
        return NewtonSettings(max_step=self.max_step_mpa, max_iter=self.max_iter)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (units in the keys)."""
        return asdict(self)


@checked_init
@dataclass(frozen=True)
class MaterialSpec:
    """How a design's Shore A hardness becomes a Mooney-Rivlin material (paper Eqs 3-6).

    Attributes
    ----------
    correlation : str
        Shore-to-modulus correlation of :meth:`~exofric.material.MooneyRivlin.from_shore`:
        ``'paper'`` (Eq 3), ``'gent'``, ``'qi'`` or ``'astm-log10'``.
    c01_ratio : float
        C01 / C10 (the paper's 0.05).
    poisson : float
        Poisson's ratio that sets the compressibility d (the paper's 0.498).

    Examples
    --------
    >>> m = MaterialSpec().material(62.5)                    # Table 2's hardness
    >>> round(m.c10_mpa, 4), round(m.c01_mpa / m.c10_mpa, 2)            # MPa, unitless
    (0.6354, 0.05)
    """

    correlation: str = "paper"
    c01_ratio: float = 0.05
    poisson: float = defaults.POISSON

    def material(self, shore: float) -> MooneyRivlin:
        """:meth:`MooneyRivlin.from_shore` with these options (constants in MPa, 1/MPa).

        Parameters
        ----------
        shore : float
            Hardness (Shore A), within the correlation's range.

        Returns
        -------
        MooneyRivlin
        """
        return MooneyRivlin.from_shore(shore, self.correlation, self.c01_ratio, self.poisson)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return asdict(self)


@checked_init
@dataclass(frozen=True)
class Design:
    """One point of the design space (sizes in mm, hardness in Shore A).

    Attributes
    ----------
    index : int
        Position in the sweep's design list.
    name : str
        Label (e.g. ``"d2=1.6"`` for a grid point, ``"family x1.2"``).
    family : str
        Grid or family it came from ('' for an unlabelled explicit design).
    hole_mm, tube_od_mm, tube_id_mm, wire_mm : float
        Hole diameter D, tube outer diameter d1 and inner diameter, wire diameter d2 (mm).
    length_mm : float
        Tube length (mm).
    shore : float
        Tube hardness (Shore A).
    key : str
        Cache key, :func:`design_key` ('' until :func:`parse_sweep` sets it).
    skip_reason : str
        Why the design cannot exist ('' for a possible design).

    Examples
    --------
    >>> d = Design(0, "base", "", 10.0, 8.3, 4.97, 1.6, 116.0, 62.5)
    >>> d.skipped, d.structure().hole_mm
    (False, 10.0)
    """

    index: int
    name: str
    family: str
    hole_mm: float
    tube_od_mm: float
    tube_id_mm: float
    wire_mm: float
    length_mm: float
    shore: float
    key: str = ""
    skip_reason: str = ""

    @property
    def skipped(self) -> bool:
        """True for a design that cannot exist (see ``skip_reason``)."""
        return bool(self.skip_reason)

    def structure(self) -> Structure:
        """The :class:`Structure` (raises :class:`InputError` for an impossible design)."""
        return Structure(self.hole_mm, self.tube_od_mm, self.tube_id_mm, self.wire_mm,
                         self.length_mm, self.name)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (mm, Shore A)."""
        return asdict(self)


@checked_init
@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: designs, pressures (MPa), friction post-processing, solver.

    Attributes
    ----------
    name : str
        Sweep name.
    pressures_mpa : tuple of float
        Increasing squeeze pressures (MPa) solved for every design.
    designs : tuple of Design
        Every design, impossible ones included (with ``skip_reason``).
    gamma, f0_n, arm_radius_m : float
        Friction model F = gamma N + F0 (gamma unitless, F0 in N) and lever arm (m) for the
        torque T = F R (Nm).
    base, base_shore : Structure, float
        Reference design for deviations and proportional families (mm, Shore A).
    threshold_pct : float
        Deviation (%) up to which the friction model was validated (paper: 20 %).
    material : MaterialSpec
        How each design's hardness becomes a material.
    solver : SolverSpec
        Mesh and solver settings of every squeeze.

    Examples
    --------
    >>> spec = parse_sweep({"name": "wires", "pressures_mpa": [0.3, 0.6],
    ...                     "grid": {"wire_mm": [1.4, 1.6, 2.0]}})
    >>> spec.name, spec.pressures_mpa, len(spec.runnable), len(spec.skipped)
    ('wires', (0.3, 0.6), 2, 1)
    """

    name: str
    pressures_mpa: tuple[float, ...]
    designs: tuple[Design, ...]
    gamma: float = defaults.PAPER_GAMMA
    f0_n: float = 0.0
    arm_radius_m: float = 0.10
    threshold_pct: float = 20.0
    base: Structure = BASE
    base_shore: float = 62.5
    material: MaterialSpec = MaterialSpec()
    solver: SolverSpec = SolverSpec()

    @property
    def runnable(self) -> tuple[Design, ...]:
        """Designs to solve (not skipped)."""
        return tuple(d for d in self.designs if not d.skipped)

    @property
    def skipped(self) -> tuple[Design, ...]:
        """Impossible designs, with their reasons."""
        return tuple(d for d in self.designs if d.skipped)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (designs as a list)."""
        return {
            "name": self.name, "pressures_mpa": list(self.pressures_mpa), "gamma": self.gamma,
            "f0_n": self.f0_n, "arm_radius_m": self.arm_radius_m,
            "threshold_pct": self.threshold_pct, "base": self.base.to_dict(),
            "base_shore": self.base_shore, "material": self.material.to_dict(),
            "solver": self.solver.to_dict(), "designs": [d.to_dict() for d in self.designs],
        }


def design_key(design: Design, spec_inputs: Mapping[str, Any]) -> str:
    """SHA-256 (hex) of a design's solve inputs plus ``spec_inputs`` (pressures, solver...).

    Name, family and index are labels and do not enter the key.

    Parameters
    ----------
    design : Design
        Its sizes (mm), length (mm) and hardness (Shore A) enter the key.
    spec_inputs : mapping
        The sweep-wide solve inputs (JSON-serialisable): :func:`parse_sweep` passes the
        pressures (MPa), material and solver settings, exofric version and schema.

    Returns
    -------
    str
        64 hexadecimal characters.

    Examples
    --------
    >>> from dataclasses import replace
    >>> d = Design(0, "base", "", 10.0, 8.3, 4.97, 1.6, 116.0, 62.5)
    >>> k = design_key(d, {"pressures_mpa": [0.3, 0.6]})
    >>> len(k), k == design_key(replace(d, name="other"), {"pressures_mpa": [0.3, 0.6]})
    (64, True)
    >>> k == design_key(d, {"pressures_mpa": [0.6]})
    False
    """
    payload = {k: getattr(design, k) for k in (*_DIMS, "length_mm", "shore")}
    payload.update(spec_inputs)
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()


# ----------------------------------------------------------------------------- parsing

_TOP = {"name", "description", "pressures_mpa", "gamma", "f0_n", "arm_radius_m",
        "threshold_pct", "base", "material", "solver", "grid", "family", "design"}


def _table(data: Mapping[str, Any], key: str) -> Mapping[str, Any]:
    v = data.get(key, {})
    if not isinstance(v, Mapping):
        raise InputError(f"sweep file: [{key}] must be a table")
    return v


def _tables(data: Mapping[str, Any], key: str) -> list[Mapping[str, Any]]:
    v = data.get(key, [])
    v = [v] if isinstance(v, Mapping) else v
    if not isinstance(v, list) or not all(isinstance(t, Mapping) for t in v):
        raise InputError(f"sweep file: [[{key}]] must be a list of tables")
    return v


def _known(where: str, table: Mapping[str, Any], allowed: Sequence[str]) -> None:
    extra = set(table) - set(allowed)
    if extra:
        raise InputError(f"sweep file: {where} has unknown key {sorted(extra)[0]!r} "
                         f"(allowed: {', '.join(sorted(allowed))})")


def _num(where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(f"sweep file: {where} must be a number, got {value!r}")
    return float(value)


def _values(where: str, value: Any) -> list[float]:
    vals = value if isinstance(value, list) else [value]
    if not vals:
        raise InputError(f"sweep file: {where} must list at least one number")
    return [_num(where, v) for v in vals]


def _base(t: Mapping[str, Any]) -> tuple[Structure, float]:
    _known("[base]", t, (*_DIMS, "length_mm", "shore", "name"))
    vals = {k: _num(f"[base] {k}", t[k]) for k in (*_DIMS, "length_mm", "shore") if k in t}
    b = Structure(vals.get("hole_mm", BASE.hole_mm), vals.get("tube_od_mm", BASE.tube_od_mm),
                  vals.get("tube_id_mm", BASE.tube_id_mm), vals.get("wire_mm", BASE.wire_mm),
                  vals.get("length_mm", BASE.length_mm), str(t.get("name", "base")))
    shore = check_range("[base] shore", vals.get("shore", 62.5), 0.0, 100.0,
                        lo_open=True, hi_open=True, unit="Shore A")
    return b, shore


def _solver(t: Mapping[str, Any]) -> SolverSpec:
    names = {"n_radial": int, "n_circ": int, "grading": float, "penalty_n_per_mm3": float,
             "density_t_per_mm3": float, "max_step_mpa": float, "max_iter": int}
    _known("[solver]", t, (*names, "gravity"))
    kw: dict[str, Any] = {}
    if "gravity" in t:
        g = str(t["gravity"])
        if g not in ("none", "toward-wall", "toward-wire"):
            raise InputError(f"sweep file: [solver] gravity must be none, toward-wall or "
                             f"toward-wire, got {g!r}")
        kw["gravity"] = g
    for k, typ in names.items():
        if k in t:
            v = _num(f"[solver] {k}", t[k])
            if typ is int and (v != int(v) or v < 1):
                raise InputError(f"sweep file: [solver] {k} must be an integer >= 1, got {v:g}")
            kw[k] = int(v) if typ is int else check_positive(f"[solver] {k}", v)
    return SolverSpec(**kw)


def _material(t: Mapping[str, Any]) -> MaterialSpec:
    _known("[material]", t, ("correlation", "c01_ratio", "poisson"))
    m = MaterialSpec(str(t.get("correlation", "paper")),
                     _num("[material] c01_ratio", t.get("c01_ratio", 0.05)),
                     _num("[material] poisson", t.get("poisson", defaults.POISSON)))
    m.material(62.5)  # validates the options once (InputError names the bad one)
    return m


def _inner(row: Mapping[str, float], base: Structure, where: str) -> float:
    if "tube_id_mm" in row and "wall_mm" in row:
        raise InputError(f"sweep file: {where} gives both tube_id_mm and wall_mm; use one")
    d1 = row["tube_od_mm"]
    if "wall_mm" in row:
        return d1 - 2.0 * row["wall_mm"]
    return row.get("tube_id_mm", base.tube_id_mm * d1 / base.tube_od_mm)


def _make(name: str, family: str, row: Mapping[str, float], base: Structure,
          base_shore: float, where: str) -> Design:
    full = {"hole_mm": base.hole_mm, "tube_od_mm": base.tube_od_mm, "wire_mm": base.wire_mm,
            "length_mm": base.length_mm, "shore": base_shore, **row}
    full["tube_id_mm"] = _inner(full, base, where)
    r = {k: round(float(full[k]), SIZE_DECIMALS) for k in (*_DIMS, "length_mm", "shore")}
    return Design(0, name, family, r["hole_mm"], r["tube_od_mm"], r["tube_id_mm"],
                  r["wire_mm"], r["length_mm"], r["shore"])


def _grid(i: int, t: Mapping[str, Any], base: Structure, shore: float) -> list[Design]:
    where = f"[[grid]] {i + 1}"
    _known(where, t, (*_AXES, "family"))
    axes = {k: _values(f"{where} {k}", t[k]) for k in _AXES if k in t}
    fam = str(t.get("family", f"grid {i + 1}"))
    out = []
    for combo in itertools.product(*axes.values()):
        row = dict(zip(axes, combo, strict=True))
        label = " ".join(f"{_SHORT[k]}={v:g}" for k, v in row.items())
        out.append(_make(label or "base", fam, row, base, shore, where))
    return out


def _family(i: int, t: Mapping[str, Any], base: Structure, shore: float) -> list[Design]:
    where = f"[[family]] {i + 1}"
    _known(where, t, ("name", "scale", "scaled", "wire_choices_mm", "shore"))
    if "scale" not in t:
        raise InputError(f"sweep file: {where} needs 'scale' (list of factors, e.g. [0.8, 1.2])")
    scales = [check_positive(f"{where} scale", s) for s in _values(f"{where} scale", t["scale"])]
    scaled = t.get("scaled", list(_DIMS))
    if not isinstance(scaled, list) or not set(scaled) <= set(_DIMS) or not scaled:
        raise InputError(f"sweep file: {where} scaled must list some of {', '.join(_DIMS)}")
    choices = _values(f"{where} wire_choices_mm", t["wire_choices_mm"]) \
        if "wire_choices_mm" in t else []
    shores = _values(f"{where} shore", t["shore"]) if "shore" in t else [shore]
    fam = str(t.get("name", f"family {i + 1}"))
    out = []
    for s, sh in itertools.product(scales, shores):
        row = {k: getattr(base, k) * (s if k in scaled else 1.0) for k in _DIMS}
        if choices:
            row["wire_mm"] = min(choices, key=lambda c: (abs(c - row["wire_mm"]), c))
        row["shore"] = sh
        label = f"{fam} x{s:g}" + (f" S{sh:g}" if len(shores) > 1 else "")
        out.append(_make(label, fam, row, base, shore, where))
    return out


def _explicit(i: int, t: Mapping[str, Any], base: Structure, shore: float) -> Design:
    where = f"[[design]] {i + 1}"
    _known(where, t, (*_AXES, "name", "family"))
    row = {k: _num(f"{where} {k}", t[k]) for k in _AXES if k in t}
    return _make(str(t.get("name", f"design {i + 1}")), str(t.get("family", "")),
                 row, base, shore, where)


def _check(d: Design, material: MaterialSpec) -> str:
    """Empty string for a design that can exist, else the one-line reason."""
    try:
        d.structure()
        material.material(d.shore)
    except InputError as exc:
        return str(exc)
    return ""


def parse_sweep(data: Mapping[str, Any], *, name: str = "sweep") -> SweepSpec:
    """Validate a parsed sweep TOML table and expand its designs.

    Parameters
    ----------
    data : mapping
        The TOML content (see the module docstring and ``examples/sweep-small.toml``).
    name : str
        Sweep name when ``data`` has none.

    Returns
    -------
    SweepSpec
        Designs in the order explicit designs, grids, families; a design equal to an
        earlier one (same key) is dropped, the earlier name kept;
        impossible ones with ``skip_reason``, each with its cache ``key``.

    Raises
    ------
    InputError
        Unknown keys, non-numeric values, bad pressures, no designs, too many designs.

    Examples
    --------
    >>> spec = parse_sweep({"pressures_mpa": [0.3, 0.6],
    ...                     "grid": {"wire_mm": [1.6, 2.0]}})
    >>> [(d.wire_mm, d.skipped) for d in spec.designs]
    [(1.6, False), (2.0, True)]
    """
    _known("the top level", data, tuple(_TOP))
    if "pressures_mpa" not in data:
        raise InputError("sweep file: needs pressures_mpa (list of increasing pressures, MPa)")
    p = check_pressures("pressures_mpa", _values("pressures_mpa", data["pressures_mpa"]),
                        max_mpa=2.0)
    base, base_shore = _base(_table(data, "base"))
    material = _material(_table(data, "material"))
    solver = _solver(_table(data, "solver"))
    designs = [_explicit(i, t, base, base_shore) for i, t in enumerate(_tables(data, "design"))]
    for i, t in enumerate(_tables(data, "grid")):
        designs += _grid(i, t, base, base_shore)
        if len(designs) > MAX_DESIGNS:
            raise InputError(f"sweep file: more than {MAX_DESIGNS} designs; split the sweep")
    for i, t in enumerate(_tables(data, "family")):
        designs += _family(i, t, base, base_shore)
    if not designs:
        raise InputError("sweep file: defines no designs (add [grid], [[family]] or [[design]])")
    if len(designs) > MAX_DESIGNS:
        raise InputError(f"sweep file: more than {MAX_DESIGNS} designs; split the sweep")
    inputs = {"pressures_mpa": [float(x) for x in p], "material": material.to_dict(),
              "solver": solver.to_dict(), "exofric": __version__, "schema": 1}
    seen: set[str] = set()
    out: list[Design] = []
    for d in designs:
        key = design_key(d, inputs)
        if key in seen:
            continue
        seen.add(key)
        out.append(replace(d, index=len(out), key=key, skip_reason=_check(d, material)))
    return SweepSpec(
        name=str(data.get("name", name)),
        pressures_mpa=tuple(float(x) for x in np.asarray(p)),
        designs=tuple(out),
        gamma=check_positive("gamma", _num("gamma", data.get("gamma", defaults.PAPER_GAMMA))),
        f0_n=_num("f0_n", data.get("f0_n", 0.0)),
        arm_radius_m=check_positive("arm_radius_m", _num("arm_radius_m",
                                                         data.get("arm_radius_m", 0.10)), "m"),
        threshold_pct=check_positive("threshold_pct", _num("threshold_pct",
                                                           data.get("threshold_pct", 20.0)), "%"),
        base=base, base_shore=base_shore, material=material, solver=solver,
    )
