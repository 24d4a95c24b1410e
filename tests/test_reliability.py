"""Reliability, round two (issue 17; docs/reliability.md, "Hostile input, round two"). Four classes:
1. a failed write ends the run on every rank (no hang: every run has a time limit), with a message
   naming the file and the cause, exit status 3, and a file whose frames, step rows and restart
   state agree, from which -restart continues: a small tmpfs filled in the middle of a run (the
   disk space reserved before HDF5 writes, and, with FECONTACT_NO_RESERVE=1, as where fallocate is
   not supported: the file extended sparse and the free space checked), and -output_file /dev/full;
2. no input is overwritten: the output compared with the restart file, the meshes and the options
   files by identity (hard and symbolic links, the XDMF index);
3. physically absurd runs stop: the energy guard, derived quantities at set-up, integer options
   past their range, a restart with another -time_step (continues at the stored time);
4. messages that name the option, body, file or vertex and the accepted range;
5. tables and regions (issue 56): values of any length (a 500-row trajectory and a 2000-row load,
   inline and as CSV, give the same run), and each of these a one-line error naming the option,
   exit 1: an empty region prescribed, a zero quaternion in a trajectory, -translate or -center
   beside a trajectory, a region given twice or under its name and its number, a box with a
   seventh number or a bound not finite, an empty table cell, a contact pair given twice, a FIFO or
   a directory as a table file, a region named with a '/' (before the output file is made); a
   group named "7" is selected by its name.
Usage: test_reliability.py [--np N]"""
import hashlib
import os
import shutil
import subprocess

import h5py
import numpy as np

import fctest
from fctest import run, out, Checker, np_from_argv, ROOT

NP = np_from_argv()
c = Checker("reliability np%d" % NP)
DROP = ["-options_file", "input/cube_drop.opts", "-quiet"]


def text(p):
    return p.stdout + p.stderr


def crashed(p):
    t = text(p)
    return p.returncode < 0 or p.returncode >= 128 or "Segmentation" in t or "traceback" in t.lower() \
        or "MPI_ABORT" in t


def expect_error(what, args, rc, *needles, np_=NP):
    """a run that must stop with exit status rc and a message holding every needle"""
    p = run(args, np_=np_, check=False, timeout=120)
    t = text(p)
    ok = p.returncode == rc and not crashed(p) and all(n in t for n in needles)
    c.check(ok, "%-40s exit %d (want %d), message names %s%s" % (what, p.returncode, rc, needles,
                                                                  "" if ok else "\n----\n" + t[-2000:]))
    return p


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


# ---------------------------------------------------------------------------------------------
# 1. A failed write
# ---------------------------------------------------------------------------------------------
def consistent(h5name, held):
    """frames, step rows and the restart state agree; `held`: the step the message says the file holds"""
    with h5py.File(h5name, "r") as f:
        ft, fs = f["frames/time"][:], f["frames/step"][:]
        pos = f["bodies/cube/positions"]
        steps = f["steps/step"][:]
        slots = [int(f["restart/slot%d/step" % k][()]) for k in (0, 1)]
        newest = max(slots)
        lastpos = pos[len(ft) - 1]
        return (len(ft) == len(fs) and len(ft) >= 2 and pos.shape[0] == len(ft)
                and np.all(np.isfinite(lastpos)) and np.abs(lastpos).max() > 0
                and np.array_equal(steps, np.arange(1, len(steps) + 1)) and steps[-1] >= fs[-1]
                and newest == held and newest in fs and newest <= fs[-1]), \
            "frames %d (last step %d), positions rows %d, step rows 1..%d, restart slots %s, message: step %d" % (
                len(ft), fs[-1], pos.shape[0], steps[-1] if len(steps) else 0, slots, held)


def disk_full(tag, env_extra):
    mnt = out("tmpfs_" + tag)
    os.makedirs(mnt, exist_ok=True)
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", mnt], capture_output=True, text=True)
    if m.returncode != 0:
        print("SKIP: reliability np%d disk full (%s): cannot mount a tmpfs (%s); needs root" % (NP, tag, m.stderr.strip()))
        return
    try:
        f = os.path.join(mnt, "run.h5")
        fctest.ENV.update(env_extra)
        try:
            p = run(DROP + ["-output_every", "1", "-output_file", f], np_=NP, check=False, timeout=120)
        finally:
            for k in env_extra:
                fctest.ENV.pop(k, None)
        t = text(p)
        held = -1
        for line in t.splitlines():
            if "holds the steps up to" in line:
                held = int(line.split("holds the steps up to")[1].split()[0])
        ok = p.returncode == 3 and not crashed(p) and f in t and "no space left on device" in t and held > 0
        c.check(ok, "disk full (%s): exit %d, message names the file and 'no space left on device'%s"
                % (tag, p.returncode, "" if ok else "\n----\n" + t[-2000:]))
        if held <= 0:
            return
        good, info = consistent(f, held)
        c.check(good, "disk full (%s): the file keeps a consistent prefix: %s" % (tag, info))
        # the file continues on a disk with room: to the end of the run
        shutil.copy(f, out("full_%s.h5" % tag))
        p = run(DROP + ["-restart", out("full_%s.h5" % tag), "-output_file", out("cont_%s.h5" % tag)], np_=NP,
                check=False, timeout=120)
        with h5py.File(out("cont_%s.h5" % tag), "r") as g:
            ft = g["frames/time"][:]
        ok = p.returncode == 0 and abs(ft[0] - 0.01 * held) < 1e-12 and abs(ft[-1] - 1.0) < 1e-12
        c.check(ok, "disk full (%s): -restart from it resumes at t = %g and ends at t = %g" % (tag, ft[0], ft[-1]))
    finally:
        subprocess.run(["umount", mnt], capture_output=True)


disk_full("space reserved", {})
disk_full("no fallocate: free space checked", {"FECONTACT_NO_RESERVE": "1"})
expect_error("-output_file /dev/full", DROP + ["-output_file", "/dev/full"], 3, "/dev/full",
             "no space left on device")

# ---------------------------------------------------------------------------------------------
# 2. No input is overwritten
# ---------------------------------------------------------------------------------------------
a = out("in_np%d.h5" % NP)
run(DROP + ["-time_steps", "5", "-output_file", a], np_=NP)
link = out("hardlink_np%d.h5" % NP)
if os.path.exists(link):
    os.remove(link)
os.link(a, link)
before = digest(a)
expect_error("output is a hard link to the restart file", DROP + ["-time_steps", "8", "-restart", a, "-output_file", link],
             1, a, link, "restart file (-restart)")
c.check(digest(a) == before, "the restart file is unchanged")
mesh = out("mesh_np%d.msh" % NP)
shutil.copy(os.path.join(ROOT, "meshes/cube_coarse.msh"), mesh)
before = digest(mesh)
expect_error("output names the input mesh", DROP + ["-cube_dm_plex_filename", mesh, "-output_file", mesh], 1, mesh,
             "mesh of body 'cube' (-cube_dm_plex_filename)")
sym = out("meshlink_np%d.h5" % NP)
if not os.path.lexists(sym):
    os.symlink(mesh, sym)
expect_error("output is a symbolic link to the mesh", DROP + ["-cube_dm_plex_filename", mesh, "-output_file", sym], 1,
             sym, mesh)
c.check(digest(mesh) == before, "the mesh is unchanged")
opts = out("scene_np%d.opts" % NP)
shutil.copy(os.path.join(ROOT, "input/cube_drop.opts"), opts)
before = digest(opts)
expect_error("output names the options file", ["-options_file", opts, "-quiet", "-output_file", opts], 1, opts,
             "options file (-options_file)")
xmf = out("index_np%d.xmf" % NP)  # the XDMF index of index.h5 would replace this options file
shutil.copy(os.path.join(ROOT, "input/cube_drop.opts"), xmf)
expect_error("XDMF index names the options file", ["-options_file", xmf, "-quiet", "-output_file",
                                                    out("index_np%d.h5" % NP)], 1, xmf, "XDMF index")
c.check(digest(opts) == before and digest(xmf) == before, "the options files are unchanged")

# ---------------------------------------------------------------------------------------------
# 3. Physically absurd runs
# ---------------------------------------------------------------------------------------------
o = ["-output_file", out("absurd_np%d.h5" % NP)]
# h = 1e3 s: the default solver (auto: Newton here) converges and the energy stays within the guard's
# bound; the sweeps alone stop at -pgs_max_it with forces whose work blows the energy up in step 1, the
# numerical blow-up the guard is for: it stops the run without step control, and with it (the default) the
# step is redone with smaller steps
expect_error("-time_step 1e3, -contact_solver pgs, -time_step_control off: energy guard",
             DROP + o + ["-time_step", "1e3", "-contact_solver", "pgs", "-time_step_control", "off"],
             2, "-energy_growth_limit", "-time_step 1000", "body 'cube'")
p = run(["-options_file", "input/cube_drop.opts", "-output_file", out("absurd_cut_np%d.h5" % NP), "-time_step", "1e3",
         "-contact_solver", "pgs", "-time_steps", "2"], np_=NP, check=False)
with h5py.File(out("absurd_cut_np%d.h5" % NP), "r") as h:
    sub = h["steps/substeps"][:]
c.check(p.returncode == 0 and sub[0] > 1 and "-energy_growth_limit" in p.stdout and "redone" in p.stdout,
        "-time_step 1e3, -contact_solver pgs, step control: the energy guard's step redone in %d sub-steps (exit %d)"
        % (sub[0], p.returncode))
p = run(DROP + o + ["-time_step", "1e3", "-time_steps", "1", "-energy_growth_limit", "0"], np_=NP, check=False)
c.check(p.returncode == 0, "-energy_growth_limit 0 relaxes the guard (exit %d)" % p.returncode)
p = run(DROP + o + ["-time_step", "1e3", "-time_steps", "1", "-energy_growth_limit", "1e6"], np_=NP, check=False)
c.check(p.returncode == 0, "-energy_growth_limit 1e6 relaxes the guard (exit %d)" % p.returncode)
expect_error("-cube_density 1e308", DROP + o + ["-cube_density", "1e308"], 1, "-cube_density", "must be at most")
SERIAL = NP == 1  # cases decided on each rank alike from the options alone: run on 1 rank only
expect_error("-cube_young 1e308", DROP + o + ["-cube_young", "1e308"], 1, "-cube_young", "must be at most")
if SERIAL:
    expect_error("-time_steps 4294967301", DROP + o + ["-time_steps", "4294967301"], 1, "-time_steps", "[0, ",
               "4294967301")
    expect_error("-output_every 4294967297", DROP + o + ["-output_every", "4294967297"], 1, "-output_every", "[1, ",
               "4294967297")
    expect_error("-contact_fe_passes 4294967298", DROP + o + ["-contact_fe_passes", "4294967298"], 1,
               "-contact_fe_passes", "[1, 2]")

# restart with another time step: continues at the stored time; a moving kinematic body does not jump
MOVE = DROP + ["-ground_velocity", "0.2,0,0"]
r1 = out("dt_a_np%d.h5" % NP)
r2 = out("dt_b_np%d.h5" % NP)
run(MOVE + ["-time_steps", "10", "-output_every", "1", "-output_file", r1], np_=NP)
run(MOVE + ["-time_steps", "20", "-output_every", "1", "-time_step", "0.005", "-restart", r1, "-output_file", r2],
    np_=NP)
with h5py.File(r1, "r") as f1, h5py.File(r2, "r") as f2:
    t1, t2 = f1["frames/time"][:], f2["frames/time"][:]
    rows = f2["steps/time"][:]
    gx = f2["bodies/ground/centroid"][:, 0]
    gpos0, gposA = f2["bodies/ground/positions"][0], f1["bodies/ground/positions"][-1]
    h = f2.attrs["time_step"]
ok = abs(t2[0] - t1[-1]) < 1e-15 and abs(t2[0] - 0.1) < 1e-12 and np.allclose(np.diff(t2), 0.005, atol=1e-12, rtol=0)
c.check(ok, "restart with -time_step 0.005 after 0.01: frame 0 at the stored t = %.6g (t1 ends %.6g), then steps of "
        "%.6g, %d frames to t = %.6g" % (t2[0], t1[-1], np.diff(t2).mean(), len(t2), t2[-1]))
ok = np.allclose(rows, 0.1 + 0.005 * np.arange(1, len(rows) + 1), atol=1e-12, rtol=0) and h == 0.005
c.check(ok, "restart with another time step: step rows at t_restart + k h (%.6g .. %.6g), attribute time_step %g"
        % (rows[0], rows[-1], h))
ok = np.array_equal(gpos0, gposA) and np.allclose(gx, 0.2 * rows, atol=1e-12, rtol=0)
c.check(ok, "the kinematic ground does not jump: frame 0 equals the earlier run's last, centroid x = v t at every step "
        "(largest error %.3g m)" % np.abs(gx - 0.2 * rows).max())

# ---------------------------------------------------------------------------------------------
# 4. Messages that say what to change
# ---------------------------------------------------------------------------------------------
expect_error("-cube_density 1e-300", DROP + o + ["-cube_density", "1e-300"], 1, "-cube_density", "must be at least",
             "Body 'cube'")
if SERIAL:
    expect_error("-cube_density 1e-310 (subnormal)", DROP + o + ["-cube_density", "1e-310"], 1, "-cube_density",
               "subnormal", "give 0 or a magnitude in")
    expect_error("-quiet maybe", DROP + o + ["-quiet", "maybe"], 1, "-quiet", "true, false", "'maybe'")
for what, f in [("node at x = -1e300", "tests/data/far_node.msh"),
                ("coordinates scaled by 1e120", "tests/data/scaled_1e120.msh")][:2 if SERIAL else 1]:
    expect_error(what, DROP + o + ["-cube_dm_plex_filename", f], 1, f, "body 'cube'",
                 "-cube_dm_plex_filename", "magnitude at most 1e+100")
expect_error("second-order tetrahedra", DROP + o + ["-cube_dm_plex_filename", "tests/data/second_order.msh"], 1,
             "tests/data/second_order.msh", "-cube_dm_plex_filename", "first-order", "gmsh -order 1")

# ---------------------------------------------------------------------------------------------
# 5. Issue 56: long values, tables and regions (docs/options.md, "Tables of time" and "Regions")
# ---------------------------------------------------------------------------------------------
CUBE = ["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
        "-cube_material", "linear", "-cube_young", "1e5", "-cube_poisson", "0.3", "-cube_density", "100",
        "-gravity", "0,0,0", "-time_step", "0.1", "-time_steps", "2", "-quiet"]
TOOL = ["-scene_bodies", "cube,tool", "-tool_type", "kinematic", "-tool_shape", "sphere", "-tool_radius", "0.1",
        "-cube_fixed", "zmin", "-time_step", "0.25", "-time_steps", "6"]


def csv(name, header, rows):
    path = out(name)
    with open(path, "w") as f:
        f.write(header + "\n" + "".join(",".join(r) + "\n" for r in rows))
    return path


def inline(rows):
    return ";".join(r[0] + ":" + ",".join(r[1:]) for r in rows)


# a 500-row trajectory and a 2000-row load table, inline (tens of kB of option value) and as CSV files,
# give the same run: no value is cut at any length
traj = [["%.17g" % t, "%.17g" % (0.3 * t), "0", "%.17g" % (0.5 * t)] for t in np.linspace(0.0, 1.0, 500)]
load = [["%.17g" % t, "0", "0", "%.17g" % (100.0 + 0.0 * t)] for t in np.linspace(0.0, 1.0, 2000)]
runs = {}
for how, tv, lv in [("inline", inline(traj), inline(load)),
                    ("csv", csv("traj500_np%d.csv" % NP, "t,x,y,z", traj), csv("load2000_np%d.csv" % NP, "t,fx,fy,fz", load))]:
    f = out("long_%s_np%d.h5" % (how, NP))
    p = run(CUBE + TOOL + ["-tool_trajectory", tv, "-cube_force", "zmax=" + lv, "-output_file", f], np_=NP, check=False)
    with h5py.File(f, "r") as h:
        runs[how] = (p.returncode, h["bodies/tool/centroid"][:], h["bodies/cube/reactions/zmin"][:],
                     fctest.sorted_positions(h, "cube")[1])
(ra, ta, Ra, xa), (rb, tb, Rb, xb) = runs["inline"], runs["csv"]
# the same tables: the same run, bit for bit on one rank (on two, the partition and the sums' order may differ)
tol = 0.0 if NP == 1 else 1e-12
ok = ra == 0 and rb == 0 and np.array_equal(ta, tb) and np.abs(Ra - Rb).max() <= tol * 100 and \
    np.abs(xa - xb).max() <= tol
c.check(ok, "a 500-row trajectory and a 2000-row load, inline (%d and %d characters) and as CSV: the same run (exit %d, %d)"
        % (len(inline(traj)), len(inline(load)), ra, rb))
c.check(np.abs(ta[-1] - [0.3, 0.0, 0.5]).max() < 1e-12 and abs(Ra[-1][2] + 100.0) < 1e-3 * 100,
        "... the tool ends at the last row (%s), the load is the table's 100 N (reaction %.12g)" % (ta[-1], Ra[-1][2]))

o5 = ["-output_file", out("inputs_np%d.h5" % NP)]
q0 = "0:0,0,0,1,0,0,0;1:0.3,0,0.5,0,0,0,0"
for what, args, needles in [
        ("displacement on an empty region", ["-cube_displacement", "box:5,5,5,6,6,6=0:0,0,0;1:0,0,0.1"],
         ("-cube_displacement", "box:5,5,5,6,6,6", "empty")),
        ("zero quaternion in a trajectory", TOOL + ["-tool_trajectory", q0, "-energy_growth_limit", "0"],
         ("-tool_trajectory", "row 2", "quaternion")),
        ("-tool_translate beside -tool_trajectory", TOOL + ["-tool_trajectory", "0:0,0,1;1:0,0,2", "-tool_translate", "1,0,0"],
         ("-tool_trajectory", "-tool_translate")),
        ("-tool_center beside -tool_trajectory", TOOL + ["-tool_trajectory", "0:0,0,1;1:0,0,2", "-tool_center", "1,0,0"],
         ("-tool_trajectory", "-tool_center")),
        ("one region under its name and number", ["-cube_fixed", "zmin,5"], ("-cube_fixed", "'5'", "'zmin'")),
        ("a region given twice", ["-cube_fixed", "zmin,zmin"], ("zmin", "twice")),
        ("a box with a seventh number", ["-cube_fixed", "box:-1,-1,-1,1,1,-0.4,5"], ("-cube_fixed", "seventh number")),
        ("a box with infinite bounds", ["-cube_fixed", "box:-inf,-inf,-inf,inf,inf,-0.4"], ("-cube_fixed", "finite")),
        ("a box with NaN bounds", ["-cube_fixed", "box:nan,-1,-1,1,1,-0.4"], ("-cube_fixed", "finite")),
        ("an empty cell in a CSV table",
         ["-cube_fixed", "zmin", "-cube_force", "zmax=" + csv("emptycell_np%d.csv" % NP, "t,fx,fy,fz", [["0", "", "0", "0", "100"]])],
         ("-cube_force", "row 1", "empty")),
        ("an empty cell inline", ["-cube_fixed", "zmin", "-cube_force", "zmax=0:0,,100"], ("-cube_force", "empty"))]:
    expect_error(what, CUBE + args + o5, 1, *needles)
expect_error("a contact pair given twice", DROP + o5 + ["-contact_pairs", "cube:ground,ground:cube"], 1, "-contact_pairs",
             "twice")

# a table file that is not a regular file: a FIFO (its read would block), a directory
fifo = out("fifo_np%d.csv" % NP)
os.mkfifo(fifo)
os.makedirs(out("tabledir"), exist_ok=True)
for what, path in [("a FIFO as a table file", fifo), ("a directory as a table file", out("tabledir"))]:
    expect_error(what, CUBE + ["-cube_fixed", "zmin", "-cube_force", "zmax=" + path] + o5, 1, "-cube_force", path,
                 "not a regular file")
    expect_error(what + " (trajectory)", CUBE + TOOL + ["-tool_trajectory", path] + o5, 1, "-tool_trajectory",
                 "not a regular file")

# region names: a group named with a '/' cannot name its reaction (refused at set-up: no output file
# is made), a group named "7" is selected by its name
with open(os.path.join(ROOT, "meshes/cube_coarse.msh"), "rb") as f:
    msh = f.read()
for name, a, b in [("slash", b'"xmax"', b'"x/ax"'), ("seven", b'"ymax"', b'"7"')]:
    with open(out("cube_%s.msh" % name), "wb") as f:
        f.write(msh.replace(a, b, 1))
f = out("slash_np%d.h5" % NP)
expect_error("a region named with a '/'", CUBE + ["-cube_dm_plex_filename", out("cube_slash.msh"), "-cube_fixed", "x/ax",
                                                  "-output_file", f], 1, "x/ax", "'/'")
c.check(not os.path.exists(f), "... refused before the output file is made")
f = out("seven_np%d.h5" % NP)
p = run(CUBE + ["-cube_dm_plex_filename", out("cube_seven.msh"), "-cube_fixed", "7", "-gravity", "0,0,-9.81",
                "-output_file", f], np_=NP, check=False)
ok = p.returncode == 0
if ok:
    with h5py.File(f, "r") as h:
        R = h["bodies/cube/reactions/7"][-1]
        ok = abs(R[2]) > 0.0 and abs(R[1]) > 0.0
c.check(ok, "a group named '7' (number 4) is selected by its name (exit %d)%s" % (p.returncode, "" if ok else text(p)[-1500:]))
c.done()
