#!/usr/bin/python3
"""The contact solver replicated (-pgs_ranks root, the default: rank 0 solves, the others wait for
its broadcast) against split over the ranks (-pgs_ranks split,
src/contact/pgs_split.c), on contact problems of FE scenes: each scene is run one step into
contact with -pgs_dump_problem, and tools/fclib_solve -dense solves the dumped problem on 1, 2
and 4 ranks (4: oversubscribed on a 2-core machine). Printed per problem and rank count: sweeps
to 1e-8 and time (the solve alone, max over ranks; the fastest of --repeat solves from zero in one
run of fclib_solve, caches warm as in a time step that has just built W), and time per sweep; the crossover is the
size where split on 2 ranks beats the replicated solver. Then, per problem, a two-point Amdahl fit
of the replicated 1-rank time and the split 2-rank time, t(p) = t(1) (f + (1 - f) / p) with the
serial share f = (2 t(2) - t(1)) / t(1) clipped to [0, 1], predicts the split solver beyond the
machine (an upper bound on the speed-up: it assumes the sweeps do not grow with p, which they do
on the Table 1 boxes at 4 ranks, and that the exchange per sweep stays negligible).

    scripts/bench_split.py [--ranks 1,2,4] [--repeat 5] [--markdown FILE]"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "fecontact")
SOLVE = os.path.join(ROOT, "build", "fclib_solve")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
OUT = os.path.join(ROOT, "build", "bench_split")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from scaling import big_mesh, serial_share  # noqa: E402

SCENES = [("cube drop 1.1k", ["-options_file", "input/cube_drop.opts", "-time_steps", "45"], 100),
          ("cube at rest 17.5k", ["-options_file", "input/cube_rest.opts", "-time_steps", "3"], 900),
          ("Table 1 box 18k", ["-options_file", "input/table1_18k.opts", "-time_steps", "4"], 800),
          ("Table 1 box 36k", ["-options_file", "input/table1_36k.opts", "-time_steps", "4"], 1400),
          ("box 149k", ["-options_file", "input/table1_36k.opts", "-time_steps", "2"], 4000)]


def solve(path, np_, split, repeat):
    cmd = [SOLVE, "-problem", path, "-dense", "-pgs_ranks", "split" if split else "root", "-repeat", str(repeat)]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    o = subprocess.run(cmd, env=ENV, capture_output=True, text=True, check=True, timeout=3600).stdout.split()
    d = dict(zip(o[0::2], o[1::2]))
    return int(d["sweeps"]), float(d["residual"]), float(d["time"]), d["converged"] == "1", int(d["rows"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", default="1,2,4")
    ap.add_argument("--repeat", type=int, default=5,
                    help="each line: the fastest of this many solves from zero in one run (fclib_solve -repeat)")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    ranks = [int(x) for x in a.ranks.split(",")]
    amdahl = ["| problem | replicated, 1 rank (s) | split, 2 ranks (s) | serial share | predicted 4 | 8 | 16 ranks (s) | "
              "speed-up at 16 |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    lines = ["| problem | rows | solver | ranks | sweeps | residual | time (s) | per sweep (ms) | vs replicated, 1 rank |",
             "|---|---:|---|---:|---:|---:|---:|---:|---:|"]
    for name, opts, rows in SCENES:
        if "149k" in name:
            opts = opts + ["-box_dm_plex_filename", big_mesh()]
        dump = os.path.join(OUT, name.replace(" ", "_") + ".hdf5")
        if not os.path.exists(dump) or os.path.getsize(dump) == 0:
            subprocess.run([EXE] + opts + ["-pgs_dump_problem", dump, "-pgs_dump_rows", str(rows), "-quiet",
                                           "-output_file", os.path.join(OUT, "run.h5")], cwd=ROOT, env=ENV, check=True)
        if os.path.getsize(dump) == 0:
            raise RuntimeError("%s: no contact problem of %d rows in the run (more -time_steps?)" % (name, rows))
        ref = None
        best2 = None
        for split in (False, True):
            for np_ in ranks:
                if split and np_ == 1:
                    continue
                best = solve(dump, np_, split, a.repeat)  # the fastest of a.repeat solves in one run
                sweeps, res, t, conv, n = best
                ref = t if ref is None else ref
                if split and np_ == 2 and conv:
                    best2 = t
                line = "| %s | %d | %s | %d%s | %d | %.1e%s | %.4f | %.3f | %.2f |" % (
                    name, n, "split" if split else "replicated", np_, " (oversubscribed)" if np_ > os.cpu_count() else "",
                    sweeps, res, "" if conv else " (not converged)", t, 1e3 * t / max(sweeps, 1), t / ref)
                print(line, flush=True)
                lines.append(line)
        if best2 is not None:
            f = serial_share([(ref, best2)])
            amdahl.append("| %s | %.4f | %.4f | %.0f%% | %s | %.1fx |" % (
                name, ref, best2, 100 * f, " | ".join("%.4f" % (ref * (f + (1 - f) / p)) for p in (4, 8, 16)),
                1.0 / (f + (1 - f) / 16)))
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("Machine: %s, %d cores, `OPENBLAS_NUM_THREADS=1`; `scripts/bench_split.py --ranks %s --repeat %d` "
                    "(the fastest of %d solves per line in one run of fclib_solve, each from a zero start, to -pgs_tol 1e-8).\n\n" %
                    (os.uname().nodename, os.cpu_count(), a.ranks, a.repeat, a.repeat))
            f.write("\n".join(lines) + "\n\nAmdahl fit of the split solver (replicated 1 rank, split 2 ranks):\n\n")
            f.write("\n".join(amdahl) + "\n")
    print("\n".join(amdahl))


if __name__ == "__main__":
    main()
