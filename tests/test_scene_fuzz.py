"""Fuzz: the two scene readers agree on mutated scene files.

Each example takes a file of the corpus (tests/scenes) and applies a few
random edits (characters of namelist syntax inserted, deleted or replaced,
lines doubled or dropped); the Python reader and the kernel's reader
(the one pendula-run uses, reached here through the binding) must both accept
or both refuse it.  Seeded (derandomized), a few hundred examples.
"""

import pathlib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pendula import Scene, SceneError, _kernel

HERE = pathlib.Path(__file__).resolve().parent / "scenes"
SEEDS = [p.read_bytes().decode("utf-8", errors="replace") for p in sorted(HERE.glob("*/*.nml"))
         if p.stat().st_size < 2000]
ALPHABET = list("&/=,'\"!*.+-eEdD0123456789 \nabc_()") + ["v0", "eps", "&scene", ".true.", "nan", "inf",
                                                           "1e400", "'rk4'", "sweep", "3*"]


def kernel_accepts(text: str) -> tuple[bool, str]:
    status, msg = _kernel.scene_check_v(text.encode("utf-8"))
    return status == 0, (msg.decode(errors="replace") if isinstance(msg, bytes) else str(msg)).strip()


def python_accepts(text: str) -> tuple[bool, str]:
    try:
        Scene.from_namelist(text)
        return True, ""
    except SceneError as exc:
        return False, str(exc)


@st.composite
def mutated(draw):
    text = draw(st.sampled_from(SEEDS))
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


@settings(max_examples=400, derandomize=True, deadline=None, suppress_health_check=list(HealthCheck))
@given(mutated())
def test_both_readers_accept_or_refuse_alike(text):
    py_ok, py_msg = python_accepts(text)
    k_ok, k_msg = kernel_accepts(text)
    assert py_ok == k_ok, f"python {'accepts' if py_ok else 'refuses: ' + py_msg}; " \
                          f"kernel {'accepts' if k_ok else 'refuses: ' + k_msg}\n---\n{text}"


@pytest.mark.parametrize("text", SEEDS[:5])
def test_fuzz_harness_sees_acceptance(text):
    # the harness is not blind: a valid file is accepted by both
    if "invalid" not in text:
        assert python_accepts(text)[0] == kernel_accepts(text)[0]
