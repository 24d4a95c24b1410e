"""The cost of self-contact detection on a body with no fold (issue 39), the runs of each scene
alternated --repeat times, with and without the self pair (the body in another contact pair either
way, so that both take the same path through the contact schemes and builders):
  cube:  the 17.5k-DOF cube of input/cube_drop_peer.opts (40 steps; it lands on the ground in step
         10), pairs cube:ground against cube:ground,cube:cube; before contact: steps 2-9, in
         contact: steps 11-40;
  ubend: the bar of input/u_bend.opts (615 vertices) over its first 150 steps, while the hands bend
         it and its neck is still open (it closes at step 197), with a kinematic plane 1 m below
         that it never reaches, pairs bar:floor against bar:floor,bar:bar; steps 2-150.
  pair:  the floor of the U bar's figure: the same bar beside a copy of itself 3 cm away (bar2, FE, at rest:
         no contact), over its first 50 steps, pairs bar:floor against bar:floor,bar:bar2 (a two-body FE pair of
         the same surfaces: both passes, edges, intersection count) and bar:floor,bar:bar; its collision column
         is what compares (bar2's own solve is in every variant's step).
Per variant: the median over the runs of the mean /steps/wall_time and of the collision phase's
time a step (/steps/timing, column collision), and the self-contacts found (none: no fold yet).
Usage: /usr/bin/python3 scripts/selfcontact_cost.py [--scene cube|ubend|pair|both] [--np N] [--repeat R]
(both: cube and ubend)"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE  # noqa: E402

OUT = os.path.join(ROOT, "build", "selfcontact_cost")
SCENES = {  # options, (pairs without, with the self pair), the steps before contact and in contact
    "cube": (["-options_file", "input/cube_drop_peer.opts", "-output_every", "40"],
             ("cube:ground", "cube:ground,cube:cube"), slice(1, 9), slice(10, None)),
    "ubend": (["-options_file", "input/u_bend.opts", "-time_steps", "150", "-output_every", "150", "-scene_bodies",
               "bar,hand_l,hand_r,floor", "-floor_type", "kinematic", "-floor_shape", "plane", "-floor_center",
               "0,0,-1"], ("bar:floor", "bar:floor,bar:bar"), slice(1, 150), None),
    "pair": (["-options_file", "input/u_bend.opts", "-time_steps", "50", "-output_every", "50", "-scene_bodies",
              "bar,hand_l,hand_r,floor,bar2", "-floor_type", "kinematic", "-floor_shape", "plane", "-floor_center",
              "0,0,-1", "-bar2_type", "fem", "-bar2_dm_plex_filename", "meshes/u_bar.msh", "-bar2_material",
              "corotational", "-bar2_young", "1e7", "-bar2_poisson", "0.3", "-bar2_density", "1000", "-bar2_translate",
              "0,0.13,0"], ("bar:floor", "bar:floor,bar:bar2", "bar:floor,bar:bar"), slice(1, 50), None),
}


def run(scene, pairs, np_, name):
    f = os.path.join(OUT, name + ".h5")
    opts = SCENES[scene][0]
    cmd = ([] if np_ == 1 else ["mpirun", "-n", str(np_), "--oversubscribe"]) + [EXE] + opts + [
        "-contact_pairs", pairs, "-output_file", f, "-quiet"]
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    return h5py.File(f, "r")


def figures(h, before, contact):
    s = h["steps"]
    w, col = s["wall_time"][:], s["timing/collision"][:]
    bodies = h["contacts/bodies"][:]
    nself = int((bodies[:, 0] == bodies[:, 1]).sum()) if len(bodies) else 0
    inw = w[contact].mean() if contact else np.nan
    inc = col[contact].mean() if contact else np.nan
    return w[before].mean(), inw, col[before].mean(), inc, nself


def measure(scene, np_, repeat):
    opts, variants, before, contact = SCENES[scene]
    res = {p: [] for p in variants}
    for r in range(repeat):
        for k, pairs in enumerate(variants):
            res[pairs].append(figures(run(scene, pairs, np_, "cost_%s_%d_%d" % (scene, k, r)), before, contact))
    print("| pairs | s / step before contact | s / step in contact | collision s / step before | collision s / step "
          "in contact | self-contacts |")
    print("|---|---:|---:|---:|---:|---:|")
    med = {}
    for pairs, rows in res.items():
        m = np.median(np.array(rows)[:, :4], axis=0)
        med[pairs] = m
        print("| %s | %.4f | %.4f | %.4f | %.4f | %d |" % (pairs, *m, max(r[4] for r in rows)))
    b, s = med[variants[0]], med[variants[-1]]
    if len(variants) == 3:
        p = med[variants[1]]
        print("%s: collision a step: the self pair adds %.2e s, the two-body pair of the same surfaces %.2e s (%d ranks, "
              "median of %d runs each)" % (scene, s[2] - b[2], p[2] - b[2], np_, repeat))
        return
    print("%s: self-contact detection adds %.1f %% to the step before contact%s (%d ranks, median of %d runs each)" %
          (scene, 100 * (s[0] / b[0] - 1), "" if contact is None else " and %.1f %% in contact" %
           (100 * (s[1] / b[1] - 1)), np_, repeat))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", choices=["cube", "ubend", "pair", "both"], default="both")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    for scene in (["cube", "ubend"] if a.scene == "both" else [a.scene]):
        measure(scene, a.np, a.repeat)


if __name__ == "__main__":
    main()
