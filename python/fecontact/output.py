"""Reader of a fecontact run's HDF5 output (layout: docs/output.md), with h5py and NumPy only.

    from fecontact.output import Output          # or fecontact.Output

    with Output("out/default.h5") as o:
        print(o.bodies)                          # scene order: what /contacts/bodies indexes
        z = o.body("cube").centroid[:, 2]        # one row per completed step
        t = o.steps.time
        for (a, b), f in o.pair_forces().items():
            print(a, b, f[-1])                   # force on a from b at the last step (N)

It needs neither MPI nor petsc4py, so it runs wherever h5py does: on a laptop after the run, or
beside a run still writing its file. The file is opened read-only without file locking and only
what the file's /complete dataset says is safely on disk is read (the steps and frames of the
last flush): a run still running, stopped by a signal or an error, or killed, reads the same way
as a finished one. Everything is returned as NumPy arrays read on access (the file stays open
until close()); data the file does not have raises a KeyError (a `MissingData`) naming it.

Rows and frames (docs/output.md): per-step arrays have one row per completed step, row i being
step `first_step + i + 1` (there is no row for the initial state: see Body.initial_centroid);
frame arrays have one entry per frame, frame 0 the initial (or restart) state.

This module imports nothing from the rest of the package, so that it can be used (and copied)
on its own.
"""
import numpy as np

import h5py

__all__ = ["Output", "Body", "Contacts", "MissingData"]

ENERGY_COLUMNS = ("kinetic", "elastic", "gravity")
REACTION_COLUMNS = ("fx", "fy", "fz", "mx", "my", "mz")
# the /contacts datasets with a record per contact, and their shapes per record (for empty results)
CONTACT_FIELDS = {"bodies": (2,), "point": (3,), "normal": (3,), "force": (3,), "gap": (), "gap_end": (),
                  "state": (), "point_end": (3,), "force_world": (3,), "force_tangential": ()}
CONTACT_INT = ("bodies", "state")


class MissingData(KeyError, AttributeError):
    """What the file does not hold (a body, a dataset, a field). A KeyError, and an AttributeError
    too, so that `hasattr(o.steps, "residual")` answers False instead of raising."""

    def __str__(self):  # KeyError's str() quotes its message; this is a sentence
        return str(self.args[0]) if self.args else ""


def _text(v):
    """An HDF5 string attribute as str (h5py returns fixed-length strings as bytes)."""
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray) and v.shape == ():
        return _text(v[()])
    if isinstance(v, np.ndarray) and v.size == 1 and v.dtype.kind in "SO":
        return _text(v.reshape(-1)[0])
    return str(v)


def _scalar(v):
    """A numeric attribute as a Python number (some are stored as 1-element arrays)."""
    a = np.asarray(v)
    return a.reshape(-1)[0].item() if a.size else None


def parse_options(text):
    """The root attribute `options` ("-name value -flag -name2 value2 ...", as PETSc lists its
    database) as a dict name -> value string, names without the leading '-', '' for a flag without
    a value. A token that starts with '-' followed by a digit or '.' is a value (-x -1)."""
    opts, name = {}, None
    for tok in text.split():
        is_name = tok.startswith("-") and len(tok) > 1 and not (tok[1].isdigit() or tok[1] == ".")
        if is_name:
            name = tok[1:]
            opts[name] = ""
        elif name is not None:
            opts[name] = tok if not opts[name] else opts[name] + " " + tok
    return opts


def _open(path):
    """h5py.File(path, "r") without file locking, so that the file of a running simulation opens;
    with the default locking where this process already holds the file open with it (HDF5 refuses
    two opens of one file with different locking flags) or h5py is older than 3.5 (no such option)."""
    try:
        return h5py.File(path, "r", locking=False)
    except TypeError:
        return h5py.File(path, "r")
    except OSError as e:
        if "locking" not in str(e):
            raise
        return h5py.File(path, "r")


class _Rows:
    """Named per-step (or per-frame) arrays of one HDF5 group, the first n rows of each, read on
    first access: attribute or item access (`s.time`, `s["time"]`), `keys()`, `in`."""

    def __init__(self, group, n, what):
        self._g, self._n, self._what, self._cache = group, n, what, {}

    def keys(self):
        """The names of the arrays (the group's datasets, sub-groups left out)."""
        if self._g is None:
            return []
        return [k for k, v in self._g.items() if isinstance(v, h5py.Dataset)]

    def __contains__(self, name):
        return name in self.keys()

    def __getitem__(self, name):
        if name not in self._cache:
            if name not in self.keys():
                raise MissingData("%s has no '%s' (it holds: %s)"
                                  % (self._what, name, ", ".join(self.keys()) or "nothing"))
            self._cache[name] = self._g[name][: self._n]
        return self._cache[name]

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return self[name]

    def __iter__(self):
        return iter(self.keys())

    def __len__(self):
        return self._n

    def __dir__(self):
        return list(super().__dir__()) + self.keys()

    def __repr__(self):
        return "<%s: %d rows of %s>" % (self._what, self._n, ", ".join(self.keys()))


class Steps(_Rows):
    """The per-step arrays of /steps (docs/output.md), one row per completed step: `time`, `step`,
    `wall_time`, `energy`, `energy_change`, `contacts`, `intersections`, `residual`, ... (whatever the
    file holds: `keys()`), and `timing`, a dict phase -> per-step wall time (s, max over ranks)."""

    @property
    def timing(self):
        """dict phase -> (S,) wall-clock time of the phase in each step (/steps/timing/*)."""
        g = self._g.get("timing") if self._g is not None else None
        if g is None:
            return {}
        return {p: g[p][: self._n] for p in g.keys()}


class Mesh(_Rows):
    """A body's mesh (/bodies/<name>/mesh): `reference` (V, 3) vertex coordinates at t = 0 after
    placement, `cells` (C, 4) tetrahedra or (C, 3) triangles of vertex indices, and for FE bodies and
    mesh shapes `rank` and `cell_origin` (the partition); `cell_type` 'tetrahedron' or 'triangle'."""

    def __init__(self, group, what):
        super().__init__(group, None, what)

    @property
    def cell_type(self):
        return _text(self._g.attrs.get("cell_type", "")) if self._g is not None else ""

    def __len__(self):
        """The number of vertices V."""
        return len(self._g["reference"]) if self._g is not None and "reference" in self._g else 0

    def __repr__(self):
        return "<%s: %s, %d vertices>" % (self._what, self.cell_type, len(self))


class Body:
    """One body of a run (/bodies/<name>): per-step data (rows of completed steps), frames and fields.

    - `name`, `type` ('fem', 'rigid' or 'kinematic'), `initial_centroid` (3,), `initial_rotation` (4,)
      (rigid and kinematic bodies);
    - per step: `centroid` (S, 3), `rotation` (S, 4) quaternion (w, x, y, z) (rigid and kinematic
      bodies), `energy` (dict 'kinetic', 'elastic', 'gravity' -> (S,) J; `energy_total` their sum),
      `reactions` (dict region -> (S, 6): force fx, fy, fz (N) and moment mx, my, mz (N m) of the
      region's supports on the body; FE bodies with fixed or prescribed regions), `inverted` (dict
      'elements' -> (S,) the elements turned inside out, 'min_volume_ratio' -> (S,) the smallest J =
      det F; FE bodies);
    - per frame: `frames` (F,) the frame times, `frame_steps`, `positions` (F, V, 3), `field(name)`
      for the fields the file holds (`fields`: displacement, velocity, von_mises, ...);
    - `mesh`: `reference`, `cells`, `cell_type`, ... (a `Mesh`).
    A dataset the file lacks for this body raises MissingData (a KeyError) naming it."""

    def __init__(self, output, name):
        self._o, self.name = output, name
        self._g = output.file["bodies"][name]

    def __repr__(self):
        return "<Body %s (%s)>" % (self.name, self.type)

    def _data(self, name, n):
        if name not in self._g or not isinstance(self._g[name], h5py.Dataset):
            raise MissingData("body '%s' (%s) has no dataset '%s' in %s" % (self.name, self.type, name, self._o.path))
        return self._g[name][:n]

    @property
    def type(self):
        return _text(self._g.attrs.get("type", ""))

    @property
    def initial_centroid(self):
        """The centroid at t = 0 (or at the restart step), after placement (m); not a row of `centroid`."""
        if "initial_centroid" not in self._g.attrs:
            raise MissingData("body '%s' has no attribute initial_centroid" % self.name)
        return np.asarray(self._g.attrs["initial_centroid"], dtype=float)

    @property
    def initial_rotation(self):
        """The orientation at t = 0, quaternion (w, x, y, z): rigid and kinematic bodies."""
        if "initial_rotation" not in self._g.attrs:
            raise MissingData("body '%s' (%s) has no attribute initial_rotation" % (self.name, self.type))
        return np.asarray(self._g.attrs["initial_rotation"], dtype=float)

    @property
    def centroid(self):
        """(S, 3) centroid at the end of each completed step (m)."""
        return self._data("centroid", self._o.nsteps)

    @property
    def rotation(self):
        """(S, 4) orientation quaternion (w, x, y, z) at the end of each step: rigid and kinematic bodies."""
        return self._data("rotation", self._o.nsteps)

    @property
    def energy(self):
        """dict 'kinetic', 'elastic', 'gravity' -> (S,) the body's energies at the end of each step (J)."""
        e = self._data("energy", self._o.nsteps)
        return {k: e[:, i] for i, k in enumerate(ENERGY_COLUMNS[: e.shape[1]])}

    @property
    def energy_total(self):
        """(S,) kinetic + elastic + gravity energy of the body at the end of each step (J)."""
        return self._data("energy", self._o.nsteps).sum(axis=1)

    @property
    def reactions(self):
        """dict region -> (S, 6) reaction of the region's supports (fx, fy, fz in N, mx, my, mz in N m
        about the region's centroid); {} for a body without fixed or prescribed regions."""
        g = self._g.get("reactions")
        if g is None:
            return {}
        return {k: g[k][: self._o.nsteps] for k in g.keys()}

    @property
    def inverted(self):
        """dict 'elements' -> (S,) the elements turned inside out (J = det F <= 0) at the end of each step,
        'min_volume_ratio' -> (S,) the smallest J of the body's elements then: FE bodies."""
        g = self._g.get("inverted")
        if g is None:
            raise MissingData("body '%s' (%s) has no group 'inverted' in %s" % (self.name, self.type, self._o.path))
        return {k: g[k][: self._o.nsteps] for k in g.keys()}

    @property
    def frames(self):
        """(F,) times of the frames (s): frame 0 is the initial (or restart) state."""
        return self._o.frames

    @property
    def frame_steps(self):
        """(F,) steps of the frames."""
        return self._o.frame_steps

    @property
    def positions(self):
        """(F, V, 3) world coordinates of the vertices at each frame (m), vertex order of `mesh.reference`."""
        return self._data("positions", self._o.nframes)

    @property
    def fields(self):
        """The names of the frame fields the file holds for this body (displacement, velocity,
        von_mises, energy_density, contact_pressure: those of -output_fields)."""
        skip = {"centroid", "rotation", "energy", "positions"}
        return [k for k in self._g.keys() if k not in skip and isinstance(self._g[k], h5py.Dataset)]

    def field(self, name):
        """A frame field: (F, V, 3) for vertex vectors, (F, V) or (F, C) for scalars."""
        if name not in self.fields and name != "positions":
            raise MissingData("body '%s' has no field '%s' in %s (it has: %s)"
                              % (self.name, name, self._o.path, ", ".join(self.fields) or "none"))
        return self._data(name, self._o.nframes)

    @property
    def mesh(self):
        """The reference mesh: `reference` (V, 3), `cells`, `cell_type`, ... (see Mesh)."""
        if "mesh" not in self._g:
            raise MissingData("body '%s' has no mesh group in %s" % (self.name, self._o.path))
        return Mesh(self._g["mesh"], "mesh of body '%s'" % self.name)


class Contacts:
    """Contact records (/contacts, docs/output.md), one per contact, of one step or of all steps:

    - `bodies` (M, 2) scene indices of side 1 (the normal points towards it) and side 2, and `pairs`,
      the list of their names [(name_1, name_2), ...];
    - `point`, `point_end` (M, 3) side-1 points at the start and end of the step (m), `normal` (M, 3),
      `force` (M, 3) in the contact frame (n, t1, t2) (N), `force_world` (M, 3) the force on side 1 in
      world axes (N), `force_normal` (= force[:, 0]), `force_tangential`, `gap`, `gap_end` (M,) (m),
      `state` (M,) 0 open, 1 stick, 2 slip;
    - `row` (M,) the row of /steps each record belongs to and `step` (M,) its step number.
    Arrays the file lacks are empty with the shape above (a scene without -contact_pairs)."""

    def __init__(self, arrays, names, row, step):
        self._a, self._names = arrays, names
        self.row, self.step = row, step

    def __len__(self):
        return len(self.row)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        if name not in self._a:
            raise MissingData("contacts have no '%s' (they have: %s)" % (name, ", ".join(sorted(self._a))))
        return self._a[name]

    def __getitem__(self, name):
        return getattr(self, name)

    def keys(self):
        return list(self._a) + ["pairs", "force_normal", "row", "step"]

    @property
    def force_normal(self):
        """(M,) the normal force lambda_n (N), column 0 of `force`."""
        return self._a["force"][:, 0]

    @property
    def pairs(self):
        """[(name of side 1, name of side 2), ...], one per record."""
        n = self._names
        return [(n[i], n[j]) for i, j in self._a["bodies"]]

    @property
    def pair_names(self):
        """(M, 2) array of the names of side 1 and side 2 (str)."""
        n = np.asarray(self._names, dtype=object) if self._names else np.zeros(0, dtype=object)
        return n[self._a["bodies"]] if len(self) else np.zeros((0, 2), dtype=object)

    def __repr__(self):
        return "<Contacts: %d records>" % len(self)


class Output:
    """A fecontact output file (HDF5, docs/output.md), read-only.

    `Output(path)`, also as a context manager (`with Output(path) as o:`); `close()`.

    - run: `bodies` (names in scene order), `time_step`, `time_steps` (as requested), `output_every`,
      `mpi_ranks`, `options` (dict name -> value string, names without '-'), `version`, `created`,
      `initial_energy`;
    - completeness: `nsteps` (S, completed step rows safely on disk), `nframes` (F), `first_step`
      (0, or the restart step of a restarted run), `last_step`, `complete` (whether the run wrote
      every requested step), `finished` (whether it ended: /memory is written at the end);
    - per step: `steps` (Steps: `steps.time`, `steps.residual`, `steps.timing`, ...), `time`;
    - per frame: `frames` (times), `frame_steps`;
    - `body(name)` (a Body), `contacts(row)` / `contacts()` (Contacts), `pair_forces()`,
      `pair_normal_forces()`, `contact_pairs` (the pairs of -contact_pairs);
    - `memory` (dict column -> (ranks,) bytes) where the run wrote it; `file`: the h5py.File itself,
      for what this class does not wrap (read its datasets up to `nsteps` rows and `nframes` frames).

    HDF5 refuses to open a file twice in one process with different locking flags: to open the
    file with h5py as well while an Output holds it, use `o.file`, or `h5py.File(path, "r",
    locking=False)`; an Output opened while h5py holds the file takes h5py's locking.
    """

    def __init__(self, path):
        self.path = str(path)
        self.file = _open(self.path)
        try:
            self._read_extent()
            self.bodies = self._scene_bodies()
        except Exception:
            self.file.close()
            raise
        self._steps = None

    # --- opening and closing

    def close(self):
        """Closes the file (arrays already returned stay valid)."""
        if self.file is not None and self.file.id.valid:
            self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def __repr__(self):
        return "<fecontact Output %s: %s, %d steps, %d frames>" % (self.path, ", ".join(self.bodies), self.nsteps,
                                                                  self.nframes)

    def _read_extent(self):
        """S and F from /complete (last step safely on disk, frames), as docs/output.md asks readers to
        do; a file without /complete (older writers) by the shortest per-step dataset."""
        f = self.file
        if "complete" in f:
            last, nf = (int(x) for x in f["complete"][:2])
            if last < 0 or nf <= 0:
                last, nf = -1, 0
        else:
            nf = len(f["frames/step"]) if "frames/step" in f else 0
            last = None
        self.nframes = nf
        self.first_step = int(f["frames/step"][0]) if nf > 0 else 0
        if last is None:
            rows = [len(f["steps/step"])] if "steps/step" in f else [0]
            rows += [len(g["centroid"]) for g in f["bodies"].values() if "centroid" in g] if "bodies" in f else []
            if "contacts/offset" in f:
                rows.append(len(f["contacts/offset"]) - 1)
            self.nsteps = max(min(rows), 0)
            last = self.first_step + self.nsteps
        else:
            self.nsteps = max(last - self.first_step, 0)
        self.last_step = last if nf > 0 else 0

    def _scene_bodies(self):
        """The body names in scene order: the root attribute scene_bodies, else -scene_bodies of the
        options attribute; alphabetical (HDF5's order) where neither names the file's body groups."""
        groups = sorted(self.file["bodies"].keys()) if "bodies" in self.file else []
        for source in (self.file.attrs.get("scene_bodies"), self.options.get("scene_bodies")):
            if source is None:
                continue
            names = [n for n in _text(source).split(",") if n]
            if sorted(names) == groups:
                return names
        return groups

    # --- run attributes

    @property
    def attrs(self):
        """The root attributes as h5py gives them (bytes for strings)."""
        return self.file.attrs

    @property
    def options(self):
        """dict option name (without '-') -> value string, from the root attribute `options`."""
        return parse_options(_text(self.file.attrs.get("options", "")))

    @property
    def time_step(self):
        return _scalar(self.file.attrs.get("time_step", np.nan))

    @property
    def time_steps(self):
        """-time_steps as requested (the number of rows written is `nsteps`)."""
        return _scalar(self.file.attrs.get("time_steps", -1))

    @property
    def output_every(self):
        return _scalar(self.file.attrs.get("output_every", -1))

    @property
    def mpi_ranks(self):
        return _scalar(self.file.attrs.get("mpi_ranks", -1))

    @property
    def version(self):
        return _text(self.file.attrs.get("fecontact_version", ""))

    @property
    def created(self):
        return _text(self.file.attrs.get("created", ""))

    @property
    def initial_energy(self):
        """Total energy at t = 0 (J), the reference of steps.energy_change."""
        return _scalar(self.file.attrs.get("initial_energy", np.nan))

    @property
    def complete(self):
        """Whether the file holds every requested step (a finished run, or one restarted to its end)."""
        return self.last_step == self.time_steps and self.nframes > 0

    @property
    def finished(self):
        """Whether the run ended normally (it writes /memory at its end; a run stopped early does not)."""
        return "memory" in self.file

    # --- per step and per frame

    @property
    def steps(self):
        """The per-step arrays (Steps): steps.time, steps.step, steps.wall_time, steps.energy,
        steps.contacts, steps.residual, steps.intersections, ..., steps.timing (dict phase -> array)."""
        if self._steps is None:
            self._steps = Steps(self.file.get("steps"), self.nsteps, "/steps of %s" % self.path)
        return self._steps

    @property
    def time(self):
        """(S,) time at the end of each completed step (s)."""
        return self.steps["time"] if "time" in self.steps else np.zeros(0)

    @property
    def frames(self):
        """(F,) times of the frames (s)."""
        return self.file["frames/time"][: self.nframes] if "frames/time" in self.file else np.zeros(0)

    @property
    def frame_steps(self):
        """(F,) step of each frame (frame k's per-step row is frame_steps[k] - first_step - 1, k > 0)."""
        return self.file["frames/step"][: self.nframes] if "frames/step" in self.file else np.zeros(0, dtype=np.int64)

    def body(self, name):
        """The body `name` (a Body); MissingData (a KeyError) listing the bodies if there is none."""
        if name not in self.bodies:
            raise MissingData("no body '%s' in %s (its bodies: %s)" % (name, self.path, ", ".join(self.bodies)))
        return Body(self, name)

    @property
    def memory(self):
        """dict column (peak_rss, W_H, ...) -> (ranks,) bytes, written by a run that completed; {} otherwise."""
        if "memory" not in self.file:
            return {}
        d = self.file["memory"]
        cols = _text(d.attrs.get("columns", "")).split(",")
        a = d[:]
        return {c: a[:, i] for i, c in enumerate(cols) if c and i < a.shape[1]}

    # --- contacts

    @property
    def contact_pairs(self):
        """The pairs of -contact_pairs, [(a, b), ...] in the order given ([] without contact pairs)."""
        out = []
        for p in self.options.get("contact_pairs", "").split(","):
            ab = p.split(":")
            if len(ab) == 2 and ab[0] and ab[1]:
                out.append((ab[0], ab[1]))
        return out

    def _offsets(self):
        g = self.file.get("contacts")
        if g is None or "offset" not in g:
            return None
        return g["offset"][: self.nsteps + 1]

    def _row(self, step):
        n = self.nsteps
        i = int(step)
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError("step row %d out of range: %s has %d completed steps" % (step, self.path, n))
        return i

    def contacts(self, step=None):
        """The contact records of one step (`step`: 0-based row of /steps, negative counts from the end)
        or of every completed step (step None), as a Contacts. Empty for a scene without contact pairs."""
        off = self._offsets()
        if step is None:
            lo, hi = 0, int(off[-1]) if off is not None and len(off) else 0
            counts = np.diff(off) if off is not None and len(off) else np.zeros(0, dtype=np.int64)
            row = np.repeat(np.arange(len(counts)), counts)
        else:
            i = self._row(step)
            lo, hi = (int(off[i]), int(off[i + 1])) if off is not None else (0, 0)
            row = np.full(hi - lo, i, dtype=np.int64)
        g = self.file.get("contacts")
        arrays = {}
        for k, shape in CONTACT_FIELDS.items():
            if g is not None and k in g:
                arrays[k] = g[k][lo:hi]
            else:
                arrays[k] = np.zeros((0,) + shape, dtype=np.int64 if k in CONTACT_INT else float)
        return Contacts(arrays, self.bodies, row, row + self.first_step + 1)

    def _pair_sums(self):
        """(keys, per-record key index, sign) for the sums per pair: a pair's key is its order in
        -contact_pairs (else as first met); a record whose side 1 is the key's second body counts
        with the opposite sign (what the pair exerts on the key's first body)."""
        c = self.contacts()
        names = self.bodies
        keys = list(self.contact_pairs)
        index = {k: i for i, k in enumerate(keys)}
        kidx = np.zeros(len(c), dtype=np.int64)
        sign = np.ones(len(c))
        code = c.bodies[:, 0] * max(len(names), 1) + c.bodies[:, 1]
        for u in np.unique(code):  # one lookup per ordered pair of bodies, not per record
            a, b = names[u // max(len(names), 1)], names[u % max(len(names), 1)]
            sel = code == u
            if (a, b) in index:
                kidx[sel] = index[(a, b)]
            elif (b, a) in index:
                kidx[sel], sign[sel] = index[(b, a)], -1.0
            else:
                index[(a, b)] = len(keys)
                keys.append((a, b))
                kidx[sel] = index[(a, b)]
        return c, keys, kidx, sign

    def pair_forces(self):
        """dict (name_a, name_b) -> (S, 3): per step, the total contact force on body a from body b in
        world axes (N): the sum of /contacts/force_world (the force on side 1) over the pair's records,
        with the opposite sign for records whose side 1 is b (an FE-FE pair has records both ways).
        Keys: the pairs of -contact_pairs in their order (zeros where a pair never touches), then any
        other pair met. A self-contact pair (a, a) sums to the net of its internal forces, ~0."""
        c, keys, kidx, sign = self._pair_sums()
        out = {k: np.zeros((self.nsteps, 3)) for k in keys}
        for i, k in enumerate(keys):
            sel = kidx == i
            np.add.at(out[k], c.row[sel], c.force_world[sel] * sign[sel, None])
        return out

    def pair_normal_forces(self):
        """dict (name_a, name_b) -> (S,): per step, the sum of the normal forces lambda_n (N, >= 0) of the
        pair's contacts, whichever body is side 1. Same keys as pair_forces()."""
        c, keys, kidx, _ = self._pair_sums()
        out = {k: np.zeros(self.nsteps) for k in keys}
        for i, k in enumerate(keys):
            sel = kidx == i
            np.add.at(out[k], c.row[sel], c.force_normal[sel])
        return out

    def pair_contacts(self):
        """dict (name_a, name_b) -> (S,) int: number of contact records of the pair per step."""
        c, keys, kidx, _ = self._pair_sums()
        out = {k: np.zeros(self.nsteps, dtype=np.int64) for k in keys}
        for i, k in enumerate(keys):
            np.add.at(out[k], c.row[kidx == i], 1)
        return out

    # --- restart

    @property
    def restart_steps(self):
        """Steps of the complete restart states (/restart/slot0|1 with step >= 0), newest last: what
        -restart from this file would continue from is the last."""
        g = self.file.get("restart")
        if g is None:
            return []
        steps = []
        for s in g.values():
            if "step" in s:
                k = int(s["step"][()])
                if 0 <= k <= self.last_step:
                    steps.append(k)
        return sorted(steps)
