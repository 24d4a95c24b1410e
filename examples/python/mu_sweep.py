"""A parameter sweep from Python (issue 40): the friction coefficient mu of a block on an incline.

The scene is input/incline.opts: a rigid box on a kinematic plane tilted by theta = 30 degrees. For each
mu the script builds one Scene (its own output file), runs it for a shortened time T, reads the box's
centroid from Python and measures how far it slid down the slope. Coulomb's law says the block slides
iff tan(theta) > mu, with the acceleration a = g (sin(theta) - mu cos(theta)), so d = a T^2 / 2 from
rest; the time integration (backward Euler: v += h a, then x += h v) gives a h^2 n (n + 1) / 2 after n
steps of h, (n + 1) / n times that. The script plots the measured distances against mu with the
expectation (matplotlib, Agg) and writes them as a CSV beside the PNG.

Run it from the repository root (build it first: scripts/build.sh):
    /usr/bin/python3 examples/python/mu_sweep.py [--png out/mu_sweep.png] [--outdir out/mu_sweep] [--steps 50]
    mpirun -n 2 /usr/bin/python3 examples/python/mu_sweep.py
sweep() does the same from a program or a test (tests/test_python_examples.py)."""
import argparse
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))
import fecontact  # noqa: E402  (before petsc4py: python/fecontact/_lib.py)

SCENE = os.path.join(ROOT, "input", "incline.opts")
THETA = np.radians(30.0)  # the scene's tilt (-ground_rotate 0,1,0,30)
G = 9.81
DOWNHILL = np.array([np.cos(THETA), 0.0, -np.sin(THETA)])  # the plane's normal is (sin, 0, cos)
MUS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.55, 0.6, 0.65, 0.7, 0.8, 1.0)


def acceleration(mu):
    """Coulomb: the acceleration of a block down the slope (0 where it sticks)"""
    return max(G * (np.sin(THETA) - mu * np.cos(THETA)), 0.0)


def expected(mu, t):
    """The distance a block released at rest slides down the slope in time t"""
    return 0.5 * acceleration(mu) * t * t


def expected_steps(mu, h, n):
    """The same after n backward Euler steps of h: a h^2 n (n + 1) / 2"""
    return 0.5 * acceleration(mu) * h * h * n * (n + 1)


def sweep(mus=MUS, outdir="out/mu_sweep", steps=50, comm=None):
    """One run of input/incline.opts per mu (steps steps, output outdir/incline_mu<mu>.h5): a list of
    dicts mu, time, distance (down the slope, m), expected (m, a T^2 / 2), expected_steps (m, that of the
    time integration), file"""
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for mu in mus:
        f = os.path.join(outdir, "incline_mu%.2f.h5" % mu)
        with fecontact.Scene(options_file=SCENE, options={"contact_mu": mu, "time_steps": steps, "output_file": f,
                                                          "quiet": None}, comm=comm) as scene:
            scene.setup()  # the bodies are placed at set-up
            box = scene.body("box")
            x0 = box.centroid
            scene.run()
            d = float(np.dot(box.centroid - x0, DOWNHILL))
            rows.append(dict(mu=mu, time=scene.time, distance=d, expected=expected(mu, scene.time),
                             expected_steps=expected_steps(mu, scene.time_step, scene.step_index),
                             steps=scene.step_index, file=f))
    return rows


def plot(rows, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    mu = np.array([r["mu"] for r in rows])
    t = rows[0]["time"]
    fine = np.linspace(0, max(mu.max(), 1.0), 400)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(fine, [expected(m, t) for m in fine], "-", color="0.6", label="Coulomb: $g(\\sin\\theta - \\mu\\cos\\theta)"
            "\\,T^2/2$")
    h, n = t / rows[0]["steps"], rows[0]["steps"]
    ax.plot(fine, [expected_steps(m, h, n) for m in fine], "--", color="C1", lw=1,
            label="the same after %d backward Euler steps" % n)
    ax.plot(mu, [r["distance"] for r in rows], "o", color="C0", label="fecontact")
    ax.axvline(np.tan(THETA), ls=":", color="k", label="$\\mu = \\tan 30^\\circ$")
    ax.set_xlabel("$\\mu$")
    ax.set_ylabel("distance slid down the slope in T = %g s (m)" % t)
    ax.set_title("Block on a 30 degree incline (input/incline.opts)")
    ax.legend()
    fig.tight_layout()
    if os.path.dirname(png):
        os.makedirs(os.path.dirname(png), exist_ok=True)
    fig.savefig(png, dpi=100)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--png", default="out/mu_sweep.png", help="the plot (default out/mu_sweep.png; the CSV beside it)")
    ap.add_argument("--outdir", default="out/mu_sweep", help="the runs' HDF5 files (default out/mu_sweep)")
    ap.add_argument("--steps", type=int, default=50, help="time steps of each run (default 50: 0.5 s)")
    a = ap.parse_args()
    rows = sweep(outdir=a.outdir, steps=a.steps)
    from petsc4py import PETSc
    if PETSc.COMM_WORLD.rank:
        return
    print("%6s %12s %12s %12s  %s" % ("mu", "slid (m)", "a T^2/2 (m)", "Euler (m)", "tan(30) > mu"))
    for r in rows:
        print("%6.2f %12.5f %12.5f %12.5f  %s" % (r["mu"], r["distance"], r["expected"], r["expected_steps"],
                                                  np.tan(THETA) > r["mu"]))
    plot(rows, a.png)
    csv = os.path.splitext(a.png)[0] + ".csv"
    with open(csv, "w") as f:
        f.write("mu,time,distance,expected,expected_steps,file\n")
        for r in rows:
            f.write("%r,%r,%r,%r,%r,%s\n" % (r["mu"], r["time"], r["distance"], r["expected"], r["expected_steps"],
                                             r["file"]))
    print("wrote %s and %s" % (a.png, csv))


if __name__ == "__main__":
    main()
