"""The LAPACK routines of the dense statics: Cholesky (``potrf``, ``potrs``; ``cholesky``
and ``cholesky_solve``) and LU (``gesv``), scipy's own double-precision ones, without the
cost of importing scipy.linalg.

``import scipy.linalg`` takes 0.2 to 0.6 s (its array-API layer imports numpy.f2py,
numpy.testing and numpy.ma), several times what a small design's whole check takes, while
the routines themselves live in one compiled module, ``scipy/linalg/_flapack``, that needs
only numpy.  ``routines()`` loads that file directly, once, on the first solve; where that
cannot be done (an unusual scipy build or layout) it imports ``scipy.linalg.lapack``
instead.  Either way the functions are the same objects that
``scipy.linalg.lapack.get_lapack_funcs(name, (float64 array,))`` returns, so the numbers
are the same to the last bit (numpy's own LAPACK is a different build; numpy has no
triangular solve either).

The module itself imports only the standard library.
"""

from __future__ import annotations

import functools
import importlib.machinery
import importlib.util
import os
from typing import NamedTuple

FLAPACK = "scipy.linalg._flapack"
"""The compiled module holding scipy's LAPACK wrappers (``d``: double precision)."""


class Routines(NamedTuple):
    """The double-precision routines, called as scipy's wrappers are:
    ``potrf(a, lower=0, clean=0) -> (factor, info)``, ``potrs(factor, b, lower=0) -> (x,
    info)``, ``gesv(a, b) -> (lu, piv, x, info)``; ``source``: where they came from
    ('file': ``_flapack`` loaded directly, 'scipy.linalg': imported through scipy)."""

    potrf: object
    potrs: object
    gesv: object
    source: str
    pbtrf: object = None
    pbtrs: object = None


@functools.cache
def routines() -> Routines:
    """scipy's double-precision potrf, potrs and gesv (see the module docstring)."""
    module = _load_flapack_file()
    if module is not None:
        return Routines(module.dpotrf, module.dpotrs, module.dgesv, "file", module.dpbtrf,
                        module.dpbtrs)
    import numpy as np
    from scipy.linalg import lapack

    found = lapack.get_lapack_funcs(("potrf", "potrs", "gesv", "pbtrf", "pbtrs"),
                                    (np.zeros(1),))
    return Routines(*found[:3], "scipy.linalg", *found[3:])


def _load_flapack_file():
    """The ``_flapack`` extension module loaded from its file in scipy's folder, or None.
    scipy's packages are not imported (Python enters the module itself in ``sys.modules``
    under its name, where a later ``import scipy.linalg`` finds and keeps it)."""
    try:
        spec = importlib.util.find_spec("scipy")
        if spec is None or not spec.submodule_search_locations:
            return None
        folder = os.path.join(list(spec.submodule_search_locations)[0], "linalg")
        for suffix in importlib.machinery.EXTENSION_SUFFIXES:
            path = os.path.join(folder, "_flapack" + suffix)
            if os.path.isfile(path):
                file_spec = importlib.util.spec_from_file_location(FLAPACK, path)
                module = importlib.util.module_from_spec(file_spec)
                file_spec.loader.exec_module(module)
                if all(hasattr(module, name)
                       for name in ("dpotrf", "dpotrs", "dgesv", "dpbtrf", "dpbtrs")):
                    return module
                return None
    except (ImportError, OSError, AttributeError, ValueError):
        return None
    return None


def cholesky(matrix):
    """The upper Cholesky factor of a symmetric matrix (its upper triangle read), None if
    it is not positive definite (LAPACK's potrf directly: scipy's wrappers cost more than
    the factoring of these small matrices)."""
    factor, info = routines().potrf(matrix, lower=0, clean=0)
    return factor if info == 0 else None


def cholesky_solve(factor, rhs):
    """x with U^T U x = rhs for the upper Cholesky factor U (``cholesky``)."""
    x, _ = routines().potrs(factor, rhs, lower=0)
    return x


def banded_cholesky(bands):
    """The upper Cholesky factor of a symmetric banded matrix in LAPACK's upper band
    storage (``bands[u + i - j, j] = A[i, j]`` for i <= j, u the bands above the
    diagonal), None if it is not positive definite (``pbtrf``)."""
    factor, info = routines().pbtrf(bands, lower=0)
    return factor if info == 0 else None


def banded_solve(factor, rhs):
    """x with U^T U x = rhs for a ``banded_cholesky`` factor U (``pbtrs``)."""
    x, _ = routines().pbtrs(factor, rhs, lower=0)
    return x
