"""The real-time control loop on the simulated device: the code path `exofric control run` drives.

Run: ``python examples/hardware_loop_sim.py`` (about 2 s; it writes hardware_loop_sim.png).
The device is ``sim://?speed=0``: the paper's plant and friction map in process, on simulated
time (speed 0: as fast as the CPU goes); a Modbus or serial rig takes the same calls with its
URL. Units: s, MPa, N.
"""

# %%
# 1. A PI loop with the model feedforward, tuned by the rule for the paper's plant: the
# controller object that `control run` builds from its flags.
from exofric.control import Controller
from exofric.hardware import SafetyLimits, open_device, run_loop
from exofric.reproduction import ControlSetup

TARGET_N = 54.4                                   # the paper's Fig 12 target (N)
setup = ControlSetup.default()
controller = Controller(setup.tuning("pi").gains, u_max=setup.plant.p_max_mpa,
                        feedforward=setup.make_feedforward())

# %%
# 2. Ten seconds at 100 Hz on the simulated rig, inside the safety limits (pressure, friction,
# a watchdog on stale sensors); the loop vents the tube at the end.
with open_device("sim://?speed=0") as device:
    result = run_loop(device, controller, TARGET_N, duration_s=10.0, rate_hz=100.0,
                      limits=SafetyLimits())
m = result.metrics
print(f"{result.cycles} cycles at {result.achieved_rate_hz:.0f} Hz: settled in "
      f"{m.settling_time_s:.2f} s (paper Fig 12, PI + model: 4.20 s), steady-state error "
      f"{m.steady_state_error_n:.3f} N, vented {result.vented}")

# %%
# 3. The log the loop wrote: time, pressure, friction, set-point, command and its PID and
# feedforward terms, timing jitter.
frame = result.to_frame()
print(frame.head(3).to_string(index=False))

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    from exofric.plots import save

    fig, (ax_f, ax_p) = plt.subplots(2, 1, figsize=(6.4, 5.0), sharex=True)
    t = frame["time_s"]
    for c in ("setpoint_n", "force_n"):
        ax_f.plot(t, frame[c], label=c)
    for c in ("command_mpa", "ff_mpa", "pressure_mpa"):
        ax_p.plot(t, frame[c], label=c)
    ax_f.set_ylabel("friction (N)")
    ax_p.set_ylabel("pressure (MPa)")
    ax_p.set_xlabel("time (s)")
    for ax in (ax_f, ax_p):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    print("wrote", save(fig, "hardware_loop_sim.png"))
