# Torsal: `make run` opens the app on an example; `make test` runs the whole suite.
# Both set everything up first: system packages (via apt-get, when root on Debian),
# the virtualenv and the Python packages — `run` only the app's (.[gui]), `test` the test
# tools too (.[test]), each pinned by constraints.txt to the versions CI tested.
# `make check-bounds` installs the lowest versions pyproject.toml allows and imports everything.

PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV   := .venv
BIN    := $(VENV)/bin
RUN_STAMP  := $(VENV)/.installed-run
TEST_STAMP := $(VENV)/.installed-test
CONSTRAINTS := constraints.txt
EXAMPLE ?= torsal/resources/examples/kaohsiung-stadium.graph

# What Qt 6's xcb plugin, VTK's OpenGL and Xvfb need on a bare Debian 12.
SYSTEM_PACKAGES := python3-venv xvfb xauth libgl1 libegl1 libglib2.0-0 libfontconfig1 \
	libdbus-1-3 libxkbcommon0 libxkbcommon-x11-0 libxcb-cursor0 libxcb-icccm4 libxcb-image0 \
	libxcb-keysyms1 libxcb-randr0 libxcb-render-util0 libxcb-shape0 libxcb-xinerama0 \
	libxcb-xkb1 libxcb-xfixes0 libxcb-sync1 libxcb-shm0 libxcb-render0 libxrender1 libxext6 \
	libxi6 libsm6 libice6 libx11-xcb1 librsvg2-bin

.PHONY: run test bench lint system venv clean fuzz check-bounds

run: system $(RUN_STAMP)
	$(BIN)/torsal gui $(EXAMPLE)

# The GUI tests run in a process of their own: Qt shares it with no thread or child
# process the other tests leave behind (a dask cluster's, say), and no other window on
# the display takes its keyboard focus. The other tests spread their files over every
# core (pytest-xdist; TEST_WORKERS=0 for one process): a file's tests stay on one worker,
# so a module's shared solve is made once.
TEST_WORKERS ?= auto
PYTEST := $(BIN)/python -m pytest
SPREAD := -n $(TEST_WORKERS) --dist loadfile
test: system $(TEST_STAMP)
	$(BIN)/ruff check .
	@if [ -n "$$DISPLAY" ] || ! command -v xvfb-run >/dev/null; then \
		$(PYTEST) $(SPREAD) --ignore=tests/app/gui && $(PYTEST) tests/app/gui; \
	else \
		xvfb-run -a -s "-screen 0 1600x1000x24" $(PYTEST) $(SPREAD) --ignore=tests/app/gui && \
		xvfb-run -a -s "-screen 0 1600x1000x24" $(PYTEST) tests/app/gui; \
	fi

bench: system $(TEST_STAMP)
	@if [ -n "$$DISPLAY" ] || ! command -v xvfb-run >/dev/null; then \
		$(BIN)/python -m pytest tests/benchmarks -o python_files="bench_*.py" -o norecursedirs=".*" -s -q; \
	else \
		xvfb-run -a -s "-screen 0 1600x1000x24" $(BIN)/python -m pytest tests/benchmarks -o python_files="bench_*.py" -o norecursedirs=".*" -s -q; \
	fi

lint: $(TEST_STAMP)
	$(BIN)/ruff check .

# A larger, seeded fuzzing corpus than make test's (SEED=n for another; about 15 minutes):
# 600 structure-aware mutants of every example, their outputs described as by --json; every
# node's numeric inputs fed hostile numbers; every capped input at its cap; 5,000 byte mutants
# of .3dm files read through the fenced rhino3dm child (tools/fuzz_3dm.py). Failing mutants
# are written to $TMPDIR/torsal-fuzz for `torsal run FILE`.
fuzz: $(TEST_STAMP)
	$(BIN)/python -m tools.fuzz_graphs --mutants 600 --seed $${SEED:-0} --summarize
	$(BIN)/python -m tools.fuzz_inputs
	$(BIN)/python -m tools.fuzz_inputs --at-caps
	$(BIN)/python -m tools.fuzz_3dm --mutants 5000 --seed $${SEED:-0}

# System packages: installed only when missing, and only when we are root with apt-get.
system:
	@missing=""; for p in $(SYSTEM_PACKAGES); do \
		dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -z "$$missing" ]; then exit 0; fi; \
	if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "Installing system packages:$$missing"; \
		DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	elif command -v dpkg >/dev/null; then \
		echo "Note: missing system packages (GUI tests may be skipped):$$missing"; \
		echo "      install them with: sudo apt-get install$$missing"; \
	fi

venv: $(TEST_STAMP)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# The app's runtime only: no pytest, no ruff.
$(RUN_STAMP): pyproject.toml $(CONSTRAINTS) | $(BIN)/python
	$(BIN)/python -m pip install --quiet -c $(CONSTRAINTS) -e '.[gui]'
	touch $(RUN_STAMP)

# The runtime and the test tools (.[test] includes .[gui]).
$(TEST_STAMP): pyproject.toml $(CONSTRAINTS) | $(BIN)/python
	$(BIN)/python -m pip install --quiet -c $(CONSTRAINTS) -e '.[test]'
	touch $(TEST_STAMP) $(RUN_STAMP)

# Slow (downloads the oldest allowed wheels): not part of `make test`. GUI=1 adds the gui
# extra's lower bounds, imports app/gui and opens the app under Xvfb.
check-bounds:
	$(PYTHON) -m tools.check_bounds $(if $(GUI),--gui)

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .ruff_cache
