"""The compiled batch executable pendula-ellip."""

import subprocess

import numpy as np
import pytest

import pendula
from conftest import EPS, venv_bin


def run(text, *args):
    return subprocess.run([venv_bin("pendula-ellip"), *args], input=text, capture_output=True, text=True)


def test_rows_match_the_python_api():
    p = run("# comment\n0.5 0.3\n\n1e5 0.5   # trailing comment\n10 0.999 1e-3\n3 1\n")
    assert p.returncode == 0, p.stderr
    rows = np.array([[float(x) for x in ln.split()] for ln in p.stdout.splitlines() if not ln.startswith("#")])
    assert rows.shape == (4, 4)
    want = np.array(pendula.ellipj([0.5, 1e5, 10, 3], [0.3, 0.5, 0.999, 1.0], [0.7, 0.5, 1e-3, 0.0])).T
    assert np.abs(rows - want).max() <= 2 * EPS * np.abs(want).max()


def test_mc_column_reaches_1e_300(tmp_path):
    f = tmp_path / "in.txt"
    f.write_text("3.0 1 1e-300\n")
    p = run("", str(f))
    assert p.returncode == 0
    sn = float(p.stdout.splitlines()[1].split()[0])
    assert abs(sn - np.tanh(3.0)) <= 2 * EPS


@pytest.mark.parametrize("text,what", [
    ("0.5 0.3\n0.5 x\n", "line 2: not a number"),
    ("0.5\n", "line 1: expected 2 or 3 numbers"),
    ("0.5 0.3\n1 2 3 4\n", "line 2: expected 2 or 3 numbers"),
    ("1 0.3 0.5\n", "line 1: m and mc disagree"),
    ("1,0 0.3\n", "line 1: not a number"),
])
def test_malformed_rows_name_the_line_and_write_nothing(text, what):
    p = run(text)
    assert p.returncode == 2
    assert what in p.stderr
    assert p.stdout == ""


def test_missing_file_is_an_error():
    p = run("", "/nonexistent/file.txt")
    assert p.returncode == 2 and "cannot open" in p.stderr
