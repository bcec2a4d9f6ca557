"""Scene files of the systems built by their own class (&double, &foucault, &network) through
Python: ``pendula run FILE`` reads, checks and runs them through the kernel's one reader and run
(kernel/dispatch/pendula_system_scenes.f90), so pendula-run (the independent route here: the
Fortran program's own text output) and the Python CLI give every file the same verdict, the same
message and exit status, and the same table to the bit.
"""

import subprocess

import numpy as np
import pytest

from pendula import cli
from pendula._system_scenes import system_group, system_table
from pendula.scene import SceneError

from conftest import DATA, venv_bin

EXAMPLES = sorted((DATA / "scenes" / "systems").glob("*.nml"))


def _fortran(path):
    return subprocess.run([venv_bin("pendula-run"), str(path)], capture_output=True, text=True)


def _python(path, outdir, capsys):
    code = cli.main(["run", str(path), "-o", str(outdir), "-q"])
    return code, capsys.readouterr()


def _rows(text):
    """The column line and the data lines of a table (comment lines dropped)."""
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    return lines[0], lines[1:]


def test_every_example_is_one_of_the_three_systems():
    assert [system_group(p) for p in EXAMPLES] == ["double", "foucault", "network"]


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_python_cli_writes_the_table_of_pendula_run_to_the_bit(tmp_path, capsys, path):
    ref = _fortran(path)
    assert ref.returncode == 0, ref.stderr
    code, out = _python(path, tmp_path, capsys)
    assert code == 0, out.err
    csv = tmp_path / f"{path.stem}.csv"
    png = tmp_path / f"{path.stem}.png"
    assert out.out.split() == [str(csv), str(png)]
    assert png.stat().st_size > 0
    heads_f, rows_f = _rows(ref.stdout)
    heads_p, rows_p = _rows(csv.read_text())
    assert heads_p == heads_f
    assert len(rows_p) == len(rows_f) > 1
    a = np.array([[float(x) for x in r.split(",")] for r in rows_f])
    b = np.array([[float(x) for x in r.split(",")] for r in rows_p])
    np.testing.assert_array_equal(b, a)         # the same doubles
    assert rows_p == rows_f                     # and the same text (17 significant digits)


MALFORMED = [
    ("double", "m1 = -1.0"), ("double", "theta1 = abc"), ("double", "mass = 1.0"),
    ("double", "method = 'gauss6', dt = 0.03, t_end = 1.0, n_samples = 11"), ("double", "rods = 3"),
    ("foucault", "latitude = 91.0"), ("foucault", "theta0 = 2.0"), ("foucault", "length = 'x'"),
    ("foucault", "theta0 = 0.0, phi_dot0 = 1.0"), ("foucault", "n_samples = 0"),
    ("network", "n = 0"), ("network", "n = 3, topology = 'ring', mass = 1.0, 2.0"),
    ("network", "n = 3, topology = 'ladder'"), ("network", "strength = -1.0"), ("network", "topology = 5"),
    ("network", "n = 2, method = 'rk4'"),
]


@pytest.mark.parametrize("group, body", MALFORMED, ids=[f"{g}:{b}" for g, b in MALFORMED])
def test_a_malformed_file_gets_the_verdict_of_pendula_run(tmp_path, capsys, group, body):
    f = tmp_path / "bad.nml"
    f.write_text(f"! a comment line\n&{group}\n  {body}\n/\n")
    ref = _fortran(f)
    assert ref.returncode == 2
    code, out = _python(f, tmp_path / "out", capsys)
    assert code == ref.returncode
    assert out.err.strip().removeprefix("pendula run: ") == ref.stderr.strip().removeprefix("pendula-run: ")
    assert f"&{group}" in out.err
    assert not (tmp_path / "out" / "bad.csv").exists()
    with pytest.raises(SceneError, match=f"&{group}"):
        system_table(f)


def test_a_file_of_no_group_is_refused_as_pendula_run_refuses_it(tmp_path, capsys):
    f = tmp_path / "empty.nml"
    f.write_text("! no group here\n")
    ref = _fortran(f)
    code, out = _python(f, tmp_path / "out", capsys)
    assert system_group(f) == ""
    assert code == ref.returncode == 2
    assert "&scene" in out.err and "&scene" in ref.stderr



# ---------------------------------------------------------------- the text as a system and its run request

SIMULATED = {"double": ("theta1", "theta2", "omega1", "omega2", "energy"),
             "foucault": ("x", "y", "z", "vx", "vy", "vz")}


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_system_from_namelist_runs_as_pendula_run_runs_the_file(path):
    """The system and its run request read from the text, run by the class's own simulate: the numbers of
    pendula-run's table to the bit (the class and the scene share the n-dimensional driver)."""
    from pendula import system_from_namelist

    ref = _fortran(path)
    assert ref.returncode == 0, ref.stderr
    heads, rows = _rows(ref.stdout)
    table = np.array([[float(x) for x in r.split(",")] for r in rows])
    system, run = system_from_namelist(path.read_text(), source=str(path))
    ds = system.simulate(**run)
    np.testing.assert_array_equal(run["t"], table[:, 0])
    group = system_group(path)
    if group == "network":
        n = system.n
        np.testing.assert_array_equal(ds["phi"].values, table[:, 1:n + 1])
        np.testing.assert_array_equal(ds["v"].values, table[:, n + 1:])
    else:
        for k, name in enumerate(SIMULATED[group], start=1):
            np.testing.assert_array_equal(ds[name].values, table[:, k], err_msg=name)


@pytest.mark.parametrize("group, body", MALFORMED, ids=[f"{g}:{b}" for g, b in MALFORMED])
def test_system_from_namelist_refuses_with_the_message_of_pendula_run(tmp_path, group, body):
    from pendula import system_from_namelist

    text = f"! a comment line\n&{group}\n  {body}\n/\n"
    f = tmp_path / "bad.nml"
    f.write_text(text)
    ref = _fortran(f)
    assert ref.returncode == 2
    with pytest.raises(SceneError) as err:
        system_from_namelist(text, source=str(f))
    assert str(err.value) == ref.stderr.strip().removeprefix("pendula-run: ")


@pytest.mark.parametrize("text", ["", "&scene eps = 1.0 /", "no group at all"])
def test_system_from_namelist_refuses_a_text_of_no_system(text):
    from pendula import system_from_namelist

    with pytest.raises(SceneError, match="&double, &foucault or &network"):
        system_from_namelist(text)


def test_a_run_that_fails_is_exit_4_with_the_message_of_pendula_run(tmp_path, capsys):
    """Damping 1e12 makes the double pendulum stiff: DOP853 stops (integrator status 6) at once.
    The computation failing is exit 4 in both programs, with the same message and no file left."""
    from pendula._system_scenes import SystemRunError

    f = tmp_path / "stiff.nml"
    f.write_text("&double\n theta1 = 2.0, damping = 1e12, 1e12, t_end = 10.0, n_samples = 2\n/\n")
    ref = _fortran(f)
    assert ref.returncode == 4, ref.stderr
    code, out = _python(f, tmp_path / "out", capsys)
    assert code == 4
    assert out.err.strip().removeprefix("pendula run: ") == ref.stderr.strip().removeprefix("pendula-run: ")
    assert not (tmp_path / "out" / "stiff.csv").exists()
    with pytest.raises(SystemRunError, match="integrator status"):
        system_table(f)


def test_an_output_folder_that_is_a_file_is_exit_5(tmp_path, capsys):
    """The table cannot be written (a file where the output folder should be): exit 5, as pendula-run's
    write errors, and the file is left as it was."""
    blocker = tmp_path / "out"
    blocker.write_text("not a folder\n")
    code, out = _python(EXAMPLES[0], blocker, capsys)
    assert code == 5 and "cannot write" in out.err
    assert blocker.read_text() == "not a folder\n"
