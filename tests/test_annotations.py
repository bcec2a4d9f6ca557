"""The public API is fully annotated, and its annotations resolve.

Every function of ``pendula.__all__`` and every public method of its classes
(``__init__``, ``__call__``, class and static methods, properties) annotates
each parameter and its return; ``typing.get_type_hints`` evaluates each
(string) annotation, so a misspelt or unimported name fails here.  The
optional packages (xarray, distributed) are named in annotations only under
``TYPE_CHECKING``; they are supplied as local names when resolving.
"""

from __future__ import annotations

import functools
import inspect
import typing

import pytest

import pendula

_SPECIAL = ("__init__", "__call__")


def _public_callables():
    """(qualified name, function) for every public function and public method."""
    out = []
    for name in pendula.__all__:
        obj = getattr(pendula, name)
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if attr.startswith("_") and attr not in _SPECIAL:
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                elif isinstance(member, property):
                    member = member.fget
                elif isinstance(member, functools.cached_property):
                    member = member.func
                if inspect.isfunction(member):
                    out.append((f"{name}.{attr}", member))
        elif callable(obj):
            out.append((name, inspect.unwrap(obj)))
    return out


def _missing_annotations(func) -> list[str]:
    """Parameters (and 'return') of ``func`` that carry no annotation."""
    sig = inspect.signature(func)
    params = list(sig.parameters.values())
    if params and params[0].name in ("self", "cls"):
        params = params[1:]
    missing = [p.name for p in params if p.annotation is inspect.Parameter.empty]
    if sig.return_annotation is inspect.Signature.empty:
        missing.append("return")
    return missing


PUBLIC = _public_callables()


def test_public_callables_are_found():
    names = {n for n, _ in PUBLIC}
    # functions, a cached function, methods, a classmethod and a property of the public API
    for expected in ("ellipk", "sweep", "period_series", "Scene.replace", "Scene.from_file",
                     "Trajectory.to_xarray", "CycloidGeometry.cord", "Spectrum.fundamental"):
        assert expected in names


def test_detector_flags_unannotated_parameter_and_return():
    def partly(x: float, y, *args, **kwargs: int):
        return x

    def whole(x: float, *args: int, **kwargs: str) -> float:
        return x

    assert _missing_annotations(partly) == ["y", "args", "return"]
    assert _missing_annotations(whole) == []


@pytest.mark.parametrize("name, func", PUBLIC, ids=[n for n, _ in PUBLIC])
def test_every_public_callable_is_fully_annotated(name, func):
    assert _missing_annotations(func) == [], f"{name} lacks annotations"


@pytest.mark.parametrize("name, func", PUBLIC, ids=[n for n, _ in PUBLIC])
def test_public_annotations_resolve(name, func):
    optional = {"xarray": pytest.importorskip("xarray"),
                "distributed": pytest.importorskip("distributed")}
    hints = typing.get_type_hints(func, localns=optional)
    assert "return" in hints
