"""A notebook shows each main result as a table (issue 34): the README's Python tour executed by
nbclient in a real Jupyter kernel, as a researcher runs it.

Each cell's last expression is a result object; Jupyter renders it through ``_repr_html_``
(exofric._display), so every output must carry ``text/html`` with a table that names the
result's quantities with their units; no output may be an error or a screen of raw arrays.
Kernel start and the solves take a few seconds (draft meshes).
"""

from __future__ import annotations

import nbformat
import pytest
from nbclient import NotebookClient

CELLS = {
    "squeeze": ("import exofric as ef\n"
                "mat = ef.MooneyRivlin.from_shore(62.5)\n"
                "res = ef.squeeze(ef.BASE, mat, [0.2, 0.4, 0.6], accuracy='draft')\n"
                "res", "squeeze_force_n"),
    "fit_gamma": ("run = ef.simulate_rig(res.pressure_mpa, res.squeeze_force_n, 0.7168, seed=1)\n"
                  "ef.fit_gamma(run, res)", "gamma"),
    "pullout": ("setup = ef.PulloutSetup(ef.BASE, mat, mu_wire=0.3, mu_wall=0.5,\n"
                "                        mu_wire_wall=0.2, accuracy='draft')\n"
                "setup.section(0.6)", "sliding_force_n_per_mm"),
    "closed_loop": ("from exofric.control import closed_loop\n"
                    "closed_loop(res, target_friction_n=54.4, controller='pi')",
                    "settling_time_s"),
}


@pytest.fixture(scope="module")
def executed() -> dict[str, dict]:
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(src) for src, _ in CELLS.values()]
    NotebookClient(nb, timeout=300, kernel_name="python3", allow_errors=False).execute()
    return {name: cell for name, cell in zip(CELLS, nb.cells, strict=True)}


@pytest.mark.parametrize("name", list(CELLS))
def test_each_main_result_renders_as_a_table_with_units(executed: dict, name: str) -> None:
    outputs = executed[name]["outputs"]
    results = [o for o in outputs if o["output_type"] == "execute_result"]
    assert len(results) == 1, f"{name}: {outputs}"
    html = results[0]["data"].get("text/html", "")
    assert "<table" in html, f"{name}: no HTML table"
    assert CELLS[name][1] in html, f"{name}: {CELLS[name][1]} not shown"
    assert "unit" in html.lower()
    assert len(html) < 20_000, f"{name}: {len(html)} characters (a screen of raw arrays?)"
