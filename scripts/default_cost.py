"""The cost of the default constraint scheme (fast: Algorithm 3, Newton iterations to -newton_tol) against the
explicit scheme (Algorithm 1, one linearization per step), the runs of each scene alternated --repeat times:
  table1: input/table1_18k.opts (the paper's Table 1 box, 18k DOFs, on its plane), 10 steps, steps 2-10;
  grasp:  input/grasp_rotate.opts (a cube turned by two fingers at 6 rad/s), 60 steps, steps 2-60;
  peer:   input/cube_drop_peer.opts (the 17.5k-DOF co-rotational cube dropped on a plane), 40 steps, the steps in
          contact (11-40).
Per scene and scheme: the median over the runs of the mean /steps/wall_time over those steps, the mean Newton
iterations a step, and the run's worst /steps/cone_violation and /steps/max_complementarity (what each scheme
leaves on the end-of-step geometry). Step control is on in both (the default); the runs cut no step.
Usage: /usr/bin/python3 scripts/default_cost.py [--scene table1|grasp|peer|all] [--np N] [--repeat R]"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from fctest import ENV, EXE  # noqa: E402

OUT = os.path.join(ROOT, "build", "default_cost")
SCENES = {
    "table1": (["-options_file", "input/table1_18k.opts", "-time_steps", "10", "-output_every", "10"], slice(1, None)),
    "grasp": (["-options_file", "input/grasp_rotate.opts", "-time_steps", "60", "-output_every", "60"], slice(1, None)),
    "peer": (["-options_file", "input/cube_drop_peer.opts", "-output_every", "40"], slice(10, None)),
}


def run(scene, scheme, np_, k):
    opts, steps = SCENES[scene]
    f = os.path.join(OUT, "%s_%s_np%d_%d.h5" % (scene, scheme, np_, k))
    cmd = [EXE] + opts + ["-constraint_scheme", scheme, "-output_file", f, "-quiet"]
    if np_ > 1:
        cmd = ["mpirun", "-n", str(np_)] + cmd
    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, capture_output=True)
    with h5py.File(f, "r") as h:
        s = h["steps"]
        return (s["wall_time"][steps].mean(), s["newton_iterations"][steps].mean(), s["cone_violation"][:].max(),
                s["max_complementarity"][:].max(), int(s["substeps"][:].max()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="all", choices=list(SCENES) + ["all"])
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    print("| scene | scheme | ms/step (median of %d) | x explicit | Newton it./step | cone violation | "
          "max natural-map error (m) | most sub-steps |" % a.repeat)
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for scene in SCENES if a.scene == "all" else [a.scene]:
        res = {"explicit": [], "fast": []}
        for k in range(a.repeat):
            for scheme in ("explicit", "fast"):
                res[scheme].append(run(scene, scheme, a.np, k))
        base = np.median([r[0] for r in res["explicit"]])
        for scheme in ("explicit", "fast"):
            r = res[scheme]
            t = np.median([x[0] for x in r])
            print("| %s | %s | %.1f | %.2f | %.2f | %.2g | %.2g | %d |" % (scene, scheme, 1e3 * t, t / base, r[0][1],
                                                                         r[0][2], r[0][3], r[0][4]))


if __name__ == "__main__":
    main()
