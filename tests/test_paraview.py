"""ParaView reads the output (issue 18): pvbatch (under xvfb-run) opens the .xmf of contact scenes
with the reader File > Open picks and with the XDMF Reader, and at the last frame (and the first)
what it reads equals what h5py reads from the .h5: the number of time steps and their times, every
body's points, cells, displacement and velocity (point data), von Mises stress and energy density
(cell data), the partition `rank` (cell data of meshed bodies), and the contact point set of the
frame's step (its count, points, force vector, normal and tangential force, state, gap); the
readers print no error or warning. Scenes: the grasp
(FE cube, two kinematic fingers, friction), the default scene (FE cube, rigid ball, ground plane),
one FE cube alone, and a grasp restarted from a half-way file. The fields are checked against
physics too: u = x - X, the FE velocity against the positions (implicit Euler: x_n = x_{n-1} + h
v_n), a kinematic finger's velocity against w x r, von Mises recomputed with numpy from the
positions, sum(energy density x volume) against /bodies/<name>/energy; on N ranks the grasp's
fields equal a 1-rank run's.
pvbatch missing: the test fails (scripts/setup.sh installs it) unless FC_SKIP_PARAVIEW=1 (skip).
Usage: test_paraview.py [--np N]"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
from fctest import ROOT, Checker, np_from_argv, out, run

NP = np_from_argv()
c = Checker("paraview np%d" % NP)
if not (shutil.which("pvbatch") and shutil.which("xvfb-run")):
    if os.environ.get("FC_SKIP_PARAVIEW") == "1":
        print("SKIP: pvbatch or xvfb-run missing and FC_SKIP_PARAVIEW=1")
        sys.exit(77)
    print("FAIL: pvbatch or xvfb-run not found: scripts/setup.sh installs them (Debian packages paraview, "
          "python3-paraview, xvfb); FC_SKIP_PARAVIEW=1 skips this test")
    sys.exit(1)

ALL = ["-output_fields", "displacement,velocity,von_mises,energy_density,contact_pressure"]
GRASP = ["-options_file", "input/grasp_rotate.opts", "-quiet"] + ALL
CUBE = ["-scene_bodies", "cube", "-cube_type", "fem", "-cube_dm_plex_filename", "meshes/cube_coarse.msh",
        "-cube_young", "1e5", "-cube_density", "100", "-cube_material", "corotational", "-cube_angular_velocity", "0,0,3",
        "-quiet"] + ALL


def pv_read(xmf, times):
    """pvbatch on xmf: (what it read, its output text)"""
    npz = xmf[:-4] + "_pv.npz"
    p = subprocess.run(["xvfb-run", "-a", "pvbatch", os.path.join(ROOT, "tests", "paraview_read.py"), xmf, npz]
                       + ["%.17g" % t for t in times], capture_output=True, text=True, timeout=300)
    text = (p.stdout + p.stderr).strip()
    if p.returncode != 0:
        sys.stderr.write(text + "\n")
        raise RuntimeError("pvbatch failed on %s" % xmf)
    return np.load(npz), text


def ref_order(X):
    return np.lexsort(np.round(X, 9).T[::-1])


def check_file(name, h5, frames_checked):
    """ParaView against h5py at the given frames of one output file"""
    f = h5py.File(h5, "r")
    ft = f["frames/time"][:]
    xmf = h5[:-3] + ".xmf"
    pv, text = pv_read(xmf, [ft[k] for k in frames_checked])
    c.check(text == "", "%s: the readers print nothing (no error, no warning)%s" % (name, "" if text == "" else ":\n" + text[:3000]))
    # the bodies in scene order (the XDMF grids' order), then the contact point set
    order = f.attrs["options"].decode().split("-scene_bodies ")[1].split()[0].split(",")
    for r in ["default", "xdmf2"]:
        times = pv[r + "/times"]
        c.check(len(times) == len(ft) and np.array_equal(times, ft),
                "%s, %s (%s): %d time steps = /frames/time" % (name, r, pv[r + "/class"], len(times)))
        for i, k in enumerate(frames_checked):
            k = k % len(ft)
            step = f["frames/step"][k]
            names = list(pv["%s/%d/names" % (r, i)])
            ok, what = True, []
            for j, b in enumerate(order):
                g = f["bodies/" + b]
                key = "%s/%d/%d/" % (r, i, j)
                nc = g["mesh/cells"].shape[0]
                same = np.array_equal(pv[key + "points"], g["positions"][k]) and int(pv[key + "ncells"]) == nc
                for fld in ["displacement", "velocity", "contact_pressure"]:
                    if fld in g:
                        same &= np.array_equal(pv[key + "point/" + fld], g[fld][k])
                for fld in ["von_mises", "energy_density"]:
                    if fld in g:
                        same &= np.array_equal(pv[key + "cell/" + fld], g[fld][k])
                if "mesh/rank" in g:  # the partition, a cell attribute of meshed bodies
                    same &= np.array_equal(pv[key + "cell/rank"], g["mesh/rank"][:])
                arrays = sorted(x.split("/")[-1] for x in pv.files if x.startswith(key + "point/") or x.startswith(key + "cell/"))
                expect = sorted([x for x in ["displacement", "velocity", "contact_pressure", "von_mises", "energy_density"] if x in g] +
                                (["rank"] if "mesh/rank" in g else []))
                same &= arrays == expect
                if r == "xdmf2" and len(names) > 1:
                    same &= names[j] == b
                ok &= same
                what.append("%s %s" % (b, "/".join(arrays)))
            c.check(ok, "%s, %s, frame %d: every body's points, cells and fields equal h5py's (%s)" % (name, r, k, "; ".join(what)))
            if "contacts" not in f:
                c.check(len(names) == len(order), "%s, %s: no contact grid without contact pairs" % (name, r))
                continue
            # the contacts of frame k's step: the rows of /steps with that step, records offset[row]:offset[row+1]
            rows = np.nonzero(f["steps/step"][:] == step)[0]
            n = int(f["steps/contacts"][rows[0]]) if len(rows) else 0
            if n == 0:
                c.check(len(names) == len(order), "%s, %s, frame %d (step %d): no contacts, no contact points" % (name, r, k, step))
                continue
            a = f["contacts/offset"][rows[0]]
            key = "%s/%d/%d/" % (r, i, len(order))
            P = pv[key + "points"]
            ok = len(names) == len(order) + 1 and P.shape == (n, 3) and int(pv[key + "ncells"]) == n
            ok = ok and np.array_equal(P, f["contacts/point_end"][a:a + n])
            ok = ok and np.array_equal(pv[key + "point/force_world"], f["contacts/force_world"][a:a + n])
            ok = ok and np.array_equal(pv[key + "point/force_normal"], f["contacts/force"][a:a + n, 0])
            ok = ok and np.array_equal(pv[key + "point/force_tangential"], f["contacts/force_tangential"][a:a + n])
            ok = ok and np.array_equal(pv[key + "point/normal"], f["contacts/normal"][a:a + n])
            ok = ok and np.array_equal(pv[key + "point/gap"], f["contacts/gap"][a:a + n])
            ok = ok and np.array_equal(pv[key + "point/state"], f["contacts/state"][a:a + n])
            if r == "xdmf2":
                ok = ok and names[-1] == "contact-points"
            c.check(ok, "%s, %s, frame %d (step %d): the contact point set has the step's %d contacts, their points, "
                    "force vector, normal and tangential force, normal, gap, state" % (name, r, k, step, n))
    return f


def check_physics(name, f, body, h):
    """The fields of an FE body at the last frame against the positions and the energies"""
    g = f["bodies/" + body]
    X, x = g["mesh/reference"][:], g["positions"][-1]
    u = g["displacement"][-1]
    d = np.abs(x - X - u).max()
    c.check(d <= 1e-12, "%s: displacement = positions - reference (%.1e m)" % (name, d))
    cells = g["mesh/cells"][:]
    # von Mises of the co-rotated linear stress, recomputed: F = Ds Dm^-1, R its rotation, H = R^T F - I
    Dm = np.stack([X[cells[:, a]] - X[cells[:, 0]] for a in (1, 2, 3)], axis=2)
    Ds = np.stack([x[cells[:, a]] - x[cells[:, 0]] for a in (1, 2, 3)], axis=2)
    F = Ds @ np.linalg.inv(Dm)
    U, _, Vt = np.linalg.svd(F)
    R = U @ Vt
    H = np.transpose(R, (0, 2, 1)) @ F - np.eye(3)
    opts = f.attrs["options"].decode().split()
    E, nu = float(opts[opts.index("-%s_young" % body) + 1]), 0.3
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    eps = 0.5 * (H + np.transpose(H, (0, 2, 1)))
    tr = np.trace(eps, axis1=1, axis2=2)
    S = 2 * mu * eps + lam * tr[:, None, None] * np.eye(3)
    s = S - np.trace(S, axis1=1, axis2=2)[:, None, None] / 3 * np.eye(3)
    vm = np.sqrt(1.5 * np.sum(s * s, axis=(1, 2)))
    e = np.abs(vm - g["von_mises"][-1]).max() / vm.max()
    c.check(vm.max() > 0 and e <= 1e-9, "%s: von Mises recomputed from the positions (max %.3g Pa, rel. %.1e)" % (name, vm.max(), e))
    vol = np.abs(np.linalg.det(Dm)) / 6
    step = f["frames/step"][-1]
    row = np.nonzero(f["steps/step"][:] == step)[0][0]
    Ee, Es = (g["energy_density"][-1] * vol).sum(), g["energy"][row, 1]
    c.check(Es > 0 and abs(Ee - Es) <= 1e-9 * Es, "%s: sum(energy density x volume) = elastic energy (%.6g J, %.6g J)" % (name, Ee, Es))


# 1. the grasp: FE cube and two kinematic fingers turning at 6 rad/s about z through the origin
g1 = out("grasp_np%d.h5" % NP)
run(GRASP + ["-time_steps", "12", "-output_every", "4", "-output_file", g1], np_=NP)
f = check_file("grasp", g1, [-1, 1])
check_physics("grasp", f, "object", float(np.ravel(f.attrs["time_step"])[0]))
fg = f["bodies/finger1"]
w = np.array([0, 0, 6.0])
e = np.abs(fg["velocity"][-1] - np.cross(w, fg["positions"][-1])).max()
c.check(e <= 1e-9, "grasp: finger velocity = w x r (%.1e m/s)" % e)
if NP > 1:  # the same fields as one rank, vertices and cells matched by their reference coordinates
    g0 = out("grasp_np1_ref.h5")
    run(GRASP + ["-time_steps", "12", "-output_every", "4", "-output_file", g0], np_=1)
    a, b = h5py.File(g0, "r")["bodies/object"], f["bodies/object"]
    pa, pb = ref_order(a["mesh/reference"][:]), ref_order(b["mesh/reference"][:])
    ca = a["mesh/reference"][:][a["mesh/cells"][:]].mean(axis=1)
    cb = b["mesh/reference"][:][b["mesh/cells"][:]].mean(axis=1)
    qa, qb = ref_order(ca), ref_order(cb)
    dv = max(np.abs(a[k][-1][pa] - b[k][-1][pb]).max() / np.abs(a[k][-1]).max() for k in ["displacement", "velocity"])
    ds = max(np.abs(a[k][-1][qa] - b[k][-1][qb]).max() / np.abs(a[k][-1]).max() for k in ["von_mises", "energy_density"])
    c.check(dv <= 1e-8 and ds <= 1e-8, "grasp: %d ranks = 1 rank (point fields rel. %.1e, cell fields rel. %.1e)" % (NP, dv, ds))

# 2. the default scene: FE cube, rigid ball, ground plane (default fields: no energy density)
d1 = out("default_np%d.h5" % NP)
run(["-options_file", "input/default.opts", "-quiet", "-time_steps", "30", "-output_every", "10", "-output_file", d1], np_=NP)
f = check_file("default scene", d1, [-1])
c.check("energy_density" not in f["bodies/cube"] and "von_mises" in f["bodies/cube"] and "von_mises" not in f["bodies/ball"],
        "default scene: the default fields (von_mises for FE bodies only, no energy_density)")

# 3. one FE cube alone, spinning in free fall, a frame every step: v_n = (x_n - x_{n-1}) / h, which is
# eq. 2 (-cube_rotation linear; the default adds the step's exact turn, src/body/fem_rotation.c)
s1 = out("single_np%d.h5" % NP)
run(CUBE + ["-cube_rotation", "linear", "-time_steps", "5", "-output_every", "1", "-output_file", s1], np_=NP)
f = check_file("single body", s1, [-1])
g, h = f["bodies/cube"], float(np.ravel(f.attrs["time_step"])[0])
e = np.abs((g["positions"][-1] - g["positions"][-2]) / h - g["velocity"][-1]).max() / np.abs(g["velocity"][-1]).max()
c.check(e <= 1e-9, "single body: velocity = (x_n - x_(n-1)) / h (rel. %.1e)" % e)
check_physics("single body", f, "cube", h)

# 4. a restarted grasp: its frame 0 is the restart step (no contacts of it in this file)
half, rest = out("grasp_half_np%d.h5" % NP), out("grasp_rest_np%d.h5" % NP)
run(GRASP + ["-time_steps", "6", "-output_every", "3", "-output_file", half], np_=NP)
run(GRASP + ["-time_steps", "12", "-output_every", "3", "-output_file", rest, "-restart", half], np_=NP)
f = check_file("restarted grasp", rest, [-1, 0])
a, b = h5py.File(g1, "r")["bodies/object"], f["bodies/object"]  # cells matched by their reference centroids
qa, qb = [ref_order(g["mesh/reference"][:][g["mesh/cells"][:]].mean(axis=1)) for g in (a, b)]
e = np.abs(a["von_mises"][-1][qa] - b["von_mises"][-1][qb]).max() / a["von_mises"][-1].max()
c.check(f["frames/step"][0] == 6 and e <= 1e-10,
        "restarted grasp: frame 0 at step 6; at step 12 the von Mises stress of the uninterrupted run (rel. %.1e)" % e)
c.done()
