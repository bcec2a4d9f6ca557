"""`make test` deselects the tests marked ``full``; `make test-full` runs them; CI runs both.

The list is tests/conftest.py's FULL.  A name there that no longer names a test
function would silently move nothing: each must be a test of its file.  And
the Makefile and CI must keep running both halves.
"""

import ast
import pathlib
import re

import conftest

TESTS = pathlib.Path(__file__).resolve().parent
ROOT = TESTS.parent


def test_every_full_test_exists():
    missing = []
    for entry in conftest.FULL:
        fname, func = entry.split("::")
        tree = ast.parse((TESTS / fname).read_text())
        names = {n.name for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
        if func not in names:
            missing.append(entry)
    assert not missing, missing
    assert len(set(conftest.FULL)) == len(conftest.FULL)


def test_every_full_case_names_a_collected_parametrisation():
    """A case of FULL_CASES names its function, and, when its file was collected in this run, one of
    the parametrisations collected (a renamed page or module would otherwise move nothing)."""
    collected_files = {name.split("::")[0] for name in conftest.COLLECTED}
    for entry in conftest.FULL_CASES:
        fname, case = entry.split("::")
        func = case.split("[")[0]
        tree = ast.parse((TESTS / fname).read_text())
        assert func in {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}, entry
        if fname in collected_files:
            assert entry in conftest.COLLECTED, f"{entry} is not among the collected tests"
    assert len(set(conftest.FULL_CASES)) == len(conftest.FULL_CASES)


def test_make_test_deselects_full_and_test_full_runs_it():
    make = (ROOT / "Makefile").read_text()
    test = re.search(r"^test: .*\n\t(.*)$", make, re.M).group(1)
    full = re.search(r"^test-full: .*\n\t(.*)$", make, re.M).group(1)
    assert '-m "not full"' in test and "-m full" in full


def test_ci_runs_both_halves():
    run = (ROOT / ".ci" / "run").read_text().splitlines()
    assert "make test" in run and "make test-full" in run
