"""``exofric control``: friction force control by inflation pressure (paper §5, Fig 12).

``exofric control`` simulates one case (PD/PI/PID, with or without the model feedforward);
``exofric control compare`` the six cases of Fig 12 beside the paper's settling times;
``exofric control identify STEP.csv`` fits the supply's lag and dead time to a step response.
Units: friction N, pressure MPa, time s; gains kp MPa/N, ki MPa/(N s), kd MPa s/N.
Plant TOMLs, squeeze curves and step CSVs are read by :mod:`exofric.io`.
"""

from __future__ import annotations

import typer

from exofric.cli.control import compare, identify, run, simulate
from exofric.cli.control._shared import _COMMON_HELP


def register(app: typer.Typer) -> None:
    """Add the ``control`` command group to ``app``: one module per command."""
    ctl = typer.Typer(help="Friction force control by inflation pressure (paper Section 5, "
                      "Fig 12): PD/PI/PID with and without the model feedforward. "
                      + _COMMON_HELP, no_args_is_help=False)
    for command in (simulate, compare, identify, run):
        command.register(ctl)
    app.add_typer(ctl, name="control")
