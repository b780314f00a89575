# exofric: two commands on a fresh machine.
#   make demo   set up .venv (if missing) with the runtime dependencies, run the main job
#   make test   add the test and development extras, then the whole test suite
#   make docs   add the docs extra, build the documentation site into docs/_build/html
SHELL  := /bin/bash
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.stamp-install
STAMP_RT := $(VENV)/.stamp-runtime
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1
export MKL_NUM_THREADS ?= 1

.PHONY: demo test setup browser calculix lint bench clean docs

# Two stamps: `make demo` needs only the runtime dependencies; `make test` adds the extras
# (Dask, Parquet, TDMS, Modbus/serial, the report's browser test, FElupe, the dev tools).
$(STAMP_RT): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@echo "exofric: installing the runtime dependencies into $(VENV) (first time: about 30 s)"
	@$(BIN)/python -m pip install -q --disable-pip-version-check --upgrade pip
	set -o pipefail; $(BIN)/python -m pip install --disable-pip-version-check -e . \
	  | { grep -E --line-buffered '^(Collecting|Successfully|ERROR)' || true; }
	@touch $@

$(STAMP): $(STAMP_RT)
	@echo "exofric: installing the test and development extras (first time: about 60 s)"
	set -o pipefail; $(BIN)/python -m pip install --disable-pip-version-check \
	  -e ".[dask,report,bench,dev,tdms,hardware,docs]" \
	  | { grep -E --line-buffered '^(Collecting|Successfully|ERROR)' || true; }
	@touch $@

setup: $(STAMP)

# Debian's Chromium for the report's browser test (skipped with a reason if it cannot be had).
browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null) \
	      || echo "warning: could not install chromium; the browser test will be skipped"; \
	  else echo "warning: chromium not installed and cannot apt-get; the browser test will be skipped"; fi; }

# CalculiX (ccx) for benchmarks/bench_peers.py (its rows are skipped if it cannot be had).
calculix:
	@command -v ccx >/dev/null 2>&1 || { \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq calculix-ccx >/dev/null) \
	      || echo "warning: could not install calculix-ccx; the CalculiX benchmark rows will be skipped"; \
	  else echo "warning: ccx not installed and cannot apt-get; the CalculiX benchmark rows will be skipped"; fi; }

demo: $(STAMP_RT)
	$(BIN)/exofric reproduce --out exofric-report
	@echo "report: $(CURDIR)/exofric-report/report.html"

test: setup browser calculix
	$(BIN)/lint-imports --no-cache
	$(BIN)/python -m pytest -q -n 2 --durations=15 tests src/exofric --doctest-modules

lint: setup
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/mypy src
	$(BIN)/lint-imports --no-cache

bench: setup calculix
	$(BIN)/python benchmarks/run.py
	# the cross-checks too slow for the test suite (Ogden-3 on the shipped silicone curves)
	EXOFRIC_FULL=1 $(BIN)/python -m pytest -q -p no:cacheprovider tests/test_material_real_data.py -k ogden

# The documentation site (Sphinx): warnings are errors, references to exofric's names checked
# (nitpicky), the examples executed by sphinx-gallery; offline (docs/conf.py). -E re-reads every
# page so that no warning hides in an unchanged one; unchanged examples are not re-run.
DOCS_STAMP := $(VENV)/.stamp-docs
$(DOCS_STAMP): $(STAMP_RT)
	@echo "exofric: installing the docs extra (Sphinx, numpydoc, MyST, sphinx-gallery, furo)"
	set -o pipefail; $(BIN)/python -m pip install --disable-pip-version-check -e ".[docs]" \
	  | { grep -E --line-buffered '^(Collecting|Successfully|ERROR)' || true; }
	@touch $@

docs: $(DOCS_STAMP)
	MPLBACKEND=Agg $(BIN)/sphinx-build -E -W --keep-going -n -q -b html docs docs/_build/html
	@echo "docs: $(CURDIR)/docs/_build/html/index.html"

clean:
	rm -rf $(VENV) exofric-report .pytest_cache .mypy_cache .ruff_cache docs/_build docs/auto_examples
