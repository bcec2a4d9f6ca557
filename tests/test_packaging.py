"""The wheel and the sdist, as a new user gets them.

``make test-wheel`` builds a portable wheel (``make wheel``: native=false,
auditwheel repair) and the sdist, then runs this file with PENDULA_WHEEL and
PENDULA_SDIST naming them.  Without them (``make test``) every test here is
skipped: building a wheel takes minutes.

The wheel is installed into a fresh virtual environment with numpy only; every
command there runs with LD_LIBRARY_PATH empty and a PATH of the environment's
bin/ and the system's, so that the bundled copies are the only GSL, FFTW,
gfortran and OpenMP runtimes the loader is told about; ldd and the process's
own memory map then show where each library really came from.
"""

from __future__ import annotations

import os
import pathlib
import re
import shutil
import subprocess
import sys
import tarfile
import zipfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
WHEEL = os.environ.get("PENDULA_WHEEL", "")
SDIST = os.environ.get("PENDULA_SDIST", "")
WHEEL, SDIST = (str(pathlib.Path(f).resolve()) if f else "" for f in (WHEEL, SDIST))
HOW = "`make test-wheel` builds them and runs these tests (PENDULA_WHEEL / PENDULA_SDIST name the files)"

needs_wheel = pytest.mark.skipif(not WHEEL, reason=f"no wheel given: {HOW}")
needs_sdist = pytest.mark.skipif(not SDIST, reason=f"no sdist given: {HOW}")

# the libraries the kernel links besides glibc, which auditwheel must bundle
BUNDLED = ("libgsl", "libgslcblas", "libfftw3", "libgfortran", "libquadmath", "libgomp")
# what a manylinux wheel may take from the system: glibc's libraries and libgcc_s
# (auditwheel's manylinux policy lists them)
SYSTEM_OK = re.compile(r"^(linux-vdso|ld-linux[-\w]*|libc|libm|libmvec|libpthread|libdl|librt|libutil|"
                       r"libresolv|libgcc_s)\.so")


def project_version() -> str:
    """The version, from its one place: meson.build's project()."""
    text = (ROOT / "meson.build").read_text()
    m = re.search(r"project\([^)]*?version:\s*'([^']+)'", text, re.S)
    assert m, "meson.build's project() has no version"
    return m.group(1)


def clean_env(venv: pathlib.Path) -> dict:
    """An environment that hides the build machine: no LD_LIBRARY_PATH, no
    PYTHONPATH, no user site, PATH = the fresh venv's bin/ and the system's."""
    env = {"PATH": f"{venv / 'bin'}:/usr/bin:/bin", "HOME": os.environ.get("HOME", "/tmp"),
           "LD_LIBRARY_PATH": "", "PYTHONNOUSERSITE": "1", "LANG": "C.UTF-8", "OMP_NUM_THREADS": "2",
           "MPLBACKEND": "Agg"}
    for key in ("PIP_INDEX_URL", "PIP_EXTRA_INDEX_URL", "PIP_TRUSTED_HOST", "PIP_CERT", "SSL_CERT_FILE",
                "REQUESTS_CA_BUNDLE", "HTTP_PROXY", "HTTPS_PROXY", "NO_PROXY", "http_proxy", "https_proxy",
                "no_proxy", "PIP_CONFIG_FILE"):
        if key in os.environ:
            env[key] = os.environ[key]
    return env


@pytest.fixture(scope="module")
def venv(tmp_path_factory):
    """A fresh virtual environment with numpy and the wheel, nothing else."""
    if not WHEEL:
        pytest.skip(f"no wheel given: {HOW}")
    d = tmp_path_factory.mktemp("wheel-venv") / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(d)], check=True)
    py = d / "bin" / "python"
    subprocess.run([str(py), "-m", "pip", "install", "-q", "--disable-pip-version-check", "numpy>=2.0", WHEEL],
                   check=True, env=clean_env(d), cwd=d)
    return d


def run(venv, args, cwd, **kw):
    return subprocess.run([str(a) for a in args], env=clean_env(venv), cwd=cwd, capture_output=True, text=True,
                          timeout=600, **kw)


def site_packages(venv) -> pathlib.Path:
    out = run(venv, ["python", "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"], venv)
    return pathlib.Path(out.stdout.strip())


def installed_binaries(venv) -> list[pathlib.Path]:
    """The extension module and the batch programs the wheel installed (auditwheel
    moves the programs to pendula.scripts/ and puts a launcher into bin/)."""
    sp = site_packages(venv)
    exts = sorted((sp / "pendula").glob("_kernel*.so"))
    assert len(exts) == 1, exts
    return exts + [sp / "pendula.scripts" / "pendula-run", sp / "pendula.scripts" / "pendula-ellip"]


# ------------------------------------------------------------------ the wheel file itself

@needs_wheel
def test_wheel_is_manylinux_and_carries_licence_version_and_data():
    name = pathlib.Path(WHEEL).name
    assert re.search(r"manylinux_\d+_\d+_x86_64", name), f"not a manylinux wheel: {name}"
    assert name.startswith(f"pendula-{project_version()}-"), name
    with zipfile.ZipFile(WHEEL) as z:
        names = z.namelist()
        dist_info = f"pendula-{project_version()}.dist-info"
        lic = f"{dist_info}/licenses/LICENSE"
        assert lic in names, [n for n in names if "dist-info" in n]
        text = z.read(lic).decode()
        assert "GNU GENERAL PUBLIC LICENSE" in text and "Version 3, 29 June 2007" in text
        meta = z.read(f"{dist_info}/METADATA").decode()
        libs = [n.split("/")[-1] for n in names if n.startswith("pendula.libs/")]
        data = [n for n in names if n.startswith("pendula/data/")]
    assert "License-Expression: GPL-3.0-or-later" in meta
    assert "License-File: LICENSE" in meta
    assert f"Version: {project_version()}" in meta
    assert "Author: The pendula developers" in meta
    for field in ("Keywords:", "Classifier: Topic :: Scientific/Engineering :: Physics", "Project-URL:",
                  "Provides-Extra: plot", "Provides-Extra: sweep", "Provides-Extra: bench",
                  "Provides-Extra: accuracy", "Provides-Extra: all"):
        assert field in meta, field
    for lib in BUNDLED:
        assert any(re.match(rf"{lib}-[0-9a-f]+\.so", n) for n in libs), f"{lib} not bundled: {libs}"
    assert {"pendula/data/elliptic_reference.csv", "pendula/data/reference_grids.csv.gz"} <= set(data)


# ------------------------------------------------------------------ installed, with the system hidden

def ldd(venv, path) -> dict[str, str]:
    """ldd's answer with LD_LIBRARY_PATH empty: soname -> resolved path ('' when ldd gives none)."""
    out = run(venv, ["ldd", path], venv)
    assert out.returncode == 0, out.stderr
    libs = {}
    for line in out.stdout.splitlines():
        line = line.strip()
        if "=>" in line:
            soname, _, rest = line.partition("=>")
            libs[soname.strip()] = rest.split("(")[0].strip()
        elif line:
            libs[line.split()[0]] = line.split()[0]
    return libs


@needs_wheel
def test_binaries_resolve_every_library_inside_the_wheel(venv):
    libdir = site_packages(venv) / "pendula.libs"
    for binary in installed_binaries(venv):
        libs = ldd(venv, binary)
        foreign = {}
        for soname, where in libs.items():
            base = soname.rsplit("/", 1)[-1]
            if SYSTEM_OK.match(base):
                continue
            if not where or where == "not found" or pathlib.Path(where).resolve().parent != libdir.resolve():
                foreign[soname] = where
        assert not foreign, f"{binary.name} takes these from outside pendula.libs: {foreign}"
        # and it does use the bundled copies: all six in the extension, the
        # gfortran runtime at least in every program
        used = {s.split("-")[0] for s in libs}
        want = set(BUNDLED) if binary.name.startswith("_kernel") else {"libgfortran"}
        assert want <= used, f"{binary.name}: {sorted(used)}"


# functions compiled for AVX2 or FMA on purpose and called only after the CPU was
# asked (__builtin_cpu_supports in kernel/elliptic/pendula_agm.c and
# kernel/mathieu/pendula_mathieu_polish.c): allowed in a portable build
DISPATCHED = {"agm_k_fma", "polish_rows_fma"}


def avx_functions(path: pathlib.Path) -> dict[str, int]:
    """Function -> its instructions on 256- or 512-bit registers (AVX and later)."""
    objdump = shutil.which("objdump")
    if objdump is None:
        pytest.skip("objdump (binutils) is not installed")
    out = subprocess.run([objdump, "-d", "--no-show-raw-insn", str(path)], capture_output=True, text=True,
                         check=True).stdout
    counts, func = {}, "?"
    for line in out.splitlines():
        m = re.match(r"^[0-9a-f]+ <(.+)>:$", line)
        if m:
            func = m.group(1)
        elif re.search(r"%[yz]mm\d+", line):
            counts[func] = counts.get(func, 0) + 1
    return counts


def undispatched_avx(path: pathlib.Path) -> dict[str, int]:
    return {f: n for f, n in avx_functions(path).items() if f.split(".")[0] not in DISPATCHED}


@needs_wheel
def test_wheel_code_is_the_portable_baseline(venv):
    """native=false for wheels: no AVX instruction in the extension or the programs,
    except in the functions the code itself dispatches on the CPU."""
    for binary in installed_binaries(venv):
        bad = undispatched_avx(binary)
        assert not bad, f"{binary.name} holds AVX instructions (built with -march=native?) in {bad}"


@needs_wheel
def test_the_avx_check_sees_a_native_build():
    """The check above can fail: the developer build (native=true) on an AVX2
    machine uses the 256-bit registers outside the dispatched functions."""
    if "avx2" not in pathlib.Path("/proc/cpuinfo").read_text():
        pytest.skip("this CPU has no AVX2: a native build is a baseline build here")
    import pendula._kernel as k

    assert len(undispatched_avx(pathlib.Path(k.__file__))) > 10


SMOKE = r"""
import math, pathlib, sys
import numpy as np
import pendula
from pendula import ellipk, ellipj, spectrum

eps = np.finfo(float).eps
# K(1/2) in closed form (Legendre): Gamma(1/4)^2 / (4 sqrt(pi))
k_half = math.gamma(0.25) ** 2 / (4 * math.sqrt(math.pi))
assert abs(float(ellipk(0.5)) - k_half) <= 4 * eps * k_half, float(ellipk(0.5))
# K(m) = pi / (2 AGM(1, sqrt(1 - m))) (Gauss), the AGM in Python, at random m
rng = np.random.default_rng(7)
for m in rng.uniform(0.0, 0.999, 20):
    a, b = 1.0, math.sqrt(1.0 - m)
    for _ in range(40):
        a, b = (a + b) / 2, math.sqrt(a * b)
    ref = math.pi / (2 * a)
    assert abs(float(ellipk(m)) - ref) <= 8 * eps * ref, (m, float(ellipk(m)), ref)
sn, cn, dn, am = ellipj(float(ellipk(0.7)), 0.7)          # sn(K|m) = 1
assert abs(float(sn) - 1.0) <= 4 * eps, float(sn)
# FFTW: a cosine with 50 whole periods over the record: its line at omega = pi (exact
# for whole periods, Spectrum.fundamental), to far below the bin width 2 pi / T
t = np.linspace(0.0, 100.0, 4096, endpoint=False)
s = spectrum(t, np.cos(math.pi * t))
assert abs(s.fundamental - math.pi) < 1e-6 * 2 * math.pi / 100.0, s.fundamental
# every GSL, FFTW, gfortran and OpenMP runtime mapped into this process is a
# copy bundled in a wheel (numpy's wheel brings its own gfortran runtime for
# OpenBLAS), none is the system's, and pendula.libs provides all six
site = pathlib.Path(pendula.__file__).resolve().parent.parent
maps = {line.split()[-1] for line in open("/proc/self/maps") if "/" in line}
want = ("libgsl", "libgslcblas", "libfftw3", "libgfortran", "libquadmath", "libgomp")
hits = [pathlib.Path(p).resolve() for p in maps if pathlib.Path(p).name.startswith(want)]
assert hits and all(p.parent.parent == site and p.parent.name.endswith(".libs") for p in hits), hits
ours = {p.name.split("-")[0] for p in hits if p.parent.name == "pendula.libs"}
assert ours == set(want), (ours, hits)
print("smoke ok", pendula.__version__, len(hits))
"""


@needs_wheel
def test_smoke_in_a_fresh_environment(venv, tmp_path):
    out = run(venv, ["python", "-c", SMOKE], tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split()[:3] == ["smoke", "ok", project_version()], out.stdout


def system_copies() -> list[str]:
    """The real files of the system's GSL, FFTW, gfortran, quadmath and OpenMP libraries."""
    import glob

    files = set()
    for d in ("/usr/lib/x86_64-linux-gnu", "/lib/x86_64-linux-gnu", "/usr/lib64", "/usr/local/lib"):
        for lib in BUNDLED:
            files.update(os.path.realpath(f) for f in glob.glob(f"{d}/{lib}.so*"))
    return sorted(f for f in files if os.path.isfile(f))


def run_hiding_system_copies(venv, command: str, cwd) -> subprocess.CompletedProcess:
    """``command`` (a shell line) in a private mount namespace in which /dev/null is
    bind-mounted over every system copy of the bundled libraries: a program that
    still needed one fails to load it ("file too short").  Skips where mount
    namespaces are not allowed (not root, no CAP_SYS_ADMIN)."""
    unshare = shutil.which("unshare")
    hidden = system_copies()
    if unshare is None or not hidden:
        pytest.skip("no unshare(1), or no system copy of the libraries to hide")
    mounts = " && ".join(f"mount --bind /dev/null '{f}'" for f in hidden)
    out = run(venv, [unshare, "--mount", "--propagation", "private", "sh", "-c", f"{mounts} && {command}"], cwd)
    if out.returncode != 0 and ("Operation not permitted" in out.stderr or "permission denied" in out.stderr):
        pytest.skip(f"mount namespaces are not allowed here: {out.stderr.strip()[:200]}")
    return out


@needs_wheel
def test_smoke_with_the_system_libraries_hidden(venv, tmp_path):
    """The wheel computes with the system's GSL, FFTW, gfortran, quadmath and
    OpenMP made unloadable, from Python and from the batch program."""
    (tmp_path / "smoke.py").write_text(SMOKE)
    scene = ROOT / "data" / "scenes" / "fig10_theta_max_vs_v0.nml"
    out = run_hiding_system_copies(venv, f"python smoke.py && pendula-run '{scene}' -o fig10.csv", tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split()[:2] == ["smoke", "ok"], out.stdout
    assert (tmp_path / "fig10.csv").stat().st_size > 0


@needs_wheel
def test_hiding_the_system_libraries_breaks_a_build_that_needs_them(venv, tmp_path):
    """The test above can fail: the development build, linked to the system's
    libraries, cannot even be imported with them hidden."""
    out = run_hiding_system_copies(venv, f"'{sys.executable}' -c 'import pendula'", tmp_path)
    assert out.returncode != 0 and "file too short" in out.stderr, (out.returncode, out.stderr)


@needs_wheel
def test_version_in_one_place(venv, tmp_path):
    out = run(venv, ["pendula", "--version"], tmp_path)
    assert out.returncode == 0 and out.stdout.strip() == f"pendula {project_version()}", (out.stdout, out.stderr)


@needs_wheel
def test_batch_program_runs_a_gallery_scene(venv, tmp_path):
    """pendula-run (Fortran, GSL, FFTW, OpenMP) from the wheel's bin/, on a sweep scene of the gallery."""
    scene = ROOT / "data" / "scenes" / "fig10_theta_max_vs_v0.nml"
    out = run(venv, ["pendula-run", scene, "-o", tmp_path / "fig10.csv"], tmp_path)
    assert out.returncode == 0, out.stderr
    rows = [ln for ln in (tmp_path / "fig10.csv").read_text().splitlines() if ln and not ln.startswith("#")]
    assert len(rows) > 10


# ------------------------------------------------------------------ numpy only: extras that fail kindly

def assert_kind_failure(out, extra):
    """One line on stderr naming the extra, exit status 6, no traceback."""
    lines = out.stderr.strip().splitlines()
    assert out.returncode == 6, (out.returncode, out.stderr)
    assert len(lines) == 1 and "Traceback" not in out.stderr, out.stderr
    assert f"pip install 'pendula[{extra}]'" in lines[0], lines[0]


SWEEP_SCENE = "&scene\n damping = 0.1\n grid = 'v0'\n grid1_range = 0, 3, 4\n measure = 'final_well'\n/\n"


@needs_wheel
@pytest.mark.parametrize("args, extra", [
    (["run", ROOT / "data" / "scenes" / "fig4_phase_portrait.nml", "-o", "out"], "plot"),
    (["sweep", "sweep.nml", "-o", "out"], "sweep"),
    (["bench", "elliptic", "--json", ""], "bench"),
    (["accuracy", "elliptic"], "accuracy"),
    (["demo", "-o", "out"], "all"),
])
def test_cli_names_the_missing_extra(venv, tmp_path, args, extra):
    (tmp_path / "sweep.nml").write_text(SWEEP_SCENE)
    out = run(venv, ["pendula", *args], tmp_path)
    assert_kind_failure(out, extra)
    assert not (tmp_path / "out").exists() or not any(f.is_file() for f in (tmp_path / "out").rglob("*"))


@needs_wheel
def test_python_api_names_the_missing_extra(venv, tmp_path):
    code = ("import pendula\n"
            "d = pendula.Scene(damping=0.1)\n"
            "try:\n"
            "    pendula.sweep(d, over={'theta0': [0.1, 0.2]}, measure='final_well')\n"
            "except ImportError as exc:\n"
            "    print(type(exc).__name__, '|', exc)\n")
    out = run(venv, ["python", "-c", code], tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == ("MissingExtraError | pendula.sweep needs xarray, which is not installed: "
                                  "pip install 'pendula[xarray]'"), out.stdout


@needs_wheel
def test_models_into_a_closed_pipe_is_quiet(venv, tmp_path):
    """`pendula models | true`: the reader is gone before pendula writes; no traceback, status 0."""
    out = run(venv, ["bash", "-o", "pipefail", "-c", "pendula models | true"], tmp_path)
    assert out.returncode == 0 and out.stderr == "", (out.returncode, out.stderr)
    out = run(venv, ["bash", "-o", "pipefail", "-c", "pendula models | head -3"], tmp_path)
    assert out.returncode == 0 and out.stderr == "" and len(out.stdout.splitlines()) == 3, out


@needs_wheel
def test_accuracy_grids_reads_the_packaged_reference(venv, tmp_path):
    """`pendula accuracy grids` needs numpy only and finds its mpmath reference
    inside the installed package, run from a folder without data/."""
    out = run(venv, ["pendula", "accuracy", "grids"], tmp_path)
    assert out.returncode == 0, out.stderr
    table = [ln for ln in out.stdout.splitlines() if ln.startswith("|")]
    assert len(table) > 5, out.stdout


# ------------------------------------------------------------------ the sdist

@needs_sdist
def test_sdist_carries_licence_sources_and_references():
    with tarfile.open(SDIST) as t:
        names = {n.split("/", 1)[1] for n in t.getnames() if "/" in n}
        top = t.getnames()[0].split("/")[0]
        pkg_info = t.extractfile(f"{top}/PKG-INFO").read().decode()
    assert top == f"pendula-{project_version()}"
    for f in ("LICENSE", "pyproject.toml", "meson.build", "meson.options", "kernel/binding/pendula_kernel.f90",
              "python/pendula/__init__.py", "data/elliptic_reference.csv", "data/reference_grids.csv.gz"):
        assert f in names, f
    assert "License-Expression: GPL-3.0-or-later" in pkg_info
    assert f"Version: {project_version()}" in pkg_info


@needs_sdist
def test_sdist_installs_with_pip_where_the_build_tools_are(tmp_path):
    """`pip install pendula-X.tar.gz` compiles the kernel (here with the build tools
    of this environment: gfortran, GSL, FFTW, meson) and the result imports and
    computes; the licence and the references come along."""
    bindir = pathlib.Path(sys.executable).parent
    if shutil.which("gfortran") is None or not (bindir / "meson").exists():
        pytest.skip("no gfortran or meson here: the sdist cannot be built")
    site = tmp_path / "site"
    env = dict(os.environ, PATH=f"{bindir}:{os.environ.get('PATH', '')}")
    out = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-build-isolation", "--no-deps",
                          "--target", str(site), SDIST], env=env, cwd=tmp_path, capture_output=True, text=True,
                         timeout=1200)
    assert out.returncode == 0, out.stderr[-3000:]
    code = ("import math, pathlib, pendula\n"
            "assert pathlib.Path(pendula.__file__).is_relative_to(pathlib.Path.cwd() / 'site'), pendula.__file__\n"
            "k = math.gamma(0.25) ** 2 / (4 * math.sqrt(math.pi))\n"
            "print(pendula.__version__, abs(float(pendula.ellipk(0.5)) - k) / k < 1e-15)\n")
    out = subprocess.run([sys.executable, "-c", code], env=dict(env, PYTHONPATH=str(site)), cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0 and out.stdout.split() == [project_version(), "True"], (out.stdout, out.stderr)
    dist_info = site / f"pendula-{project_version()}.dist-info"
    assert "GNU GENERAL PUBLIC LICENSE" in (dist_info / "licenses" / "LICENSE").read_text()
    assert (site / "pendula" / "data" / "reference_grids.csv.gz").is_file()


def _install_blocks():
    """The install page's command blocks (``:class: install-commands``): (commands, expected output)."""
    text = (ROOT / "docs" / "source" / "install.rst").read_text()
    blocks = re.findall(r"^\.\. code-block:: console\n   :class: install-commands\n\n((?:   .*\n)+)", text, re.M)
    out = []
    for b in blocks:
        lines = [ln[3:] for ln in b.splitlines()]
        out.append(([ln[2:] for ln in lines if ln.startswith("$ ")], [ln for ln in lines if not ln.startswith("$ ")]))
    return out


def test_install_page_has_its_command_blocks():
    blocks = _install_blocks()
    assert len(blocks) == 2
    assert any(".tar.gz" in c for c in blocks[1][0]) and any("'.[plot,sweep]'" in c for c in blocks[0][0])


def _run_install_block(commands, expected, cwd):
    """Run the page's commands as written, in bash, in ``cwd``; the last one's output is the page's."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = "/usr/local/bin:/usr/bin:/bin"      # the system's python3, not this test's environment
    for cmd in commands:
        out = subprocess.run(["bash", "-c", cmd], cwd=cwd, env=env, capture_output=True, text=True, timeout=3600)
        assert out.returncode == 0, (cmd, out.stdout[-2000:], out.stderr[-3000:])
    assert out.stdout.splitlines() == expected, (out.stdout, expected)


@needs_sdist
def test_install_page_commands_from_the_sdist_run_as_written(tmp_path):
    """The page's sdist block, as written, in a fresh folder holding dist/ and a clean venv: pip builds the
    kernel in an isolated environment (it fetches meson-python, meson, ninja and numpy from the index)."""
    commands, expected = _install_blocks()[1]
    (tmp_path / "dist").mkdir()
    name = f"pendula-{project_version()}.tar.gz"
    assert any(name in c for c in commands), f"the page names another version than {name}"
    os.symlink(SDIST, tmp_path / "dist" / name)
    _run_install_block(commands, expected, tmp_path)


@needs_sdist
def test_install_page_commands_in_a_fresh_clone_run_as_written(tmp_path):
    """The page's clone block, as written, in a fresh clone of this repository (its committed files)."""
    if shutil.which("git") is None:
        pytest.skip("no git here")
    commands, expected = _install_blocks()[0]
    clone = tmp_path / "pendula"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True, timeout=600)
    _run_install_block(commands, expected, clone)


def test_version_is_written_once():
    """meson.build holds the version; pyproject declares it dynamic; the package reads the metadata."""
    tomllib = pytest.importorskip("tomllib")  # Python 3.11

    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert "version" not in pyproject["project"] and "version" in pyproject["project"]["dynamic"]
    init = (ROOT / "python" / "pendula" / "__init__.py").read_text()
    assert project_version() not in init
    import pendula

    assert pendula.__version__ == project_version()


def test_licence_is_the_same_in_meson_and_pyproject():
    """meson.build's project(license:) and pyproject's SPDX expression agree, and LICENSE is the GPL 3."""
    tomllib = pytest.importorskip("tomllib")  # Python 3.11
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    m = re.search(r"project\([^)]*?license:\s*'([^']+)'", (ROOT / "meson.build").read_text(), re.S)
    assert m and m.group(1) == pyproject["license"] == "GPL-3.0-or-later"
    assert pyproject["license-files"] == ["LICENSE"]
    text = (ROOT / "LICENSE").read_text()
    assert text.lstrip().startswith("GNU GENERAL PUBLIC LICENSE") and "Version 3, 29 June 2007" in text


# ------------------------------------------------------------------ the same behaviour in the development build
# (run by make test: the optional packages are hidden by a None in sys.modules)

def run_hidden(hidden, args, cwd):
    """``pendula ARGS`` in a fresh interpreter in which the modules ``hidden`` cannot be imported."""
    code = ("import sys\n"
            f"for m in {list(hidden)!r}: sys.modules[m] = None\n"
            "from pendula.cli import main\n"
            f"sys.exit(main({[str(a) for a in args]!r}))\n")
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("hidden, args, extra", [
    (["matplotlib"], ["run", ROOT / "data" / "scenes" / "fig4_phase_portrait.nml", "-o", "out"], "plot"),
    (["xarray"], ["sweep", "sweep.nml", "-o", "out"], "sweep"),
    (["distributed", "dask.distributed"], ["sweep", "sweep.nml", "-o", "out", "--workers", "1"], "sweep"),
    (["scipy", "scipy.special", "scipy.integrate"], ["bench", "elliptic", "--json", ""], "bench"),
    (["scipy", "scipy.special"], ["accuracy", "elliptic"], "accuracy"),
    (["matplotlib"], ["demo", "-o", "out"], "all"),
])
def test_cli_names_the_missing_extra_in_the_development_build(tmp_path, hidden, args, extra):
    (tmp_path / "sweep.nml").write_text(SWEEP_SCENE)
    out = run_hidden(hidden, args, tmp_path)
    assert_kind_failure(out, extra)
    assert hidden[0] in out.stderr


def test_missing_extra_is_an_import_error_naming_the_extra():
    from pendula._optional import MissingExtraError, require

    with pytest.raises(MissingExtraError, match=r"^pendula.sweep needs no_such_module_for_pendula, which is not "
                                               r"installed: pip install 'pendula\[sweep\]'$") as info:
        require("no_such_module_for_pendula.sub", "sweep", "pendula.sweep")
    assert isinstance(info.value, ImportError) and info.value.name == "no_such_module_for_pendula"


def test_optional_docstring_examples():
    import doctest

    import pendula._optional as mod

    failures, tried = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert failures == 0 and tried >= 4


def test_cli_into_a_closed_pipe_is_quiet_in_the_development_build(tmp_path):
    code = "import sys; from pendula.cli import main; sys.exit(main(['models']))"
    out = subprocess.run(["bash", "-o", "pipefail", "-c", f'"{sys.executable}" -c "{code}" | true'], cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0 and out.stderr == "", (out.returncode, out.stderr)
