"""The friction-control experiment of paper §5 (Fig 12): one case, and the six side by side.

A *case* is one controller (PD, PI or PID) with or without the model feedforward, on a
:class:`ControlSetup` (plant, friction model, target, sample time). Gains come from the
IMC/SIMC rule of :mod:`exofric.control` for the loop linearised at the target (or are
given), and are the same with and without the model, as in the paper. The true plant's
friction map is the model's times (1 + mismatch).

Units: friction N, pressure MPa, time s.

Examples
--------
>>> from exofric.reproduction import ControlSetup, run_case
>>> r = run_case(ControlSetup.default(), "pi", feedforward=True)
>>> round(r.metrics.steady_state_error_n, 3) + 0.0
0.0
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Literal, Protocol

from exofric import paper
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.control import (
    CONTROLLERS,
    AntiWindup,
    Controller,
    CubicFrictionMap,
    ModelFeedforward,
    PIDGains,
    PlantParams,
    SimulationResult,
    StepMetrics,
    TuningResult,
    local_slope,
    rule_gains,
    simulate,
    step_metrics,
)
from exofric.errors import InputError, check_positive, check_range

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["FrictionMapLike", "ControlSetup", "CaseResult", "CompareResult", "run_case",
           "compare", "PAPER_SETTLING_S"]

#: The paper's settling times in s (Section 5, Fig 12): (controller, with model) -> s.
PAPER_SETTLING_S: dict[tuple[str, bool], float | None] = {
    ("pd", False): None,    # steady-state error: never settles to the target
    ("pd", True): paper.scalar("settling_pd_model_s"),
    ("pi", False): paper.scalar("settling_pi_s"),
    ("pi", True): paper.scalar("settling_pi_model_s"),
    ("pid", False): paper.scalar("settling_pid_s"),
    ("pid", True): paper.scalar("settling_pid_model_s"),
}


class FrictionMapLike(Protocol):
    """A friction map F(P) (MPa -> N) with an inverse P(F) and a scaled copy.

    Calling it evaluates F (N) at pressures in MPa. :class:`~exofric.control.CubicFrictionMap`
    (Eq 9) and :class:`~exofric.control.CurveFrictionMap` (an FE curve times gamma) satisfy it.

    Examples
    --------
    >>> m = ControlSetup.default().model_map        # Eq 9: 0.7168 x Eq 8
    >>> round(float(m(0.4)), 2), round(m.inverse(54.40), 4), round(float(m.scaled(2.0)(0.4)), 2)
    (108.98, 0.2926, 217.97)
    """

    def __call__(self, pressure_mpa: Any) -> Any: ...

    def inverse(self, friction_n: float) -> float:
        """The pressure (MPa) at which the map gives ``friction_n``.

        Parameters
        ----------
        friction_n : float
            Friction (N) within the map's range.

        Returns
        -------
        float
            Pressure (MPa); implementations raise :class:`~exofric.errors.InputError` when
            ``friction_n`` is out of reach.
        """

    def scaled(self, factor: float) -> Any:
        """A copy whose friction is ``factor`` times this map's (model mismatch).

        Parameters
        ----------
        factor : float
            Multiplier of the friction (unitless, > 0), e.g. 1 + mismatch.

        Returns
        -------
        FrictionMapLike
        """

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description of the map (coefficients in N, MPa)."""


@checked_init
@dataclass(frozen=True)
class ControlSetup:
    """Everything a Fig 12 case needs besides the controller choice.

    Parameters
    ----------
    plant : PlantParams
        Supply, sensor and mismatch (true gamma = (1 + mismatch) model gamma).
    model_map : FrictionMapLike
        The friction model F(P) (e.g. Eq 9) used for the feedforward and the tuning.
    target_n : float
        Step target in N (paper: 54.40 N).
    dt, duration_s : float
        Sample time and simulated horizon in s.
    ff_mode : {'2dof', 'static'}
        How the model feedforward is combined with the feedback (see
        :class:`~exofric.control.ModelFeedforward`).
    tau_c_s : float or None
        Closed-loop time constant of the tuning rule in s (default tau + theta).
    band : float
        Settling band (fraction of the step, default 0.02).
    antiwindup : str
        Anti-windup scheme of the controllers.
    plant_source : str
        Where the plant's numbers come from, for :meth:`plant_description` (e.g.
        ``"identified from step.csv"``).

    Examples
    --------
    >>> s = ControlSetup.default(duration_s=2.0)    # test 5, Eq 9, default plant
    >>> s.target_n, s.dt, round(s.feedforward_pressure(), 4)    # N, s, MPa
    (54.4, 0.01, 0.2926)
    >>> s.tuning("pi").gains.kd
    0.0
    """

    plant: PlantParams
    model_map: FrictionMapLike
    target_n: float = 54.40
    dt: float = 0.01
    duration_s: float = 15.0
    ff_mode: Literal["2dof", "static"] = "2dof"
    tau_c_s: float | None = None
    band: float = 0.02
    antiwindup: AntiWindup = "back-calculation"
    plant_source: str = "exofric's default (an assumption)"

    def __post_init__(self) -> None:
        check_positive("target_n (target friction)", self.target_n, "N")
        check_range("dt (sample time)", self.dt, 1e-5, 1.0, unit="s")
        check_range("duration_s", self.duration_s, 10 * self.dt, 1e4, unit="s")
        if self.ff_mode not in ("2dof", "static"):
            raise InputError(f"ff_mode must be 2dof or static, got {self.ff_mode!r}")

    @classmethod
    def default(cls, **changes: Any) -> ControlSetup:
        """The test-5 structure with Eq 9 (gamma 0.7168) and the default plant.

        Parameters
        ----------
        **changes
            Fields to replace (e.g. ``target_n=40.0`` in N, ``duration_s=5.0`` in s,
            ``plant=PlantParams(mismatch=0.1)``, ``model_map=...``).

        Returns
        -------
        ControlSetup

        Examples
        --------
        >>> ControlSetup.default(target_n=40.0).target_n
        40.0
        """
        from exofric.friction import CubicFit

        g = CubicFrictionMap(CubicFit(paper.eq8(), *paper.load()["eq8"]["fit_range_mpa"]),
                             paper.scalar("gamma"))
        return replace(cls(PlantParams(), g), **changes)

    def plant_description(self) -> str:
        """The simulated plant in words: which model, its numbers and where they came from.

        Printed beside every settling time, so that times from different plants (this
        lag + dead time; the physical pneumatic plant of ``control run --device sim://``) are
        not compared unknowingly.

        Examples
        --------
        >>> ControlSetup.default().plant_description()[:60]
        'simulated supply, lag + dead time: gain 1 MPa/MPa, lag 0.8 s'
        """
        pp = self.plant
        kind = "on/off valves by PWM" if pp.pwm_period_s > 0 else "lag + dead time"
        return (f"simulated supply, {kind}: gain {pp.gain:.4g} MPa/MPa, lag "
                f"{pp.time_constant_s:.4g} s, dead time {pp.delay_s:.4g} s, {self.plant_source};"
                " `control run --device sim://` uses the physical pneumatic plant instead, so "
                "its times differ")

    @property
    def true_map(self) -> FrictionMapLike:
        """The plant's friction map: model x (1 + mismatch)."""
        m = self.plant.mismatch
        return self.model_map if m == 0.0 else self.model_map.scaled(1.0 + m)

    def feedforward_pressure(self) -> float:
        """P_ff = g^-1(target) in MPa from the model (InputError if unreachable)."""
        return float(self.model_map.inverse(self.target_n))

    def tuning(self, controller: str) -> TuningResult:
        """Rule gains for the loop linearised at the target (model map, plant lag/delay).

        Parameters
        ----------
        controller : {'pd', 'pi', 'pid'}
            Controller structure.

        Returns
        -------
        TuningResult
            IMC/SIMC gains (kp MPa/N, ki MPa/(N s), kd MPa s/N) for the local slope
            dF/dP (N/MPa) at the feedforward pressure.
        """
        p_ff = self.feedforward_pressure()
        slope = local_slope(self.model_map, p_ff) * self.plant.gain
        return rule_gains(controller, slope, self.plant.time_constant_s, self.plant.delay_s,
                          tau_c_s=self.tau_c_s)

    def make_feedforward(self) -> ModelFeedforward:
        """The model feedforward (2-DOF with the plant's lag/delay, or static)."""
        p = self.plant
        if self.ff_mode == "static":
            return ModelFeedforward(self.model_map.inverse, gain=p.gain, p_max_mpa=p.p_max_mpa)
        return ModelFeedforward(self.model_map.inverse, self.model_map,
                                time_constant_s=p.time_constant_s, delay_s=p.delay_s,
                                gain=p.gain, p_max_mpa=p.p_max_mpa)


@checked_init
@dataclass(frozen=True)
class CaseResult(DisplayMixin):
    """One closed-loop step response and its metrics (N, MPa, s).

    Attributes
    ----------
    controller : str
        ``'pd'``, ``'pi'`` or ``'pid'``.
    feedforward : bool
        Whether the model feedforward was used.
    ff_mode : str
        The setup's feedforward mode (``'2dof'`` or ``'static'``).
    tuning : TuningResult
        The gains used (kp MPa/N, ki MPa/(N s), kd MPa s/N) and how they were obtained.
    metrics : StepMetrics
        Settling and rise times (s), overshoot (%), steady-state error (N).
    final_pressure_mpa : float
        Mean pressure over the last 5% of the horizon (MPa).
    feedforward_pressure_mpa : float or None
        P_ff = g^-1(target) (MPa), None without feedforward.
    mismatch : float
        Plant-model friction mismatch (fraction, unitless): true map = model x (1 + mismatch).
    paper_settling_time_s : float or None
        The paper's settling time for this case (s, Fig 12), None where it prints none.
    simulation : SimulationResult
        The trajectories (s, N, MPa).

    Examples
    --------
    >>> r = run_case(ControlSetup.default(duration_s=2.0), "pi", feedforward=True)
    >>> r.controller, r.feedforward, r.ff_mode, round(r.feedforward_pressure_mpa, 4)
    ('pi', True, '2dof', 0.2926)
    """

    controller: str
    feedforward: bool
    ff_mode: str
    tuning: TuningResult
    metrics: StepMetrics
    final_pressure_mpa: float
    feedforward_pressure_mpa: float | None
    mismatch: float
    paper_settling_time_s: float | None
    simulation: SimulationResult = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no trajectories): the CLI's ``exofric control --json``."""
        m = self.metrics.to_dict()
        return {
            "controller": self.controller,
            "feedforward": self.feedforward,
            "ff_mode": self.ff_mode if self.feedforward else None,
            "settling_time_s": m["settling_time_s"],
            "rise_time_s": m["rise_time_s"],
            "overshoot_pct": m["overshoot_pct"],
            "steady_state_error_n": m["steady_state_error_n"],
            "steady_state_error_pct": 100.0 * self.metrics.steady_state_error_n
            / self.metrics.target_friction_n,
            "final_friction_n": m["final_friction_n"],
            "final_pressure_mpa": self.final_pressure_mpa,
            "target_friction_n": m["target_friction_n"],
            "settling_band_pct": m["settling_band_pct"],
            "feedforward_pressure_mpa": self.feedforward_pressure_mpa,
            "mismatch": self.mismatch,
            "gains": self.tuning.gains.to_dict(),
            "tuning": self.tuning.to_dict(),
            "paper_settling_time_s": self.paper_settling_time_s,
        }

    def to_frame(self) -> pd.DataFrame:
        """The step response as a DataFrame: one row per time sample (s, N, MPa).

        The columns of :meth:`exofric.control.SimulationResult.to_frame` (``time_s``,
        ``setpoint_n``, ``friction_n``, ``measured_friction_n``, ``command_mpa``,
        ``pressure_mpa``).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> r = run_case(ControlSetup.default(duration_s=2.0), "pi", feedforward=True)
        >>> df = r.to_frame()
        >>> len(df), float(df["time_s"].iloc[-1])
        (201, 2.0)
        """
        return self.simulation.to_frame()

    def plot(self, fig: Any | None = None) -> Any:
        """Draw the step response: friction (N) and pressure (MPa) against time (s).

        :func:`exofric.plots.plot_control_cases` with this case alone (target and settling
        band, the paper's settling time in the title); write the figure with
        :func:`exofric.plots.save`.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on (default a new one).

        Returns
        -------
        matplotlib Figure

        Examples
        --------
        >>> r = run_case(ControlSetup.default(duration_s=2.0), "pi", feedforward=True)
        >>> len(r.plot().axes)      # friction above, pressure below
        2
        """
        from exofric.plots import plot_control_cases

        return plot_control_cases([self], fig,
                                  title=f"target {self.metrics.target_friction_n:g} N")


def run_case(
    setup: ControlSetup,
    controller: str,
    *,
    feedforward: bool,
    gains: PIDGains | None = None,
) -> CaseResult:
    """Simulate one Fig 12 case: ``controller`` ('pd', 'pi', 'pid') with/without the model.

    Parameters
    ----------
    setup : ControlSetup
    controller : {'pd', 'pi', 'pid'}
    feedforward : bool
        Add the model feedforward P_ff = g^-1(target).
    gains : PIDGains or None
        Override the rule's gains (kp MPa/N, ki MPa/(N s), kd MPa s/N).

    Returns
    -------
    CaseResult

    Examples
    --------
    >>> r = run_case(ControlSetup.default(duration_s=2.0), "pid", feedforward=False)
    >>> r.paper_settling_time_s, r.metrics.settling_time_s   # s; 2 s is too short to settle
    (6.17, None)
    """
    kind = controller.lower()
    if kind not in CONTROLLERS:
        raise InputError(f"controller must be one of {', '.join(CONTROLLERS)}, got {controller!r}")
    tuning = setup.tuning(kind)
    if gains is not None:
        tuning = replace(tuning, gains=gains, method="given")
    ff = setup.make_feedforward() if feedforward else None
    c = Controller(tuning.gains, u_max=setup.plant.p_max_mpa, antiwindup=setup.antiwindup,
                   feedforward=ff)
    sim = simulate(c, setup.plant, setup.true_map, setup.target_n,
                   duration_s=setup.duration_s, dt=setup.dt)
    met = step_metrics(sim.time_s, sim.friction_n, setup.target_n, band=setup.band)
    tail = sim.pressure_mpa[sim.time_s >= sim.time_s[-1] - 0.05 * setup.duration_s]
    return CaseResult(kind, bool(feedforward), setup.ff_mode, tuning, met, float(tail.mean()),
                      setup.feedforward_pressure() if feedforward else None,
                      setup.plant.mismatch, PAPER_SETTLING_S.get((kind, bool(feedforward))),
                      sim)


@checked_init
@dataclass(frozen=True)
class CompareResult(DisplayMixin):
    """The six Fig 12 cases and the settling-time reductions (ours and the paper's, %).

    Attributes
    ----------
    cases : tuple of CaseResult
        PD, PI, PID, each without then with the model feedforward.
    target_n : float
        Step target friction (N).
    mismatch : float
        Plant-model friction mismatch (fraction, unitless).
    ff_mode : str
        Feedforward mode (``'2dof'`` or ``'static'``).

    Examples
    --------
    >>> c = compare(ControlSetup.default())
    >>> [(k.controller, k.feedforward) for k in c.cases][:2], c.target_n
    ([('pd', False), ('pd', True)], 54.4)
    >>> round(c.reduction_pct("pi"), 1)                     # %; the paper prints 26
    32.7
    """

    cases: tuple[CaseResult, ...]
    target_n: float
    mismatch: float
    ff_mode: str

    def reduction_pct(self, controller: str) -> float | None:
        """Settling-time reduction with the model, in % of the time without (None if n/a).

        Parameters
        ----------
        controller : {'pd', 'pi', 'pid'}
            Controller whose two cases are compared.

        Returns
        -------
        float or None
            100 (t_without - t_with) / t_without (%), None when either case does not
            settle or the controller was not run.
        """
        by = {(c.controller, c.feedforward): c.metrics.settling_time_s for c in self.cases}
        t0, t1 = by.get((controller, False)), by.get((controller, True))
        if t0 is None or t1 is None or t0 <= 0:
            return None
        return 100.0 * (t0 - t1) / t0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``cases`` (each as :meth:`CaseResult.to_dict`) and the reductions."""
        red = {k: self.reduction_pct(k) for k in ("pi", "pid")}
        paper_red = {"pi": paper.scalar("settling_reduction_pi_pct"),
                     "pid": paper.scalar("settling_reduction_pid_pct")}
        return {
            "target_friction_n": self.target_n,
            "mismatch": self.mismatch,
            "ff_mode": self.ff_mode,
            "cases": [c.to_dict() for c in self.cases],
            "settling_reduction_pct": red,
            "paper_settling_reduction_pct": paper_red,
        }

    def to_frame(self) -> pd.DataFrame:
        """Every case's step response in one DataFrame: one row per case and time sample.

        Columns ``controller``, ``feedforward`` (bool), then those of
        :meth:`CaseResult.to_frame` (s, N, MPa).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> c = compare(ControlSetup.default(duration_s=2.0))
        >>> c.to_frame().groupby(["controller", "feedforward"]).size().tolist()
        [201, 201, 201, 201, 201, 201]
        """
        import pandas as pd

        frames = []
        for c in self.cases:
            f = c.to_frame()
            f.insert(0, "feedforward", c.feedforward)
            f.insert(0, "controller", c.controller)
            frames.append(f)
        return pd.concat(frames, ignore_index=True)

    def plot(self, fig: Any | None = None, *, pressure: bool = True) -> Any:
        """Draw Fig 12: friction (and pressure) against time, one column per controller.

        :func:`exofric.plots.plot_control_cases` (red without, blue with the model; the
        paper's settling times in the titles); write the figure with
        :func:`exofric.plots.save`.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            Empty figure to draw on (default a new one).
        pressure : bool
            Add the pressure row under the friction row.

        Returns
        -------
        matplotlib Figure

        Examples
        --------
        >>> c = compare(ControlSetup.default(duration_s=2.0))
        >>> len(c.plot(pressure=False).axes)
        3
        """
        from exofric.plots import plot_control_cases

        return plot_control_cases(self.cases, fig, title=f"target {self.target_n:g} N",
                                  pressure=pressure)


def compare(setup: ControlSetup) -> CompareResult:
    """Run PD, PI and PID, each without and with the model (Fig 12c-e).

    Parameters
    ----------
    setup : ControlSetup
        Plant, friction model, target (N), sample time and horizon (s).

    Returns
    -------
    CompareResult

    Examples
    --------
    >>> c = compare(ControlSetup.default(duration_s=2.0))
    >>> len(c.cases), sorted({k.controller for k in c.cases})
    (6, ['pd', 'pi', 'pid'])
    """
    cases = tuple(run_case(setup, k, feedforward=ff) for k in CONTROLLERS for ff in (False, True))
    return CompareResult(cases, setup.target_n, setup.plant.mismatch, setup.ff_mode)
