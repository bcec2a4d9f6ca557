"""pendula: the nonlinear pendulum and its relatives.

Exact where exactness is possible (Jacobi elliptic functions for the
conservative pendulum), fast everywhere (a Fortran kernel), and honest about
what accuracy costs.

Elliptic functions
------------------
ellipk, ellipe, ellipf, ellipeinc, ellipj, nome
"""

from . import _kernel as _k

_k.gsl_init()  # GSL must never abort the process: switch its handler off once
del _k

from .elliptic import ellipe, ellipeinc, ellipf, ellipj, ellipk, nome  # noqa: E402

__version__ = "0.1.0"

__all__ = ["ellipk", "ellipe", "ellipf", "ellipeinc", "ellipj", "nome"]
