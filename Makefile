# Two commands (see README.md): `make figures` regenerates every figure, `make test` runs every
# test and executes every notebook. Both build the virtual environment first if it is missing.

PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: figures test benchmark clean-venv

$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r environment.txt
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps \
		--no-build-isolation --editable .
	touch $@

figures: $(STAMP)
	$(BIN)/python -m harp_analysis.build

# Notebooks under test save their figures to a scratch folder, never over the committed ones.
test: $(STAMP)
	HARP_ANALYSIS_FIGURES_DIR="$$(mktemp -d)" $(BIN)/python -m pytest -n 2 tests --nbmake notebooks

benchmark: $(STAMP)
	$(BIN)/python benchmarks/bench_atmosphere.py
	$(BIN)/python benchmarks/bench_trajectories.py
	$(BIN)/python benchmarks/bench_mks.py
	$(BIN)/python benchmarks/bench_mlt.py

clean-venv:
	rm -rf $(VENV)
