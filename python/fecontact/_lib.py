"""Finding and loading libfecontact.so (no petsc4py, no MPI initialization here).

The library is loaded with RTLD_GLOBAL, and before petsc4py loads PETSc and MUMPS if fecontact is
imported first: the library defines the BLAS symbol dgemm_ (src/util/blas.c, a one-column product
computed as dgemv_), which MUMPS must bind to as it does in the executable. Loaded after petsc4py,
MUMPS keeps the BLAS library's dgemm_: results then differ from the executable's at round-off, and
solves with one right-hand side are slower."""
import ctypes
import ctypes.util
import os
import subprocess
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
_lib = None
#: petsc4py had loaded PETSc before fecontact loaded its library (see above)
petsc_first = "petsc4py.PETSc" in sys.modules


def path():
    """libfecontact.so: $FECONTACT_LIBRARY, else the build tree this package sits in
    (<repo>/python/fecontact -> <repo>/build), else the installed one (the loader's path, then
    pkg-config's libdir); None if none is found"""
    env = os.environ.get("FECONTACT_LIBRARY")
    if env:
        return env
    tree = os.path.join(_HERE, "..", "..", "build", "libfecontact.so")
    if os.path.exists(tree):
        return os.path.abspath(tree)
    found = ctypes.util.find_library("fecontact")
    if found:
        return found
    try:
        libdir = subprocess.run(["pkg-config", "--variable=libdir", "fecontact"], capture_output=True, text=True,
                                check=True).stdout.strip()
        if libdir and os.path.exists(os.path.join(libdir, "libfecontact.so")):
            return os.path.join(libdir, "libfecontact.so")
    except (OSError, subprocess.CalledProcessError):
        pass
    return None


def load():
    """The library, loaded once (RTLD_GLOBAL); OSError if it cannot be found or loaded"""
    global _lib
    if _lib is None:
        p = path()
        if p is None:
            raise OSError("libfecontact.so not found: build fecontact (scripts/build.sh), install it "
                          "(cmake --install build), or set FECONTACT_LIBRARY to its path")
        _lib = ctypes.CDLL(p, mode=ctypes.RTLD_GLOBAL)
    return _lib
