#!/usr/bin/python3
"""Hertz check of FE-FE contact: runs input/hertz.opts (a linear FE sphere resting under gravity
on a 1000x stiffer FE block, two-way detection, damped to rest) on the three mesh resolutions of
meshes/hertz_{sphere,block}_{1,2,3}.msh (scripts/make_meshes.sh) and three loads, measures the
total normal contact force F and the indentation d, and compares F with Hertz's
F_H = 4/3 E* sqrt(R) d^(3/2), 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

What is measured (docs/hertz.md):
  F  the sum of the normal contact forces of the last step (/contacts/force[:, 0]);
  d  the approach of the sphere's centre, corrected for the sphere's far field:
     d = drop + w(R), where drop is the downward displacement of the sphere's centre (P1
     interpolation of the FE displacement at the placed centre; the block's bottom is fixed,
     so the drop includes the block's own deformation), and w(z) is the displacement, on the
     axis at depth z, of a half-space (the sphere's E, nu) under the Hertz pressure of the
     measured F, relative to infinity. Hertz's d is the approach of points far from the contact
     in half-spaces; the centre of the sphere is at depth R only, where w(R) is 10 % of d.
     The same estimate taken at other depths on the axis (0.1 R to R) agrees to ~1 %
     (printed as d(z) for the check). The block's far-field term is 1000x smaller: neglected.

Usage: /usr/bin/python3 scripts/hertz.py [--levels 1,2,3] [--np N] [--no-plot]
Writes docs/hertz.png and prints the table of docs/hertz.md (Markdown) on stdout. Needs
build/fecontact (or $FECONTACT) and the meshes."""
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np
from scipy.integrate import quad

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))
OPTS = "input/hertz.opts"
LC_MIN = {1: 0.04, 2: 0.02, 3: 0.01}  # gmsh lc_min of meshes/hertz_*_<level>.msh (make_meshes.sh)
GRAVITY = (3.47, 9.81, 18.0)  # m/s^2: d/R ~ 1 %, 2 %, 3 %
RADIUS = 0.5  # meshes/hertz_sphere.geo


def read_opts(path=OPTS):
    """The options of an options file as a dict (last value wins), without the leading '-'"""
    opts = {}
    with open(os.path.join(ROOT, path)) as f:
        for line in f:
            w = line.split("#")[0].split()
            if w:
                opts[w[0].lstrip("-")] = w[1] if len(w) > 1 else ""
    return opts


def params(path=OPTS):
    o = read_opts(path)
    E1, nu1 = float(o["ball_young"]), float(o.get("ball_poisson", 0.3))
    E2, nu2 = float(o["block_young"]), float(o.get("block_poisson", 0.3))
    return dict(R=RADIUS, E1=E1, nu1=nu1, Estar=1.0 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2),
                centre=np.array([float(x) for x in o["ball_translate"].split(",")]))


def mesh_args(level):
    return ["-ball_dm_plex_filename", "meshes/hertz_sphere_%d.msh" % level,
            "-block_dm_plex_filename", "meshes/hertz_block_%d.msh" % level]


def hertz_force(P, d):
    return 4.0 / 3.0 * P["Estar"] * np.sqrt(P["R"]) * d**1.5


def w_axis(P, F, z):
    """Displacement (into the body) on the axis at depth z of a half-space with the sphere's
    E, nu under the Hertz pressure p0 sqrt(1 - r^2/a^2) of total force F, relative to infinity:
    Boussinesq's point-load solution integrated over the contact disc. w(0) = pi p0 a (1-nu^2)/(2E)."""
    E, nu = P["E1"], P["nu1"]
    G = E / (2 * (1 + nu))
    a = (3 * F * P["R"] / (4 * P["Estar"]))**(1.0 / 3.0)
    p0 = 3 * F / (2 * np.pi * a * a)

    def f(r):
        rho = np.hypot(r, z)
        return p0 * np.sqrt(max(0.0, 1 - r * r / (a * a))) / (4 * np.pi * G) * (z * z / rho**3 + 2 * (1 - nu) / rho) * 2 * np.pi * r

    return quad(f, 0, a, limit=200)[0]


def p1_displacement(cells, X, U, x):
    """The P1 interpolation at x of the vertex field U on the tetrahedra cells of vertices X"""
    T = X[cells]
    A = np.transpose(T[:, 1:] - T[:, :1], (0, 2, 1))
    lam = np.linalg.solve(A, (x - T[:, 0])[:, :, None])[:, :, 0]
    bary = np.column_stack([1 - lam.sum(1), lam])
    k = np.argmax(bary.min(1))
    if bary[k].min() < -1e-9:
        raise RuntimeError("point %s is in no tetrahedron" % x)
    return bary[k] @ U[cells[k]]


def measure(h5path, P, frame=-1):
    """F (last step), d (at the written frame `frame`) and Hertz's force for d from a finished
    run (see the module docstring)"""
    with h5py.File(h5path, "r") as H:
        off = H["contacts/offset"][:]
        F = H["contacts/force"][off[-2]:off[-1], 0].sum()
        cells = H["bodies/ball/mesh/cells"][:]
        X = H["bodies/ball/positions"][0]
        U = H["bodies/ball/positions"][frame] - X
        steps = H["steps"]
        m = dict(F=F, contacts=int(steps["contacts"][-1]), residual=float(steps["residual"][-1]),
                 intersections=int(steps["intersections"][:].max()),
                 sweeps=int(steps["pgs_iterations"][:].max()),
                 unconverged=int((steps["residual"][:] > 1.0001e-8).sum()),  # above -pgs_tol (the default)
                 kinetic=float(H["bodies/ball/energy"][-1, 0]),
                 vertices=X.shape[0] + H["bodies/block/positions"].shape[1])
    c = P["centre"]
    drops = {}
    for depth in (0.2, 0.5, 1.0):  # in units of R, below the contact point c - R e_z
        z = depth * P["R"]
        drops[depth] = -p1_displacement(cells, X, U, c + np.array([0, 0, z - P["R"]]))[2]
    m["drop"] = drops[1.0]
    m["w"] = w_axis(P, F, P["R"])
    m["d"] = m["drop"] + m["w"]
    m["d_depth"] = {k: v + w_axis(P, F, k * P["R"]) for k, v in drops.items()}
    m["F_hertz"] = hertz_force(P, m["d"])
    m["error"] = F / m["F_hertz"] - 1
    return m


def run(args, np_=1, opts=OPTS):
    cmd = [EXE, "-options_file", opts, "-quiet"] + [str(a) for a in args]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    t0 = time.time()
    p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    if p.returncode:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("fecontact failed (%d): %s" % (p.returncode, " ".join(cmd)))
    return time.time() - t0


def main():
    levels = [1, 2, 3]
    np_ = 1
    plot = "--no-plot" not in sys.argv
    for i, a in enumerate(sys.argv):
        if a == "--levels":
            levels = [int(x) for x in sys.argv[i + 1].split(",")]
        if a == "--np":
            np_ = int(sys.argv[i + 1])
    P = params()
    tmp = tempfile.mkdtemp(prefix="hertz-")
    rows = []
    for level in levels:
        for g in GRAVITY:
            f = os.path.join(tmp, "hertz_%d_%g.h5" % (level, g))
            wall = run(mesh_args(level) + ["-gravity", "0,0,%g" % -g, "-output_file", f], np_)
            m = measure(f, P)
            m.update(level=level, g=g, wall=wall)
            rows.append(m)
            sys.stderr.write("level %d g %5.2f: F %.1f N d %.5f m (d(z) %s) error %+.2f %% (%.1f s)\n" %
                             (level, g, m["F"], m["d"], " ".join("%.5f" % v for v in m["d_depth"].values()),
                              100 * m["error"], wall))
    print("| mesh | lc_min near the contact (m) | vertices (sphere + block) | g (m/s^2) | contacts | F (N) "
          "| centre drop (m) | w(R) (m) | d (m) | d/R | F_Hertz(d) (N) | F / F_Hertz - 1 | max sweeps "
          "| steps above pgs_tol | max intersections | wall (s) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for m in rows:
        print("| %d | %g | %d | %g | %d | %.1f | %.5f | %.5f | %.5f | %.2f %% | %.1f | %+.2f %% | %d | %d | %d | %.1f |" %
              (m["level"], LC_MIN[m["level"]], m["vertices"], m["g"], m["contacts"], m["F"], m["drop"], m["w"],
               m["d"], 100 * m["d"] / P["R"], m["F_hertz"], 100 * m["error"], m["sweeps"], m["unconverged"],
               m["intersections"], m["wall"]))
    if plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
        dd = np.linspace(0, 1.1 * max(m["d"] for m in rows), 200)
        a1.plot(1e3 * dd, hertz_force(P, dd), "k-", label="Hertz $4/3\\,E^*\\sqrt{R}\\,d^{3/2}$")
        for level, mk in zip(levels, "os^"):
            r = [m for m in rows if m["level"] == level]
            a1.plot([1e3 * m["d"] for m in r], [m["F"] for m in r], mk, mfc="none",
                    label="FE, lc_min %g m" % LC_MIN[level])
        a1.set_xlabel("indentation d (mm)")
        a1.set_ylabel("total normal contact force F (N)")
        a1.set_title("FE sphere (R 0.5 m) on FE block, two-way contact")
        a1.legend()
        for g, mk in zip(GRAVITY, "os^"):
            r = [m for m in rows if m["g"] == g]
            a2.plot([LC_MIN[m["level"]] for m in r], [100 * m["error"] for m in r], mk + "-",
                    label="d/R = %.1f %%" % (100 * r[-1]["d"] / P["R"]))
        a2.axhline(5, color="grey", ls=":")
        a2.axhline(0, color="k", lw=0.5)
        a2.set_xscale("log")
        a2.set_xlabel("mesh size near the contact lc_min (m)")
        a2.set_ylabel("F / F_Hertz(d) - 1 (%)")
        a2.set_title("error against Hertz")
        a2.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(ROOT, "docs", "hertz.png"), dpi=100)


if __name__ == "__main__":
    main()
