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


def test_make_test_deselects_full_and_test_full_runs_it():
    make = (ROOT / "Makefile").read_text()
    test = re.search(r"^test: .*\n\t(.*)$", make, re.M).group(1)
    full = re.search(r"^test-full: .*\n\t(.*)$", make, re.M).group(1)
    assert '-m "not full"' in test and "-m full" in full


def test_ci_runs_both_halves():
    run = (ROOT / ".ci" / "run").read_text().splitlines()
    assert "make test" in run and "make test-full" in run
