#!/usr/bin/python3
"""What accuracy costs in time: sweeps of the settings users trade (constraint scheme, Newton
iterations, PGS sweeps, time step, mesh size, compliance option) on the fast-rotating grasp
(input/grasp_rotate.opts) and on a Table 1 scene (input/table1_18k.opts), one setting at a time
around a baseline, plus the full scheme x Newton-iterations grid.

For every run it records the time per step (the sum of the /steps/timing rows divided by the
steps: set-up excluded) and the errors the code measures at the end of every step (max and RMS
penetration, complementarity of the final forces in the end-of-step frames, friction-cone
violation, energy drift; docs/output.md), plus the distance to a converged reference run
(quarter time step, 10 Newton iterations, PGS to 1e-10): the largest distance between the
body's best-fit rigid pose and the reference's, evaluated at the corners of its bounding box
(comparable across meshes), relative to the body size.

Writes docs/accuracy/accuracy.csv, docs/accuracy/pareto_<scene>.png (error against time per
step) and docs/accuracy.md (the tables and the recommended settings for a few accuracy targets).

    scripts/accuracy_vs_time.py [--np 1] [--quick] [--scenes grasp,table1]

--quick runs a reduced sweep (for a smoke test; its figures are not the ones in the doc)."""
import argparse
import csv
import math
import os
import platform
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "fecontact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
OUT = os.path.join(ROOT, "build", "accuracy")

# scene: options file, FE body, final time T (the runs use T / h steps), baseline settings
SCENES = {
    "grasp": dict(opts="input/grasp_rotate.opts", body="object", T=0.6, mesh_option="-object_dm_plex_filename",
                  meshes=["meshes/cube_coarse.msh", "meshes/cube_medium.msh", "meshes/cube.msh"],
                  base=dict(scheme="fast", newton=5, pgs_max_it=1000, pgs_tol=1e-8, h=0.01, mesh="meshes/cube_coarse.msh",
                            compliance="dense", refactor=1),
                  refactor_option="-object_"),
    "table1": dict(opts="input/table1_18k.opts", body="box", T=0.04, mesh_option="-box_dm_plex_filename",
                   meshes=["meshes/table1_18k.msh"],  # the other Table 1 meshes are other boxes, not refinements
                   base=dict(scheme="fast", newton=5, pgs_max_it=1000, pgs_tol=1e-8, h=0.01, mesh="meshes/table1_18k.msh",
                             compliance="dense", refactor=1),
                   refactor_option=None),
}
FIELDS = ["scene", "group", "label", "scheme", "newton", "pgs_max_it", "pgs_tol", "h", "mesh", "compliance", "refactor",
          "steps", "time_per_step", "time_per_second", "compliance_first", "compliance_later", "wall", "pose_error", "iteration_error", "max_penetration", "rms_penetration", "complementarity",
          "cone_violation", "energy_drift", "pgs_sweeps_per_step", "newton_per_step"]


def options(scene, s):
    sc = SCENES[scene]
    steps = int(round(sc["T"] / s["h"]))
    o = ["-options_file", sc["opts"], "-time_step", repr(s["h"]), "-time_steps", str(steps), "-output_every", str(steps),
         "-constraint_scheme", s["scheme"]] + \
        (["-newton_max_it", str(s["newton"]), "-newton_tol", "0"] if s["scheme"] != "explicit" else []) + \
        ["-pgs_max_it", str(s["pgs_max_it"]), "-pgs_tol", repr(s["pgs_tol"]), "-compliance_type", s["compliance"],
         sc["mesh_option"], s["mesh"], "-quiet"]
    if s["refactor"] != 1:  # reuse (src/body/fem_schedule.c) refactoring every k steps, its other triggers off
        b = sc["refactor_option"]
        o += [b + "factorization", "reuse", b + "refactor_every", str(s["refactor"]), b + "refactor_rotation", "100",
              b + "refactor_residual", "100", b + "refactor_iterations", "1000"]
    return o, steps


REUSE = False  # --reuse: measure the output files of an earlier run of this script instead of running


def run(scene, s, tag, np_):
    o, steps = options(scene, s)
    f = os.path.join(OUT, "%s_%s.h5" % (scene, tag))
    if REUSE and os.path.exists(f):
        return f, steps, float("nan")  # same sweep order, same file names
    cmd = [EXE] + o + ["-output_file", f]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    t0 = time.time()
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("run failed: " + " ".join(cmd))
    return f, steps, wall


def pose(h5, body):
    """Best-fit rigid transform (R, t) of the body's final frame onto its reference coordinates,
    applied to the corners of the reference bounding box; and the body size"""
    X = h5["bodies/%s/mesh/reference" % body][:]
    x = h5["bodies/%s/positions" % body][-1]
    C, c = X.mean(0), x.mean(0)
    U, _, Vt = np.linalg.svd((x - c).T @ (X - C))
    R = U @ np.diag([1, 1, np.linalg.det(U @ Vt)]) @ Vt
    lo, hi = X.min(0), X.max(0)
    corners = np.array([[a[0], b[1], d[2]] for a in (lo, hi) for b in (lo, hi) for d in (lo, hi)])
    return (corners - C) @ R.T + c, np.linalg.norm(hi - lo)


def measure(scene, f, steps, wall):
    h5 = h5py.File(f, "r")
    s = h5["steps"]
    t = sum(s["timing/" + k][:].sum() for k in s["timing"])
    E = s["energy"][:]
    E0 = h5.attrs["initial_energy"][0]
    scale = max(np.abs(E).max(), abs(E0), 1e-30)
    comp = s["timing/compliance"][:]
    return dict(steps=steps, time_per_step=t / steps, time_per_second=t / (steps * h5.attrs["time_step"]), wall=wall,
                compliance_first=comp[0] if len(comp) else 0.0, compliance_later=comp[1:].mean() if len(comp) > 1 else 0.0, max_penetration=s["max_penetration"][:].max(),
                rms_penetration=np.sqrt(np.mean(s["rms_penetration"][:] ** 2)), complementarity=s["complementarity"][:].max(),
                cone_violation=s["cone_violation"][:].max(), energy_drift=(E[-1] - E0) / scale,
                pgs_sweeps_per_step=s["pgs_iterations"][:].sum() / steps, newton_per_step=s["newton_iterations"][:].sum() / steps), h5


def sweeps(scene, quick):
    """(group, label, settings) around the baseline"""
    sc = SCENES[scene]
    b = sc["base"]
    out = []

    def add(group, label, **kw):
        s = dict(b)
        s.update(kw)
        out.append((group, label, s))

    newtons = [1, 2, 3, 5] if quick else ([1, 2, 3, 4, 5, 6, 8] if scene == "grasp" else [1, 2, 3, 5, 8])
    add("scheme", "explicit", scheme="explicit", newton=1)
    for k in newtons:
        add("scheme", "fast n=%d" % k, scheme="fast", newton=k)
    for k in (newtons if scene == "grasp" and not quick else [1, 3, 5]):
        add("scheme", "standard n=%d" % k, scheme="standard", newton=k)
    for m in ([5, 30, 1000] if quick else [3, 10, 30, 100, 300, 1000]):
        add("pgs", "pgs %d sweeps" % m, pgs_max_it=m, pgs_tol=1e-12)
    for h in ([0.02, 0.01] if quick else ([0.04, 0.02, 0.01, 0.005] if scene == "grasp" else [0.02, 0.01, 0.005])):
        add("time step", "h=%g" % h, h=h)
    if len(sc["meshes"]) > 1:
        for m in sc["meshes"][: 2 if quick else None]:
            add("mesh", os.path.basename(m)[:-4], mesh=m)
    for c in ["dense", "schur", "precomputed"]:
        add("compliance", c, compliance=c)
    if sc["refactor_option"]:
        add("compliance", "condensed", compliance="condensed")
        for k in ([4] if quick else [2, 4, 8]):
            add("compliance", "condensed, reuse, refactor every %d" % k, compliance="condensed", refactor=k)
    return out


def pareto(rows, key="pose_error"):
    """Rows not dominated in (time per step, error)"""
    front = []
    for r in sorted(rows, key=lambda r: (r["time_per_step"], r[key])):
        if not front or r[key] < front[-1][key]:
            front.append(r)
    return front


def plot(scene, rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(19, 5.5))
    groups = sorted(set(r["group"] for r in rows))
    markers = dict(zip(groups, "osD^v<>"))
    for ax, key, title in [(axes[0], "pose_error", "distance to the h/4 reference (relative)"),
                           (axes[1], "iteration_error", "distance to the converged run, same h and mesh (relative)"),
                           (axes[2], "complementarity", "complementarity on the end-of-step geometry (m)")]:
        for g in groups:
            rr = [r for r in rows if r["group"] == g]
            ax.scatter([r["time_per_step"] * 1e3 for r in rr], [max(r[key], 1e-16) for r in rr], marker=markers[g], label=g, s=36)
            for r in rr:
                ax.annotate(r["label"], (r["time_per_step"] * 1e3, max(r[key], 1e-16)), fontsize=6, xytext=(3, 2),
                            textcoords="offset points")
        fr = pareto(rows, key)
        ax.plot([r["time_per_step"] * 1e3 for r in fr], [max(r[key], 1e-16) for r in fr], "k--", lw=0.8, label="Pareto front")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("time per step (ms)")
        ax.set_ylabel(title)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("%s: error against time per step (%s)" % (scene, SCENES[scene]["opts"]))
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def fmt(x):
    return "%.2e" % x if isinstance(x, float) else str(x)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--scenes", default="grasp,table1")
    ap.add_argument("--docdir", default=os.path.join(ROOT, "docs"))
    ap.add_argument("--reuse", action="store_true", help="measure the files of an earlier run instead of running")
    a = ap.parse_args()
    global REUSE
    REUSE = a.reuse
    os.makedirs(OUT, exist_ok=True)
    figdir = os.path.join(a.docdir, "accuracy")
    os.makedirs(figdir, exist_ok=True)
    allrows = []
    for scene in a.scenes.split(","):
        sc = SCENES[scene]
        # PGS to 1e-10: below, round-off stalls it (a floor near 5e-12 on the grasp)
        ref = dict(sc["base"], h=sc["base"]["h"] / 4, newton=10, pgs_tol=1e-10, pgs_max_it=20000)
        f, steps, wall = run(scene, ref, "reference", a.np)
        refm, refh5 = measure(scene, f, steps, wall)
        refpose, size = pose(refh5, sc["body"])
        print("%s reference: %d steps of %g s, %.1f s wall, complementarity %.2e" % (scene, steps, ref["h"], wall, refm["complementarity"]), flush=True)
        converged = {}  # (h, mesh) -> final pose of the converged run with that time step and mesh
        for i, (group, label, s) in enumerate(sweeps(scene, a.quick)):
            key = (s["h"], s["mesh"])
            if key not in converged:
                cs = dict(sc["base"], h=s["h"], mesh=s["mesh"], newton=10, pgs_tol=1e-10, pgs_max_it=20000)
                f, steps, wall = run(scene, cs, "converged_%d" % len(converged), a.np)
                converged[key] = pose(measure(scene, f, steps, wall)[1], sc["body"])[0]
            f, steps, wall = run(scene, s, "%02d" % i, a.np)
            m, h5 = measure(scene, f, steps, wall)
            p, _ = pose(h5, sc["body"])
            m["pose_error"] = np.abs(p - refpose).max() / size
            m["iteration_error"] = np.abs(p - converged[key]).max() / size
            row = dict(scene=scene, group=group, label=label, scheme=s["scheme"], newton=s["newton"], pgs_max_it=s["pgs_max_it"],
                       pgs_tol=s["pgs_tol"], h=s["h"], mesh=os.path.basename(s["mesh"]), compliance=s["compliance"],
                       refactor=s["refactor"], **m)
            row["final_pose"], row["size"] = p, size  # for the mesh group's differences (reading), not in the CSV
            allrows.append(row)
            print("%-7s %-11s %-32s %8.2f ms/step  pose err %.2e  iter err %.2e  compl %.2e  pen %.2e  cone %.2e" % (
                scene, group, label, m["time_per_step"] * 1e3, m["pose_error"], m["iteration_error"], m["complementarity"], m["max_penetration"],
                m["cone_violation"]), flush=True)
        plot(scene, [r for r in allrows if r["scene"] == scene], os.path.join(figdir, "pareto_%s.png" % scene))
    write_csv(allrows, os.path.join(figdir, "accuracy.csv"))
    write_doc(a, allrows, os.path.join(a.docdir, "accuracy.md"))


def reading(scene, rr):
    """Sentences computed from the measurements: what each knob buys"""
    by = {r["label"]: r for r in rr}
    L = ["### Reading the %s results" % scene, ""]
    fast = [by["fast n=%d" % k] for k in range(1, 9) if "fast n=%d" % k in by]
    if len(fast) > 2 and fast[0]["iteration_error"] > 0:
        e = [r["iteration_error"] for r in fast]
        if e[-1] < 1e-3 * e[0]:
            rate = (e[-1] / e[0]) ** (1.0 / (fast[-1]["newton"] - fast[0]["newton"]))
            L.append("- **Newton iterations** (fast scheme): the iteration error falls from %.1e (1 iteration, the explicit "
                     "scheme's linearization) to %.1e (%d), a factor %.2f per iteration; the complementarity from %.1e m to "
                     "%.1e m. Each iteration adds %.2f ms/step (PGS, W_k rebuild)." % (
                         e[0], e[-1], fast[-1]["newton"], rate, fast[0]["complementarity"], fast[-1]["complementarity"],
                         (fast[-1]["time_per_step"] - fast[0]["time_per_step"]) * 1e3 / max(fast[-1]["newton"] - 1, 1)))
        else:
            L.append("- **Newton iterations** change nothing measurable here (iteration error %.1e to %.1e): the contact "
                     "normals do not change within a step (a plane), so one linearization is exact." % (e[0], e[-1]))
    std = [r for r in rr if r["label"].startswith("standard n=")]
    if std:
        k = max(std, key=lambda r: r["newton"])
        f = by.get("fast n=%d" % k["newton"])
        if f:
            d = abs(k["iteration_error"] - f["iteration_error"]) / max(f["iteration_error"], 1e-300)
            L.append("- **Standard against fast update** at %d iterations: the same errors (iteration error %.2e against "
                     "%.2e), %.1f against %.1f ms/step (%.1fx): the fast update rebuilds W_k from W_H instead of "
                     "recomputing the compliance." % (k["newton"], k["iteration_error"], f["iteration_error"],
                                                      k["time_per_step"] * 1e3, f["time_per_step"] * 1e3,
                                                      k["time_per_step"] / f["time_per_step"]))
    pgs = sorted([r for r in rr if r["group"] == "pgs"], key=lambda r: r["pgs_max_it"])
    if pgs:
        ref = pgs[-1]
        enough = next((r for r in pgs if abs(r["iteration_error"] - ref["iteration_error"]) <= 0.01 * ref["iteration_error"]
                       and r["max_penetration"] <= 10 * ref["max_penetration"] + 1e-12), ref)
        L.append("- **PGS sweeps** (per Newton iteration, NNCG): %d sweeps already give the iteration error of %d (%.2e); "
                 "fewer leave penetration (%.1e m with %d). Capping the sweeps costs accuracy only below that." % (
                     enough["pgs_max_it"], ref["pgs_max_it"], ref["iteration_error"], pgs[0]["max_penetration"], pgs[0]["pgs_max_it"]))
    hs = sorted([r for r in rr if r["group"] == "time step"], key=lambda r: r["h"])
    if len(hs) > 1:
        L.append("- **Time step**: pose error " + ", ".join("%.1e (h = %g)" % (r["pose_error"], r["h"]) for r in hs) +
                 "; at 5 Newton iterations and more, the discretization error of implicit Euler dominates the pose "
                 "error (compare the iteration errors). Halving h costs twice the steps: %s s per simulated second." %
                 ", ".join("%.2f" % r["time_per_second"] for r in hs))
    ms = [r for r in rr if r["group"] == "mesh"]
    if len(ms) > 1:
        L.append("- **Mesh**: " + ", ".join("%s %.1f ms/step (pose error %.1e)" % (r["label"], r["time_per_step"] * 1e3, r["pose_error"]) for r in ms) + ".")
        # the reference is the coarsest mesh's h/4 run, so a finer mesh's pose error holds the coarse mesh's own
        # discretization error; whether the meshes converge shows in their distances to each other at the same h
        d = ["%s to %s %.1e" % (a["label"], b["label"], np.abs(a["final_pose"] - b["final_pose"]).max() / a["size"])
             for a, b in zip(ms, ms[1:])]
        L.append("  The reference is the %s mesh's (h/4), so the pose error of a finer mesh includes the %s mesh's own "
                 "discretization error. Each mesh against the next finer one, the same pose distance at h = %g: %s." % (
                     ms[0]["label"], ms[0]["label"], ms[0]["h"], ", ".join(d)))
    comp = {r["label"]: r for r in rr if r["group"] == "compliance"}
    if "precomputed" in comp and "dense" in comp:
        p, d = comp["precomputed"], comp["dense"]
        L.append("- **Precomputed compliance**: W costs %.1f ms in the first step (the surface columns of A_0^-1 are "
                 "computed as vertices enter contact) and %.2f ms per later step, against %.1f ms per step for dense; its "
                 "iteration error is %.1e (%s)." % (
                     p["compliance_first"] * 1e3, p["compliance_later"] * 1e3, d["compliance_later"] * 1e3, p["iteration_error"],
                     "exact: a linear material" if p["iteration_error"] < 1e-8 else "the rotation-warped reference compliance of a co-rotational body"))
    rf = [r for r in rr if r["refactor"] > 1]
    if rf:
        L.append("- **Older factorization** (co-rotational, `-object_factorization reuse` factoring every k steps and "
                 "nothing else: CG free motion, warped compliance; docs/method.md): " + ", ".join(
            "%s: %.1f ms/step, iteration error %.1e" % (r["label"], r["time_per_step"] * 1e3, r["iteration_error"]) for r in rf) +
                 "; the factorization is a small share of a step on this mesh, so little is saved for the error "
                 "(the section \"Factorization schedule\" measures it where the factorization dominates).")
    L.append("")
    return L


def kept_sections(path, scenes):
    """The sections ("## ...") of an existing page that this run does not regenerate, kept as they
    are: those of the scenes it does not measure (a run with --scenes grasp regenerates only the
    grasp section), and those other commands wrote (after the scenes')"""
    keep, other, cur = {}, [], None
    if os.path.exists(path):
        for line in open(path).read().split("\n"):
            if line.startswith("## "):
                name = line[3:].split()[0]
                cur = None if name in scenes else (keep.setdefault(name, []) if name in SCENES else other)
            elif line.startswith("The CSV with every column"):
                cur = None
                continue
            if cur is not None:
                cur.append(line)
    return keep, other


def write_csv(rows, path):
    """This run's rows, and an existing CSV's rows of the scenes it did not measure"""
    scenes = set(r["scene"] for r in rows)
    old = []
    if os.path.exists(path):
        with open(path, newline="") as f:
            old = list(csv.DictReader(f))
    # --reuse measures earlier files: their wall time (nan here) is the earlier run's
    walls = {(r["scene"], r["group"], r["label"]): r["wall"] for r in old}
    old = [r for r in old if r["scene"] not in scenes]
    rows = [dict(r, wall=walls.get((r["scene"], r["group"], r["label"]), r["wall"])) if math.isnan(r["wall"]) else r
            for r in rows]
    with open(path, "w", newline="") as fcsv:
        w = csv.DictWriter(fcsv, fieldnames=FIELDS)
        w.writeheader()
        order = list(SCENES)
        for r in sorted(old + rows, key=lambda r: order.index(r["scene"]) if r["scene"] in order else len(order)):
            w.writerow({k: r.get(k, "") for k in FIELDS})


def write_doc(a, rows, path):
    cmd = "scripts/accuracy_vs_time.py --np %d%s --scenes %s%s" % (a.np, " --quick" if a.quick else "", a.scenes,
                                                                 " --reuse" if a.reuse else "")
    made = "Generated by `%s` (%s, %s, %d core(s), %d MPI rank(s), one run per setting%s)." % (
        cmd, time.strftime("%Y-%m-%d"), platform.machine(), os.cpu_count(), a.np,
        "; --reuse: measured from the output files of an earlier run of the same settings" if a.reuse else "")
    keep, other = kept_sections(path, set(r["scene"] for r in rows))
    L = ["# Accuracy against time per step", "",
         "Each section below says which command generated it and when (a run with `--scenes` regenerates only "
         "those scenes' sections and CSV rows). Wall times on this machine are noisy: compare within a table.", "",
         "Each setting is changed alone around a baseline (fast scheme, 5 Newton iterations, PGS to 1e-8 or 1000 "
         "sweeps, h = 0.01 s, coarsest mesh, dense compliance). Errors:", "",
         "- **pose error**: largest distance, at the corners of the body's bounding box, between the body's "
         "best-fit rigid pose at the final time and that of a converged reference run (h/4, 10 Newton iterations, "
         "PGS to 1e-10, on the baseline's mesh), relative to the body's diagonal: time discretization, mesh and solver "
         "errors together;",
         "- **iteration error**: the same distance to the converged run (10 Newton iterations, PGS to 1e-10, dense "
         "compliance, refactored every step) with the **same** time step and mesh: what the cheaper Newton/PGS/"
         "compliance settings cost, without the time-discretization error;",
         "- **complementarity** (m), **penetration** (m), **cone violation** (-): the worst step of "
         "`/steps/complementarity`, `/steps/max_penetration`, `/steps/cone_violation` (docs/output.md): how far the "
         "final forces and positions are from a contact solution on the real end-of-step geometry;",
         "- **energy drift**: (E_end - E_0) / max |E| (the grasp's fingers do work on the cube, so it is not zero there);",
         "- **time per step**: the sum of the per-phase timing rows divided by the steps (set-up excluded).", ""]
    for scene in SCENES:
        if scene in keep:
            L += keep[scene]
            continue
        rr = [r for r in rows if r["scene"] == scene]
        if not rr:
            continue
        sc = SCENES[scene]
        L += ["## %s (`%s`, %g s simulated)" % (scene, sc["opts"], sc["T"]), "", made, "",
              "![Pareto plot](accuracy/pareto_%s.png)" % scene, "",
              "| group | setting | ms/step | pose error | iteration error | complementarity (m) | max penetration (m) | cone violation | energy drift | PGS sweeps/step |",
              "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for r in rr:
            L.append("| %s | %s | %.1f | %.2e | %.2e | %.2e | %.2e | %.2e | %.2e | %.0f |" % (
                r["group"], r["label"], r["time_per_step"] * 1e3, r["pose_error"], r["iteration_error"], r["complementarity"], r["max_penetration"],
                r["cone_violation"], r["energy_drift"], r["pgs_sweeps_per_step"]))
        for key, what in [("pose_error", "the pose error (to the h/4 reference)"),
                          ("iteration_error", "the iteration error (to the converged run at the same h and mesh)")]:
            L += ["", "Recommended for a target on %s and on the complementarity (m, for a ~1 m body): the measured "
                  "setting meeting both that simulates one second fastest (time per step / h):" % what, "",
                  "| target | setting | ms/step | s per simulated s | %s | complementarity (m) |" % key.replace("_", " "),
                  "|---|---|---:|---:|---:|---:|"]
            for tgt in (1e-2, 1e-3, 1e-4, 1e-6):
                ok = [r for r in rr if r[key] <= tgt and r["complementarity"] <= tgt]
                if ok:
                    best = min(ok, key=lambda r: r["time_per_second"])
                    L.append("| %g | %s (%s) | %.1f | %.2f | %.2e | %.2e |" % (
                        tgt, best["label"], best["group"], best["time_per_step"] * 1e3, best["time_per_second"], best[key],
                        best["complementarity"]))
                else:
                    L.append("| %g | none of the measured settings | | | | |" % tgt)
        L += [""] + reading(scene, rr)
        L.append("")
    L += ["The CSV with every column (scene, settings, time, every error) is `docs/accuracy/accuracy.csv`.", ""]
    L += other
    with open(path, "w") as f:
        f.write("\n".join(L))
    print("wrote", path)


if __name__ == "__main__":
    main()
