# pendula: two commands do everything on a fresh Debian 12 machine.
#   make demo   set up what is missing, then run the main job on its default
#   make test   set up what is missing, then run the test suite
# Each step is skipped when already done (apt packages checked with dpkg,
# .venv and the installed package kept fresh by stamp files).

SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
APT_PKGS := gfortran libgsl-dev libfftw3-dev pkg-config python3-venv
export PATH := $(CURDIR)/$(VENV)/bin:$(PATH)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
SOURCES := $(shell find kernel python data/scenes -type f \( -name "*.f90" -o -name "*.c" -o -name "*.py" -o -name "*.inc" -o -name "*.nml" \)) meson.build pyproject.toml

.PHONY: demo test test-debug bench bench-peers system-deps clean

demo: $(VENV)/.installed
	$(PY) -m pendula demo

test: $(VENV)/.installed
	$(PY) -m pytest -q tests

# the debug variant (-fcheck=all; ASan and UBSan on the batch programs): see .ci/debug
test-debug: $(VENV)/.installed
	bash .ci/debug

bench: $(VENV)/.installed
	$(PY) -m pendula bench

# the peers of the work-precision study (SciPy, SUNDIALS CVODE, numbalsoda): the extra pendula[bench]
bench-peers: $(VENV)/.installed
	$(PY) -m pip install -q "scipy>=1.11" "scikit-sundae>=1.0" "numbalsoda>=0.3.4" "numba>=0.59"

system-deps:
	@dpkg -s $(APT_PKGS) >/dev/null 2>&1 || { \
	  echo "installing system packages: $(APT_PKGS)"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $(APT_PKGS); }

$(VENV)/.deps: pyproject.toml | system-deps
	@[ -x $(PY) ] || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q "numpy>=2.0" "meson>=1.3" "meson-python>=0.15" ninja \
	    "matplotlib>=3.7" "pytest>=7" "mpmath>=1.3" "scipy>=1.11" "hypothesis>=6" \
	    "xarray>=2024.1" "dask[distributed]>=2024.1" "tqdm>=4.60"
	@touch $@

$(VENV)/.installed: $(VENV)/.deps $(SOURCES) | system-deps
	$(PY) -m pip install -q --no-build-isolation --no-deps -Cbuild-dir=build .
	@touch $@

clean:
	rm -rf build build-asan build-debug out $(VENV)/.installed
