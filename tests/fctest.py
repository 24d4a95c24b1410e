"""Shared helpers of the fecontact tests: run the executable (optionally under mpirun) and read
its HDF5 output. The executable comes from $FECONTACT (set by ctest), the repository root is the
working directory."""
import os
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OPENBLAS_NUM_THREADS="1", OMPI_MCA_rmaps_base_oversubscribe="1")
TMP = tempfile.mkdtemp(prefix="fctest-")


def run(args, np_=1, check=True, timeout=600):
    """Run fecontact with a list of option strings; returns the CompletedProcess."""
    cmd = [EXE] + [str(a) for a in args]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    # errors="replace": PETSc 3.18's -help prints -dm_plex_boundary_label's default from an
    # uninitialized buffer, whatever bytes it holds
    t0 = time.time()
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True, errors="replace", timeout=timeout)
    if os.environ.get("FCTEST_TIMES"):  # where the suite's time goes: seconds, test, command (one line a run)
        with open(os.environ["FCTEST_TIMES"], "a") as log:
            log.write("%.2f\t%s\t%s\n" % (time.time() - t0, os.path.basename(sys.argv[0]), " ".join(cmd)))
    sanitizer_check(p, cmd)
    if check and p.returncode != 0:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("fecontact failed (%d): %s" % (p.returncode, " ".join(cmd)))
    return p


def start(args, np_=1):
    """Start fecontact without waiting (a session of its own, so that a signal reaches mpirun and
    every rank): returns the Popen"""
    cmd = [EXE] + [str(a) for a in args]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    return subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)


def wait_for_frames(f, extra, timeout=300):
    """Wait until a started run has written a few frames to f (the file grows with HDF5's allocation,
    ~6 kB a frame of the coarse cube, kept a reserved margin ahead of it: src/io/reserve.c; it cannot
    be read while open), then `extra` seconds: robust to a loaded machine"""
    t0 = time.time()
    while not os.path.exists(f) and time.time() - t0 < timeout:
        time.sleep(0.05)
    time.sleep(0.2)
    size0 = os.path.getsize(f)
    while os.path.getsize(f) < size0 + 20000 and time.time() - t0 < timeout:
        time.sleep(0.05)
    time.sleep(extra)


def complete_prefix(h):
    """What /complete says is safely on disk in an output file h (an h5py.File), read and checked as a
    reader after a crash must (docs/output.md): (S, F) = /complete; every per-step dataset holds at
    least S rows; the rows up to S, the contacts of those steps and the frames up to F read and are
    finite, and the frames are those of steps 0..S; nothing beyond is read. Returns (S, F, rows: the
    per-step datasets' lengths, frame steps); raises RuntimeError naming what fails."""
    S, F = (int(x) for x in h["complete"][:])
    steps = [k for k in h["steps"] if isinstance(h["steps/" + k], h5py.Dataset)]
    rows = [len(h["steps/" + k]) for k in steps]
    rows += [len(h["steps/timing/" + k]) for k in h["steps/timing"]]
    rows += [len(h["bodies/%s/centroid" % b]) for b in h["bodies"]]
    rows.append(len(h["contacts/offset"]) - 1)
    if S > min(rows):
        raise RuntimeError("/complete step %d, per-step datasets hold %d..%d rows" % (S, min(rows), max(rows)))
    for k in steps:
        if not np.isfinite(h["steps/" + k][:S]).all():
            raise RuntimeError("steps/%s not finite up to step %d" % (k, S))
    if not np.array_equal(h["steps/step"][:S], np.arange(1, S + 1)):
        raise RuntimeError("steps/step is not 1..%d" % S)
    for b in h["bodies"]:
        h["bodies/%s/centroid" % b][:S]
    if h["contacts/offset"][S] > len(h["contacts/force"]):
        raise RuntimeError("contacts/offset[%d] beyond the contact records" % S)
    h["contacts/force"][:h["contacts/offset"][S]]
    fstep = list(h["frames/step"][:F])
    for b in h["bodies"]:
        pos = h["bodies/%s/positions" % b]
        for k in range(F):
            if not np.isfinite(pos[k]).all():
                raise RuntimeError("frame %d (step %d) of %s not finite" % (k, fstep[k], b))
    if fstep != list(range(S + 1)):
        raise RuntimeError("the frames are not those of steps 0..%d: %s" % (S, fstep))
    return S, F, rows, fstep


def final_state(h5):
    """The final state of a run in a partition-independent order: every FE body's vertex positions
    (sorted_positions), then the centroid and orientation of the others, bodies by name"""
    parts = []
    for b in sorted(h5["bodies"]):
        g = h5["bodies/" + b]
        if g.attrs["type"] == b"fem":
            parts.append(sorted_positions(h5, b)[1].ravel())
        else:
            parts.append(g["centroid"][-1])
            if "rotation" in g:
                parts.append(g["rotation"][-1])
    return np.concatenate(parts)


SANITIZER_REPORTS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:")


def sanitizer_check(p, cmd):
    """A run with an ASan/UBSan report fails the test even where a non-zero exit is expected
    (build with -DFC_SANITIZE=address,undefined: scripts/test.sh runs the suite that way too)."""
    text = (p.stdout or "") + (p.stderr or "")
    if any(s in text for s in SANITIZER_REPORTS):
        sys.stderr.write(text)
        raise RuntimeError("sanitizer report from: %s" % " ".join(cmd))


def out(name):
    return os.path.join(TMP, name)


def sorted_positions(h5, body, frame=-1):
    """Positions of a body's vertices at a frame, in an order independent of the MPI partition
    (lexicographic order of the reference coordinates)."""
    ref = h5["bodies/%s/mesh/reference" % body][:]
    pos = h5["bodies/%s/positions" % body][frame]
    key = np.round(ref, 9)  # placement may differ by round-off between partitions
    order = np.lexsort(key.T[::-1])
    return ref[order], pos[order]


def contact_force_on(h5, body):
    """The force on a body from its contacts at each step (S, 3), N, world axes: the sum of the contacts'
    force_world (the force on side 1) where the body is side 1, minus it where the body is side 2"""
    names = h5.attrs["scene_bodies"].decode().split(",")
    i = names.index(body)
    off, b, fw = h5["contacts/offset"][:], h5["contacts/bodies"][:], h5["contacts/force_world"][:]
    sign = (b[:, 0] == i).astype(float) - (b[:, 1] == i).astype(float)
    return np.array([(sign[off[k]:off[k + 1], None] * fw[off[k]:off[k + 1]]).sum(0) for k in range(len(off) - 1)])


def same_as_1_rank(H1, Hn, body, steps=None):
    """Whether Hn has H1's contacts at every step (the offsets) and the largest relative difference of their forces
    (matched by point), over the first `steps` steps (or all), and of the body's end positions (matched by reference
    position)"""
    o1, on = H1["contacts/offset"][:], Hn["contacts/offset"][:]
    n = len(o1) if steps is None else steps + 1
    same, ef = np.array_equal(o1[:n], on[:n]), 0.0
    for k in range(len(o1) - 1 if steps is None else steps):
        if not same:
            break
        p1, pn = H1["contacts/point"][o1[k]:o1[k + 1]], Hn["contacts/point"][on[k]:on[k + 1]]
        f1, fn_ = H1["contacts/force"][o1[k]:o1[k + 1]], Hn["contacts/force"][on[k]:on[k + 1]]
        i1, i_n = np.lexsort(np.round(p1, 8).T), np.lexsort(np.round(pn, 8).T)
        scale = np.abs(f1).max() if len(f1) else 0.0
        if scale > 0:
            ef = max(ef, np.abs(f1[i1] - fn_[i_n]).max() / scale)
    X1, Xn = H1["bodies/%s/mesh/reference" % body][:], Hn["bodies/%s/mesh/reference" % body][:]
    dx = np.abs(H1["bodies/%s/positions" % body][-1][np.lexsort(X1.T)] -
                Hn["bodies/%s/positions" % body][-1][np.lexsort(Xn.T)]).max()
    return same, ef, dx


class Checker:
    """Collects named assertions, prints each with its measured value, exits non-zero on failure."""

    def __init__(self, name):
        self.name, self.failed, self.count = name, 0, 0

    def check(self, ok, what):
        self.count += 1
        print("%s: %s  %s" % ("PASS" if ok else "FAIL", self.name, what))
        if not ok:
            self.failed += 1

    def done(self):
        print("%d passed, %d failed" % (self.count - self.failed, self.failed))
        if not self.failed:  # the run's files are kept only for a failure, to look at
            shutil.rmtree(TMP, ignore_errors=True)
        sys.exit(1 if self.failed else 0)


def only_from_argv():
    """--only NAME: a test that runs a list of scenes runs only the scene NAME (and none of its
    other checks), e.g. to repeat one case: tests/test_parallel.py --np 3 --only two_cubes"""
    for i, a in enumerate(sys.argv):
        if a == "--only":
            return sys.argv[i + 1]
    return None


def np_from_argv(default=1):
    for i, a in enumerate(sys.argv):
        if a == "--np":
            return int(sys.argv[i + 1])
    return default
