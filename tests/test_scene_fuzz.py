"""Fuzz: pendula-run and Scene.from_file give one verdict on mutated scene files.

Each example takes a file of the corpus (tests/scenes) and applies a few
random edits (characters of namelist syntax inserted, deleted or replaced,
lines doubled or dropped); ``pendula-run FILE --check`` (the batch program's
reading and checking, nothing run) and :meth:`pendula.Scene.from_file` (what
``pendula run`` reads with) must both accept it, or both refuse it with the
same message.  Seeded (derandomized), a few hundred examples.
"""

import pathlib
import subprocess
import tempfile

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import venv_bin
from pendula import Scene, SceneError

HERE = pathlib.Path(__file__).resolve().parent / "scenes"
CORPUS = [p.read_bytes().decode("utf-8", errors="replace") for p in sorted(HERE.glob("*/*.nml"))
          if p.stat().st_size < 2000]
ALPHABET = list("&/=,'\"!*.+-eEdD0123456789 \nabc_()") + [
    "v0", "eps", "&scene", ".true.", "nan", "inf", "1e400", "1d999", "'rk4'", "sweep", "3*", "''",
    "grid", "grid1", "grid2_range", "measure", "'locked'", "'spectrum'", "'series'", "'lindstedt'", "'period'",
    "outputs", "theta0", "1e308", "dt", "'cycloid'", "'flexible'", "4.0"]
EXE = venv_bin("pendula-run")
WORK = pathlib.Path(tempfile.mkdtemp(prefix="pendula_scene_fuzz_"))


def native_verdict(path: pathlib.Path) -> tuple[bool, str]:
    p = subprocess.run([EXE, str(path), "--check"], capture_output=True, timeout=60)
    err = p.stderr.decode("utf-8", errors="replace").strip()
    assert p.returncode in (0, 2), (p.returncode, err)
    return p.returncode == 0, err.removeprefix("pendula-run: ")


def python_verdict(path: pathlib.Path) -> tuple[bool, str]:
    try:
        Scene.from_file(path)
        return True, ""
    except SceneError as exc:
        return False, str(exc)


@st.composite
def mutated(draw):
    text = draw(st.sampled_from(CORPUS))
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(["insert", "delete", "replace", "dup_line", "drop_line"]))
        pos = draw(st.integers(0, max(len(text) - 1, 0)))
        if kind == "insert":
            text = text[:pos] + draw(st.sampled_from(ALPHABET)) + text[pos:]
        elif kind == "delete":
            text = text[:pos] + text[pos + 1:]
        elif kind == "replace":
            text = text[:pos] + draw(st.sampled_from(ALPHABET)) + text[pos + 1:]
        else:
            lines = text.split("\n")
            k = draw(st.integers(0, max(len(lines) - 1, 0)))
            if kind == "dup_line":
                lines.insert(k, lines[k])
            elif len(lines) > 1:
                del lines[k]
            text = "\n".join(lines)
    return text


@settings(max_examples=300, derandomize=True, deadline=None, suppress_health_check=list(HealthCheck))
@given(mutated())
def test_both_programs_accept_or_refuse_alike_with_one_message(text):
    path = WORK / "fuzz.nml"
    path.write_bytes(text.encode("utf-8", errors="surrogateescape"))
    py_ok, py_msg = python_verdict(path)
    n_ok, n_msg = native_verdict(path)
    assert (py_ok, py_msg) == (n_ok, n_msg), f"python: {py_ok} {py_msg}\nnative: {n_ok} {n_msg}\n---\n{text}"


@pytest.mark.parametrize("path", sorted(HERE.glob("valid/*.nml"))[:4] + sorted(HERE.glob("invalid/*.nml"))[:4],
                         ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_fuzz_harness_sees_acceptance_and_refusal(path):
    # the harness is not blind: the corpus files get the verdicts their folders say, from both
    expected = path.parent.name == "valid"
    assert python_verdict(path)[0] == native_verdict(path)[0] == expected
