"""Elements turned inside out (issue 55), on --np ranks: the soft block of
input/hard/crush_neohookean.opts made co-rotational (E = 100 kPa, nu = 0.45, glued at zmin) crushed by
the kinematic plate to 15 % of its height in 0.4 s, held 0.1 s, and the plate lifted off (80 steps):

- by default (a co-rotational body runs on) the run ends; elements turn inside out under the plate
  (/steps/inverted_elements, /steps/min_volume_ratio below 0) and are turned back once the plate is
  gone (none at the end, the smallest J above 0.5); /bodies/block/inverted/ holds the same columns;
  the count recorded at each frame's step is the number of tetrahedra of the frame's positions with a
  non-positive volume; the positions and velocities stay finite; the summary's line gives the steps
  with inverted elements, the most at once and the smallest J of /steps;
- -block_inverted error makes the first step with an inverted element a failed step: step control
  redoes it with smaller time steps, which invert the element too, and the run stops there, naming
  the body, the cause and the option, with the steps before it readable;
- the linear material fails there by default (it has no force against inversion; 1 rank);
- --np > 1: the counts of every step are the 1-rank ones exactly, the smallest J the same to 1e-10."""
import re

import h5py
import numpy as np

from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("inverted np%d" % NP)
CRUSH = ["-options_file", "input/hard/crush_neohookean.opts", "-block_material", "corotational", "-time_steps", 80,
         "-plate_trajectory", "0:0,0,0.5;0.4:0,0,-0.35;0.5:0,0,-0.35;0.8:0,0,1"]


def volumes(f):
    """The volume of every tetrahedron at every frame (F, C)"""
    P, cells = f["bodies/block/positions"][:], f["bodies/block/mesh/cells"][:]
    q = P[:, cells]
    return np.einsum("fij,fij->fi", q[:, :, 1] - q[:, :, 0], np.cross(q[:, :, 2] - q[:, :, 0], q[:, :, 3] - q[:, :, 0]))


def crush(np_):
    f = out("crush_np%d.h5" % np_)
    p = run(CRUSH + ["-output_file", f], np_=np_)
    return p, h5py.File(f, "r")


p, h = crush(NP)
s = h["steps"]
n, J = s["inverted_elements"][:], s["min_volume_ratio"][:]
c.check(len(n) == 80 and n.max() >= 50 and (J[n > 0] <= 0).all() and (J[n == 0] > 0).all() and J.min() < -0.5,
        "default (co-rotational: allow): 80 steps, up to %d elements inside out at once in %d steps, J down to %.3f" %
        (n.max(), (n > 0).sum(), J.min()))
c.check((n[-15:] == 0).all() and J[-1] > 0.5,
        "the plate lifted: every element turned back (none inside out over the last 15 steps, J = %.3f at the end)" %
        J[-1])
g = h["bodies/block/inverted"]
c.check(np.array_equal(g["elements"][:], n) and np.array_equal(g["min_volume_ratio"][:], J)
        and s["inverted_elements"].dtype == np.int64, "/bodies/block/inverted/: the same columns as /steps")
frames = h["frames/step"][:]
counted = (volumes(h) <= 0).sum(axis=1)
recorded = np.concatenate([[0], n])[frames]
c.check(np.array_equal(counted, recorded) and counted.max() > 0,
        "the count at each frame's step is that of the frame's positions: %s" % list(counted))
vel = h["bodies/block/velocity"][:]
c.check(np.isfinite(h["bodies/block/positions"][:]).all() and np.isfinite(vel).all(),
        "positions and velocities finite (largest speed %.2f m/s)" % np.abs(vel).max())
m = re.search(r"elements inside out \(J = det F <= 0\) at the end of (\d+) of (\d+) steps, at most (\d+) at once, "
              r"J down to (\S+)", p.stdout)
c.check(m is not None and int(m.group(1)) == (n > 0).sum() and int(m.group(2)) == 80 and int(m.group(3)) == n.max()
        and abs(float(m.group(4)) - J.min()) <= 1e-5 * abs(J.min()),
        "the summary: %s" % (m.group(0) if m else "no line"))

first = int(np.argmax(n > 0)) + 1  # the first step with an inverted element
f = out("crush_error_np%d.h5" % NP)
p = run(CRUSH + ["-block_inverted", "error", "-time_steps", first, "-output_file", f], np_=NP, check=False)
msg = p.stdout + p.stderr
he = h5py.File(f, "r")
c.check(p.returncode != 0 and "Body 'block'" in msg and "inside out at step %d" % first in msg
        and "-block_inverted allow" in msg and "step %d redone" % first in msg and he["complete"][0] == first - 1,
        "-block_inverted error: step %d fails, is redone with smaller time steps (%d times) and the run stops (exit %d), "
        "naming the body and the option; %d steps readable" % (first, msg.count("step %d redone" % first), p.returncode,
                                                               he["complete"][0]))
if NP == 1:  # the material's default: the same on any number of ranks
    f = out("crush_linear.h5")
    p = run(CRUSH + ["-block_material", "linear", "-output_file", f], check=False)
    msg = p.stdout + p.stderr
    c.check(p.returncode != 0 and "Body 'block'" in msg and "inside out" in msg and "small-strain" in msg,
            "linear material: fails and stops by default (exit %d): %s" % (
                p.returncode, [l for l in msg.splitlines() if "error:" in l and "inside out" in l][:1]))
else:
    _, h1 = crush(1)
    d = np.abs(h1["steps/min_volume_ratio"][:] - J).max()
    c.check(np.array_equal(h1["steps/inverted_elements"][:], n) and d <= 1e-10,
            "%d ranks: the counts of every step are the 1-rank ones, the smallest J to %.1e" % (NP, d))
c.done()
