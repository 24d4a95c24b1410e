"""fecontact from Python.

    import fecontact
    with fecontact.Scene(options_file="input/ball_drop.opts", options={"time_steps": 50}) as s:
        s.step(10)
        print(s.time, s.body("ball").centroid, s.contacts()["force"])
    o = fecontact.Output("out/ball_drop.h5")          # a run's HDF5 file, without MPI

Scene, Body and FecontactError (fecontact.scene) drive the C library through ctypes and need
petsc4py, which they import at their first use; Output (fecontact.output) reads a run's file with
h5py alone. docs/python.md."""

from . import _lib

try:  # the C library now, before petsc4py loads PETSc (fecontact/_lib.py); the reader needs none
    _lib.load()
except OSError:
    pass

__version__ = "0.1.0"
__all__ = ["Scene", "Body", "FecontactError", "Output"]


def __getattr__(name):
    if name in ("Scene", "Body", "FecontactError"):
        from . import scene
        return getattr(scene, name)
    if name == "Output":
        from . import output
        return output.Output
    raise AttributeError("module 'fecontact' has no attribute '%s'" % name)
