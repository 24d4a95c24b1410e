#!/usr/bin/python3
"""Strong and weak scaling of fecontact, per phase.

Strong scaling: the 36k-DOF Table 1 scene (input/table1_36k.opts: 480 contacts) and a 149k-DOF
box of the same family (40 x 40 x 31 vertices, 1600 contacts, made here with gmsh into
build/meshes/table1_150k.msh) at 1, 2, ... ranks. Weak scaling: a fixed DOF count per rank
(the 18k box on 1 rank, the 36k box on 2). Also measured: the W_H builders that run on several
ranks (-compliance_type dense: distributed MUMPS solves with dense right-hand sides; schur: the
MUMPS Schur complement centralized on rank 0; inverse: MUMPS' selected entries of A^-1 from the
distributed factor; redundant: the same from a sequential factor on every rank, 1/p of the columns
each; condensed, the default: (A^-1)_SS from the body's own factorization with the contact DOFs
last), their peak memory per rank, and where the contact solver runs
(-pgs_ranks auto, the default: split over the ranks from 900 rows, which every scene here has;
root: rank 0 and a broadcast; all: replicated on every rank).

Per-phase times per step come from the HDF5 rows /steps/timing/<phase> (max over ranks, set-up
excluded); the set-up (load, distribution, first assembly and factorization) from the wall time
minus the steps; -log_view's CSV gives the message and reduction counts. Every run with more than
one rank is checked against the 1-rank run (final vertex positions, relative).

    scripts/scaling.py [--ranks 1,2] [--check-ranks 4] [--steps 3] [--markdown docs/scaling.md] [--reuse | --redraw]
    scripts/scaling.py --repeat-pair N [--steps 3]

--repeat-pair N runs only issue 16's pair (the 36k box and the co-rotational cube, default builder,
1 and 2 ranks), N times, 1 and 2 ranks alternating so that both see the machine in the same state,
and prints the 2-rank / 1-rank ratio of every repeat, per phase, as a markdown table (nothing is
written to docs/): on this shared VM the ratio moves from run to run and from day to day, and one
pair of runs does not say how far.

A run whose final state differs from the 1-rank run by more than 1e-8 (relative) is marked wrong
in the table and left out of the speed sentences, the Amdahl table and the plots.

Ranks beyond the machine's cores are run with --oversubscribe for correctness only; their times
are not reported as scaling."""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "fecontact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
OUT = os.path.join(ROOT, "build", "scaling")
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import sorted_positions  # noqa: E402

BUILDERS = ["dense", "schur", "inverse", "redundant", "condensed"]
PHASES = ["assembly", "factorization", "free_motion", "collision", "compliance", "contact_solver", "correction",
          "rebuild_w", "proximity_update", "integration", "output"]


def table1_mesh(name, nx, ny, nz):
    """build/meshes/<name>.msh: the Table 1 box family (meshes/table1.geo) at nx x ny x nz vertices, made
    by gmsh the first time"""
    m = os.path.join(ROOT, "build", "meshes", name + ".msh")
    if not os.path.exists(m):
        os.makedirs(os.path.dirname(m), exist_ok=True)
        subprocess.run(["gmsh", "-3", "-nt", "1", "-format", "msh41", "-bin", "-setnumber", "nx", str(nx), "-setnumber",
                        "ny", str(ny), "-setnumber", "nz", str(nz), "-setnumber", "d", "0.05",
                        os.path.join(ROOT, "meshes", "table1.geo"), "-o", m], check=True, capture_output=True)
    return m


def big_mesh():
    return table1_mesh("table1_150k", 40, 40, 31)


def scene(name):
    if name == "cube":  # the co-rotational 17.5k-DOF cube at rest on a plane: A refactored every step
        return ["-options_file", "input/cube_rest.opts"], 17496
    if name == "36k":
        return ["-options_file", "input/table1_36k.opts"], 36000
    if name == "18k":
        return ["-options_file", "input/table1_36k.opts", "-box_dm_plex_filename", "meshes/table1_18k.msh"], 18000
    return ["-options_file", "input/table1_36k.opts", "-box_dm_plex_filename", big_mesh()], 148800


def timed(path):
    """/usr/bin/time in front of every rank, appending each rank's peak RSS to `path` (one short
    line per rank, O_APPEND: the lines cannot interleave as the ranks' stderr did, which once left
    a run's RSS empty)"""
    if os.path.exists(path):
        os.remove(path)
    return ["/usr/bin/time", "-a", "-o", path, "-f", "maxrss_kb %M"]


def peak_rss(path):
    """The ranks' peak RSS (MB) from the file that timed() named"""
    with open(path) as f:
        return [int(x) / 1024.0 for x in re.findall(r"maxrss_kb (\d+)", f.read())]


def run(tag, args, np_, steps):
    f = os.path.join(OUT, tag + ".h5")
    log = os.path.join(OUT, tag + ".csv")
    cmd = [EXE] + args + ["-time_steps", str(steps), "-output_every", str(steps), "-constraint_scheme", "fast",
                          "-newton_max_it", "5", "-quiet", "-output_file", f, "-log_view", ":%s:ascii_csv" % log]
    rssf = os.path.join(OUT, tag + ".rss")
    cmd = timed(rssf) + cmd  # on every rank
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + cmd
    t0 = time.time()
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode:
        sys.stderr.write(p.stdout + p.stderr)
        why = [l for l in (p.stdout + p.stderr).splitlines() if "error:" in l][:1]
        raise RuntimeError("exit %d, %s" % (p.returncode, why[0].strip() if why else "no message"))
    rss = max(peak_rss(rssf) or [float("nan")])
    h = h5py.File(f, "r")
    s = h["steps"]
    per = {ph: float(s["timing/" + ph][:].mean()) for ph in PHASES}
    # the step's wall time (the ranks meet at the end of every step), not the sum of the phases:
    # each phase is the largest time of a rank, and a rank waiting in one phase for another's work
    # in the previous one would count that work twice
    step = float(s["wall_time"][:].mean())
    msgs = reds = 0.0
    with open(log) as fl:
        for row in csv.reader(fl):
            if len(row) > 7 and row[0] == "Main Stage" and row[1] == "summary":
                msgs = max(msgs, float(row[5]))
                reds = max(reds, float(row[7]))
    return dict(tag=tag, ranks=np_, steps=steps, wall=wall, setup=wall - step * steps, step=step,
                contacts=int(s["contacts"][-1]), messages=msgs, reductions=reds, rss_mb=rss, **per), h


def memory(mesh, np_):
    """Peak resident memory of every rank (MB) loading the 149k box and taking one step"""
    rssf = os.path.join(OUT, "mem.rss")
    cmd = ["mpirun", "-n", str(np_), "--oversubscribe"] + timed(rssf) + [EXE,
           "-options_file", "input/table1_36k.opts", "-box_dm_plex_filename", mesh,
           "-time_steps", "1", "-quiet", "-output_file", os.path.join(OUT, "mem.h5")]
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    if p.returncode:
        sys.stderr.write(p.stdout + p.stderr)
        raise RuntimeError("failed: " + " ".join(cmd))
    return sorted(peak_rss(rssf))


def stored(a, name, stamp, compute):
    """compute(), kept in build/scaling/<name>.json: --reuse takes it back when the stamp (binary, steps)
    matches, --redraw whatever the last sweep stored"""
    cache = os.path.join(OUT, name + ".json")
    if a.redraw or (a.reuse and os.path.exists(cache) and json.load(open(cache))["stamp"] == stamp):
        return json.load(open(cache))["value"]
    value = compute()
    with open(cache, "w") as f:
        json.dump({"stamp": stamp, "value": value}, f)
    return value


def serial_share(pairs):
    """Two-point Amdahl fit of (1-rank, 2-rank) times, one pair per phase: each phase's serial part
    is 2 t(2) - t(1), clipped to [0, t(1)]; returns the serial share of the summed 1-rank times (the
    fit then predicts t(p) = t(1) (f + (1 - f) / p))"""
    ser = sum(min(max(0.0, 2 * t2 - t1), t1) for t1, t2 in pairs)
    return ser / max(sum(t1 for t1, _ in pairs), 1e-30)


def phase_ratios(r1, r2):
    """per phase, the 2-rank time over the 1-rank time ("-" for a phase under 1 ms on 1 rank)"""
    return ["%.2f" % (r2[ph] / r1[ph]) if r1[ph] >= 1e-3 else "-" for ph in PHASES]


def diff(h1, h2):
    body = "cube" if "cube" in h1["bodies"] else "box"
    a, b = sorted_positions(h1, body)[1], sorted_positions(h2, body)[1]
    return float(np.abs(a - b).max() / np.abs(a).max())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--check-ranks", default="4")
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--reuse", action="store_true",
                    help="reuse the runs of an interrupted sweep (same binary and steps, build/scaling/*.json)")
    ap.add_argument("--redraw", action="store_true",
                    help="run nothing: redraw the CSV, plots and markdown from the stored runs of the last sweep")
    ap.add_argument("--markdown", default=os.path.join(ROOT, "docs", "scaling.md"))
    ap.add_argument("--repeat-pair", type=int, default=0, metavar="N",
                    help="only issue 16's pair (36k, cube; 1 and 2 ranks), N times; print the ratios")
    ap.add_argument("--versus", default="", metavar="OPTS",
                    help="with --repeat-pair: each repeat also runs the pair with these options added (after the "
                    "defaults' pair), so that both variants' ratios come from one run")
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    if a.repeat_pair < 0:
        ap.error("--repeat-pair N: N must be >= 1 (0: the whole sweep), got %d" % a.repeat_pair)
    if a.versus and not a.repeat_pair:
        ap.error("--versus goes with --repeat-pair N")
    if a.repeat_pair:
        return repeat_pair(a)
    figdir = os.path.join(os.path.dirname(a.markdown), "scaling")
    os.makedirs(figdir, exist_ok=True)
    ranks = [int(r) for r in a.ranks.split(",")]
    check = [int(r) for r in a.check_ranks.split(",") if r]
    rows = []
    failed = a.failed = []

    def rec(kind, scene_name, ctype, pgs, np_, ref=None):
        args, dofs = scene(scene_name)
        args = args + ["-compliance_type", ctype, "-pgs_ranks", pgs]
        tag = "%s_%s_%s_%s_np%d" % (kind, scene_name, ctype, pgs, np_)
        try:
            r = stored(a, tag, [os.path.getmtime(EXE), a.steps], lambda: run(tag, args, np_, a.steps)[0])
        except RuntimeError as e:  # a run that stops (the W check, exit 2) is reported, not hidden
            failed.append("%s, %s DOFs, `%s`, %d ranks: %s" % (kind, scene_name, ctype, np_, e.args[0]))
            print("FAILED", failed[-1], flush=True)
            return ref
        h = h5py.File(os.path.join(OUT, tag + ".h5"), "r")
        r.update(kind=kind, scene=scene_name, dofs=dofs, builder=ctype, pgs_ranks=pgs,
                 oversubscribed=np_ > (os.cpu_count() or 1), vs_np1=diff(ref, h) if ref is not None else 0.0)
        r["wrong"] = not (r["vs_np1"] <= 1e-8)
        rows.append(r)
        print("%-6s %-5s %-9s pgs=%-4s np=%d  step %.3f s  setup %.2f s  W_H %.3f  PGS %.3f  RSS %.0f MB  vs np1 %.1e%s" % (
            kind, scene_name, ctype, pgs, np_, r["step"], r["setup"], r["compliance"], r["contact_solver"], r["rss_mb"], r["vs_np1"],
            "  (oversubscribed: correctness only)" if r["oversubscribed"] else ""), flush=True)
        return h

    # strong scaling, and the W_H builders, on the 36k scene; the contact solver where it runs by
    # default (auto: split over the ranks at these sizes)
    for ctype in BUILDERS:
        ref = None
        for np_ in ranks + check:
            h = rec("strong", "36k", ctype, "auto", np_, ref)
            ref = h if ref is None else ref
    # the co-rotational cube (issue 16's second scene)
    ref = None
    for np_ in ranks + check:
        h = rec("strong", "cube", "condensed", "auto", np_, ref)
        ref = h if ref is None else ref
    # where the contact solver runs: on rank 0, the others waiting for its broadcast (-pgs_ranks root)
    for sc in ("36k", "cube"):
        for np_ in ranks[1:]:
            rec("solver", sc, "condensed", "root", np_)
    # the 149k scene (not dense: J^T and A^-1 J^T would be 2 x 149k x 4800 doubles, 11 GB)
    for ctype in BUILDERS[1:]:
        ref = None
        for np_ in ranks:
            h = rec("strong", "150k", ctype, "auto", np_, ref)
            ref = h if ref is None else ref
    # weak scaling: ~18k DOFs per rank
    rec("weak", "18k", "condensed", "auto", 1)
    for np_ in ranks[1:]:
        rec("weak", "36k" if np_ == 2 else "150k", "condensed", "auto", np_)

    # memory: a gmsh file is read whole on rank 0; PETSc's HDF5 format in slices on every rank
    msh = big_mesh()
    h5 = msh[:-4] + ".h5"
    if not os.path.exists(h5):
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "msh2h5.py"), msh, h5], check=True, capture_output=True)
    mem = {}
    for fmt, m in (("msh", msh), ("h5", h5)):
        for np_ in ranks:
            mem[(fmt, np_)] = stored(a, "memory_%s_np%d" % (fmt, np_), [os.path.getmtime(EXE)], lambda: memory(m, np_))
    for k, v in mem.items():
        print("memory %s np=%d: peak RSS per rank %s MB" % (k[0], k[1], ", ".join("%.0f" % x for x in v)), flush=True)
    a.memory = mem

    keys = ["kind", "scene", "dofs", "builder", "pgs_ranks", "ranks", "oversubscribed", "steps", "contacts", "wall", "setup",
            "step"] + PHASES + ["messages", "reductions", "rss_mb", "vs_np1", "wrong"]
    with open(os.path.join(figdir, "scaling.csv"), "w", newline="") as fc:
        w = csv.DictWriter(fc, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r[k] for k in keys})
    plot(rows, figdir)
    write_doc(a, rows)


def repeat_pair(a):
    """--repeat-pair: issue 16's 2-rank / 1-rank ratios, N repeats, printed as markdown; --versus OPTS: each
    repeat runs the pair with the defaults, then with OPTS added"""
    import platform
    import shlex
    variants = [("defaults", [])] + ([(a.versus, shlex.split(a.versus))] if a.versus else [])
    ratios = {(sc, v): [] for sc in ("36k", "cube") for v, _ in variants}
    print("`scripts/scaling.py --repeat-pair %d --steps %d%s` on %s (%s, %d cores): the 2-rank / 1-rank ratio of the "
          "step (mean of `/steps/wall_time`) and of each phase (means of `/steps/timing`), default builder "
          "(`condensed`), the default contact solver placement (`-pgs_ranks auto`: split over the ranks at these "
          "sizes); each repeat runs 1 rank, then 2%s.\n"
          % (a.repeat_pair, a.steps, " --versus '%s'" % a.versus if a.versus else "", time.strftime("%Y-%m-%d"),
             platform.machine(), os.cpu_count(),
             ", with the defaults, then with `%s`" % a.versus if a.versus else ""))
    vcol = "options | " if a.versus else ""
    print("| scene | " + vcol + "repeat | step 1 rank (s) | 2 ranks (s) | step | step 1 | steps 2.. | "
          + " | ".join(ph.replace("_", " ") for ph in PHASES) + " |")
    print("|---|" + ("---|" if a.versus else "") + "---:|---:|---:|---:|---:|---:|" + "---:|" * len(PHASES))
    later = {key: [] for key in ratios}
    for k in range(a.repeat_pair):
        for sc in ("36k", "cube"):
            for i, (v, extra) in enumerate(variants):
                args = scene(sc)[0] + ["-compliance_type", "condensed", "-pgs_ranks", "auto"] + extra
                r1, h1 = run("pair%d_%s_np1" % (i, sc), args, 1, a.steps)
                r2, h2 = run("pair%d_%s_np2" % (i, sc), args, 2, a.steps)
                vc = ("`%s` | " % v) if a.versus else ""
                d = diff(h1, h2)
                if not d <= 1e-8:
                    print("| %s | %s%d | the 2-rank run ended %.1e (relative) from the 1-rank run: left out |"
                          % (sc, vc, k + 1, d))
                    continue
                ratio = r2["step"] / r1["step"]
                ratios[(sc, v)].append(ratio)
                cells = phase_ratios(r1, r2)
                # step 1 holds the run's first factorization (of a linear body, its only one)
                w1, w2 = h1["steps/wall_time"][:], h2["steps/wall_time"][:]
                first = w2[0] / w1[0]
                rest = w2[1:].mean() / w1[1:].mean() if len(w1) > 1 else float("nan")
                later[(sc, v)].append(rest)
                print("| %s | %s%d | %.3f | %.3f | **%.2f** | %.2f | %.2f | %s |"
                      % (sc, vc, k + 1, r1["step"], r2["step"], ratio, first, rest, " | ".join(cells)), flush=True)
    print("\n(a phase under 1 ms on 1 rank: -)\n")
    for (sc, v), x in ratios.items():
        if x:
            print("- %s%s: step ratio %s; min %.2f, median %.2f, max %.2f; %d of %d at most 0.65" % (
                sc, " (%s)" % v if a.versus else "", ", ".join("%.2f" % y for y in x), min(x), float(np.median(x)),
                max(x), sum(y <= 0.65 for y in x), len(x)))
            y = later[(sc, v)]
            print("  steps 2..%d alone: %s; median %.2f; %d of %d at most 0.65" % (
                a.steps, ", ".join("%.2f" % z for z in y), float(np.median(y)), sum(z <= 0.65 for z in y), len(y)))


def plot(rows, figdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    groups = []
    for r in rows:
        if r["kind"] == "strong" and (r["scene"], r["builder"]) not in groups:
            groups.append((r["scene"], r["builder"]))
    ncol = 4
    nrow = (len(groups) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(20, 5 * nrow), squeeze=False)
    for ax in axes.flat[len(groups):]:
        ax.axis("off")
    for ax, (sc, ct) in zip(axes.flat, groups):
        rr = [r for r in rows if r["kind"] == "strong" and r["scene"] == sc and r["builder"] == ct and not r["oversubscribed"]
              and not r["wrong"]]
        if not rr:
            continue
        x = np.arange(len(rr))
        bottom = np.zeros(len(rr))
        for ph in PHASES:
            v = np.array([r[ph] for r in rr])
            if v.max() > 0.01 * max(r["step"] for r in rr):
                ax.bar(x, v, bottom=bottom, label=ph, color="C%d" % PHASES.index(ph))
                bottom += v
        ax.set_xticks(x)
        ax.set_xticklabels(["%d rank%s" % (r["ranks"], "s" if r["ranks"] > 1 else "") for r in rr])
        ax.set_ylabel("time per step (s), max over ranks")
        ax.set_title("%s DOFs, %s W_H, %d contacts" % (sc, ct, rr[0]["contacts"]), fontsize=10)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "strong.png"), dpi=100)
    wk = [r for r in rows if r["kind"] == "weak"]
    if wk:
        fig, ax = plt.subplots(figsize=(6, 4.5))
        ax.plot([r["ranks"] for r in wk], [r["step"] for r in wk], "o-", label="time per step")
        ax.plot([r["ranks"] for r in wk], [r["setup"] for r in wk], "s--", label="set-up")
        ax.set_xlabel("ranks (~18k DOFs each)")
        ax.set_ylabel("s")
        ax.set_title("weak scaling (Table 1 boxes)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(figdir, "weak.png"), dpi=100)


KEPT_BEGIN, KEPT_END = "<!-- begin kept", "<!-- end kept -->"


def kept_block(path):
    """The lines of the page between its kept markers (where things stand and the measurements of
    other commands: memory_ranks.py, scaling16.sh, the --repeat-pair tables), markers included, so
    that a regeneration keeps them, at the top of the page"""
    if not os.path.exists(path):
        return []
    lines = open(path).read().split("\n")
    begin = next((i for i, l in enumerate(lines) if l.startswith(KEPT_BEGIN)), None)
    end = next((i for i, l in enumerate(lines) if l.startswith(KEPT_END)), None)
    if begin is None or end is None or end < begin:
        return []
    return lines[begin:end + 1] + [""]


def write_doc(a, rows):
    import platform

    def strong(sc, ct):
        return {r["ranks"]: r for r in rows if r["kind"] == "strong" and r["scene"] == sc and r["builder"] == ct
                and not r["oversubscribed"] and not r["wrong"]}

    L = ["# Scaling", ""] + kept_block(a.markdown) + [
         "## Time per phase: scripts/scaling.py", "",
         "Generated by `scripts/scaling.py --ranks %s --check-ranks %s --steps %d` (%s, %d cores; the date is the "
         "page's, at its top), one run per "
         "line, fast scheme, 5 Newton iterations, `OPENBLAS_NUM_THREADS=1`, one rank per core. The step time is the "
         "mean of `/steps/wall_time` (the ranks meet at the end of every step); the phases are the means of the "
         "`/steps/timing` rows, each the largest time of a rank, so on several ranks they can add up to more than "
         "the step (a rank that waits in one phase for another rank's work in the previous one). Set-up is the rest "
         "of the wall time (mesh load and distribution, first assembly and factorization, output). RSS is the largest peak resident memory of the "
         "ranks (`/usr/bin/time`)." % (a.ranks, a.check_ranks, a.steps, platform.machine(),
                                        os.cpu_count()), "",
         "W_H builders (`-compliance_type`, src/compliance/): `dense` solves A X = J^T with dense "
         "right-hand sides on the distributed factor; `schur` has MUMPS factor [[0, J],[J^T, A]] and return the Schur "
         "complement on rank 0; `inverse` asks MUMPS for the block of A^-1 on the contact DOFs S (ICNTL(30), "
         "W_b = J_S (A^-1)_SS J_S^T) from the distributed factor, on rank 0; `redundant` does the same "
         "from a sequential factor of A that every rank keeps, each rank computing 1/p of the columns of (A^-1)_SS, "
         "and sums the partial W_b; `condensed` (the default since issue 14) is the body's own factorization of A "
         "with the contact DOFs S ordered last (MUMPS called directly, METIS nested dissection before S): "
         "(A^-1)_SS is the inverse of the Schur complement it leaves on rank 0, a linear body refactors only when "
         "its contacts leave S, and the same factor solves the free motion and the correction. The linear boxes "
         "here rest in contact from step 1, where `condensed` factors A once with its first contacts ordered last "
         "(S from a proximity query at the start positions, before the first free motion) and then builds W_H from "
         "products alone (0.01-0.05 factorizations a step): its step means over %d steps are mostly that first "
         "step." % a.steps, "",
         "![strong scaling](scaling/strong.png)", "",
         "| kind | scene | W_H | PGS on | ranks | contacts | step (s) | set-up (s) | W_H (s) | PGS (s) | rebuild W (s) | free motion (s) | collision (s) | correction (s) | messages | reductions | RSS (MB) | vs 1 rank |",
         "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        L.append("| %s | %s | %s | %s | %d%s | %d | %.3f | %.2f | %.3f | %.3f | %.3f | %.3f | %.4f | %.3f | %.0f | %.0f | %.0f | %.1e%s |" % (
            r["kind"], r["scene"], r["builder"], r["pgs_ranks"], r["ranks"], " (oversubscribed)" if r["oversubscribed"] else "",
            r["contacts"], r["step"], r["setup"], r["compliance"], r["contact_solver"], r["rebuild_w"], r["free_motion"],
            r["collision"], r["correction"], r["messages"], r["reductions"], r["rss_mb"], r["vs_np1"],
            " **wrong**" if r["wrong"] else ""))
    # sentences from the data
    L += ["", "## What the measurements say", ""]
    for f_ in a.failed:
        L.append("- **Failed run** (stopped with an error, left out of the table): %s" % f_)
    for r in rows:
        if r["wrong"]:
            L.append("- **Wrong run**: %s, %s DOFs, `%s`, %d ranks ended %.1e (relative) away from the 1-rank run "
                     "(%d contacts at the last step); it is left out of the figures below and the plots. fecontact did not "
                     "detect it; the compliance W is now checked at every build (symmetric, non-negative diagonal, "
                     "src/scheme/scheme.c) and a run whose W fails stops with exit status 2." % (
                         r["kind"], r["scene"], r["builder"], r["ranks"], r["vs_np1"], r["contacts"]))
    for sc in ("36k", "150k"):
        g = {ct: strong(sc, ct) for ct in BUILDERS}
        g = {ct: v for ct, v in g.items() if 1 in v and 2 in v}
        if not g:
            continue
        best1 = min(g, key=lambda ct: g[ct][1]["compliance"])
        best2 = min(g, key=lambda ct: g[ct][2]["compliance"])
        L.append("- **%s DOFs, %d contacts**: W_H takes %s on 1 rank and %s on 2 ranks (s). Fastest on 1 rank: %s; on "
                 "2 ranks: %s, whose W_H runs %.2fx faster than on 1 rank (step %.2fx)." % (
                     sc, g[best1][1]["contacts"],
                     ", ".join("%s %.2f" % (ct, g[ct][1]["compliance"]) for ct in g),
                     ", ".join("%s %.2f" % (ct, g[ct][2]["compliance"]) for ct in g), best1, best2,
                     g[best2][1]["compliance"] / g[best2][2]["compliance"], g[best2][1]["step"] / g[best2][2]["step"]))
    L += ["", "### Two ranks against one (issue 16: at most 0.65x)", "",
          "The 2-rank time over the 1-rank time of the same run of this script, per phase and for the whole step "
          "(wall time), for the two scenes of issue 16 with the default builder (`condensed`) and contact solver "
          "placement (`-pgs_ranks auto`: split over the ranks at these sizes):", "",
          "| scene | step | " + " | ".join(ph.replace("_", " ") for ph in PHASES) + " | target 0.65x |",
          "|---|---:|" + "---:|" * len(PHASES) + "---|"]
    for sc in ("36k", "cube"):
        rr = strong(sc, "condensed")
        if 1 not in rr or 2 not in rr:
            continue
        ratio = rr[2]["step"] / rr[1]["step"]
        cells = phase_ratios(rr[1], rr[2])
        L.append("| %s (%.3f s -> %.3f s) | **%.2f** | %s | %s |" % (sc, rr[1]["step"], rr[2]["step"], ratio, " | ".join(cells),
                                                                   "met" if ratio <= 0.65 else "not met"))
    L += ["", "(a phase under 1 ms on 1 rank: -)", ""]
    L += ["Per phase, a two-point Amdahl fit of the 1- and 2-rank times, t(p) = t_serial + t_parallel / p with "
          "t_serial = 2 t(2) - t(1) (at least 0) and t_parallel = t(1) - t_serial, predicts the step time beyond the "
          "machine (the serial share of the phases applied to the 1-rank step time). It ignores the growth of communication with p (the W Allreduce is O(m^2) words per step on every "
          "rank, MUMPS' communication grows with p), so it is an upper bound on the speed-up:", "",
          "| scene | W_H | step 1 rank (s) | 2 ranks (s) | serial share | predicted 4 | 8 | 16 ranks (s) | speed-up at 16 |",
          "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for sc in ("36k", "cube", "150k"):
        for ct in BUILDERS:
            rr = strong(sc, ct)
            if 1 not in rr or 2 not in rr:
                continue
            f = serial_share([(rr[1][ph], rr[2][ph]) for ph in PHASES])  # applied to the step's wall time
            pred = {p: rr[1]["step"] * (f + (1 - f) / p) for p in (4, 8, 16)}
            L.append("| %s | %s | %.3f | %.3f | %.0f%% | %.3f | %.3f | %.3f | %.1fx |" % (
                sc, ct, rr[1]["step"], rr[2]["step"], 100 * f, pred[4], pred[8], pred[16], rr[1]["step"] / pred[16]))
    L += ["", "The model behind it, phase by phase (m contacts, M = 3m rows with friction, N DOFs, p ranks, "
          "|S| <= 3 m contact DOFs):", "",
          "- **distributed, O(N/p)**: assembly, the free-motion solve, the factorization (MUMPS, nested dissection: "
          "O(N^2) flops for a 3D mesh, with a parallel efficiency below 1), the correction (one solve, or the product "
          "with the kept A^-1 J^T columns for `dense`), the collision detection of each rank's own surface vertices;",
          "- **W_H, by builder**: `condensed` costs the Schur-ordered factorization when the contacts leave S (a "
          "linear body in steady contact: never) and a dense inversion of |S| with it (on rank 0: ScaLAPACK over the ranks, `-compliance_condensed_inverse scalapack`, was not faster here), then products on rank 0 "
          "that do not shrink with p; `redundant` splits the |S| columns of (A^-1)_SS over the ranks, each computed from a "
          "sequential factor: its time falls like 1/p (the table shows the 1 to 2 rank ratio), until the sum of the "
          "partial W_b (an Allreduce of (3m)^2 numbers) dominates. `dense` solves all columns with the distributed "
          "factor, whose solve phase does not speed up on these sizes; `schur` and `inverse` gather the dense part "
          "on rank 0, so they are serial in effect;",
          "- **split**: the contact solver (O(sweeps (3m)^2) a Newton iteration), by default (`-pgs_ranks auto`) "
          "over the ranks from 900 rows, each rank sweeping its block of contacts (O(sweeps 3m (3m/p))), with "
          "`root` on rank 0 and a broadcast of 3m numbers (the `solver` rows); with it the W_k rebuild "
          "(O(M 3m 3 / p) a Newton iteration: each rank forms the block rows its sweeps read, `-fast_wk_rows`);",
          "- **replicated, does not shrink with p**: the sum and checks of W_H (O((3m)^2) when a body's part "
          "changed), the W_k rebuild below 900 rows, the frame and proximity updates (O(m)), and the gathered "
          "contact surfaces (O(surface) per rank);",
          "- **memory**: W_H is 8 (3m)^2 bytes on every rank, W_k 8 M^2 / p where the sweeps are split (its "
          "block rows) and 8 M^2 elsewhere; U and U^T (8 (2 M 3m)) only with non-host matrix types "
          "(-contact_memory_limit stops a step that would exceed it); `redundant` adds a sequential factor of A on every rank (its fill "
          "grows like N^(4/3) for a 3D mesh and does not shrink with p: MUMPS' estimate is checked against -compliance_redundant_memory_limit at set-up; use fewer copies or `inverse` when it does not fit); "
          "`dense` keeps J^T and A^-1 J^T, 16 N 3m / p bytes per rank; a gmsh mesh is read whole on rank 0, a PETSc "
          "HDF5 mesh in slices (below).", "",
          "The `redundant` prediction holds only while a sequential factor of A fits in every rank's memory and the "
          "Allreduce of the partial W_b ((3m)^2 numbers: 184 MB at 1600 contacts) stays small against W_H / p; "
          "`-compliance_redundant_groups k` keeps k copies instead of p when memory is short.", "",
          "So with `redundant` the W_H phase scales until the replicated contact phases set the floor: with m fixed, "
          "the step time tends to t_serial (the W_H sum and checks, the serial parts of the factorization); with m growing like the surface "
          "(N^(2/3)), the replicated O(m^2) work grows like N^(4/3) per rank while the distributed work shrinks like "
          "N/p, and it dominates at scale. The contact solver's sweeps are split over the ranks by default "
          "(`-pgs_ranks auto`: each rank its own block of contacts, damped Jacobi between blocks, rank 0 going on "
          "alone where the split sweeps stall: src/contact/pgs_split.c, solver.c); their sweeps and times against the "
          "replicated solver on 1, 2 and 4 ranks, up to the 149k box's 1600 contacts, are in "
          "[docs/contact-solver.md](contact-solver.md#split-over-the-ranks) (`scripts/bench_split.py`). The mesh "
          "partitioners (ptscotch, metis, simple) are compared in [docs/partitioners.md](partitioners.md).", "",
          "![weak scaling](scaling/weak.png)", "", "The CSV is `docs/scaling/scaling.csv`.", "",
          "## Memory of the mesh", "",
          "Peak resident memory of every rank (MB, `/usr/bin/time`) loading the 149k-DOF box and taking one step with "
          "the default builder, from the gmsh file (read whole on rank 0, then distributed) and from PETSc's HDF5 "
          "format (`scripts/msh2h5.py`, read in slices by every rank):", "",
          "| mesh file | ranks | peak RSS per rank (MB) |", "|---|---:|---|"]
    for (fmt, np_), v in sorted(a.memory.items()):
        L.append("| .%s | %d | %s |" % (fmt, np_, ", ".join("%.0f" % x for x in v)))
    L.append("")
    with open(a.markdown, "w") as f:
        f.write("\n".join(L))
    print("wrote", a.markdown)


if __name__ == "__main__":
    main()
