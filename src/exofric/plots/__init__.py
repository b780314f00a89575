"""Every picture exofric draws: the only package that imports matplotlib.

Each function takes computed results (and an optional matplotlib ``Axes``) and returns the Axes
or Figure it drew on; :func:`save` writes a figure to a file. Library code never selects a
backend: the CLI selects a non-interactive one once at start-up.

Units: as the axes say (mm, N, MPa, s, Nm).

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> from exofric.plots import draw_section
"""

from exofric.plots._design import map_axes, plot_design_map
from exofric.plots._fe import draw_section, plot_inflation, plot_squeeze, save, section_polygons
from exofric.plots._friction import plot_gamma_fit, plot_predictions

__all__ = [
    "draw_section", "map_axes", "plot_design_map", "plot_gamma_fit", "plot_inflation",
    "plot_predictions", "plot_squeeze", "save", "section_polygons",
]
