"""The cost of driving a scene from Python (issue 40): the same scene run by the executable and stepped
from Python (fecontact.Scene.step(), one call a step, reading the step's contacts and one body's
centroid between steps, as a controller does), the runs alternated --repeat times, on 1 rank:
  small: input/finger_push.opts, 100 steps (907 vertices);
  cube:  the 17.5k-DOF co-rotational cube of input/cube_drop_peer.opts, 40 steps (it lands in step 10).
Per variant: the median over the runs of the mean step (/steps/wall_time: a step's wall time runs from
the end of the step before, so it holds what Python does between steps) and of the whole run (the
process, start-up and set-up included). Prints a markdown table and the overhead per step.
Usage: /usr/bin/python3 scripts/python_overhead.py [--scene small|cube|both] [--repeat R]"""
import argparse
import os
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE  # noqa: E402

OUT = os.path.join(ROOT, "build", "python_overhead")
SCENES = {
    "small": (["-options_file", "input/finger_push.opts", "-time_steps", "100", "-output_every", "100"], "tool"),
    "cube": (["-options_file", "input/cube_drop_peer.opts", "-time_steps", "40", "-output_every", "40"], "cube"),
}
DRIVE = """
import sys
sys.path.insert(0, %r)
import fecontact
with fecontact.Scene(options=%r) as s:
    b = s.body(%r)
    for k in range(s.time_steps):
        s.step()
        c = s.contacts()
        x = b.centroid
"""


def measure(scene, variant, name):
    opts, body = SCENES[scene]
    f = os.path.join(OUT, name + ".h5")
    args = opts + ["-output_file", f, "-quiet"]
    if variant == "executable":
        cmd = [EXE] + args
    else:
        script = os.path.join(OUT, name + ".py")
        with open(script, "w") as g:
            g.write(DRIVE % (os.path.join(ROOT, "python"), " ".join(args), body))
        cmd = ["/usr/bin/python3", script]
    env = dict(ENV, FECONTACT_LIBRARY=os.path.join(os.path.dirname(os.path.abspath(EXE)), "libfecontact.so"))
    t0 = time.time()
    subprocess.run(cmd, cwd=ROOT, env=env, check=True, capture_output=True)
    total = time.time() - t0
    with h5py.File(f, "r") as h:
        return h["steps/wall_time"][:].mean(), total


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", choices=["small", "cube", "both"], default="both")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    print("| scene | variant | s / step | s / run |")
    print("|---|---|---:|---:|")
    for scene in (["small", "cube"] if a.scene == "both" else [a.scene]):
        res = {"executable": [], "python": []}
        for r in range(a.repeat):
            for v in res:
                res[v].append(measure(scene, v, "%s_%s_%d" % (scene, v, r)))
        med = {v: np.median(np.array(res[v]), axis=0) for v in res}
        for v in res:
            print("| %s | %s | %.5f | %.2f |" % (scene, v, med[v][0], med[v][1]))
        d = med["python"][0] - med["executable"][0]
        print("%s: stepping from Python adds %.2e s a step, %+.1f %% of the executable's step (medians of %d runs)" %
              (scene, d, 100.0 * d / med["executable"][0], a.repeat))


if __name__ == "__main__":
    main()
