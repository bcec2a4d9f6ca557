"""One scene reader, one verdict: pendula-run and `pendula run` both read and
check scenes with the kernel's reader, so they accept and refuse every file of
the corpus (tests/scenes/valid, tests/scenes/invalid) alike, with the same exit
status and the same message; a refused scene leaves no output file behind."""

import pathlib
import subprocess

import pytest

from conftest import venv_bin
from pendula import Scene, SceneError
from pendula.cli import main

HERE = pathlib.Path(__file__).resolve().parent / "scenes"
VALID = sorted((HERE / "valid").glob("*.nml"))
INVALID = sorted((HERE / "invalid").glob("*.nml"))
EXE = venv_bin("pendula-run")


def native(path, out):
    return subprocess.run([EXE, str(path), "-o", str(out)], capture_output=True, text=True, timeout=120)


def python_run(path, out, capsys):
    capsys.readouterr()
    code = main(["run", str(path), "-o", str(out), "-q"])
    return code, capsys.readouterr().err.strip()


def test_corpus_is_there():
    assert len(VALID) >= 10 and len(INVALID) >= 40


@pytest.mark.parametrize("path", VALID + INVALID, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_both_programs_give_one_verdict_with_one_message(path, tmp_path, capsys):
    p = native(path, tmp_path / "o.csv")
    code, err = python_run(path, tmp_path / "py", capsys)
    assert code == p.returncode, (code, err, p.returncode, p.stderr)
    if code:
        assert p.stderr.startswith("pendula-run: ") and err.startswith("pendula run: ")
        assert err.removeprefix("pendula run: ") == p.stderr.strip().removeprefix("pendula-run: ")
        assert "Traceback" not in err and "runtime error" not in p.stderr.lower()
    if path in VALID:
        assert code == 0, err
    else:
        assert code == 2, err
        assert str(path) in err
        # nothing written by either program
        assert [f.name for f in tmp_path.iterdir() if f.name != "py"] == []
        assert not (tmp_path / "py").exists() or list((tmp_path / "py").iterdir()) == []


@pytest.mark.parametrize("path", VALID, ids=lambda p: p.stem)
def test_valid_scene_settles_the_same_numbers_in_both_programs(path, tmp_path):
    scene = Scene.from_file(path)
    p = native(path, tmp_path / "o.csv")
    assert p.returncode == 0, p.stderr
    header = (tmp_path / "o.csv").read_text().splitlines()[1]
    got = dict(kv.split(" = ") for kv in header.lstrip("# ").split(", ")[:3])
    assert float(got["eps"]) == scene.eps
    assert float(got["theta0"]) == scene.theta0 and float(got["v0"]) == scene.v0


@pytest.mark.parametrize("path", INVALID, ids=lambda p: p.stem)
def test_invalid_scene_is_refused_by_scene_from_file_with_the_native_message(path):
    with pytest.raises(SceneError) as exc:
        Scene.from_file(path)
    p = subprocess.run([EXE, str(path), "--check"], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2
    assert p.stderr.strip() == "pendula-run: " + str(exc.value)


def test_replace_eps_really_changes_eps():
    s = Scene(g=9.81, length=2.0)
    assert s.eps == 9.81 / 2.0
    assert s.replace(eps=1.0).eps == 1.0
    assert s.replace(length=1.0).eps == 9.81
    assert [m.eps for m in s.replace(sweep="eps", sweep_values=(0.5, 2.0)).members()] == [0.5, 2.0]


def test_eps_contradicting_g_and_length_is_an_error():
    with pytest.raises(SceneError, match="contradict"):
        Scene(g=9.81, length=1.0, eps=5.0)


def test_huge_integer_is_an_error_naming_the_field():
    with pytest.raises(SceneError, match="v0"):
        Scene(v0=10**400)
