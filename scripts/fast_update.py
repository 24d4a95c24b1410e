#!/usr/bin/python3
"""When the fast scheme's frames follow the forces (-fast_update): between contact solves, as the
paper (newton), or after every sweep of the contact solver too (sweep, the paper's closing
remark). For each scene and Newton iteration count k, both updates: the iteration error left at
the end of the step (max complementarity and cone violation, docs/output.md), the distance of the
final vertex positions to a converged reference (fast, 20 Newton iterations of the paper's update,
-pgs_tol 1e-11), the PGS sweeps and the time per step (all phases but output). One run each, this
machine; prints a markdown table (docs/accuracy.md).

  /usr/bin/python3 scripts/fast_update.py [--steps 30] [--newton 1,2,3,5,8]
"""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
SCENES = [("grasp, 6 rad/s (input/grasp_rotate.opts)", "input/grasp_rotate.opts", [], "object"),
          ("grasp, 12 rad/s (input/hard/grasp_fast.opts)", "input/hard/grasp_fast.opts",
           ["-finger1_angular_velocity", "0,0,12", "-finger2_angular_velocity", "0,0,12"], "object")]


def run(opts, steps, extra, tmp, name):
    f = os.path.join(tmp, name + ".h5")
    subprocess.run([os.path.join(ROOT, "build", "fecontact"), "-options_file", opts[0]] + opts[1] + ["-time_steps", str(steps),
                    "-output_every", str(steps), "-constraint_scheme", "fast", "-newton_tol", "0", "-output_file", f,
                    "-quiet"] + extra, cwd=ROOT, env=ENV, check=True)
    return h5py.File(f, "r")


def sorted_positions(h, body):
    ref = h["bodies/%s/mesh/reference" % body][:]
    return h["bodies/%s/positions" % body][-1][np.lexsort(np.round(ref, 9).T[::-1])]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--steps", type=int, default=30)
    p.add_argument("--newton", default="1,2,3,5,8")
    a = p.parse_args()
    tmp = tempfile.mkdtemp(prefix="fast-update-")
    print("| scene | update | Newton it. | complementarity (m) | cone violation | position error (m) | PGS sweeps / step | ms / step |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for si, (title, opts, scene_extra, body) in enumerate(SCENES):
        opts = (opts, scene_extra)
        ref = run(opts, a.steps, ["-newton_max_it", "20", "-pgs_tol", "1e-11",
                                  "-pgs_max_it", "20000"], tmp, "ref%d" % si)
        xref = sorted_positions(ref, body)
        for update in ("newton", "sweep"):
            for k in [int(x) for x in a.newton.split(",")]:
                h = run(opts, a.steps, ["-newton_max_it", str(k), "-fast_update", update], tmp, "%s%d_%d" % (update, k, si))
                s, t = h["steps"], h["steps/timing"]
                ms = 1e3 * sum(np.sum(t[q][:]) for q in t if q != "output") / a.steps
                err = np.abs(sorted_positions(h, body) - xref).max()
                print("| %s | %s | %d | %.1e | %.1e | %.1e | %.0f | %.2f |" % (
                    title, update, k, s["complementarity"][:].max(), s["cone_violation"][:].max(), err,
                    s["pgs_iterations"][:].sum() / a.steps, ms))


if __name__ == "__main__":
    main()
