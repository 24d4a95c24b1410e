"""Accuracy measures and the cheaper settings they judge (issue 5):
- /steps/complementarity and /steps/cone_violation (end-of-step frames, src/contact/measures.c)
  fall as the fast scheme does more Newton iterations on the fast-rotating grasp, and one
  iteration gives exactly the explicit scheme's measures (same linearization, same forces);
- /steps/energy_change adds up to /steps/energy from the attribute initial_energy;
- -<body>_factorization reuse with -<body>_refactor_every k (the other triggers off) factors A
  every k steps (timing rows of the factorization), and -refactor_every is an error for a linear
  material; -pgs_acceleration nncg and none give the same motion.
Usage: test_accuracy.py [--np N]"""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv, sorted_positions

NP = np_from_argv()
c = Checker("accuracy np%d" % NP)
grasp = ["-options_file", "input/grasp_rotate.opts", "-time_steps", "30", "-quiet"]


def go(name, args):
    f = out("acc_%s_np%d.h5" % (name, NP))
    run(args + ["-output_file", f], np_=NP)
    return h5py.File(f, "r")


m = {}
for k in (1, 3, 8):
    h = go("fast%d" % k, grasp + ["-constraint_scheme", "fast", "-newton_max_it", str(k), "-newton_tol", "0"])
    m[k] = (h["steps/complementarity"][:].max(), h["steps/cone_violation"][:].max(), h["steps/violation"][:].max())
e = go("explicit", grasp + ["-constraint_scheme", "explicit"])
me = (e["steps/complementarity"][:].max(), e["steps/cone_violation"][:].max(), e["steps/violation"][:].max())
c.check(all(np.isfinite(v) for k in m for v in m[k]), "measures are finite")
c.check(m[8][0] < m[3][0] < m[1][0], "complementarity falls with Newton iterations: %.2e (1) > %.2e (3) > %.2e (8) m" % (m[1][0], m[3][0], m[8][0]))
# the recursive scheme converges: 8 iterations leave far less than the explicit linearization
c.check(m[8][0] < 1e-3 * m[1][0], "8 iterations: complementarity %.2e < 1e-3 x that of 1 (%.2e)" % (m[8][0], m[1][0]))
# (the fingers' exact contact points, -contact_rounded_surface exact, take their normals where the fingers will be after
# the step, so 1 iteration's forces are off the end cone by much less than with their picture's points; what is left
# of the turn still puts them outside it by more than 5e-3)
c.check(m[8][1] < m[3][1] < m[1][1] and m[1][1] > 5e-3, "cone violation falls: %.2e > %.2e > %.2e (explicit-like 1 iteration > 5e-3: the normals turn)" % (m[1][1], m[3][1], m[8][1]))
rel = max(abs(me[i] - m[1][i]) / me[i] for i in range(3))
c.check(rel < 1e-6, "fast with 1 iteration = explicit: measures rel. diff %.1e < 1e-6" % rel)
# energy change adds up
E, dE, E0 = e["steps/energy"][:], e["steps/energy_change"][:], e.attrs["initial_energy"][0]
err = np.abs(E0 + np.cumsum(dE) - E).max() / max(np.abs(E).max(), 1e-30)
c.check(err < 1e-12 and np.abs(dE).max() > 0, "initial_energy + cumsum(energy_change) = energy (rel. %.1e)" % err)

# refactor every k steps: the factorization timing row is non-zero exactly at steps 1 + k j (step 1:
# A is factored at its first use, the free motion of the first step)
drop = ["-options_file", "input/cube_drop.opts", "-time_steps", "20", "-quiet"]
h = go("refactor4", drop + ["-cube_factorization", "reuse", "-cube_refactor_every", "4", "-cube_refactor_rotation", "10",
                             "-cube_refactor_residual", "100", "-cube_refactor_iterations", "1000"])
steps = list(h["steps/step"][:][h["steps/timing/factorization"][:] > 0])
c.check(steps == [1, 5, 9, 13, 17], "reuse, refactor_every 4: factored at steps %s (expected [1, 5, 9, 13, 17])" % steps)
h1 = go("refactor1", drop + ["-cube_factorization", "every_step"])
n1 = int((h1["steps/timing/factorization"][:] > 0).sum())
c.check(n1 == 20, "every_step: factored at %d of 20 steps" % n1)
pa, pb = sorted_positions(h1, "cube")[1], sorted_positions(h, "cube")[1]
d = np.abs(pa - pb).max()
c.check(0 < d < 1e-3, "older factor: positions differ from refactoring every step by %.2e m (0 < d < 1e-3)" % d)
p = run(drop + ["-cube_material", "linear", "-cube_refactor_every", "2", "-output_file", out("bad.h5")], check=False)
c.check(p.returncode != 0 and "-cube_refactor_every" in p.stdout + p.stderr, "refactor_every with a linear material: error naming the option")

# NNCG acceleration changes the sweeps, not the solution
tight = drop + ["-pgs_tol", "1e-10", "-pgs_max_it", "100000"]  # below ~1e-11 round-off stalls both
a, b = go("nncg", tight + ["-pgs_acceleration", "nncg"]), go("gs", tight + ["-pgs_acceleration", "none"])
pa, pb = sorted_positions(a, "cube")[1], sorted_positions(b, "cube")[1]
d = np.abs(pa - pb).max()
c.check(d < 1e-8, "nncg vs plain PGS at tol 1e-10: positions differ by %.2e m < 1e-8" % d)
c.check(a["steps/residual"][:].max() <= 1e-10 and b["steps/residual"][:].max() <= 1e-10, "both converge to 1e-10")
sa, sb = a["steps/pgs_iterations"][:].sum(), b["steps/pgs_iterations"][:].sum()
print("sweeps: nncg %d, plain %d" % (sa, sb))
c.done()
