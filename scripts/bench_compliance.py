#!/usr/bin/python3
"""Factorization alone against factorization + compliance, per compliance builder.

For each scene the FE body starts 2 cm above the plane it rests on, so that the first steps of the
run are free fall (no contact: the factorization of A alone) and the later ones are in contact (the
factorization and W_b = J A^-1 J^T, eq. 17). Per step, from /steps/timing of the output file (rank
0's wall clock; the explicit scheme builds W once per step):
  F      median of the factorization phase over the free steps after the first (the floor),
  F+W 1  factorization + compliance of the first step in contact (the builder learns its contacts),
  F+W    median of factorization + compliance over the later steps in contact,
  step   median of the whole step (every phase) over the later steps in contact,
and the ratios to F measured in the same run; "best F" is the smallest F of all the builders of a
scene and rank count (the plain factorization with the best ordering), the floor the ratios in the
last column are taken against.

Scenes: cube = input/cube_rest.opts (co-rotational, 17.5k DOFs, 18^3 vertices, refactored every
step); 18k..36k = input/table1_*.opts (linear boxes of Table 1, factored once: F is that
factorization, and F+W of a later step is W alone).

Usage: scripts/bench_compliance.py [--scenes cube,18k,24k,30k,36k] [--np 1,2]
                                   [--builders condensed,redundant,schur,precomputed] [--steps 14]
                                   [--markdown FILE]"""
import argparse
import os
import platform
import statistics
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {"cube": ("input/cube_rest.opts", "cube"), "18k": ("input/table1_18k.opts", "box"),
          "24k": ("input/table1_24k.opts", "box"), "30k": ("input/table1_30k.opts", "box"),
          "36k": ("input/table1_36k.opts", "box")}


def lifted(opts, body):
    """the body's -<body>_translate of the options file, 2 cm higher"""
    x = [0.0, 0.0, 0.0]
    with open(os.path.join(ROOT, opts)) as f:
        for line in f:
            w = line.split()
            if len(w) == 2 and w[0] == "-%s_translate" % body:
                x = [float(v) for v in w[1].split(",")]
    return "%g,%g,%g" % (x[0], x[1], x[2] + 0.02)


def run(scene, builder, np_, steps, tmp):
    opts, body = SCENES[scene]
    out = os.path.join(tmp, "%s_%s_np%d.h5" % (scene, builder, np_))
    cmd = [os.path.join(ROOT, "build", "fecontact"), "-options_file", opts, "-time_steps", str(steps),
           "-output_every", str(steps), "-%s_translate" % body, lifted(opts, body), "-compliance_type", builder,
           "-output_file", out, "-quiet"]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    subprocess.run(cmd, cwd=ROOT, env=env, check=True)
    with h5py.File(out, "r") as f:
        t = f["steps/timing"]
        fact, comp = t["factorization"][:], t["compliance"][:] + t["rebuild_w"][:]
        contacts = f["steps/contacts"][:]
        total = sum(t[k][:] for k in t.keys())
    os.remove(out)
    free = [i for i in range(1, len(contacts)) if contacts[i] == 0 and i < np.argmax(contacts > 0)]
    touch = [i for i in range(len(contacts)) if contacts[i] > 0]
    if not touch or (not free and fact[0] == 0):
        raise SystemExit("%s: no step before contact or no contact in %d steps" % (scene, steps))
    # a linear body factors once, at its first step: that is its F
    F = statistics.median(fact[free]) if free and np.all(fact[free] > 0) else fact[0]
    first = fact[touch[0]] + comp[touch[0]]
    steady = statistics.median(fact[touch[1:]] + comp[touch[1:]]) if len(touch) > 1 else float("nan")
    step = statistics.median(total[touch[1:]]) if len(touch) > 1 else float("nan")
    return F, first, steady, step, int(contacts[touch[-1]])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", default="cube,18k,24k,30k,36k")
    ap.add_argument("--np", default="1,2")
    ap.add_argument("--builders", default="condensed,redundant,schur,precomputed")
    ap.add_argument("--steps", type=int, default=14)
    ap.add_argument("--markdown")
    a = ap.parse_args()
    lines = ["Command: `scripts/bench_compliance.py --scenes %s --np %s --builders %s --steps %d`" %
             (a.scenes, a.np, a.builders, a.steps), "",
             "Machine: %s, %d cores, %s. OPENBLAS_NUM_THREADS=1; times in ms, rank 0's wall clock per step." %
             (platform.node(), os.cpu_count(), platform.platform()), "",
             "| scene | ranks | builder | contacts | F (ms) | F+W first contact (ms) | F+W in contact (ms) | "
             "(F+W) / F | (F+W) / best F | step in contact (ms) |", "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
    for line in lines:
        print(line, flush=True)
    with tempfile.TemporaryDirectory(prefix="bench-comp-") as tmp:
        for scene in a.scenes.split(","):
            for np_ in [int(x) for x in a.np.split(",")]:
                rows = []
                for b in a.builders.split(","):
                    rows.append((b,) + run(scene, b, np_, a.steps, tmp))
                best = min(r[1] for r in rows)
                for b, F, first, steady, step, nc in rows:
                    line = "| %s | %d | %s | %d | %.0f | %.0f | %.0f | %.2f | %.2f | %.0f |" % (
                        scene, np_, b, nc, 1e3 * F, 1e3 * first, 1e3 * steady, steady / F, steady / best, 1e3 * step)
                    lines.append(line)
                    print(line, flush=True)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
