"""Write the small intersphinx inventories the docs build reads (no network).

The build machine has no internet, so intersphinx cannot download numpy's,
scipy's, xarray's, matplotlib's and Python's ``objects.inv``.  This script
writes, into ``docs/inventories/``, inventories holding only the names
pendula's pages and docstrings refer to, with the URLs of those projects'
published documentation.  Run it again after referring to a new outside name:

    .venv/bin/python docs/make_inventories.py
"""

from __future__ import annotations

import pathlib
import zlib

OUT = pathlib.Path(__file__).resolve().parent / "inventories"

# project: {name: (domain:role, uri)}; '$' in a uri stands for the name
INVENTORIES = {
    "python": {
        **{n: ("py:class", "library/functions.html#$") for n in
           ("float", "int", "str", "bool", "dict", "list", "tuple")},
        **{n: ("py:exception", "library/exceptions.html#$") for n in
           ("ValueError", "TypeError", "RuntimeWarning", "NotImplementedError", "OSError")},
        "fractions.Fraction": ("py:class", "library/fractions.html#$"),
        "pathlib.Path": ("py:class", "library/pathlib.html#$"),
        "os.PathLike": ("py:class", "library/os.html#$"),
    },
    "numpy": {
        "numpy.ndarray": ("py:class", "reference/generated/$.html#$"),
        **{f"numpy.{n}": ("py:function", "reference/generated/$.html#$") for n in
           ("linspace", "arange", "sin", "empty", "asarray")},
        "numpy.fft.rfft": ("py:function", "reference/generated/$.html#$"),
    },
    "scipy": {
        **{f"scipy.special.{n}": ("py:data", "reference/generated/$.html#$") for n in
           ("ellipj", "ellipk", "ellipkm1", "ellipe", "ellipkinc", "ellipeinc")},
        "scipy.integrate.solve_ivp": ("py:function", "reference/generated/$.html#$"),
    },
    "xarray": {
        "xarray.Dataset": ("py:class", "generated/$.html#$"),
        "xarray.DataArray": ("py:class", "generated/$.html#$"),
    },
    "matplotlib": {
        "matplotlib.figure.Figure": ("py:class", "api/figure_api.html#$"),
        "matplotlib.axes.Axes": ("py:class", "api/_as_gen/$.html#$"),
        "matplotlib.animation.FuncAnimation": ("py:class", "api/_as_gen/$.html#$"),
    },
}


def write(project: str, entries: dict) -> pathlib.Path:
    head = (f"# Sphinx inventory version 2\n# Project: {project}\n# Version: \n"
            "# The remainder of this file is compressed using zlib.\n").encode()
    lines = "".join(f"{name} {role} 1 {uri.replace('$', name) if uri.count('$') > 1 else uri} -\n"
                    for name, (role, uri) in sorted(entries.items()))
    path = OUT / f"{project}.inv"
    path.write_bytes(head + zlib.compress(lines.encode()))
    return path


if __name__ == "__main__":
    OUT.mkdir(exist_ok=True)
    for project, entries in INVENTORIES.items():
        print(write(project, entries))
