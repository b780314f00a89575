"""One call for a closed friction loop: map, tuning, feedforward, simulation and metrics.

:func:`closed_loop` builds what a PI loop otherwise needs nine imports for: the friction map
F(P) from a squeeze result (or a structure, solved here) and gamma, the IMC/SIMC gains at the
target, the model feedforward (2-DOF or static), the FOPDT supply, the simulation and its step
metrics. Units: friction N, pressure MPa, time s; gains kp MPa/N, ki MPa/(N s), kd MPa s/N.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric.errors import InputError

if TYPE_CHECKING:
    import pandas as pd

    from exofric.control._metrics import StepMetrics
    from exofric.control._plant import PlantParams
    from exofric.control._simulate import SimulationResult
    from exofric.control._tuning import TuningResult
    from exofric.material import HyperelasticModel

__all__ = ["ClosedLoopResult", "closed_loop"]

FeedforwardKind = Literal["2dof", "static"]


@checked_init
@dataclass(frozen=True)
class ClosedLoopResult(DisplayMixin):
    """A closed-loop friction step: the gains, the trajectories and their metrics (N, MPa, s).

    Attributes
    ----------
    controller : str
        ``'pd'``, ``'pi'`` or ``'pid'``.
    feedforward : str or None
        ``'2dof'``, ``'static'`` or None (feedback only).
    target_friction_n : float
        The step's target friction (N).
    feedforward_pressure_mpa : float
        P_ff = g^-1(target) from the model map (MPa), also reported without feedforward.
    mismatch : float
        Plant-model mismatch (fraction): the true friction is model x (1 + mismatch).
    tuning : TuningResult
        The gains used and how they were obtained.
    metrics : StepMetrics
        Rise and settling times (s), overshoot (%), steady-state error (N).
    simulation : SimulationResult
        The trajectories (s, N, MPa).

    Examples
    --------
    >>> from exofric.control import CurveFrictionMap, PlantParams, closed_loop
    >>> fmap = CurveFrictionMap((0.0, 0.3, 0.6), (0.0, 150.0, 300.0), 0.5)   # F = 250 P
    >>> r = closed_loop(fmap, 50.0, "pi", plant=PlantParams(delay_s=0.0), duration_s=8.0)
    >>> round(r.feedforward_pressure_mpa, 9), r.to_dict()["overshoot_pct"]
    (0.2, 0.0)
    >>> r.to_frame().columns[:3].tolist()
    ['time_s', 'setpoint_n', 'friction_n']
    """

    controller: str
    feedforward: str | None
    target_friction_n: float
    feedforward_pressure_mpa: float
    mismatch: float
    tuning: TuningResult
    metrics: StepMetrics
    simulation: SimulationResult

    @property
    def settling_time_s(self) -> float | None:
        """Settling time into the band (s), None if the loop never settles."""
        return self.metrics.settling_time_s

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the loop's settings, gains and metrics (no trajectories; see
        :meth:`to_frame`)."""
        return {
            "controller": self.controller,
            "feedforward": self.feedforward,
            "target_friction_n": self.target_friction_n,
            "feedforward_pressure_mpa": self.feedforward_pressure_mpa,
            "mismatch": self.mismatch,
            "settling_time_s": self.metrics.settling_time_s,
            "rise_time_s": self.metrics.rise_time_s,
            "overshoot_pct": self.metrics.overshoot_pct,
            "steady_state_error_n": self.metrics.steady_state_error_n,
            "final_pressure_mpa": float(self.simulation.pressure_mpa[-1]),
            "tuning": self.tuning.to_dict(),
        }

    def to_frame(self) -> pd.DataFrame:
        """The trajectories, one row per sample (s, N, MPa): see
        :meth:`SimulationResult.to_frame`."""
        return self.simulation.to_frame()

    def plot(self, ax: Any | None = None) -> Any:
        """Friction (N) and its set-point against time (s), the settling time in the title.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib Axes
        """
        from exofric.plots import plot_simulation

        ax = plot_simulation(self.simulation, ax)
        ts = self.metrics.settling_time_s
        ff = {None: "feedback only", "2dof": "+ 2-DOF model", "static": "+ static model"}
        ax.set_title(f"{self.controller.upper()} {ff[self.feedforward]}: "
                     + ("never settles" if ts is None else f"settles in {ts:.2f} s"),
                     fontsize=10)
        return ax


def _friction_map(source: Any, gamma: float | None, material: HyperelasticModel | None) -> Any:
    """A friction map F(P) from a map, a squeeze result or curve, or a structure (solved)."""
    from exofric import paper
    from exofric.control._plant import CurveFrictionMap
    from exofric.geometry import Structure

    if callable(getattr(source, "inverse", None)) and callable(source):
        if gamma is not None:
            raise InputError("gamma: the friction map already has its gamma", param="gamma")
        return source
    g = paper.scalar("gamma") if gamma is None else gamma
    if isinstance(source, Structure):
        from exofric.material import MooneyRivlin
        from exofric.simulate import squeeze

        mat = MooneyRivlin.from_shore(paper.table2()["shore"]) if material is None else material
        source = squeeze(source, mat, [round(0.05 * i, 2) for i in range(1, 13)],
                         keep_fields=False)
    elif material is not None:
        raise InputError("material: only with a Structure (a squeeze result has its own)",
                         param="material")
    p = getattr(source, "pressure_mpa", None)
    n = getattr(source, "squeeze_force_n", None)
    if p is None or n is None:
        raise InputError("closed_loop: give a Structure, a squeeze result (pressure_mpa, "
                         f"squeeze_force_n) or a friction map, got {type(source).__name__}",
                         param="source")
    return CurveFrictionMap(tuple(float(v) for v in p), tuple(float(v) for v in n), g)


def closed_loop(
    source: Any,
    target_friction_n: float,
    controller: str = "pi",
    feedforward: FeedforwardKind | None = "2dof",
    *,
    gamma: float | None = None,
    material: HyperelasticModel | None = None,
    plant: PlantParams | None = None,
    duration_s: float = 15.0,
    dt_s: float = 0.01,
) -> ClosedLoopResult:
    """Simulate a friction step in one call: tuned controller, model feedforward, plant.

    The gains come from the IMC/SIMC rule on the model map's slope dF/dP at the target
    (:func:`rule_gains`); the feedforward is the model's inverse, 2-DOF (a reference shaped by
    the plant's lag and delay; the feedback acts on the deviation from it) or static; the plant
    is the FOPDT supply of ``plant`` with the true friction = model x (1 + ``plant.mismatch``).

    Parameters
    ----------
    source : Structure, squeeze result or friction map
        A :class:`~exofric.geometry.Structure` (its N(P) is solved at 0.05-0.6 MPa), anything
        with ``pressure_mpa`` and ``squeeze_force_n`` (a
        :class:`~exofric.simulate.SqueezeResult`, a :class:`~exofric.friction.SqueezeCurve`;
        F = gamma N), or a friction map with ``inverse`` (:class:`CubicFrictionMap`,
        :class:`CurveFrictionMap`).
    target_friction_n : float
        The step's target friction (N).
    controller : {'pi', 'pd', 'pid'}
        Controller structure (default PI).
    feedforward : {'2dof', 'static'} or None
        The model feedforward, or None for feedback only.
    gamma : float, optional
        Equivalent friction coefficient (default the paper's 0.7168); not with a map.
    material : HyperelasticModel, optional
        The tube material when ``source`` is a Structure (default the paper's Shore 62.5).
    plant : PlantParams, optional
        Supply (gain, lag s, dead time s, p_max MPa, mismatch; default :class:`PlantParams`).
    duration_s, dt_s : float
        Simulated time and sample time (s).

    Returns
    -------
    ClosedLoopResult

    Examples
    --------
    >>> from exofric.control import CubicFrictionMap, closed_loop
    >>> from exofric.friction import CubicFit
    >>> from exofric import paper
    >>> lo, hi = paper.load()["eq8"]["fit_range_mpa"]
    >>> fmap = CubicFrictionMap(CubicFit(paper.eq8(), lo, hi), 0.7168)      # Eq 9
    >>> r = closed_loop(fmap, 54.4, "pi")
    >>> round(r.feedforward_pressure_mpa, 4), round(r.settling_time_s, 2)
    (0.2926, 4.08)
    >>> round(closed_loop(fmap, 54.4, "pi", None).settling_time_s, 2)     # feedback only
    6.06
    """
    from exofric.control._metrics import step_metrics
    from exofric.control._pid import Controller, ModelFeedforward
    from exofric.control._plant import PlantParams, local_slope
    from exofric.control._simulate import simulate
    from exofric.control._tuning import CONTROLLERS, rule_gains

    kind = str(controller).lower()
    if kind not in CONTROLLERS:
        raise InputError(f"controller must be one of {', '.join(CONTROLLERS)}, got "
                         f"{controller!r}", param="controller")
    if feedforward not in ("2dof", "static", None):
        raise InputError(f"feedforward must be '2dof', 'static' or None, got {feedforward!r}",
                         param="feedforward")
    pp = PlantParams() if plant is None else plant
    model = _friction_map(source, gamma, material)
    p_ff = float(model.inverse(target_friction_n))
    tuning = rule_gains(kind, local_slope(model, p_ff) * pp.gain, pp.time_constant_s,
                        pp.delay_s)
    ff = None
    if feedforward == "static":
        ff = ModelFeedforward(model.inverse, gain=pp.gain, p_max_mpa=pp.p_max_mpa)
    elif feedforward == "2dof":
        ff = ModelFeedforward(model.inverse, model, time_constant_s=pp.time_constant_s,
                              delay_s=pp.delay_s, gain=pp.gain, p_max_mpa=pp.p_max_mpa)
    ctrl = Controller(tuning.gains, u_max=pp.p_max_mpa, feedforward=ff)
    true_map = model if pp.mismatch == 0.0 else model.scaled(1.0 + pp.mismatch)
    sim = simulate(ctrl, pp, true_map, target_friction_n, duration_s=duration_s, dt=dt_s)
    met = step_metrics(sim.time_s, sim.friction_n, target_friction_n)
    return ClosedLoopResult(kind, feedforward, float(target_friction_n), p_ff, pp.mismatch,
                            tuning, met, sim)
