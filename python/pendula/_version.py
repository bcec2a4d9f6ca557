"""The version of the installed distribution.

Written in one place, meson.build's ``project(version: ...)``; meson-python puts
it into the distribution's metadata, and this module reads it from there.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version


def _installed_version() -> str:
    try:
        return version("pendula")
    except PackageNotFoundError:  # imported from a build folder that was never installed
        return "0+unknown"


__version__ = _installed_version()
