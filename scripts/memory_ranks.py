"""Memory per rank of the contact phase against the number of ranks (issue 37): the 149k-DOF box
of docs/scaling.md (input/table1_36k.opts on the 40 x 40 x 31 mesh: 1600 contacts, fast scheme,
condensed builder, the fast scheme of docs/scaling.md) run for --steps steps on each of --ranks (oversubscribed beyond the cores), with
the default thresholds (distributed from 1000 contacts and a 3000-DOF Schur block), and once with
the replicated contact phase forced on the largest rank count for contrast. Reads /memory (each
rank's largest over the steps: peak RSS, W_H, W_k, W_b, Sigma / C, MUMPS' factor) and prints a
markdown table: the largest rank's values, their ratio to 1 rank, and the final positions' largest
difference from the 1-rank run over the displacement.
--scene large: input/large_box.opts instead (245,760 DOFs, 4096 contacts; its mesh made here first).
A second table gives, for the largest rank of each run, how much its peak RSS grew in the set-up and
in each phase that grew it (/memory_phases). --tables: print the tables from the files of the last
runs, without running.
Usage: /usr/bin/python3 scripts/memory_ranks.py [--scene 149k|large] [--ranks 1,2,4] [--steps 2] [--csv FILE] [--tables]"""
import argparse
import csv
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, sorted_positions  # noqa: E402
import scaling  # noqa: E402

EXE = os.environ.get("FECONTACT", os.path.join(ROOT, "build", "fecontact"))  # as the tests: another build
COLS = ["peak_rss", "W_H", "W_k", "W_b", "Sigma", "factor", "contact_data"]
REPLICATED = ["-fast_distributed_contacts", "1000000", "-compliance_condensed_inverse", "host"]


def scene_args(name):
    if name == "large":  # input/large_box.opts reads build/meshes/large_box.msh
        scaling.table1_mesh("large_box", 64, 64, 20)
        return ["-options_file", "input/large_box.opts"]
    return ["-options_file", "input/table1_36k.opts", "-box_dm_plex_filename", scaling.big_mesh(),
            "-constraint_scheme", "fast"]


def run(scene, np_, steps, extra, tag, again=True):
    path = os.path.join(scaling.OUT, "memory_%s_%s_np%d.h5" % (scene, tag, np_))
    cmd = ["mpirun", "-n", str(np_), "--oversubscribe", EXE] + scene_args(scene) + [
           "-time_steps", str(steps), "-quiet", "-output_file", path] + extra
    if again:
        subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    with h5py.File(path, "r") as f:
        mem = f["memory"][:]
        contacts = int(f["steps/contacts"][-1])
        ref, pos = sorted_positions(f, "box")
        ph = f["memory_phases"]
        cols = ph.attrs["columns"]
        phases = (cols.decode() if isinstance(cols, bytes) else cols).split(","), ph[:]
    return mem, contacts, ref, pos, phases


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="149k", choices=["149k", "large"])
    ap.add_argument("--ranks", default="1,2,4")
    ap.add_argument("--steps", type=int, default=2)
    ap.add_argument("--csv", default=None)
    ap.add_argument("--tables", action="store_true")
    a = ap.parse_args()
    os.makedirs(scaling.OUT, exist_ok=True)
    ranks = [int(r) for r in a.ranks.split(",")]
    rows = []
    for np_ in ranks:
        rows.append(("default", np_) + run(a.scene, np_, a.steps, [], "default", not a.tables))
        print("# %s, %d rank(s): done" % (a.scene, np_), file=sys.stderr, flush=True)
    rows.append(("replicated", ranks[-1]) + run(a.scene, ranks[-1], a.steps, REPLICATED, "replicated", not a.tables))
    one = rows[0][2].max(axis=0)
    ref, x1 = rows[0][4], rows[0][5]
    scale = np.abs(x1 - ref).max()
    print("| contact phase | ranks | contacts | peak RSS (MB) | vs 1 rank | W_H (MB) | W_k (MB) | W_b (MB) | "
          "Sigma / C (MB) | contact data (MB) | x p vs 1 rank | MUMPS factor (MB) | positions vs 1 rank |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    out = []
    for tag, np_, mem, contacts, _, pos, _ in rows:
        big = mem.max(axis=0)  # the largest rank, per column
        mb = big / 1048576.0
        dx = np.abs(pos - x1).max() / scale
        r = dict(phase=tag, ranks=np_, contacts=contacts, rss_mb=mb[0], rss_ratio=big[0] / one[0], wh_mb=mb[1],
                 wk_mb=mb[2], wb_mb=mb[3], sigma_mb=mb[4], data_mb=mb[6], data_ratio_p=big[6] / one[6] * np_,
                 factor_mb=mb[5], dx=dx)
        out.append(r)
        print("| %s | %d%s | %d | %.0f | %.2f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.0f | %.1e |"
              % (tag, np_, " (oversubscribed)" if np_ > 2 else "", contacts, r["rss_mb"], r["rss_ratio"], r["wh_mb"],
                 r["wk_mb"], r["wb_mb"], r["sigma_mb"], r["data_mb"], r["data_ratio_p"], r["factor_mb"], dx))
    names = rows[0][6][0]
    grown = [j for j in range(len(names)) if any(r[6][1][:, j].max() >= 1048576.0 for r in rows)]
    print("\nPeak RSS growth of the largest rank (MB) in the set-up and in each phase that grew it "
          "(/memory_phases; the row sums to its peak RSS):\n")
    print("| contact phase | ranks | largest rank | " + " | ".join(names[j] for j in grown) + " |")
    print("|---|---:|---:|" + "---:|" * len(grown))
    for tag, np_, mem, _, _, _, (_, ph) in rows:
        big = int(np.argmax(mem[:, 0]))
        print("| %s | %d | %d | " % (tag, np_, big) + " | ".join("%.0f" % (ph[big, j] / 1048576.0) for j in grown) + " |")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(out[0].keys()))
            w.writeheader()
            w.writerows(out)


if __name__ == "__main__":
    main()
