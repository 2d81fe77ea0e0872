# Two commands (see README.md): `make figures` regenerates every figure, `make test` runs every
# test and executes every notebook. Both build the virtual environment first if it is missing.

PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: figures test lint benchmark clean-venv

$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r environment.txt
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps \
		--no-build-isolation --editable .
	touch $@

# Figures go to the committed figures/ only here; notebooks run elsewhere write to a scratch
# folder (harp_analysis.paths.FIGURES_DIR).
figures: $(STAMP)
	HARP_ANALYSIS_FIGURES_DIR="$(CURDIR)/figures" $(BIN)/python -m harp_analysis.build

# Style (ruff), types (mypy) and the package's layers (import-linter, contracts in pyproject.toml).
lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports

# Notebooks under test save their figures to a scratch folder, never over the committed ones.
test: lint
	HARP_ANALYSIS_FIGURES_DIR="$$(mktemp -d)" $(BIN)/python -m pytest -n 2 tests --nbmake notebooks

benchmark: $(STAMP)
	$(BIN)/python benchmarks/bench_atmosphere.py
	$(BIN)/python benchmarks/bench_trajectories.py
	$(BIN)/python benchmarks/bench_mks.py
	$(BIN)/python benchmarks/bench_mlt.py

clean-venv:
	rm -rf $(VENV)
