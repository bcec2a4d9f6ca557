"""One scene-reader contract: Python's reader and pendula-run's native reader
accept and refuse the same files (tests/scenes/valid, tests/scenes/invalid),
and a refused scene leaves no output file behind."""

import pathlib
import subprocess

import pytest

from conftest import venv_bin
from pendula import Scene, SceneError

HERE = pathlib.Path(__file__).resolve().parent / "scenes"
VALID = sorted((HERE / "valid").glob("*.nml"))
INVALID = sorted((HERE / "invalid").glob("*.nml"))
EXE = venv_bin("pendula-run")


def _run(path, out):
    return subprocess.run([EXE, str(path), "-o", str(out)], capture_output=True, text=True, timeout=60)


def test_corpus_is_there():
    assert len(VALID) >= 10 and len(INVALID) >= 25


@pytest.mark.parametrize("path", VALID, ids=lambda p: p.stem)
def test_valid_scene_is_accepted_by_both_readers(path, tmp_path):
    scene = Scene.from_file(path)
    p = _run(path, tmp_path / "o.csv")
    assert p.returncode == 0, p.stderr
    header = (tmp_path / "o.csv").read_text().splitlines()[1]
    # both readers settled on the same eps, theta0 and v0
    got = dict(kv.split(" = ") for kv in header.lstrip("# ").split(", ")[:3])
    assert float(got["eps"]) == scene.eps
    assert float(got["theta0"]) == scene.theta0 and float(got["v0"]) == scene.v0


@pytest.mark.parametrize("path", INVALID, ids=lambda p: p.stem)
def test_invalid_scene_is_refused_by_both_readers_and_leaves_no_file(path, tmp_path):
    with pytest.raises(SceneError) as exc:
        Scene.from_file(path)
    assert str(path) in str(exc.value)
    p = _run(path, tmp_path / "o.csv")
    assert p.returncode == 2, (p.returncode, p.stdout[-200:], p.stderr)
    assert "Traceback" not in p.stderr and "runtime error" not in p.stderr.lower()
    assert p.stderr.startswith("pendula-run: ")
    assert list(tmp_path.iterdir()) == []


def test_python_command_refuses_without_traceback(tmp_path):
    import sys

    for path in INVALID:
        p = subprocess.run([sys.executable, "-m", "pendula", "run", str(path), "-o", str(tmp_path / "out"), "-q"],
                           capture_output=True, text=True, timeout=60)
        assert p.returncode == 2, (path.name, p.stderr)
        assert "Traceback" not in p.stderr, (path.name, p.stderr)
        assert not (tmp_path / "out").exists() or list((tmp_path / "out").iterdir()) == []


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
