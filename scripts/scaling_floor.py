#!/usr/bin/python3
"""What 2 ranks can gain on this machine: the floor of issue 16's 2-rank / 1-rank step ratio.

Two ranks share the machine's memory system and caches, so even work that splits perfectly does
not halve. This script measures that with the same work: per repeat and scene, one 1-rank run
alone on core 0, then two identical 1-rank runs at once (one on each core, `taskset`), then the
2-rank run (`mpirun -n 2`, Open MPI binds a rank to a core). A 1-rank run slowed down by its
twin by a factor s ("shared", per phase) means a perfect split of that phase's work over 2 ranks
takes s/2 of the 1-rank time; and MUMPS' numeric factorization does not split perfectly: its
busier rank does a share b > 1/2 of the flops (RINFO(3) against RINFOG(3), printed with -info),
so its floor is s b. The report gives per scene, for step 1 (the run's factorization: analysis,
numeric, Sigma^-1) and for the steps after it (no refactorization for a linear body), the
measured 2-rank ratio beside s/2, and the -log_view events of the factorization beside s/2 and
s b.

    /usr/bin/python3 scripts/scaling_floor.py [--scenes 36k,cube] [--repeat 3] [--steps 4]

Build first (Release); needs taskset (util-linux). Step times are /steps/wall_time, phases
/steps/timing (the largest time of a rank), events -log_view's max over the ranks."""
import argparse
import csv
import os
import re
import subprocess
import sys

import h5py

from scaling import ENV, EXE, ROOT, scene  # the scenes of issue 16's pair, as scripts/scaling.py runs them

OUT = os.path.join(ROOT, "build", "scaling_floor")
EVENTS = ["SchurAnalysis", "SchurNumeric", "SchurInverse"]
PHASES = ["factorization", "free_motion", "compliance", "contact_solver", "correction", "rebuild_w"]


def command(name, tag, steps):
    f = os.path.join(OUT, tag)
    return [EXE] + scene(name)[0] + ["-time_steps", str(steps), "-output_every", str(steps), "-constraint_scheme", "fast",
                                    "-newton_max_it", "5", "-quiet", "-output_file", f + ".h5",
                                    "-log_view", ":%s.csv:ascii_csv" % f, "-info", ":sys"]


def result(tag, out):
    """step 1 and the later steps' mean (wall time and phases), -log_view's events (max over the
    ranks, seconds over the run), the busier rank's share of the factorization flops"""
    s = h5py.File(os.path.join(OUT, tag + ".h5"), "r")["steps"]
    wall = s["wall_time"][:]
    r = {"step1": float(wall[0]), "later": float(wall[1:].mean())}
    for ph in PHASES:
        t = s["timing/" + ph][:]
        r["step1_" + ph], r["later_" + ph] = float(t[0]), float(t[1:].mean())
    with open(os.path.join(OUT, tag + ".csv")) as fl:
        for row in csv.reader(fl):
            if len(row) > 4 and row[0] == "Main Stage" and row[1] in EVENTS:
                r[row[1]] = max(r.get(row[1], 0.0), float(row[4]))
    shares = [float(a) / float(b) for b, a in re.findall(r"Schur DOFs: ([0-9.e+]+) flops \(([0-9.e+]+) on this rank\)", out)
              if float(b) > 0]
    r["busy"] = max(shares) if shares else float("nan")  # of the first factorization's lines (any rank)
    return r


def run(cmds):
    """runs the commands at once; their output"""
    ps = [subprocess.Popen(c, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True) for c in cmds]
    outs = [p.communicate()[0] for p in ps]
    for p, o, c in zip(ps, outs, cmds):
        if p.returncode:
            sys.stderr.write(o)
            raise RuntimeError("exit %d: %s" % (p.returncode, " ".join(c)))
    return outs


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="36k,cube")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--steps", type=int, default=4, help="steps per run (step 1 and the mean of the rest)")
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    rows = []
    for rep in range(1, a.repeat + 1):
        for sc in a.scenes.split(","):
            alone = result("alone", run([["taskset", "-c", "0"] + command(sc, "alone", a.steps)])[0])
            twins = run([["taskset", "-c", str(c)] + command(sc, "twin%d" % c, a.steps) for c in (0, 1)])
            twin = [result("twin%d" % c, twins[c]) for c in (0, 1)]
            out2 = run([["mpirun", "-n", "2", "--bind-to", "core"] + command(sc, "two", a.steps)])[0]
            two = result("two", out2)
            rows.append((sc, rep, alone, twin, two))
            shared = lambda k: max(t[k] for t in twin) / alone[k]  # noqa: E731
            print("%s %d: step 1 %.3f s alone, %.3f with its twin (x%.2f), %.3f on 2 ranks (%.2f, floor %.2f); "
                  "later steps %.3f, x%.2f, %.3f (%.2f, floor %.2f); busier rank %.0f %% of the flops" %
                  (sc, rep, alone["step1"], max(t["step1"] for t in twin), shared("step1"), two["step1"],
                   two["step1"] / alone["step1"], shared("step1") / 2, alone["later"], shared("later"), two["later"],
                   two["later"] / alone["later"], shared("later") / 2, 100 * two["busy"]), flush=True)
    print()
    print("`/usr/bin/python3 scripts/scaling_floor.py --scenes %s --repeat %d --steps %d`: per scene and repeat, "
          "the 1-rank run alone on a core, slowed down by an identical run on the other core by x (\"shared\"), "
          "and the 2-rank run against it; floor = x/2, and x b for MUMPS' numeric factorization, whose busier rank "
          "does a share b of the flops.\n" % (a.scenes, a.repeat, a.steps))
    print("| scene | repeat | step 1 alone (s) | shared | 2 ranks / alone | floor x/2 | SchurNumeric: shared | "
          "2 ranks / alone | floor x b (b) | SchurAnalysis, SchurInverse: 2 ranks / alone | later steps alone (s) | "
          "shared | 2 ranks / alone | floor x/2 |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for sc, rep, alone, twin, two in rows:
        sh = lambda k: max(t[k] for t in twin) / alone[k]  # noqa: E731
        print("| %s | %d | %.3f | %.2f | **%.2f** | %.2f | %.2f | %.2f | %.2f (%.2f) | %.2f, %.2f | %.3f | %.2f | **%.2f** | %.2f |" %
              (sc, rep, alone["step1"], sh("step1"), two["step1"] / alone["step1"], sh("step1") / 2, sh("SchurNumeric"),
               two["SchurNumeric"] / alone["SchurNumeric"], sh("SchurNumeric") * two["busy"], two["busy"],
               two["SchurAnalysis"] / alone["SchurAnalysis"], two["SchurInverse"] / alone["SchurInverse"],
               alone["later"], sh("later"), two["later"] / alone["later"], sh("later") / 2))
    print()
    print("Phases of the later steps, 2 ranks / alone (shared):")
    for sc, rep, alone, twin, two in rows:
        print("- %s %d: " % (sc, rep) + ", ".join(
            "%s %.2f (x%.2f)" % (ph, two["later_" + ph] / alone["later_" + ph], max(t["later_" + ph] for t in twin) / alone["later_" + ph])
            for ph in PHASES if alone["later_" + ph] >= 1e-3))


if __name__ == "__main__":
    main()
