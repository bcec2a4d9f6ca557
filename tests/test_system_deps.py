"""make system-deps at the door: present packages pass without sudo; missing ones without root or sudo
are named, with the commands that install them, and make stops.

Each test runs tools/system_deps.sh (and `make system-deps`) with a PATH of a
few stand-in programs: a dpkg that knows only some packages, an id that says
the user is not root, no sudo and no apt-get; or, for a machine that is not
Debian, no dpkg and a pkg-config that finds or does not find GSL and FFTW.
"""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "tools" / "system_deps.sh"
APT = ["gfortran", "libgsl-dev", "libfftw3-dev", "pkg-config", "python3-venv"]
BASH = shutil.which("bash")


def _fake_bin(tmp_path, installed=None, uid=1000, pkgconfig=None, extra=()):
    """A folder of stand-in programs: dpkg knowing `installed` (None: no dpkg), id -u printing `uid`,
    pkg-config finding the modules in `pkgconfig` (None: no pkg-config); `extra` real programs linked in."""
    b = tmp_path / "bin"
    b.mkdir()

    def prog(name, text):
        p = b / name
        p.write_text(f"#!{BASH}\n{text}\n")
        p.chmod(0o755)

    if installed is not None:
        cases = " ".join(installed) or "none-installed"
        prog("dpkg", f'[ "$1" = -s ] || exit 2\ncase "$2" in {cases.replace(" ", "|")}) exit 0;; esac\nexit 1')
    prog("id", f"echo {uid}")
    if pkgconfig is not None:
        mods = "|".join(pkgconfig) or "no-module"
        prog("pkg-config", f'[ "$1" = --exists ] || exit 2\ncase "$2" in {mods}) exit 0;; esac\nexit 1')
    for name in extra:
        # python3: the interpreter itself (shutil.which may find a launcher script such as pyenv's shim)
        real = os.path.realpath(sys.executable) if name == "python3" else shutil.which(name)
        os.symlink(real, b / name)
    return b


def _run(cmd, b, **env):
    return subprocess.run(cmd, env={"PATH": str(b), "HOME": "/nonexistent", **env}, capture_output=True,
                          text=True, timeout=60, cwd=ROOT)


def test_present_packages_pass_without_root_or_sudo(tmp_path):
    b = _fake_bin(tmp_path, installed=APT)
    r = _run([BASH, str(SCRIPT)], b)
    assert r.returncode == 0, r.stderr
    assert r.stdout == r.stderr == ""


def test_missing_packages_without_root_or_sudo_are_named_with_the_install_commands(tmp_path):
    b = _fake_bin(tmp_path, installed=["gfortran", "pkg-config", "python3-venv"])
    r = _run([BASH, str(SCRIPT)], b)
    assert r.returncode != 0
    named = [ln.strip() for ln in r.stderr.splitlines() if ln.startswith("    ") and ":" not in ln]
    assert named == ["libgsl-dev", "libfftw3-dev"]
    assert "sudo apt-get install gfortran libgsl-dev libfftw3-dev pkg-config python3-venv" in r.stderr
    assert "sudo dnf install gcc-gfortran gsl-devel fftw-devel" in r.stderr
    assert "brew install gcc gsl fftw" in r.stderr
    assert "installing" not in r.stdout


def test_make_system_deps_stops_when_packages_are_missing(tmp_path):
    make = shutil.which("make")
    if make is None:
        pytest.skip("make is not installed")
    b = _fake_bin(tmp_path, installed=["gfortran", "libgsl-dev", "libfftw3-dev", "pkg-config"], extra=("bash",))
    r = _run([make, "-s", "system-deps"], b)
    assert r.returncode != 0
    assert "python3-venv" in r.stderr and "sudo apt-get install" in r.stderr
    b2 = tmp_path / "ok"
    b2.mkdir()
    b2 = _fake_bin(b2, installed=APT, extra=("bash",))
    r = _run([make, "-s", "system-deps"], b2)
    assert r.returncode == 0, r.stderr


def test_without_dpkg_the_libraries_are_found_by_pkg_config(tmp_path):
    """Fedora or macOS: no dpkg; gfortran and python3 are the machine's, pkg-config a stand-in."""
    if shutil.which("gfortran") is None:
        pytest.skip("needs gfortran on this machine")
    b = _fake_bin(tmp_path, installed=None, pkgconfig=["gsl", "fftw3"], extra=("gfortran", "python3"))
    r = _run([BASH, str(SCRIPT)], b)
    assert r.returncode == 0, r.stderr
    (b / "pkg-config").unlink()
    (b / "pkg-config").write_text(f"#!{BASH}\n[ \"$2\" = gsl ]\n")
    (b / "pkg-config").chmod(0o755)
    r = _run([BASH, str(SCRIPT)], b)
    assert r.returncode != 0
    assert "FFTW 3 (pkg-config fftw3)" in r.stderr and "GSL (pkg-config gsl)" not in r.stderr
    assert "brew install" in r.stderr


def test_check_only_never_installs(tmp_path):
    """--check as root on Debian: says what is missing and does not call apt-get (a stand-in that would record it)."""
    b = _fake_bin(tmp_path, installed=APT[:-1], uid=0)
    (b / "apt-get").write_text(f"#!{BASH}\necho called >> {tmp_path}/apt.log\n")
    (b / "apt-get").chmod(0o755)
    r = _run([BASH, str(SCRIPT), "--check"], b)
    assert r.returncode != 0 and "python3-venv" in r.stderr
    assert not (tmp_path / "apt.log").exists()
    # without --check, root installs through apt-get (the stand-in records both calls)
    r = _run([BASH, str(SCRIPT)], b)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "apt.log").read_text().split() == ["called", "called"]
