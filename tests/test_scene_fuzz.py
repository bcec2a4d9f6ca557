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


# ------------------------------------------ the fields and the text: one check

# (NaN has no namelist spelling; infinity is written 1e999, which reads as infinity)
_NUMBERS = st.one_of(st.sampled_from([0.0, -1.0, 0.5, 1.0, 2.0, 4.0, 1.6, 1e-300, 1e300, 1e308, 2.0 ** 53,
                                      float("inf"), -float("inf")]),
                     st.floats(-10.0, 10.0, allow_nan=False))
_FIELD_VALUES = {
    "eps": _NUMBERS, "theta0": _NUMBERS, "v0": _NUMBERS, "t_start": _NUMBERS, "t_end": _NUMBERS,
    "damping": _NUMBERS, "torque": _NUMBERS, "drive_amplitude": _NUMBERS, "dt": _NUMBERS, "rtol": _NUMBERS,
    "cycloid_radius": _NUMBERS, "gravity_distance": _NUMBERS, "gravity_gradient": _NUMBERS,
    "restitution": _NUMBERS, "min_flight": _NUMBERS,
    "n_samples": st.integers(-2, 10 ** 9), "max_flips": st.integers(-2, 10 ** 9),
    "method": st.sampled_from(["auto", "exact", "rk4", "DOP853", "gsl-rk8pd", "rk5", ""]),
    "cord": st.sampled_from(["rigid", "flexible", "elastic"]),
    "guide": st.sampled_from(["none", "cycloid", "cycloyd"]),
    "gravity": st.sampled_from(["uniform", "linear", "inverse-square", ""]),
    "outputs": st.lists(st.sampled_from(["trajectory", "spectrum", "series", "lindstedt", "period", "omega",
                                         "theta_t", "thetat", ""]), min_size=1, max_size=3).map(tuple),
    "sweep": st.sampled_from(["", "v0", "theta0", "eps", "damping", "drive_phase"]),
    "sweep_values": st.lists(_NUMBERS, max_size=3).map(tuple),
}


def _namelist(kw: dict) -> str:
    from pendula.scene import _fmt as fmt

    def _fmt(x):
        return ("-1e999" if x < 0 else "1e999") if isinstance(x, float) and abs(x) == float("inf") else fmt(x)

    return "&scene\n" + "\n".join(f"  {k} = " + (", ".join(_fmt(x) for x in v) if isinstance(v, tuple)
                                                  else _fmt(v)) for k, v in kw.items() if v != ()) + "\n/\n"


@settings(max_examples=300, derandomize=True, deadline=None, suppress_health_check=list(HealthCheck))
@given(st.fixed_dictionaries({}, optional=_FIELD_VALUES))
def test_scene_of_fields_and_scene_of_text_get_one_verdict_with_one_message(kw):
    import re

    verdicts = []
    for make in (lambda: Scene(**kw), lambda: Scene.from_namelist(_namelist(kw))):
        try:
            verdicts.append((True, make()))
        except SceneError as exc:
            verdicts.append((False, re.sub(r"^<scene>(, line \d+)?: ", "", str(exc))))
    (ok_f, got_f), (ok_t, got_t) = verdicts
    assert ok_f == ok_t and (got_f == got_t or ok_f), (kw, got_f, got_t)
    if ok_f:
        assert got_t == got_f, (kw, got_f, got_t)
