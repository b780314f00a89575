# exofric: two commands on a fresh machine.
#   make demo   set up .venv (if missing) with everything, run the main job
#   make test   same set-up, then the whole test suite
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.stamp-install
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1
export MKL_NUM_THREADS ?= 1

.PHONY: demo test setup browser calculix lint bench clean

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e ".[dask,report,bench,dev,tdms]"
	@touch $(STAMP)

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

demo: setup
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

clean:
	rm -rf $(VENV) exofric-report .pytest_cache .mypy_cache .ruff_cache
