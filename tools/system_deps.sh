#!/usr/bin/env bash
# The system packages pendula's build needs: checked, installed when this
# machine can (Debian or Ubuntu, as root or through sudo), otherwise named
# with the commands that install them, and a non-zero exit.
#
#   tools/system_deps.sh                  check the build's packages (make system-deps)
#   tools/system_deps.sh --check          only say what is missing (exit 1 if anything is)
#
# What is needed, in each family's names:
#   Debian/Ubuntu  gfortran libgsl-dev libfftw3-dev pkg-config python3-venv
#   Fedora         gcc-gfortran gsl-devel fftw-devel pkgconf-pkg-config python3
#   macOS          (Homebrew) gcc gsl fftw pkgconf python
# On Debian the packages are checked with dpkg; elsewhere by what they
# provide: gfortran and pkg-config on the PATH, GSL and FFTW found by
# pkg-config (gsl, fftw3), python3 with its venv module.
set -u

# the Makefile passes its list (APT_PKGS); this is the same list
read -r -a APT_PKGS <<< "${APT_PKGS:-gfortran libgsl-dev libfftw3-dev pkg-config python3-venv}"
DNF_PKGS="gcc-gfortran gsl-devel fftw-devel pkgconf-pkg-config python3"
BREW_PKGS="gcc gsl fftw pkgconf python"
PYTHON=${PYTHON:-python3}

check_only=0
[ "${1:-}" = "--check" ] && check_only=1

have() { command -v "$1" >/dev/null 2>&1; }

missing=()
if have dpkg; then
    for p in "${APT_PKGS[@]}"; do
        dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
    done
else
    # not Debian: look for what each package provides
    have gfortran || missing+=("a Fortran compiler (gfortran)")
    if have pkg-config; then
        pkg-config --exists gsl || missing+=("GSL (pkg-config gsl)")
        pkg-config --exists fftw3 || missing+=("FFTW 3 (pkg-config fftw3)")
    else
        missing+=("pkg-config" "GSL (pkg-config gsl)" "FFTW 3 (pkg-config fftw3)")
    fi
    { have "$PYTHON" && "$PYTHON" -c "import venv, ensurepip" >/dev/null 2>&1; } \
        || missing+=("Python 3 with venv ($PYTHON)")
fi

[ ${#missing[@]} -eq 0 ] && exit 0

# Debian as root, or with sudo: install them (the way make has always set up a fresh machine)
if [ $check_only = 0 ] && have dpkg && have apt-get; then
    if [ "$(id -u)" = 0 ]; then
        SUDO=()
    elif have sudo; then
        SUDO=(sudo)
    else
        SUDO=(none)
    fi
    if [ "${SUDO[*]:-}" != none ]; then
        echo "installing system packages: ${missing[*]}"
        "${SUDO[@]}" apt-get update -qq \
            && DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y -qq "${missing[@]}" \
            && exit 0
        echo "system-deps: apt-get could not install ${missing[*]}" >&2
        exit 1
    fi
fi

{
    echo "pendula's build needs system packages that are missing here:"
    for p in "${missing[@]}"; do echo "    $p"; done
    echo "Install them (as an administrator), then run make again:"
    echo "    Debian, Ubuntu:    sudo apt-get install ${APT_PKGS[*]}"
    echo "    Fedora:            sudo dnf install $DNF_PKGS"
    echo "    macOS (Homebrew):  brew install $BREW_PKGS"
} >&2
exit 1
