"""Every picture exofric draws: the only package that imports matplotlib.

Each function takes computed results (read through their attributes, so this package sits
below every computing stage) and an optional matplotlib ``ax`` -- or ``fig``, an empty Figure,
when it needs several Axes -- and returns the Axes or Figure it drew on (a new pyplot figure
when none is given). Nothing here writes files except :func:`save`, and nothing selects a
backend: the CLI sets ``MPLBACKEND=Agg`` once at start-up. The result objects' ``.plot()``
methods delegate here.

* FE: :func:`plot_squeeze` (Figs 6-7), :func:`plot_squeeze_force` (Fig 7),
  :func:`plot_contact_pressure` (pressure and friction along the contact arcs),
  :func:`plot_squeeze_curves`, :func:`plot_inflation`, :func:`plot_inflation_curve`,
  :func:`draw_section`, :func:`section_polygons`.
* Calibration: :func:`plot_calibration` (Fig 5b), :func:`plot_table1`,
  :func:`plot_material_calibration` (joint material calibration: data vs model, misfit profile).
* Friction: :func:`plot_gamma_fit` (Fig 4), :func:`plot_predictions` (Figs 8-10),
  :func:`plot_cubic_fit` (Fig 11), :func:`plot_torque`, :func:`plot_interface_fit` (the
  two-interface law against the pooled gamma).
* Raw rig logs: :func:`plot_reduction` (plateaus, pulls and averaging windows).
* Pull-out: :func:`plot_pullout`, :func:`plot_joint_stiffness`, :func:`plot_pullout_fit`
  (measured against fitted pulls, with residuals).
* Control: :func:`plot_simulation`, :func:`plot_control_cases` (Fig 12).
* Design: :func:`plot_design_map`, :func:`map_axes`.
* Materials: :func:`plot_material_fit` (hyperelastic fit per test mode, with residuals).

Units: as the axes say (mm, N, MPa, s, Nm).

Examples
--------
>>> from exofric.friction import fit_gamma
>>> from exofric.plots import plot_gamma_fit, save
>>> fit = fit_gamma([0.2, 0.4, 0.6], [70.0, 140.0, 193.0], [0.2, 0.4, 0.6],
...                 [100.0, 200.0, 268.55])
>>> fig = plot_gamma_fit(fit, "three points")
>>> len(fig.axes)
3
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.plots._calibrate import (
        plot_calibration,
        plot_material_calibration,
        plot_table1,
    )
    from exofric.plots._common import save
    from exofric.plots._control import plot_control_cases, plot_simulation
    from exofric.plots._design import map_axes, plot_design_map
    from exofric.plots._fe import (
        draw_section,
        plot_contact_pressure,
        plot_inflation,
        plot_inflation_curve,
        plot_squeeze,
        plot_squeeze_curves,
        plot_squeeze_force,
        plot_tube_ends,
        section_polygons,
    )
    from exofric.plots._friction import (
        plot_cubic_fit,
        plot_gamma_fit,
        plot_predictions,
        plot_torque,
    )
    from exofric.plots._gait import plot_gait, plot_gait_compare
    from exofric.plots._interfaces import plot_interface_fit
    from exofric.plots._material import plot_material_fit
    from exofric.plots._pullfit import plot_pullout_fit
    from exofric.plots._pullout import plot_joint_stiffness, plot_pullout
    from exofric.plots._rig import plot_reduction
    from exofric.plots._ring import plot_ring_test


# Lazy facade (PEP 562): ``save`` or one figure does not load every plotting module; each name is
# loaded from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
