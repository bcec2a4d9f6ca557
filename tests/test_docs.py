"""The examples in the docstrings run and print what they say."""

import doctest
import importlib

import pytest

MODULES = ["pendula.elliptic", "pendula.motion", "pendula.series", "pendula.spectrum", "pendula.scene",
           "pendula.integrate",
           "pendula.density", "pendula.systems.cycloid", "pendula.systems.gravity"]  # issue 13


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    mod = importlib.import_module(name)
    failures, tried = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert failures == 0
