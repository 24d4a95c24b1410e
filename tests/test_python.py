"""The Python module (python/fecontact, issue 40) and the C library it drives, on --np ranks (the
scripts under mpirun -n NP):

- a scene stepped from Python (step() a few times, reading its state and contacts between steps,
  then run() to the end) writes the executable's HDF5 output for the same options: on 1 rank every
  dataset but the timings and memory figures equal, bit for bit (input/finger_push.opts, 60 steps: the tool pushes from step 52);
  on NP ranks, whose partition may differ between two runs, the executable's run on NP ranks to
  round-off (positions to 1e-12 m, contact forces to 1e-10 relative);
- a kinematic body moved by set_pose every step (to the poses its -tool_trajectory gives at the
  ends of the steps, read from the executable's run) gives that run, and set_velocity the run of
  -tool_velocity (the same bounds; on 1 rank equal);
- contacts() is the step's /contacts rows, and body().positions the step's frame;
- a Scene restarts (-restart) from the file of a Python-driven run and ends where the uninterrupted
  run ends (1e-10 m);
- errors: a wrong option value, an unknown body type, a misspelt option (found at set-up, the first
  step) and set_pose on an FE body raise FecontactError with fecontact's message, and the same
  interpreter then builds and steps a good scene;
- the C library installed (cmake --install to a temporary prefix): examples/c/driver.c builds
  against it with pkg-config and with CMake (find_package(fecontact)), and its run steering the tool
  writes the file the same steering from Python writes; pip installs python/ and the installed module
  finds the installed library through its pkg-config file (1 rank)."""
import glob
import os
import re
import shutil
import signal
import subprocess
import sys

import h5py
import numpy as np

from fctest import run, out, Checker, TMP, np_from_argv, only_from_argv, sorted_positions, ROOT, ENV, EXE

NP = np_from_argv()
ONLY = only_from_argv()  # --only reliability: the checks of issue 56 alone (reliability() below)
c = Checker("python np%d" % NP)
PY = "/usr/bin/python3"
LIB = os.path.join(os.path.dirname(os.path.abspath(EXE)), "libfecontact.so")
PENV = dict(ENV, FECONTACT_LIBRARY=LIB, PYTHONPATH=os.path.join(ROOT, "python"))
TOLD = out("told")  # tell()'s files: TOLD.<rank>
SCENE = ["-options_file", "input/finger_push.opts", "-time_steps", "60", "-output_every", "5", "-quiet"]


def python(code, np_=NP, check=True, timeout=600):
    """Run a Python script (fecontact importable) on np_ ranks; returns the CompletedProcess (None if it
    ran past timeout seconds: it is killed)"""
    f = out("script_%d.py" % abs(hash(code)))
    with open(f, "w") as g:
        g.write("import sys\nimport numpy as np\nimport fecontact\nfrom petsc4py import PETSc\n"
                "say = print if PETSc.COMM_WORLD.getRank() == 0 else (lambda *a: None)  # one rank's lines\n"
                "def tell(*a):  # a line of this rank's (a file each: the ranks' stdout may interleave)\n"
                "    with open(%r + '.%%d' %% PETSc.COMM_WORLD.getRank(), 'a') as g:\n"
                "        g.write(' '.join(str(x) for x in a) + '\\n')\n" % TOLD + code)
    cmd = ([] if np_ == 1 else ["mpirun", "-n", str(np_), "--oversubscribe"]) + [PY, f]
    # a session of its own: past the timeout, SIGTERM reaches mpirun and every rank (mpirun killed alone
    # would leave its ranks waiting forever)
    q = subprocess.Popen(cmd, cwd=ROOT, env=PENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        o, e = q.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(q.pid, sig)
                q.communicate(timeout=20)
                break
            except (subprocess.TimeoutExpired, ProcessLookupError):
                pass
        if check:
            raise RuntimeError("python script ran past %d s: %s" % (timeout, f))
        return None
    p = subprocess.CompletedProcess(cmd, q.returncode, o, e)
    if check and p.returncode:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("python script failed (%d): %s" % (p.returncode, f))
    return p


def told():
    """The lines the ranks of the last script wrote with tell(), every rank's (then forgotten)"""
    lines = []
    for f in glob.glob(TOLD + ".*"):
        lines += open(f).read().splitlines()
        os.remove(f)
    return lines


def differing(fa, fb):
    """The datasets of two output files that differ (timings, wall times and memory figures aside)"""
    a, b, bad = h5py.File(fa, "r"), h5py.File(fb, "r"), []

    def walk(g, p):
        for k in g:
            n = p + "/" + k
            if isinstance(g[k], h5py.Group):
                walk(g[k], n)
            elif not any(s in n for s in ("timing", "wall", "memory")):
                x, y = g[k][()], b[n][()] if n in b else None
                if y is None or not np.array_equal(x, y):
                    bad.append(n)
    walk(a, "")
    return bad


def reliability():
    """Issue 56: each check fails without its fix (a wrong answer, a crash, a hang or a leak)"""
    quick = SCENE[:2] + ["-time_steps", "3", "-quiet"]
    # 1. an option value with spaces is passed whole: the trajectory's three rows, not the first one
    traj = "0:0.03,0,0.08; 0.5:0.0195,0,0.08; 1.0:0.0,0,0.08"
    p = python("""
with fecontact.Scene(options_file="input/finger_push.opts", options={"time_steps": 10, "quiet": None,
                     "output_file": %r, "tool_trajectory": %r}) as s:
    s.step(10)
    say("TOOL", s.body("tool").centroid[0])
""" % (out("rel_traj.h5"), traj), check=False)
    x = [float(ln.split()[1]) for ln in p.stdout.splitlines() if ln.startswith("TOOL")]
    c.check(len(x) == 1 and abs(x[0] - (0.03 - 0.0105 * 0.1 / 0.5)) < 1e-12, "an option value with spaces (%r) is "
            "passed whole: the tool at x = %s m after 10 steps (its second row: 0.0279 m)" % (traj, x or p.stderr[-300:]))
    # 8. a step beyond -time_steps: a clear error, the scene unchanged (time, finish(), the output's /memory)
    f8 = out("rel_past.h5")
    p = python("""
s = fecontact.Scene(options=%r)
s.step(3)
for n in (1, 2):
    try:
        s.step(n)
        say("NOERROR")
    except fecontact.FecontactError as e:
        say("PAST", e)
say("AFTER", s.time, s.step_index)
s.finish()
s.destroy()
""" % " ".join(quick + ["-output_file", f8]), check=False)
    past = [ln for ln in p.stdout.splitlines() if ln.startswith("PAST")]
    after = [ln.split() for ln in p.stdout.splitlines() if ln.startswith("AFTER")]
    mem = os.path.exists(f8) and "memory" in h5py.File(f8, "r")
    c.check(p.returncode == 0 and len(past) == 2 and "-time_steps 3" in past[0] and after and
            float(after[0][1]) == 0.03 and after[0][2] == "3" and mem, "step() beyond -time_steps: FecontactError "
            "'%s', then time %s, finish() and the output's /memory (%s)" %
            (past[0][5:] if past else p.stderr[-300:], after[0][1:] if after else "-", mem))
    # 3. a Body used after its scene is destroyed (destroy(), the end of a with block): FecontactError
    p = python("""
s = fecontact.Scene(options=%r)
b = s.body("tool")
s.destroy()
with fecontact.Scene(options=%r) as s2:
    b2 = s2.body("finger")
for what, f in (("centroid", lambda: b.centroid), ("set_pose", lambda: b.set_pose([0, 0, 0])),
                ("positions", lambda: b2.positions), ("energy", lambda: b2.energy)):
    try:
        f()
        say("NOERROR", what)
    except fecontact.FecontactError as e:
        say("GONE", what, "|", e)
""" % (" ".join(quick + ["-output_file", out("rel_gone1.h5")]), " ".join(quick + ["-output_file", out("rel_gone2.h5")])),
               check=False)
    gone = [ln for ln in p.stdout.splitlines() if ln.startswith("GONE") and "scene is destroyed" in ln]
    c.check(p.returncode == 0 and len(gone) == 4, "a Body after its scene's destroy() or with block: FecontactError "
            "(%s), no crash (exit %d)" % (gone[0].split("| ")[-1] if gone else p.stderr[-300:], p.returncode))

    # 5. an input that fails on rank 0 only (PETSc's gmsh reader reads there; a table file is read there):
    # every rank raises, none waits (timeout 120 s)
    trunc = out("truncated.msh")
    with open(os.path.join(ROOT, "meshes/finger.msh"), "rb") as g, open(trunc, "wb") as h:
        h.write(g.read(100000))
    for what, opt, msg in (("a truncated mesh", {"finger_dm_plex_filename": trunc}, "Cannot read mesh file"),
                           ("a directory as a table file", {"tool_trajectory": TMP}, "is not a regular file")):
        p = python("""
try:
    with fecontact.Scene(options_file="input/finger_push.opts", options=dict(%r, time_steps=3, quiet=None,
                         output_file=%r)) as s:
        s.step()
    tell("NOERROR")
except fecontact.FecontactError as e:
    tell("RAISED", e)
""" % (opt, out("rel_rank0.h5")), check=False, timeout=120)
        raised = [ln for ln in told() if ln.startswith("RAISED") and msg in ln]
        c.check(p is not None and len(raised) == NP, "%s, on %d rank(s): FecontactError on every rank (%s)" %
                (what, NP, "ran past 120 s: a rank waits" if p is None else raised[0][7:] if raised else
                 p.stdout[-300:] + p.stderr[-300:]))
    # 5b. an error of one rank only at the scene's entry points (here an option whose value differs between the
    # ranks, checked after the last collective call of FCSceneSetFromOptions): raised on every rank, the others
    # naming the failing rank (FCErrorAgree)
    if NP > 1:
        p = python("""
r = PETSc.COMM_WORLD.getRank()
try:
    with fecontact.Scene(options_file="input/finger_push.opts", options={"time_steps": 3, "quiet": None,
                         "output_file": %r, "contact_settle_rtol": -1 if r == 1 else 1e-8}) as s:
        s.step()
    tell("NOERROR")
except fecontact.FecontactError as e:
    tell("RAISED", e)
""" % out("rel_onerank.h5"), check=False, timeout=120)
        lines = told() if p is not None else []
        raised = [ln for ln in lines if ln.startswith("RAISED") and "-contact_settle_rtol" in ln]
        named = [ln for ln in raised if "(on rank 1)" in ln]
        c.check(len(raised) == NP and len(named) == NP - 1, "an error on rank 1 only (-contact_settle_rtol -1 there): "
                "FecontactError on every rank, the others naming rank 1 (%s)" %
                ("ran past 120 s: a rank waits" if p is None else named[0][7:] if named else lines or p.stderr[-300:]))
    # 2. set_pose (set_velocity) with different values on different ranks: an error naming the body on every rank
    if NP > 1:
        p = python("""
r = PETSc.COMM_WORLD.getRank()
with fecontact.Scene(options=%r) as s:
    b = s.body("tool")
    for what, f in (("pose", lambda: b.set_pose(b.centroid + [1e-3 * r, 0, 0])),
                    ("velocity", lambda: b.set_velocity([0, 0, 0], [r, 0, 0]))):
        try:
            f()
            tell("NOERROR", what)
        except fecontact.FecontactError as e:
            tell("DIFFER", what, "|", e)
    b.set_pose(b.centroid)  # the same on every rank: accepted, and the scene steps on
    s.step()
    tell("STEPPED", s.step_index)
""" % " ".join(quick + ["-output_file", out("rel_differ.h5")]), check=False, timeout=120)
        lines = told()
        differ = [ln for ln in lines if ln.startswith("DIFFER") and "Body 'tool'" in ln and "differs between" in ln]
        stepped = [ln for ln in lines if ln == "STEPPED 1"]
        c.check(len(differ) == 2 * NP and len(stepped) == NP, "set_pose and set_velocity with values that differ "
                "between the ranks: FecontactError on every rank (%s); the same pose then steps" %
                (differ[0].split("| ")[-1] + "...)" if differ else "-" if p is None else p.stdout[-300:] + p.stderr[-300:]))
    # 6. two live scenes on one output file (by its name, by a symbolic link to it): the second is refused at
    # set-up; the first steps on and writes a complete file; once it is destroyed the name is free again
    f6, link = out("rel_shared.h5"), out("rel_shared_link.h5")
    if os.path.lexists(link):
        os.remove(link)
    os.symlink(f6, link)
    p = python("""
a = fecontact.Scene(options=%r)
a.step()
for name in (%r, %r):
    b = fecontact.Scene(options=%r + " -output_file " + name)
    try:
        b.step()
        tell("NOERROR")
    except fecontact.FecontactError as e:
        tell("REFUSED", e)
    b.destroy()
a.step(2)
a.finish()
a.destroy()
with fecontact.Scene(options=%r) as s:
    s.step()
    tell("AFTER", s.step_index)
""" % (" ".join(quick + ["-output_file", f6]), f6, link, " ".join(quick), " ".join(quick + ["-output_file", f6])),
               check=False, timeout=300)
    lines = told() if p is not None else []
    refused = [ln for ln in lines if ln.startswith("REFUSED") and "another live scene" in ln]
    ok = os.path.exists(f6) and h5py.File(f6, "r")["complete"][0] == 1  # the third scene's file: 1 step
    c.check(len(refused) == 2 * NP and lines.count("AFTER 1") == NP and ok, "a second live scene on the output file "
            "of another (its name, a symbolic link): refused (%s); the first ends its run, and a scene after it "
            "writes the file" % (refused[0][8:] if refused else lines or (p.stderr[-300:] if p else "timeout")))
    # 7. a set-up that fails (a fixed region the mesh does not have; a table file that is a directory) frees what it
    # built: the resident memory (after malloc_trim) over 30 such failures, after 10 first ones, grows < 1 MB
    p = python("""
import ctypes
libc = ctypes.CDLL("libc.so.6")
def rss():
    libc.malloc_trim(0)
    return int(open("/proc/self/statm").read().split()[1]) * 4096
for what, opt in (("region", {"finger_fixed": "nosuch"}), ("table", {"finger_displacement": "base=%s"})):
    for i in range(40):
        if i == 10:
            r0 = rss()
        try:
            with fecontact.Scene(options_file="input/finger_push.opts", options=dict(opt, time_steps=3, quiet=None,
                                 output_file=%r)) as s:
                s.setup()
        except fecontact.FecontactError:
            pass
    tell("GROWTH", what, rss() - r0)
""" % (TMP, out("rel_leak.h5")), check=False, timeout=300)
    growth = [ln.split() for ln in (told() if p is not None else []) if ln.startswith("GROWTH")]
    worst = max((int(g[2]) for g in growth), default=-1)
    c.check(len(growth) == 2 * NP and worst < 1 << 20,
            "a failing set-up repeated (a wrong fixed region, a directory as a table file): the resident memory grows "
            "by %s over 30 failures (< 1 MB; per rank and case: %s)" %
            ("%.0f kB" % (worst / 1024) if growth else "-", [g[1] + " " + g[2] for g in growth] if growth else
             (p.stderr[-300:] if p else "timeout")))
    # 4. the C API with NULL arguments: every function of include/fecontact.h that takes a pointer or a handle,
    # called with NULL for all of its arguments, and the red team's calls with a live scene: an error whose
    # message names the argument, no crash
    header = open(os.path.join(ROOT, "include/fecontact.h")).read()
    sigs = re.findall(r"PETSC_EXTERN\s+PetscErrorCode\s+(FC\w+)\(([^;]*)\);", re.sub(r"/\*.*?\*/", "", header, flags=re.S))
    handles = ("*", "[", "FCBody", "FCScene", "Vec", "DM ")
    sweep = [(n, len(re.split(r",(?![^(]*\))", a))) for n, a in sigs if any(h in a for h in handles)]
    p = python("""
import ctypes
from fecontact import scene as S
lib = S._lib
def null(name, *args):
    f = lib[name]  # a new function object: none of the argument types scene.py declares
    f.restype = ctypes.c_int
    try:
        S._call(f, *args)
        say("NULLNOERROR", name)
    except fecontact.FecontactError as e:
        say("NULLERROR", name, "|", e)
for name, n in %r:
    null(name, *([None] * n))
with fecontact.Scene(options=%r) as s:
    b = s.body("tool")
    null("FCSceneGetBody", s._h, None, ctypes.byref(ctypes.c_void_p()))
    null("FCSceneGetContacts", s._h, None, None)
    null("FCBodyGetCentroid", b._h, None)
    null("FCBodySetKinematicPose", b._h, None, None)
    s.step()
    say("STEPPED", s.step_index)
""" % (sweep, " ".join(quick + ["-output_file", out("rel_null.h5")])), check=False, timeout=300)
    errs = [ln for ln in p.stdout.splitlines() if ln.startswith("NULLERROR") and "is NULL" in ln] if p else []
    c.check(p is not None and p.returncode == 0 and len(errs) == len(sweep) + 4 and "STEPPED 1" in p.stdout,
            "the C API's %d functions with pointers or handles, called with NULL, and FCSceneGetBody(s, NULL), "
            "FCSceneGetContacts(s, NULL), FCBodyGetCentroid(b, NULL), FCBodySetKinematicPose(b, NULL, NULL): %d errors "
            "naming the argument (%s), no crash; the scene then steps" %
            (len(sweep), len(errs), errs[-3].split("| ")[-1] if errs else
             "exit %s: %s" % (p.returncode if p else "timeout", [ln for ln in p.stdout.splitlines()[-2:]] if p else "")))

if ONLY == "reliability":
    reliability()
    c.done()

# the executable's run, and the same scene stepped from Python
fe = out("exe.h5")
run(SCENE + ["-output_file", fe], NP)
fp = out("py.h5")
p = python("""
s = fecontact.Scene(options=%r)
s.step(3)
t, k = s.time, s.step_index
c = s.contacts()
x = s.body("finger").positions
s.step(12)
np.save(%r, s.contacts()["force"])
s.run()
say("TIME", t, k, len(c["gap"]), x.shape[0], s.step_index)
s.destroy()
""" % (" ".join(SCENE + ["-output_file", fp]), out("forces15.npy")))


def compare(a, b):
    """The largest difference of the finger's positions over the frames (by reference position: on several ranks
    the partition may differ between runs) and of the contact forces (relative)"""
    dx = max(np.abs(sorted_positions(a, "finger", k)[1] - sorted_positions(b, "finger", k)[1]).max()
             for k in range(len(a["frames/time"])))
    fa, fb = a["contacts/force"][:], b["contacts/force"][:]
    df = np.abs(fa - fb).max() / np.abs(fa).max() if fa.shape == fb.shape and len(fa) else np.inf
    return dx, df


if NP == 1:
    bad = differing(fe, fp)
    c.check(not bad, "stepped from Python (3 steps, 12, then run() to 60), the executable's output: %s" %
            ("every dataset equal" if not bad else "DIFFERENT " + ", ".join(bad[:5])))
else:  # the partition may differ between two runs: the same answer to round-off
    dx, df = compare(h5py.File(fe, "r"), h5py.File(fp, "r"))
    c.check(dx <= 1e-12 and df <= 1e-10, "stepped from Python on %d ranks, the executable's run: positions to %.1e m, "
            "contact forces to %.1e (relative)" % (NP, dx, df))
words = p.stdout.split("TIME")[1].split()
h = h5py.File(fe, "r")
off, fw = h["contacts/offset"][:], h["contacts/force_world"][:]
f15 = np.load(out("forces15.npy"))
c.check(float(words[0]) == 0.03 and int(words[1]) == 3 and int(words[4]) == 60 and
        int(words[3]) == h["bodies/finger/positions"].shape[1] and np.array_equal(f15, fw[off[14]:off[15]]),
        "time %s s and step %s after 3 steps, %s steps after run(); the finger's %s vertices; contacts() of step 15 "
        "are its /contacts rows (%d)" % (words[0], words[1], words[4], words[3], len(f15)))
c.check(np.abs(h["contacts/force"][:, 0]).max() > 0, "the tool pushes the finger (largest contact force %.3g N)" %
        np.abs(h["contacts/force"][:, 0]).max())

# a kinematic body moved by the program: set_pose to the trajectory's poses (80 steps: the tool pushes the finger
# from step 52 on), set_velocity as -tool_velocity; the scene's options without the file's -tool_trajectory
OPTS = []
for ln in open(os.path.join(ROOT, "input/finger_push.opts")):
    w = ln.split("#")[0].split()
    OPTS += w if w and w[0] != "-tool_trajectory" else []
MOVE = OPTS + ["-time_steps", "80", "-output_every", "5", "-quiet"]
ft = out("trajectory.h5")
run(MOVE + ["-tool_trajectory", "0:0.03,0,0.08;0.5:0.0195,0,0.08;1.0:0.0,0,0.08", "-output_file", ft], NP)
h = h5py.File(ft, "r")
tool = h["bodies/tool/centroid"][:]  # the end of each step
fs = out("set_pose.h5")
python("""
tool = np.array(%r)
with fecontact.Scene(options=%r) as s:
    b = s.body("tool")
    for x in tool:
        b.set_pose(x)
        s.step()
""" % (tool.tolist(), " ".join(MOVE + ["-output_file", fs, "-tool_center", "0.03,0,0.08"])))
hs = h5py.File(fs, "r")
dx, df = compare(h, hs)
fmax = np.abs(h["contacts/force"][:, 0]).max()
c.check(dx <= 1e-12 and df <= 1e-10 and fmax > 0, "set_pose every step to -tool_trajectory's poses: the finger's "
        "positions to %.1e m, the contact forces to %.1e (relative; up to %.3g N)" % (dx, df, fmax))
V = "-0.05,0,0"
fv, fo = out("vel_option.h5"), out("vel_set.h5")
VS = OPTS + ["-time_steps", "40", "-output_every", "5", "-quiet", "-tool_center", "0.03,0,0.08"]
run(VS + ["-tool_velocity", V, "-output_file", fo], NP)
python("""
with fecontact.Scene(options=%r) as s:
    s.body("tool").set_velocity([-0.05, 0, 0])
    s.run()
""" % " ".join(VS + ["-output_file", fv]))
ho, hv = h5py.File(fo, "r"), h5py.File(fv, "r")
dx, df = compare(ho, hv)
c.check(dx <= 1e-12 and df <= 1e-10 and np.abs(ho["contacts/force"][:, 0]).max() > 0, "set_velocity(-0.05, 0, 0) "
        "from the start: -tool_velocity's run, the finger's positions to %.1e m, the contact forces to %.1e (relative)" %
        (dx, df))

# a restart from a file a Python-driven scene wrote: 30 steps, then a new Scene continues to 60 with -restart; the
# executable's uninterrupted run of 60 steps (fe)
fr, fr2 = out("restart_a.h5"), out("restart_b.h5")
python("""
with fecontact.Scene(options=%r) as s:
    s.step(30)
with fecontact.Scene(options=%r) as s:
    k0 = s.step_index
    s.run()
    say("RESTART", k0, s.step_index)
""" % (" ".join(SCENE + ["-output_file", fr, "-output_every", "10"]),
       " ".join(SCENE + ["-output_file", fr2, "-restart", fr])))
a, b = h5py.File(fe, "r"), h5py.File(fr2, "r")
dx = np.abs(sorted_positions(a, "finger", -1)[1] - sorted_positions(b, "finger", -1)[1]).max()
c.check(b["steps/step"][0] == 31 and b["steps/step"][-1] == 60 and dx <= 1e-10, "restart: a Scene continues a "
        "Python-driven run's file from step 30 to 60 (steps %d to %d), the uninterrupted run's end positions to %.1e m" %
        (b["steps/step"][0], b["steps/step"][-1], dx))

# errors: raised with fecontact's message; the interpreter goes on
p = python("""
def expect(what, f):
    try:
        f()
        say("NOERROR", what)
    except fecontact.FecontactError as e:
        say("ERROR", what, "|", e)
expect("mu", lambda: fecontact.Scene(options=%r))
expect("type", lambda: fecontact.Scene(options={"scene_bodies": "a", "a_type": "nothing"}))
s = fecontact.Scene(options=%r)
expect("typo", lambda: s.step())
s.destroy()
s = fecontact.Scene(options=%r)
expect("fe_pose", lambda: s.body("finger").set_pose([0, 0, 0]))
s.step(2)
say("STEPS", s.step_index)
s.destroy()
""" % (" ".join(SCENE + ["-contact_mu", "-1"]), " ".join(SCENE + ["-contact_mux", "1"]),
       " ".join(SCENE + ["-output_file", out("ok.h5")])))
lines = {ln.split()[1]: ln for ln in p.stdout.splitlines() if ln.startswith(("ERROR", "NOERROR"))}
exe_mu = run(SCENE + ["-contact_mu", "-1"], 1, check=False).stderr.strip()
msgs = {"mu": exe_mu.replace("fecontact: error: ", ""), "type": "Unknown body type 'nothing'",
        "typo": "-contact_mux", "fe_pose": "not kinematic"}
for k, m in msgs.items():
    ln = lines.get(k, "")
    c.check(ln.startswith("ERROR") and m in ln, "error (%s): FecontactError '%s'" % (k, ln.split("| ")[-1]))
c.check("STEPS 2" in p.stdout, "after the errors, the same interpreter steps a good scene (%s)" %
        [ln for ln in p.stdout.splitlines() if ln.startswith("STEPS")])

# the installed library: the C driver built with pkg-config and with CMake, against the same steering from Python
if NP == 1:
    prefix, bdir = out("prefix"), os.path.join(ROOT, os.path.dirname(os.path.relpath(EXE, ROOT)))
    subprocess.run(["cmake", "--install", bdir, "--prefix", prefix], check=True, capture_output=True)
    pc = os.path.join(prefix, "lib", "pkgconfig")
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "fecontact"], env=dict(ENV, PKG_CONFIG_PATH=pc),
                           capture_output=True, text=True, check=True).stdout.split()
    d1 = out("driver_pc")
    b1 = subprocess.run(["cc", os.path.join(ROOT, "examples/c/driver.c"), "-o", d1] + flags, capture_output=True,
                        text=True)
    d2 = out("driver_cmake")
    b2 = subprocess.run(["cmake", "-S", os.path.join(ROOT, "examples/c"), "-B", d2, "-DCMAKE_PREFIX_PATH=" + prefix],
                        capture_output=True, text=True)
    if b2.returncode == 0:
        b2 = subprocess.run(["cmake", "--build", d2], capture_output=True, text=True)
    c.check(b1.returncode == 0 and b2.returncode == 0, "examples/c/driver.c builds against the installed library "
            "with pkg-config (%s) and with CMake (%s)" % ("ok" if b1.returncode == 0 else b1.stderr[-300:],
                                                           "ok" if b2.returncode == 0 else b2.stderr[-300:]))
    fd, fq = out("driver.h5"), out("driver_py.h5")
    DRV = SCENE + ["-driver_travel", "0.03"]
    r1 = subprocess.run([d1] + DRV + ["-output_file", fd], cwd=ROOT, env=ENV, capture_output=True, text=True)
    r2 = subprocess.run([os.path.join(d2, "driver")] + DRV + ["-output_file", out("driver2.h5")], cwd=ROOT, env=ENV,
                        capture_output=True, text=True)
    python("""
with fecontact.Scene(options=%r) as s:
    b = s.body("tool")
    x0, n = b.centroid, s.time_steps
    for k in range(1, n + 1):
        q = 2.0 * k / n
        b.set_pose([x0[0] - 0.03 * (q if q <= 1 else 2 - q), x0[1], x0[2]])
        s.step()
""" % " ".join(SCENE + ["-output_file", fq]), 1)
    bad = differing(fd, fq) if r1.returncode == 0 else ["(the driver failed: %s)" % r1.stderr[-300:]]
    forces = [ln for ln in r1.stdout.splitlines() if ln.startswith("step")]
    c.check(r1.returncode == 0 and r2.returncode == 0 and len(forces) == 60 and not bad,
            "the installed driver steers the tool over 60 steps (%s), and writes the file the same steering from "
            "Python writes: %s" % (forces[19].split("force on it")[-1].strip() if len(forces) > 19 else "-",
                                   "every dataset equal" if not bad else "DIFFERENT " + ", ".join(bad[:4])))
    # pip install from (a copy of) the repository's python/, the library found through the installed pkg-config file
    src, target = out("pysrc"), out("pytarget")
    shutil.copytree(os.path.join(ROOT, "python"), src, ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    pip = subprocess.run([PY, "-m", "pip", "install", "--no-deps", "--no-build-isolation", "--target", target, src],
                         capture_output=True, text=True)
    env = {k: v for k, v in PENV.items() if k not in ("FECONTACT_LIBRARY", "PYTHONPATH")}
    env.update(PYTHONPATH=target, PKG_CONFIG_PATH=pc)
    q = subprocess.run([PY, "-c", "import fecontact, fecontact._lib as L\nwith fecontact.Scene(options=%r) as s:\n"
                        "    s.step(2)\n    print('PIP', L.path(), s.step_index)" %
                        " ".join(SCENE + ["-output_file", out("pip.h5")])], cwd=ROOT, env=env, capture_output=True,
                       text=True)
    c.check(pip.returncode == 0 and "PIP %s" % os.path.join(pc, "..", "..", "lib", "libfecontact.so") in q.stdout and
            q.stdout.split()[-1] == "2", "pip install of python/, outside the repository: it finds the installed "
            "library through pkg-config and steps a scene (%s)" % (q.stdout.strip() or pip.stderr[-200:] + q.stderr[-300:]))
    shutil.rmtree(prefix, ignore_errors=True)
reliability()
c.done()
