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
# folder (harp_analysis.paths.FIGURES_DIR). `make figures FIG=4.11` runs only its notebook.
figures: $(STAMP)
	HARP_ANALYSIS_FIGURES_DIR="$(CURDIR)/figures" $(BIN)/python -m harp_analysis.build \
		$(if $(FIG),--figure $(FIG))

# Style (ruff), types (mypy) and the package's layers (import-linter, contracts in pyproject.toml).
lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports

# Notebooks under test save their figures to a scratch folder, never over the committed ones.
# The figures they draw are then compared with the committed ones, to an image tolerance.
test: lint
	scratch="$$(mktemp -d)" && \
	HARP_ANALYSIS_FIGURES_DIR="$$scratch" $(BIN)/python -m pytest -n 2 tests --nbmake notebooks && \
	HARP_ANALYSIS_REGENERATED_FIGURES="$$scratch" $(BIN)/python -m pytest -q tests/test_figure_images.py

benchmark: $(STAMP)
	$(BIN)/python benchmarks/bench_atmosphere.py
	$(BIN)/python benchmarks/bench_trajectories.py
	$(BIN)/python benchmarks/bench_mks.py
	$(BIN)/python benchmarks/bench_mlt.py

clean-venv:
	rm -rf $(VENV)
