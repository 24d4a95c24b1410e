"""fecontact scenes from Python: the C library (libfecontact.so, include/fecontact.h) through ctypes,
with petsc4py for PETSc itself (its initialization, the MPI communicator).

A Scene is built from the options the executable takes (an options file and/or options), in an
options database of its own, so that two scenes of one script do not share options. Every call into
the library runs with fecontact's error handler; an error raises FecontactError with fecontact's
message, and the interpreter goes on."""
import atexit
import ctypes
import os
import warnings
import weakref

import numpy as np

from . import _lib as _loader

_lib = _loader.load()  # before petsc4py loads PETSc (fecontact/_lib.py)
from petsc4py import PETSc  # noqa: E402


class FecontactError(RuntimeError):
    """An error of fecontact (a wrong option or input, a run that diverged, ...): its message"""


if _loader.petsc_first:
    warnings.warn("petsc4py was imported before fecontact: MUMPS keeps the BLAS library's dgemm_, so results differ "
                  "from the executable's at round-off and one-column solves are slower; import fecontact first "
                  "(docs/python.md)", RuntimeWarning, stacklevel=2)

INT = np.dtype(PETSc.IntType)
REAL = np.dtype(PETSc.RealType)
_cint = ctypes.c_int32 if INT.itemsize == 4 else ctypes.c_int64
_creal = ctypes.c_double
_ptr = ctypes.c_void_p
_real3 = np.ctypeslib.ndpointer(dtype=REAL, flags="C_CONTIGUOUS")

# FCContactInfo (include/fecontact.h), the C layout
CONTACT = np.dtype([("body", INT, 2), ("point", REAL, 3), ("normal", REAL, 3), ("force", REAL, 3),
                    ("force_world", REAL, 3), ("gap", REAL), ("gap_end", REAL), ("state", INT)], align=True)


def _declare(name, *args, restype=ctypes.c_int):
    f = getattr(_lib, name)
    f.argtypes = list(args)
    f.restype = restype
    return f


_FCPushErrorHandler = _declare("FCPushErrorHandler", ctypes.c_int)
_PetscPopErrorHandler = _declare("PetscPopErrorHandler")
_FCGetLastErrorMessage = _declare("FCGetLastErrorMessage", restype=ctypes.c_char_p)
_MPI_Comm_f2c = _declare("MPI_Comm_f2c", ctypes.c_int, restype=_ptr)
_PetscOptionsCreate = _declare("PetscOptionsCreate", ctypes.POINTER(_ptr))
_PetscOptionsDestroy = _declare("PetscOptionsDestroy", ctypes.POINTER(_ptr))
_PetscOptionsInsertFile = _declare("PetscOptionsInsertFile", _ptr, _ptr, ctypes.c_char_p, ctypes.c_int)
_PetscOptionsInsertString = _declare("PetscOptionsInsertString", _ptr, ctypes.c_char_p)
_PetscOptionsSetValue = _declare("PetscOptionsSetValue", _ptr, ctypes.c_char_p, ctypes.c_char_p)
_PetscOptionsPush = _declare("PetscOptionsPush", _ptr)
_PetscOptionsPop = _declare("PetscOptionsPop")
_FCSceneCreate = _declare("FCSceneCreate", _ptr, ctypes.POINTER(_ptr))
_FCSceneSetFromOptions = _declare("FCSceneSetFromOptions", _ptr)
_FCSceneSetUp = _declare("FCSceneSetUp", _ptr)
_FCSceneStep = _declare("FCSceneStep", _ptr)
_FCSceneRun = _declare("FCSceneRun", _ptr)
_FCSceneFinish = _declare("FCSceneFinish", _ptr)
_FCSceneDestroy = _declare("FCSceneDestroy", ctypes.POINTER(_ptr))
_FCSceneGetTime = _declare("FCSceneGetTime", _ptr, ctypes.POINTER(_creal), ctypes.POINTER(_cint))
_FCSceneGetTimeStep = _declare("FCSceneGetTimeStep", _ptr, ctypes.POINTER(_creal), ctypes.POINTER(_cint))
_FCSceneGetNumBodies = _declare("FCSceneGetNumBodies", _ptr, ctypes.POINTER(_cint))
_FCSceneGetBodyByIndex = _declare("FCSceneGetBodyByIndex", _ptr, _cint, ctypes.POINTER(_ptr))
_FCSceneGetBody = _declare("FCSceneGetBody", _ptr, ctypes.c_char_p, ctypes.POINTER(_ptr))
_FCSceneGetContacts = _declare("FCSceneGetContacts", _ptr, ctypes.POINTER(_cint), _ptr)
_FCBodyGetName = _declare("FCBodyGetName", _ptr, ctypes.POINTER(ctypes.c_char_p))
_FCBodyGetType = _declare("FCBodyGetType", _ptr, ctypes.POINTER(ctypes.c_char_p))
_FCBodyGetCentroid = _declare("FCBodyGetCentroid", _ptr, _real3)
_FCBodyGetRotation = _declare("FCBodyGetRotation", _ptr, _real3, ctypes.POINTER(ctypes.c_int))
_FCBodyGetVelocity = _declare("FCBodyGetVelocity", _ptr, _real3, _real3)
_FCBodyGetPositions = _declare("FCBodyGetPositions", _ptr, ctypes.c_int, ctypes.POINTER(_cint), _ptr)
_FCBodyGetVelocities = _declare("FCBodyGetVelocities", _ptr, ctypes.c_int, ctypes.POINTER(_cint), _ptr)
_FCBodySetKinematicPose = _declare("FCBodySetKinematicPose", _ptr, _real3, _real3)
_FCBodySetKinematicVelocity = _declare("FCBodySetKinematicVelocity", _ptr, _real3, _real3)
_FCBodyGetReactions = _declare("FCBodyGetReactions", _ptr, ctypes.POINTER(_cint),
                               ctypes.POINTER(ctypes.POINTER(ctypes.c_char_p)), ctypes.POINTER(ctypes.POINTER(_creal)))
_FCBodyGetEnergy = _declare("FCBodyGetEnergy", _ptr, _real3)


def _call(f, *args):
    """f(*args) with fecontact's error handler (no traceback printed: the message is raised)"""
    _FCPushErrorHandler(0)
    try:
        err = f(*args)
    finally:
        _PetscPopErrorHandler()
    if err:
        raise FecontactError(_FCGetLastErrorMessage().decode(errors="replace") or "fecontact error %d" % err)


def _comm_handle(comm):
    """The C MPI_Comm of a petsc4py or mpi4py communicator (PETSc.COMM_WORLD when None)"""
    if comm is None:
        comm = PETSc.COMM_WORLD
    if hasattr(comm, "py2f"):  # mpi4py
        fortran = comm.py2f()
    else:
        fortran = comm.fortran
    return _MPI_Comm_f2c(fortran)


def _vector(x, n, what):
    """x as n reals (a copy the C call may keep nothing of); ValueError naming what otherwise"""
    a = np.array(x, dtype=REAL).ravel()
    if a.shape != (n,):
        raise ValueError("%s must have %d components, got %s" % (what, n, np.shape(x)))
    return a


def _value(v):
    """An option's value as the options database holds it (None: an option without a value)"""
    if v is None:
        return None
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (list, tuple, np.ndarray)):
        return ",".join(repr(float(x)) if isinstance(x, (float, np.floating)) else str(x) for x in v)
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    return str(v)


def _is_name(word):
    """Whether a word of an option list is an option's name (-name, not a negative number)"""
    return len(word) > 1 and word[0] == "-" and not (word[1].isdigit() or word[1] == ".")


# options that PetscOptionsInsertString acts on rather than stores (another file, a prefix): passed as
# words, never as a name and its value
_DIRECTIVES = ("-options_file", "-options_file_yaml", "-options_string_yaml", "-prefix_push", "-prefix_pop")


def _option_pairs(options):
    """(name, value) pairs from a dict ({"time_steps": 10, "quiet": None}) or a list of strings
    (["-time_steps", "10"]), each value whole (a value with spaces, e.g. a trajectory "0:0,0,0; 1:1,0,0",
    is one value), and the text of a string (split at spaces by PETSc); returns (pairs, text)"""
    if options is None:
        return [], ""
    if isinstance(options, str):
        return [], options
    if isinstance(options, dict):
        items = [(k if k.startswith("-") else "-" + k, _value(v)) for k, v in options.items()]
    else:
        words, items, i = [str(o) for o in options], [], 0
        while i < len(words):
            if words[i].split() != [words[i]] or not _is_name(words[i]):
                # several words in one ("-a 1"), or a word that follows no option: as text, for PETSc to read
                items.append((words[i], None))
                i += 1
                continue
            value = words[i + 1] if i + 1 < len(words) and not _is_name(words[i + 1]) else None
            items.append((words[i], value))
            i += 1 if value is None else 2
    pairs, text = [], []
    for k, v in items:
        if k in _DIRECTIVES or k.split() != [k] or not _is_name(k):
            text += [k] + ([] if v is None else [v])
        else:
            pairs.append((k, v))
    return pairs, " ".join(text)


_live = weakref.WeakSet()


class Body:
    """A body of a scene (scene.body(name)): its state now, and for a kinematic body its motion"""

    def __init__(self, scene, handle):
        self._scene, self._h = scene, handle
        name, kind = ctypes.c_char_p(), ctypes.c_char_p()
        scene._do(_FCBodyGetName, handle, ctypes.byref(name))
        scene._do(_FCBodyGetType, handle, ctypes.byref(kind))
        self.name, self.type = name.value.decode(), kind.value.decode()

    def __repr__(self):
        return "<fecontact.Body %s (%s)>" % (self.name, self.type)

    def _do(self, f, *args):
        """f(self's handle, *args) through the scene; FecontactError naming the body once the scene is
        destroyed (its handle then points to freed memory)"""
        if not self._scene._h:
            raise FecontactError("body '%s': its scene is destroyed" % self.name)
        self._scene._do(f, self._h, *args)

    @property
    def centroid(self):
        c = np.zeros(3, REAL)
        self._do(_FCBodyGetCentroid, c)
        return c

    @property
    def rotation(self):
        """The unit quaternion (w, x, y, z) of a rigid or kinematic body; None for an FE body"""
        q, has = np.zeros(4, REAL), ctypes.c_int()
        self._do(_FCBodyGetRotation, q, ctypes.byref(has))
        return q if has.value else None

    def _picture(self, f, gathered):
        n = _cint()
        self._do(f, int(gathered), ctypes.byref(n), None)
        x = np.zeros((n.value, 3), REAL)
        self._do(f, int(gathered), ctypes.byref(n), x.ctypes.data_as(_ptr))
        return x

    def get_positions(self, gathered=True):
        """The positions of the body's vertices (FE: its mesh's; rigid and kinematic: its shape's
        picture), (n, 3): all of them on every rank in the output's order, or this rank's"""
        return self._picture(_FCBodyGetPositions, gathered)

    @property
    def positions(self):
        return self.get_positions(True)

    @property
    def velocity(self):
        """Rigid or kinematic: (v, w), the velocity of its centre and its angular velocity over the
        last step; FE: its vertices' velocities, (n, 3), gathered"""
        if self.type == "fem":
            return self._picture(_FCBodyGetVelocities, True)
        v, w = np.zeros(3, REAL), np.zeros(3, REAL)
        self._do(_FCBodyGetVelocity, v, w)
        return v, w

    @property
    def energy(self):
        """(kinetic, elastic, gravity) in joules"""
        e = np.zeros(3, REAL)
        self._do(_FCBodyGetEnergy, e)
        return dict(kinetic=e[0], elastic=e[1], gravity=e[2])

    @property
    def reactions(self):
        """The reactions of its constrained regions in the last step: name -> (force, moment about the
        region's centroid), the supports' action on the body"""
        n, names, vals = _cint(), ctypes.POINTER(ctypes.c_char_p)(), ctypes.POINTER(_creal)()
        self._do(_FCBodyGetReactions, ctypes.byref(n), ctypes.byref(names), ctypes.byref(vals))
        return {names[k].decode(): (np.array(vals[6 * k:6 * k + 3]), np.array(vals[6 * k + 3:6 * k + 6]))
                for k in range(n.value)}

    def set_pose(self, position, quaternion=(1.0, 0.0, 0.0, 0.0)):
        """A kinematic body: the pose it reaches at the end of the next step (centre, unit quaternion
        (w, x, y, z)), moving there at constant velocity and angular velocity over that step, then held"""
        self._do(_FCBodySetKinematicPose, _vector(position, 3, "position"),
                        _vector(quaternion, 4, "quaternion"))

    def set_velocity(self, v, w=(0.0, 0.0, 0.0)):
        """A kinematic body: a constant velocity and angular velocity (about its centre) from the next
        step on"""
        self._do(_FCBodySetKinematicVelocity, _vector(v, 3, "velocity"),
                        _vector(w, 3, "angular velocity"))


class Scene:
    """A scene built as the executable builds it, from options_file (read first) and options (a dict
    {"time_steps": 10}, a list ["-time_steps", "10"] or a string), on comm (petsc4py or mpi4py;
    PETSc.COMM_WORLD by default). Step it (step, run), read it (time, step_index, body(name),
    contacts()), and destroy it (destroy, or a with block). Its output is the executable's HDF5 file
    (-output_file)."""

    def __init__(self, options=None, options_file=None, comm=None):
        self._h, self._opts, self._finished, self._failed = _ptr(), _ptr(), False, None
        self._comm = _comm_handle(comm)
        _call(_PetscOptionsCreate, ctypes.byref(self._opts))
        try:
            if options_file is not None:
                if not os.path.exists(options_file):
                    raise FecontactError("Options file '%s' not found" % options_file)
                _call(_PetscOptionsInsertFile, self._comm, self._opts, str(options_file).encode(), 1)
            pairs, text = _option_pairs(options)
            if text:
                _call(_PetscOptionsInsertString, self._opts, text.encode())
            for k, v in pairs:  # each value whole: PetscOptionsInsertString would split it at its spaces
                _call(_PetscOptionsSetValue, self._opts, k.encode(), None if v is None else v.encode())
            self._do(_FCSceneCreate, self._comm, ctypes.byref(self._h))
            self._do(_FCSceneSetFromOptions, self._h)
        except Exception:
            self.destroy()
            raise
        _live.add(self)

    def _do(self, f, *args):
        """f(*args) with this scene's options database the default one"""
        _call(_PetscOptionsPush, self._opts)
        try:
            _call(f, *args)
        finally:
            _PetscOptionsPop()

    def _check(self):
        if not self._h:
            raise FecontactError("the scene is destroyed")
        if self._failed:
            raise FecontactError("the scene failed (%s): destroy it" % self._failed)

    def _advance(self, f):
        """a step or the run: a failure leaves the scene part-way through a step, never stepped again"""
        try:
            self._do(f, self._h)
        except FecontactError as e:
            self._failed = str(e)
            raise

    def setup(self):
        """Set the scene up (the first step does it otherwise): bodies, contact, output header"""
        self._check()
        self._advance(_FCSceneSetUp)  # a failed set-up leaves the scene half built: destroy it

    def step(self, n=1):
        """n time steps (each writes its output as the executable's does). More steps than remain to
        -time_steps: FecontactError before any step, the scene unchanged (still stepped, read, finished)"""
        self.setup()  # a restart's step is known at set-up
        k, last = self._time()[1], self._stepping()[1]
        if k + n > last:
            raise FecontactError("step(%d): the scene is at step %d of -time_steps %d, %d step(s) remain (raise "
                                 "-time_steps)" % (n, k, last, last - k))
        for _ in range(n):
            self._advance(_FCSceneStep)

    def run(self):
        """The remaining steps to -time_steps, then the run's summary, as the executable"""
        self._check()
        self._advance(_FCSceneRun)
        self._finished = True

    def _time(self):
        self._check()
        t, k = _creal(), _cint()
        self._do(_FCSceneGetTime, self._h, ctypes.byref(t), ctypes.byref(k))
        return t.value, k.value

    @property
    def time(self):
        return self._time()[0]

    @property
    def step_index(self):
        """The number of steps done (a restart's included)"""
        return self._time()[1]

    def _stepping(self):
        self._check()
        h, n = _creal(), _cint()
        self._do(_FCSceneGetTimeStep, self._h, ctypes.byref(h), ctypes.byref(n))
        return h.value, n.value

    @property
    def time_step(self):
        return self._stepping()[0]

    @property
    def time_steps(self):
        """-time_steps: the last step"""
        return self._stepping()[1]

    @property
    def bodies(self):
        """The bodies' names in scene order (the indices of contacts()["bodies"])"""
        self._check()
        n = _cint()
        self._do(_FCSceneGetNumBodies, self._h, ctypes.byref(n))
        out = []
        for i in range(n.value):
            b = _ptr()
            self._do(_FCSceneGetBodyByIndex, self._h, i, ctypes.byref(b))
            out.append(Body(self, b).name)
        return out

    def body(self, name):
        """The body named name; the scene is set up first (the bodies are placed at set-up)"""
        self._check()
        self.setup()
        b = _ptr()
        self._do(_FCSceneGetBody, self._h, name.encode(), ctypes.byref(b))
        return Body(self, b)

    def contacts(self):
        """The contacts of the last step (the same on every rank), as arrays: point and normal (out of
        the second body) at the start of the step, force on the first body in world axes (force) and in
        the contact frame n, t1, t2 (force_local), gap at the start and at the end of the step, state
        (0 open, 1 stick, 2 slip), bodies (indices, n x 2) and pairs (their names)"""
        self._check()
        n = _cint()
        self._do(_FCSceneGetContacts, self._h, ctypes.byref(n), None)
        rec = np.zeros(n.value, CONTACT)
        if n.value:
            self._do(_FCSceneGetContacts, self._h, ctypes.byref(n), rec.ctypes.data_as(_ptr))
        names = self.bodies
        return dict(point=rec["point"].copy(), normal=rec["normal"].copy(), force=rec["force_world"].copy(),
                    force_local=rec["force"].copy(), gap=rec["gap"].copy(), gap_end=rec["gap_end"].copy(),
                    state=rec["state"].copy(), bodies=rec["body"].astype(int),
                    pairs=[(names[a], names[b]) for a, b in rec["body"]])

    def finish(self):
        """After the last step: the summary and the memory report, as the end of a run"""
        self._check()
        if not self._finished:
            self._do(_FCSceneFinish, self._h)
            self._finished = True

    def destroy(self):
        """Free the scene (its output file closed) and its options"""
        try:
            if self._h:
                try:
                    _call(_PetscOptionsPush, self._opts)
                    try:
                        _call(_FCSceneDestroy, ctypes.byref(self._h))
                    finally:
                        _PetscOptionsPop()
                finally:
                    self._h = _ptr()
        finally:
            if self._opts:
                opts, self._opts = self._opts, _ptr()
                _call(_PetscOptionsDestroy, ctypes.byref(opts))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.destroy()
        return False

    def __del__(self):
        """(collective: under MPI, destroy a scene explicitly, or with a with block, so that every rank
        does it at the same point)"""
        try:
            self.destroy()
        except Exception:
            pass


@atexit.register
def _destroy_live():
    """Before petsc4py finalizes PETSc (atexit runs in reverse order of registration)"""
    for s in list(_live):
        try:
            s.destroy()
        except Exception:
            pass
