"""Options and helpers shared by the ``control`` commands (one owner)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import typer

from exofric.cli._common import (
    save_figure,
)
from exofric.cli._options import OptionGroup

if TYPE_CHECKING:
    from exofric.reproduction import CaseResult, ControlSetup


_COMMON_HELP = "Units: N, MPa, s."


def _stuck_note(case: dict[str, Any], target_n: float) -> str:
    """Why a case ends far from its target at zero friction (e.g. PD without the model)."""
    f, p = case.get("final_friction_n"), case.get("final_pressure_mpa")
    if f is None or p is None or abs(f) > 0.01 * abs(target_n):
        return ""
    name = f"{case.get('controller', '').upper()}{' + model' if case.get('feedforward') else ''}"
    return (f"{name}: the pressure settles at {p:.3f} MPa, where the friction map gives "
            f"{f:.2f} N: below contact onset the friction does not respond to pressure, and "
            "without integral action the loop never reaches contact. Add the model "
            "(--feedforward) or use PI/PID.")


def _opt(default: Any, help_: str) -> Any:
    return typer.Option(default, help=help_)


# Options shared by the default action and `compare` (declared once, used twice).
TARGET = _opt(54.40, "Target friction in N (paper: 54.40 N).")
STRUCTURE = _opt("test5", "Friction map: 'test5' (Eq 9) or a JSON file from "
                 "`exofric squeeze --json` (pressure_mpa, squeeze_force_n).")
GAMMA = _opt(None, "Equivalent coefficient gamma of the model (default: the paper's 0.7168).")
PLANT = _opt(None, "Plant TOML file with a plant table (see data/examples/plant-default.toml).")
STEP_CSV = _opt(None, "Step-response CSV (time_s, pressure_mpa[, command_mpa]): use the "
                "identified gain, lag and delay.")
MISMATCH = _opt(None, "Model mismatch: true gamma = (1 + mismatch) x model gamma, in (-0.9, 10).")
TAU_C = _opt(None, "Closed-loop time constant of the IMC/SIMC rule in s (default tau + theta).")
FF_MODE = _opt("2dof", "Feedforward structure: 2dof (feedback on the deviation from the "
               "model-predicted friction) or static (P_ff added to the PID output).")
ANTIWINDUP = _opt("back-calculation", "Anti-windup: back-calculation, clamping or none.")
DT = _opt(None, "Sample time in s (default 0.01 s, or the plant's PWM period).")
DURATION = _opt(15.0, "Simulated time in s.")
BAND = _opt(2.0, "Settling band in % of the step.")
PLOT = _opt(None, "Write a PNG plot of the response(s) to this path.")


class LoopOptions(OptionGroup):
    """The simulated loop of ``control`` and ``control compare``: target friction (N), friction
    map, gamma, plant (TOML, step CSV, mismatch), tau_c (s), feedforward structure,
    anti-windup, sample time and duration (s), settling band (%)."""

    target_friction: float
    structure: str
    gamma: float | None
    plant: str | None
    step_csv: str | None
    mismatch: float | None
    tau_c: float | None
    ff_mode: str
    antiwindup: str
    dt: float | None
    duration: float
    band: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "target_friction": TARGET, "structure": STRUCTURE, "gamma": GAMMA, "plant": PLANT,
        "step_csv": STEP_CSV, "mismatch": MISMATCH, "tau_c": TAU_C, "ff_mode": FF_MODE,
        "antiwindup": ANTIWINDUP, "dt": DT, "duration": DURATION, "band": BAND}

    def setup(self) -> ControlSetup:
        """The checked :class:`~exofric.reproduction.ControlSetup` of these options."""
        return _setup(self.target_friction, self.structure, self.gamma, self.plant,
                      self.step_csv, self.mismatch, self.tau_c, self.ff_mode, self.antiwindup,
                      self.dt, self.duration, self.band)


def _plant_from_file(path: str) -> dict[str, Any]:
    from exofric.errors import InputError
    from exofric.io import read_toml

    p = Path(path)
    if not p.is_file():
        raise InputError(f"--plant {path}: file not found")
    try:
        data = read_toml(p)
    except InputError as exc:
        raise InputError(f"--plant {exc}") from None
    extra = sorted(set(data) - {"plant"})
    if extra:
        raise InputError(f"--plant {p.name}: unknown table(s) {', '.join(extra)}; expected [plant]")
    table = data.get("plant", {})
    if not isinstance(table, dict):
        raise InputError(f"--plant {p.name}: [plant] must be a table")
    return dict(table)


def _structure_map(structure: str, gamma: float) -> Any:
    from exofric import paper
    from exofric.control import CubicFrictionMap, CurveFrictionMap
    from exofric.errors import InputError
    from exofric.friction import CubicFit
    from exofric.io import read_squeeze_curve

    if structure.lower() == "test5":
        lo, hi = paper.load()["eq8"]["fit_range_mpa"]
        return CubicFrictionMap(CubicFit(paper.eq8(), lo, hi), gamma)
    p = Path(structure)
    if not p.is_file():
        raise InputError(f"--structure must be 'test5' or an existing JSON file, got {structure!r}")
    try:
        curve = read_squeeze_curve(p)
    except InputError as exc:
        raise InputError(f"--structure {exc}") from None
    pres = tuple(float(v) for v in curve["pressure_mpa"])
    force = tuple(float(v) for v in curve["squeeze_force_n"])
    return CurveFrictionMap(pres, force, gamma)


def _identify_csv(path: str, columns: str | None = None) -> Any:
    from exofric.control import identify_step
    from exofric.io import parse_column_map, read_step_response

    mapping = (parse_column_map(columns, columns=("time_s", "pressure_mpa", "command_mpa"))
               if columns else None)
    df = read_step_response(path, mapping)
    cmd = df["command_mpa"].to_numpy() if "command_mpa" in df.columns else None
    return identify_step(df["time_s"].to_numpy(), df["pressure_mpa"].to_numpy(), cmd)


def _setup(target: float, structure: str, gamma: float | None, plant: str | None,
           step_csv: str | None, mismatch: float | None, tau_c: float | None, ff_mode: str,
           antiwindup: str, dt: float | None, duration: float, band_pct: float) -> ControlSetup:
    from exofric import paper
    from exofric.control import PlantParams
    from exofric.errors import InputError, check_range
    from exofric.reproduction import ControlSetup

    params = _plant_from_file(plant) if plant else {}
    source = f"from {Path(plant).name}" if plant else "exofric's default (an assumption)"
    if step_csv:
        source = f"identified from {Path(step_csv).name}"
        ident = _identify_csv(step_csv)
        params.update(gain=ident.gain, time_constant_s=ident.time_constant_s,
                      delay_s=ident.delay_s)
    if mismatch is not None:
        params["mismatch"] = mismatch
    pp = PlantParams.from_mapping(params)
    if ff_mode not in ("2dof", "static"):
        raise InputError(f"--ff-mode must be 2dof or static, got {ff_mode!r}")
    if antiwindup not in ("back-calculation", "clamping", "none"):
        raise InputError(f"--antiwindup must be back-calculation, clamping or none, got "
                         f"{antiwindup!r}")
    if dt is None:
        dt = pp.pwm_period_s if pp.pwm_period_s > 0 else 0.01
    band = check_range("--band (settling band, %)", band_pct, 0.0, 50.0, lo_open=True) / 100.0
    g = paper.scalar("gamma") if gamma is None else gamma
    setup = ControlSetup(pp, _structure_map(structure, g), target_n=target, dt=dt,
                         duration_s=duration, ff_mode=ff_mode,  # type: ignore[arg-type]
                         tau_c_s=tau_c, band=band, antiwindup=antiwindup,  # type: ignore[arg-type]
                         plant_source=source)
    p_ff = setup.feedforward_pressure()
    if p_ff > pp.p_max_mpa:
        raise InputError(f"--target-friction {target:g} N needs {p_ff:.3f} MPa, above the plant's "
                         f"p_max_mpa {pp.p_max_mpa:g} MPa")
    return setup


def _plot_cases(cases: list[CaseResult], path: str, title: str) -> str:
    """Write the response plot; return the path written (``out`` -> ``out.png``)."""
    from exofric.plots import plot_control_cases

    return str(save_figure(plot_control_cases(cases, title=title), path))


def _fmt(v: float | None, spec: str) -> str:
    return "-" if v is None else format(v, spec)
