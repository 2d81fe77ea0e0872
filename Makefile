# Two commands (see README.md): `make figures` regenerates every figure, `make test` runs every
# test and executes every notebook. Both build the virtual environment first if it is missing.

PYTHON ?= $(shell command -v python3.11 || command -v python3)

# OpenBLAS picks its kernels by processor, and results that sum through BLAS (scipy's DOP853
# adds its stages with it, numpy's matrix products use it) differ in their last bits from one
# kernel to another; adaptive steps and iterations follow them (the 6DOF's operations in
# Fig 4.7, a raid's MKS trajectories: CHANGELOG.md). The figures, the ledger and the tests run
# with one kernel, AVX2's, which every x86-64 machine of the last decade runs, so that they
# regenerate alike on any of them.
ifeq ($(shell uname -m),x86_64)
OPENBLAS_CORETYPE ?= Haswell
export OPENBLAS_CORETYPE
endif
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

KERNELS := $(VENV)/.kernels

.PHONY: figures test lint benchmark explore check-browser docs check-docs clean-venv

$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r environment.txt
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps \
		--no-build-isolation --editable .
	touch $@

# The engines' compiled kernels (numba), built once per version of the sources and cached on
# disk (harp_analysis.foundation.compiled), so that no notebook waits for a compiler. The cache
# is the user's (~/.cache/harp-analysis/kernels, or HARP_ANALYSIS_KERNEL_CACHE), found by the
# sources' contents alone: in a fresh clone of sources compiled before, this loads in seconds.
$(KERNELS): $(STAMP) $(shell find src/harp_analysis -name '*.py')
	$(BIN)/python -c "from harp_analysis.engines import threedof; threedof.warm_up()" & \
	threedof=$$!; \
	$(BIN)/python -c "from harp_analysis.engines import flight_grid, mks, mks_improved, mlt, sixdof; \
		from harp_analysis.analyses.fire_control import solver as firing_solver; \
		sixdof.warm_up(); mlt.warm_up(); mks.warm_up(); mks_improved.warm_up(); \
		firing_solver.warm_up(); flight_grid.warm_up()" && wait $$threedof
	touch $@

# Figures go to the committed figures/ only here; notebooks run elsewhere write to a scratch
# folder (harp_analysis.foundation.paths.FIGURES_DIR). `make figures FIG=4.11` runs only its notebook.
figures: $(KERNELS)
	HARP_ANALYSIS_FIGURES_DIR="$(CURDIR)/figures" $(BIN)/python -m harp_analysis.reporting.build \
		$(if $(FIG),--figure $(FIG))

# Style (ruff), types (mypy) and the package's layers (import-linter, contracts in pyproject.toml).
lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports

# Notebooks under test save their figures to a scratch folder, never over the committed ones.
# The figures they draw are then compared with the committed ones, to an image tolerance.
test: lint $(KERNELS)
	scratch="$$(mktemp -d)" && \
	HARP_ANALYSIS_FIGURES_DIR="$$scratch" $(BIN)/python -m pytest -n 2 --dist loadgroup tests --nbmake notebooks && \
	HARP_ANALYSIS_REGENERATED_FIGURES="$$scratch" $(BIN)/python -m pytest -q tests/test_figure_images.py

# The explorer (notebooks/00_explorer.ipynb) as a web page, served by Voila on this machine only;
# serve/voila.py culls idle kernels and caps the live ones.
explore: $(KERNELS)
	@echo "Explorer: http://127.0.0.1:8866/"
	$(BIN)/voila notebooks/00_explorer.ipynb --no-browser --port=8866 --Voila.ip=127.0.0.1 \
		--Voila.port_retries=0 --Voila.config_file_paths=serve

# Only the explorer's browser tests, its load test and its served ping test (about 1.5 minutes,
# so not in `make test`);
# a missing chromium or chromium-driver fails them, never skips.
check-browser: $(KERNELS)
	HARP_ANALYSIS_REQUIRE_BROWSER=1 HARP_ANALYSIS_EXPLORER_LOAD=1 $(BIN)/python -m pytest -q tests/browser

# The documentation site, offline, into build/docs/html (docs/, harp_analysis.reporting.site):
# its pages assembled in build/docs/source (the notebooks run once, the ledger evaluated once,
# the benchmarks run once, each cached in build/docs/cache until the sources change), built by
# Sphinx with every warning an error (broken cross-references included; -E reads every page
# again, so a second build reports what the first did), then every internal
# link, anchor and image of the built pages checked, and nothing loaded from outside.
# HARP_ANALYSIS_DOCS_EXECUTE=0 leaves the notebooks unrun; HARP_ANALYSIS_DOCS_BENCHMARKS=smoke
# or off runs the benchmarks in their smoke mode or not at all (for iterating on the pages).
DOCS := build/docs
docs: $(KERNELS)
	$(BIN)/python -m harp_analysis.reporting.site sources $(DOCS)/source
	$(BIN)/sphinx-build -E -W --keep-going -n -q -b html -c docs -d $(DOCS)/doctrees \
		$(DOCS)/source $(DOCS)/html
	$(BIN)/python -m harp_analysis.reporting.site check $(DOCS)/html
	@echo "The site: $(CURDIR)/$(DOCS)/html/index.html"

# The built site in Debian's headless Chromium (tests/browser/test_docs_site.py); a missing
# chromium or chromium-driver fails it, never skips.
check-docs: docs
	HARP_ANALYSIS_REQUIRE_BROWSER=1 HARP_ANALYSIS_DOCS_SITE="$(CURDIR)/$(DOCS)/html" \
		$(BIN)/python -m pytest -q -p no:cacheprovider tests/browser/test_docs_site.py

# Every engine against its reference, then the cold compile (a minute) and a fresh clone's CI
# (about ten minutes): the budgets of issue 36, each printed against its target.
benchmark: $(KERNELS)
	$(BIN)/python benchmarks/bench_atmosphere.py
	$(BIN)/python benchmarks/bench_threedof.py
	$(BIN)/python benchmarks/bench_sixdof.py
	$(BIN)/python benchmarks/bench_mlt.py
	$(BIN)/python benchmarks/bench_mks.py
	$(BIN)/python benchmarks/bench_fire_control.py
	$(BIN)/python benchmarks/bench_sweeps.py
	$(BIN)/python benchmarks/bench_figures.py
	$(BIN)/python benchmarks/bench_mks_improved.py
	$(BIN)/python benchmarks/bench_calibrated_mks.py
	$(BIN)/python benchmarks/cold_compile.py
	$(BIN)/python benchmarks/fresh_clone_ci.py

clean-venv:
	rm -rf $(VENV)
