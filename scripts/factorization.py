#!/usr/bin/python3
"""What the factorization schedule of a co-rotational body costs in time and in accuracy
(-<body>_factorization every_step | reuse; src/body/fem_schedule.c).

For every scene, one run with `every_step` (A factored every step: the exact reference of the
linearized step) and runs with `reuse` over a range of its thresholds (-<body>_refactor_residual,
-<body>_refactor_rotation, -<body>_ksp_rtol; the others at their defaults), all in one invocation on the same machine, with an output frame every step.
Per run:
  - time per step (the sum of the /steps/timing phases but output), its median over the steps
    before the first contact (free fall, the first step excluded: it factors in both modes) and
    over the steps in contact, the ratio to every_step's, the factorizations and CG iterations;
  - the peak resident memory of the process (/usr/bin/time), against the dense compliance a
    precomputed mode keeps (8 N^2 bytes, N the body's DOFs);
  - errors against every_step, per step: the largest distance between the two runs' vertex
    positions over the displacement scale of every_step (the largest displacement of a vertex
    over its run); the difference of the total contact force per body pair over the largest such
    force of every_step; the constraint residual of both (/steps/complementarity, the worst step).
Writes docs/accuracy/factorization.csv, docs/accuracy/factorization_<scene>.png (error against
time and the step time of each setting) and prints the markdown tables of docs/accuracy.md and
docs/benchmarks.md.

    scripts/factorization.py [--scenes drop,rest,grasp,spin] [--np 1] [--quick]
    scripts/factorization.py --momentum     (the momentum of two colliding cubes in both modes)
"""
import argparse
import csv
import os
import platform
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE  # noqa: E402  (the executable and its environment)

OUT = os.path.join(ROOT, "build", "factorization")
# scene: options file, FE body, steps
SCENES = {
    "drop": dict(opts="input/cube_drop_peer.opts", body="cube", steps=30,
                 title="0.2 m co-rotational cube (17.5k DOFs, E = 1e4) dropped 5 cm on a plane, `input/cube_drop_peer.opts`"),
    "rest": dict(opts="input/cube_rest.opts", body="cube", steps=10,
                 title="1 m co-rotational cube (17.5k DOFs) resting on a plane, `input/cube_rest.opts`"),
    "grasp": dict(opts="input/grasp_rotate.opts", body="object", steps=60,
                  title="the grasp, a cube turned by two fingers at 6 rad/s, `input/grasp_rotate.opts`"),
    "spin": dict(opts="input/cube_spin.opts", body="cube", steps=60,
                 title="a cube spinning at 12 rad/s that lands on a corner, `input/cube_spin.opts`"),
}
# label, options (body prefix added)
SETTINGS = [("every_step", ["factorization", "every_step"])] + \
    [("reuse res=%g" % r, ["factorization", "reuse", "refactor_residual", str(r)]) for r in (0.001, 0.003, 0.01, 0.03, 0.1)] + \
    [("reuse rot=%g res=off" % r, ["factorization", "reuse", "refactor_rotation", str(r), "refactor_residual", "1e9"])
     for r in (0.05, 0.2)] + \
    [("reuse res=0.003 rtol=%g" % t, ["factorization", "reuse", "ksp_rtol", str(t)]) for t in (1e-4, 1e-8)]
FIELDS = ["scene", "setting", "steps", "t_free", "t_contact", "t_contact_mean", "ratio_free", "ratio_contact",
          "factorizations", "krylov_per_step", "peak_rss_mb", "dense_compliance_mb", "pos_err", "centroid_err", "force_err",
          "complementarity", "max_penetration"]


def run(scene, label, opts, np_):
    sc = SCENES[scene]
    h5 = os.path.join(OUT, "%s_%s.h5" % (scene, label.replace(" ", "_").replace("=", "")))
    args = ["-options_file", sc["opts"], "-time_steps", str(sc["steps"]), "-output_every", "1", "-output_file", h5]
    for i in range(0, len(opts), 2):
        args += ["-%s_%s" % (sc["body"], opts[i]), opts[i + 1]]
    cmd = ["/usr/bin/time", "-f", "maxrss %M", EXE] + args
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    if p.returncode != 0:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("fecontact failed: " + " ".join(cmd))
    rss = max(float(l.split()[1]) for l in p.stderr.splitlines() if l.startswith("maxrss")) / 1024.0
    return h5, rss


def pair_forces(f):
    """Per step, the total contact force (world axes) of each body pair: {pair: (steps, 3)}"""
    off = f["contacts/offset"][:]
    if len(off) < 2:
        return {}
    bodies, force = f["contacts/bodies"][:], f["contacts/force_world"][:]
    pairs = {tuple(b) for b in bodies}
    out = {p: np.zeros((len(off) - 1, 3)) for p in pairs}
    for s in range(len(off) - 1):
        for k in range(off[s], off[s + 1]):
            out[tuple(bodies[k])][s] += force[k]
    return out


def measure(scene, h5, ref):
    body = SCENES[scene]["body"]
    with h5py.File(h5, "r") as f:
        tm = f["steps/timing"]
        t = sum(tm[k][:] for k in tm if k != "output")
        nc = f["steps/contacts"][:] if "contacts" in f["steps"] else np.zeros(len(t))
        x = f["bodies/%s/positions" % body][:]
        cen = f["bodies/%s/centroid" % body][:]
        fac = f["steps/factorizations"][:]
        kry = f["steps/krylov_iterations"][:]
        compl = f["steps/complementarity"][:] if "complementarity" in f["steps"] else np.zeros(1)
        pen = f["steps/max_penetration"][:] if "max_penetration" in f["steps"] else np.zeros(1)
        F = pair_forces(f)
    first = np.argmax(nc > 0) if (nc > 0).any() else len(nc)
    free = t[1:first] if first > 1 else t[1:]
    cont = t[nc > 0]
    m = dict(t=t, nc=nc, x=x, cen=cen, F=F, t_free=float(np.median(free)) if len(free) else float("nan"),
             t_contact=float(np.median(cont)) if len(cont) else float("nan"),
             t_contact_mean=float(np.mean(cont)) if len(cont) else float("nan"),
             factorizations=int(fac.sum()), krylov_per_step=float(kry.mean()),
             complementarity=float(np.max(compl)), max_penetration=float(np.max(pen)))
    if ref is not None:
        xr = ref["x"]
        D = np.abs(xr - xr[0]).max()
        n = min(len(x), len(xr))
        m["pos_curve"] = np.abs(x[:n] - xr[:n]).max(axis=(1, 2)) / D
        m["pos_err"] = float(m["pos_curve"].max())
        k = min(len(cen), len(ref["cen"]))
        m["centroid_err"] = float(np.linalg.norm(cen[:k] - ref["cen"][:k], axis=1).max() / D)
        fmax = max((np.abs(v).max() for v in ref["F"].values()), default=0.0)
        curve = np.zeros(n - 1)
        for p, v in ref["F"].items():
            w = F.get(p, np.zeros_like(v))
            k = min(len(v), len(w), n - 1)
            curve[:k] = np.maximum(curve[:k], np.linalg.norm(w[:k] - v[:k], axis=1) / fmax if fmax > 0 else 0.0)
        m["force_curve"] = curve
        m["force_err"] = float(curve.max()) if len(curve) else 0.0
    return m


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default="drop,rest,grasp,spin")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--quick", action="store_true", help="every_step and one reuse setting (a smoke test)")
    ap.add_argument("--momentum", action="store_true",
                    help="only the momentum of two colliding cubes (input/two_cubes.opts) in both modes")
    a = ap.parse_args()
    if a.momentum:
        momentum(a.np)
        return
    os.makedirs(OUT, exist_ok=True)
    settings = SETTINGS[:1] + SETTINGS[2:3] if a.quick else SETTINGS  # every_step, the default
    rows, curves = [], {}
    for scene in a.scenes.split(","):
        ref = None
        for label, opts in settings:
            t0 = time.time()
            h5, rss = run(scene, label, opts, a.np)
            m = measure(scene, h5, ref)
            if ref is None:
                ref = m
                m["pos_err"] = m["force_err"] = m["centroid_err"] = 0.0
                m["pos_curve"] = np.zeros(len(m["x"]))
                m["force_curve"] = np.zeros(max(len(m["t"]) - 1, 0))
            with h5py.File(h5, "r") as f:
                ndof = 3 * f["bodies/%s/positions" % SCENES[scene]["body"]].shape[1]
            row = dict(scene=scene, setting=label, steps=len(m["t"]), t_free=m["t_free"], t_contact=m["t_contact"],
                       t_contact_mean=m["t_contact_mean"], ratio_free=m["t_free"] / ref["t_free"],
                       ratio_contact=m["t_contact"] / ref["t_contact"], factorizations=m["factorizations"],
                       krylov_per_step=m["krylov_per_step"], peak_rss_mb=rss, dense_compliance_mb=8.0 * ndof**2 / 2**20,
                       pos_err=m["pos_err"], centroid_err=m["centroid_err"], force_err=m["force_err"], complementarity=m["complementarity"],
                       max_penetration=m["max_penetration"])
            rows.append(row)
            curves[(scene, label)] = (m["pos_curve"], m["force_curve"], m["t"])
            print("%-6s %-24s free %7.1f ms  contact %7.1f ms  (x%.3f, x%.3f)  pos %.2e  centroid %.2e  force %.2e  %3d fact  %4.1f CG/step  %.0f MB  [%.0f s]"
                  % (scene, label, 1e3 * m["t_free"], 1e3 * m["t_contact"], row["ratio_free"], row["ratio_contact"],
                     row["pos_err"], row["centroid_err"], row["force_err"], row["factorizations"], row["krylov_per_step"], rss,
                     time.time() - t0), flush=True)
    os.makedirs(os.path.join(ROOT, "docs", "accuracy"), exist_ok=True)
    if not a.quick:
        with open(os.path.join(ROOT, "docs", "accuracy", "factorization.csv"), "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=FIELDS)
            w.writeheader()
            for r in rows:
                w.writerow(r)
        plot(rows, curves)
    print("\nMachine: %s, %d cores, %s; %d rank(s); %s\n" % (platform.machine(), os.cpu_count(), platform.platform(),
                                                          a.np, time.strftime("%Y-%m-%d")))
    print("| scene | setting | free-fall step (ms) | contact step, median (ms) | contact step, mean (ms) | x every_step, free | x every_step, contact | factorizations | CG it./step | position error | centroid error | force error | complementarity (m) | peak RSS (MB) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print("| %s | %s | %.1f | %.1f | %.1f | %.3f | %.3f | %d | %.1f | %.1e | %.1e | %.1e | %.1e | %.0f |"
              % (r["scene"], r["setting"], 1e3 * r["t_free"], 1e3 * r["t_contact"], 1e3 * r["t_contact_mean"],
                 r["ratio_free"], r["ratio_contact"], r["factorizations"], r["krylov_per_step"], r["pos_err"],
                 r["centroid_err"], r["force_err"], r["complementarity"], r["peak_rss_mb"]))


def momentum(np_):
    """The drift of the two cubes' centroid sum over the run (no gravity, frictionless: it stays at
    its initial value when momentum is conserved), as tests/test_fe_fe.py measures it"""
    for mode in ("every_step", "reuse"):
        h5 = os.path.join(OUT, "two_cubes_%s.h5" % mode)
        cmd = [EXE, "-options_file", "input/two_cubes.opts", "-pgs_tol", "1e-12", "-pgs_max_it", "20000", "-quiet",
               "-left_factorization", mode, "-right_factorization", mode, "-output_file", h5]
        if np_ > 1:
            cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
        subprocess.run(cmd, cwd=ROOT, env=ENV, check=True)
        with h5py.File(h5, "r") as f:
            L, R = f["bodies/left/centroid"][:], f["bodies/right/centroid"][:]
            L0, R0 = f["bodies/left"].attrs["initial_centroid"], f["bodies/right"].attrs["initial_centroid"]
            print("two cubes, %-10s: centroid sum drifts %.1e m over %d steps" % (mode, np.abs((L + R) - (L0 + R0)).max(),
                                                                                 len(L)))


def plot(rows, curves):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for scene in sorted({r["scene"] for r in rows}):
        fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
        for r in rows:
            if r["scene"] != scene or r["setting"] == "every_step":
                continue
            pc, fc, t = curves[(scene, r["setting"])]
            ax[0].semilogy(np.maximum(pc, 1e-16), label=r["setting"])
            ax[1].semilogy(np.maximum(fc, 1e-16), label=r["setting"])
        for r in rows:
            if r["scene"] == scene:
                ax[2].plot(1e3 * curves[(scene, r["setting"])][2], label=r["setting"])
        ax[0].set(xlabel="step", ylabel="position error / displacement scale", title=scene + ": positions vs every_step")
        ax[1].set(xlabel="step", ylabel="contact force error / max force", title="contact forces vs every_step")
        ax[2].set(xlabel="step", ylabel="ms", title="time per step")
        for x in ax:
            x.grid(True, which="both", alpha=0.3)
        ax[2].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(ROOT, "docs", "accuracy", "factorization_%s.png" % scene), dpi=90)
        plt.close(fig)


if __name__ == "__main__":
    main()
