"""Optional packages: one import helper that names the extra to install.

pendula itself needs only numpy (and tqdm for its progress bars, which are
simply not drawn without it).  Figures need matplotlib, results as Datasets
xarray, sweeps at scale dask and zarr, the benchmarks and the accuracy
reports compare with scipy.
Each of these is imported through :func:`require`, so that a missing package
gives one line saying what to install (``pip install 'pendula[sweep]'``)
instead of a bare ``ModuleNotFoundError``; the ``pendula`` command prints that
line and exits with :data:`EXIT_MISSING_EXTRA`.

The extras (``[project.optional-dependencies]`` in pyproject.toml):

=========  ==============================================  =========================
extra      packages                                        needed by
=========  ==============================================  =========================
plot       matplotlib                                      figures (``pendula run``; its
                                                           CSV tables need only numpy)
xarray     xarray                                          results as Datasets: ``sweep``
                                                           in memory, ``iv_curve``, the
                                                           ``to_xarray`` methods
sweep      xarray, dask[distributed], tqdm, scipy, zarr    ``sweep(out=...)`` (the Zarr
                                                           store), ``client=``, ``pendula
                                                           sweep`` (``--netcdf``: scipy)
bench      scipy; the work-precision study's peers         ``pendula bench``,
           (scikit-sundae, numbalsoda, numba)              ``pendula accuracy integrators``
accuracy   scipy, matplotlib                               ``pendula accuracy``
all        all of the above                                ``pendula demo``
=========  ==============================================  =========================
"""

from __future__ import annotations

import importlib
import sys

__all__ = ["MissingExtraError", "require", "EXIT_MISSING_EXTRA"]

#: exit status of the ``pendula`` command when an optional package is missing
EXIT_MISSING_EXTRA = 6


class MissingExtraError(ImportError):
    """An optional package is missing; the message names the extra that installs it.

    Parameters
    ----------
    package : str
        The top-level name of the missing package (``"xarray"``).
    extra : str
        The pendula extra that installs it (``"sweep"``; several as ``"plot,sweep"``).
    feature : str
        What needs it, as a user would name it (``"pendula.sweep"``).

    Examples
    --------
    >>> err = MissingExtraError("xarray", "sweep", "pendula.sweep")
    >>> print(err)
    pendula.sweep needs xarray, which is not installed: pip install 'pendula[sweep]'
    >>> isinstance(err, ImportError), err.name, err.extra
    (True, 'xarray', 'sweep')
    """

    def __init__(self, package: str, extra: str, feature: str):
        super().__init__(f"{feature} needs {package}, which is not installed: pip install 'pendula[{extra}]'",
                         name=package)
        self.extra = extra
        self.feature = feature


def require(module: str, extra: str, feature: str):
    """Import ``module``, or raise :class:`MissingExtraError` naming the extra.

    Parameters
    ----------
    module : str
        The module to import, dotted names allowed (``"scipy.special"``).
    extra : str
        The pendula extra that provides it (``"bench"``).
    feature : str
        What needs it, for the message (``"pendula bench"``).

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtraError
        When the module's top-level package is not installed.  An ImportError
        raised from inside an installed package (a broken installation) is not
        hidden: it propagates unchanged.

    Examples
    --------
    >>> require("json", "plot", "a figure").dumps([1])
    '[1]'
    >>> require("no_such_package_xyz.sub", "sweep", "pendula.sweep")
    Traceback (most recent call last):
      ...
    pendula._optional.MissingExtraError: pendula.sweep needs no_such_package_xyz, which is not installed: \
pip install 'pendula[sweep]'
    """
    loaded = sys.modules.get(module)
    if loaded is not None:      # imported already: the common case, kept cheap for per-call checks
        return loaded
    before = set(sys.modules)
    try:
        return importlib.import_module(module)
    except KeyboardInterrupt:
        # Ctrl-C in the middle of a (slow, lazy) import: the modules it made are half made, and a later
        # import would find them in sys.modules as they are (xarray without DataTree); forget them all so
        # that the process stays usable and the next import starts clean
        for name in set(sys.modules) - before:
            sys.modules.pop(name, None)
        raise
    except ModuleNotFoundError as exc:
        top = module.split(".")[0]
        missing = (exc.name or "").split(".")[0]
        if missing != top:
            raise  # the package is there but one of its own dependencies is not: show it as it is
        raise MissingExtraError(top, extra, feature) from None
