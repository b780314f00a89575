"""Sphinx configuration of exofric's documentation site.

Build: ``make docs`` (``sphinx-build -W --keep-going -n -b html docs docs/_build/html``).
Warnings are errors, references to exofric's own names are checked (nitpicky), the build runs
offline: intersphinx links to NumPy/SciPy/pandas/matplotlib are made only when the environment
variable ``EXOFRIC_DOCS_INTERSPHINX=1`` is set (it downloads their inventories), never in CI.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import exofric_docs  # noqa: E402

import exofric  # noqa: E402

project = "exofric"
author = "exofric developers"
copyright = "exofric developers, MIT licence"  # noqa: A001
release = exofric.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "exofric_docs",
]
INTERSPHINX = os.environ.get("EXOFRIC_DOCS_INTERSPHINX") == "1"
if INTERSPHINX:  # optional, needs the network: links to the libraries' own docs
    extensions.append("sphinx.ext.intersphinx")
    intersphinx_mapping = {
        "python": ("https://docs.python.org/3", None),
        "numpy": ("https://numpy.org/doc/stable/", None),
        "scipy": ("https://docs.scipy.org/doc/scipy/", None),
        "pandas": ("https://pandas.pydata.org/docs/", None),
        "matplotlib": ("https://matplotlib.org/stable/", None),
    }

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "Thumbs.db", ".DS_Store",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip"]

# --- references: nitpicky for exofric's own names ------------------------------------------
# Every reference to an ``exofric`` name must resolve; references to other libraries' names
# (numpy.ndarray, pandas.DataFrame, Path, ...) are not checked (with intersphinx on, those it
# knows become links).
nitpicky = True
nitpick_ignore_regex = [(r"py:.*", r"(?!exofric\b).*")]

# To be fixed after the merge: references in docstrings of modules that other helpers were
# editing when the site landed (cli, friction, control, material, calibration, geometry,
# simulate, io/_rawlog). Each entry is (role, target); the lead deletes them as the docstrings
# are fixed. Shrink only.
# Internal types that public low-level FE kernels name in their signatures (documented there as
# internal to the solver; not part of the API): the one exception to nitpicky references.
nitpick_ignore: list[tuple[str, str]] = [
    ("py:class", "exofric.fe._hyperelastic.ElementState"),
    # Assembler.factorize's result (a solver's factorisation, used by the Newton solver only)
    ("py:class", "exofric.fe._assembly.Factorization"),
    # SectionPullout.held_ends: the held end zones' law, carried for the length model
    ("py:class", "exofric.simulate._shear_lag.HeldEnds"),
    # SqueezeProblem.refine_direction's switches: the Newton solver's stick/slip predictor
    ("py:class", "exofric.fe._contact.StickSlipModel"),
]

# --- autodoc / numpydoc ----------------------------------------------------------------------
exofric_docs.public_home_modules()
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_typehints_format = "short"
autodoc_preserve_defaults = True
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_attributes_as_param_list = True

# --- MyST (the Markdown pages) ---------------------------------------------------------------
myst_enable_extensions = ["deflist", "colon_fence", "dollarmath"]
myst_heading_anchors = 4  # GitHub-style #section-links inside docs/*.md

# --- sphinx-gallery: examples/*.py executed at build time ------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(HERE.parent / "examples"),
    "gallery_dirs": "auto_examples",
    # every script runs (none needs hardware: the hardware loop uses the simulated device)
    "filename_pattern": r".*\.py$",
    "ignore_pattern": r"__init__\.py$",
    "within_subsection_order": "exofric_docs.PipelineOrder",
    "image_scrapers": ("matplotlib", "exofric_docs.WRITTEN_IMAGES"),
    "reset_modules": ("matplotlib", "exofric_docs.mark_example_start"),
    "download_all_examples": False,
    "write_computation_times": False,
    "show_memory": False,
    "show_signature": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "capture_repr": (),
    "min_reported_time": 1e9,  # no per-example timing line (it changes on every build)
    "abort_on_example_error": False,  # all failures listed at the end; the build still fails
}

# --- HTML ------------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"exofric {release}"
html_static_path = ["_static"]
html_css_files = ["exofric.css"]
html_show_sourcelink = False
html_copy_source = False
html_theme_options = {
    "navigation_with_keys": True,
    "source_repository": "",
}
html_last_updated_fmt = None
