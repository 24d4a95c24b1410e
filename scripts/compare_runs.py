#!/usr/bin/python3
"""Before/after comparison of two builds of fecontact on the same scenes.

Runs the scenes below with the fecontact of a reference checkout (--ref-root, built in its
build/) and of this checkout, then prints, per scene and per output dataset, the largest
difference relative to the dataset's largest magnitude, and the mean time per phase of both
runs (/steps/timing). A refactoring that must not change behaviour shows differences at
round-off (the issue asks for 1e-12); anything above --tol is flagged and the exit status is 1.
On several ranks the reductions need not sum in the same order from run to run: --noise runs the
reference twice and flags only differences above both --tol and 10x the reference's own.

  /usr/bin/python3 scripts/compare_runs.py --ref-root /path/to/old/checkout [--np 1] [--tol 1e-12]
      [--scenes default,table1_18k_fast,...] [--out out/compare]

Make the reference checkout with e.g. `git worktree add /tmp/old <commit> && (cd /tmp/old &&
scripts/build.sh)`.
"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCENES = {
    "default": ["-options_file", "input/default.opts"],
    "table1_18k_fast": ["-options_file", "input/table1_18k.opts", "-constraint_scheme", "fast"],
    "table1_18k_standard": ["-options_file", "input/table1_18k.opts", "-constraint_scheme", "standard"],
    "grasp": ["-options_file", "input/grasp_rotate.opts"],
}

# What a run computed: body trajectories, contact forces and geometry, solver statistics
COMPARED = ("bodies/*/positions", "bodies/*/centroid", "bodies/*/rotation", "bodies/*/energy", "contacts/force",
            "contacts/point", "contacts/normal", "contacts/gap", "contacts/gap_end", "contacts/state",
            "contacts/bodies", "steps/contacts", "steps/constraint_rows", "steps/pgs_iterations",
            "steps/newton_iterations", "steps/residual", "steps/max_penetration", "steps/energy")


def run(root, scene, np_, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    cmd = [os.path.join(root, "build", "fecontact")] + SCENES[scene] + ["-output_file", out, "-quiet"]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    subprocess.run(cmd, cwd=root, env=env, check=True)


def datasets(f):
    names = []
    for pattern in COMPARED:
        if pattern.startswith("bodies/*/"):
            for b in f["bodies"]:
                name = "bodies/%s/%s" % (b, pattern.split("/")[-1])
                if name in f:
                    names.append(name)
        elif pattern in f:
            names.append(pattern)
    return names


def load(f, name):
    """A dataset; vertex positions in an order independent of the MPI partition (lexicographic
    order of the reference coordinates, as tests/fctest.py sorted_positions)"""
    x = np.asarray(f[name][()], dtype=float)
    if name.endswith("/positions"):
        ref = f[name.replace("/positions", "/mesh/reference")][()]
        x = x[:, np.lexsort(np.round(ref, 9).T[::-1]), :]
    return x


def differences(ref, new):
    """{dataset: (max |diff|, relative to the dataset's largest magnitude)}, or a string when the
    datasets do not match"""
    out = {}
    with h5py.File(ref, "r") as a, h5py.File(new, "r") as b:
        for name in datasets(a):
            if name not in b or b[name].shape != a[name].shape:
                out[name] = "missing or shape %s != %s" % (b[name].shape if name in b else None, a[name].shape)
                continue
            x, y = load(a, name), load(b, name)
            scale = np.max(np.abs(x)) if x.size else 0.0
            diff = np.max(np.abs(x - y)) if x.size else 0.0
            out[name] = (diff, diff / scale if scale > 0 else diff)
    return out


def compare(ref, new, tol, noise=None):
    """Prints the differences; a dataset fails when it is above tol and above 10x the reference's own
    run-to-run difference (noise: the same comparison between two runs of the reference)"""
    worst, bad = 0.0, []
    d = differences(ref, new)
    with h5py.File(ref, "r") as a, h5py.File(new, "r") as b:
        for name in datasets(a):
            if isinstance(d[name], str):
                bad.append("%s: %s" % (name, d[name]))
                continue
            diff, rel = d[name]
            floor = noise[name][1] if noise and not isinstance(noise.get(name), str) else 0.0
            worst = max(worst, rel)
            above = rel > tol and rel > 10 * floor
            flag = "  <-- above tol" if above else ""
            print("    %-32s max |diff| %.3e  relative %.3e%s%s" % (
                name, diff, rel, "  (reference vs itself %.3e)" % floor if noise else "", flag))
            if above:
                bad.append(name)
        ta, tb = a["steps/timing"], b["steps/timing"]
        print("    mean time per step and phase (s): reference / this checkout")
        for phase in ta:
            ma, mb = float(np.mean(ta[phase][()])), float(np.mean(tb[phase][()])) if phase in tb else float("nan")
            if ma > 1e-4 or mb > 1e-4:
                print("      %-16s %.4f / %.4f" % (phase, ma, mb))
    return worst, bad


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--ref-root", required=True, help="reference checkout, built in its build/")
    p.add_argument("--np", type=int, default=1, help="MPI ranks (default 1)")
    p.add_argument("--tol", type=float, default=1e-12, help="largest relative difference accepted")
    p.add_argument("--scenes", default=",".join(SCENES), help="comma-separated, from: " + ", ".join(SCENES))
    p.add_argument("--out", default=os.path.join(ROOT, "out", "compare"))
    p.add_argument("--reuse-ref", action="store_true", help="keep reference outputs already in --out")
    p.add_argument("--noise", action="store_true",
                   help="run the reference twice and accept differences up to 10x its own run-to-run difference "
                        "(several ranks: MPI reductions need not sum in the same order every run)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    failed = []
    for scene in args.scenes.split(","):
        if scene not in SCENES:
            sys.exit("compare_runs: unknown scene '%s' (known: %s)" % (scene, ", ".join(SCENES)))
        ref = os.path.abspath(os.path.join(args.out, "%s_np%d_ref.h5" % (scene, args.np)))
        new = os.path.abspath(os.path.join(args.out, "%s_np%d_new.h5" % (scene, args.np)))
        if not (args.reuse_ref and os.path.exists(ref)):
            run(os.path.abspath(args.ref_root), scene, args.np, ref)
        noise = None
        if args.noise:
            ref2 = ref.replace("_ref.h5", "_ref2.h5")
            if not (args.reuse_ref and os.path.exists(ref2)):
                run(os.path.abspath(args.ref_root), scene, args.np, ref2)
            noise = differences(ref, ref2)
        run(ROOT, scene, args.np, new)
        print("%s (%d rank%s):" % (scene, args.np, "s" if args.np > 1 else ""))
        worst, bad = compare(ref, new, args.tol, noise)
        print("    largest relative difference %.3e%s" % (worst, "" if not bad else "  FAILED: " + ", ".join(bad)))
        if bad:
            failed.append(scene)
    print("compare_runs: %s" % ("all scenes within %.0e" % args.tol if not failed else "differ: " + ", ".join(failed)))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
