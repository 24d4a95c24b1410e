"""A batch campaign from Python (issue 40): one HDF5 file per run, then a summary read from the files.

The scene is input/neohookean_ball.opts, a soft Neo-Hookean ball (r = 5 cm) dropped on a plane. The
campaign runs it for each pair of a drop height (the gap under the ball at the start) and a Young's
modulus: each run is a Scene built from that options file plus its own options (-ball_translate,
-ball_young, -time_steps long enough for the fall, the impact and the rebound's apex, and its own
-output_file in the campaign's directory). Once every run is done, the summary is read back from the
files alone with fecontact.Output (h5py, no MPI): the impact speed against sqrt(2 g h), the peak normal
force on the ground, how far the ball's centre came down at the impact, its rebound height.

Run it from the repository root (build it first: scripts/build.sh):
    /usr/bin/python3 examples/python/campaign.py [out/campaign] [--heights 0.05,0.1,0.2] [--young 5e4,1e5]
    mpirun -n 2 /usr/bin/python3 examples/python/campaign.py out/campaign
run_campaign() and summarize() do the same from a program or a test (tests/test_python_examples.py)."""
import argparse
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))
import fecontact  # noqa: E402  (before petsc4py: python/fecontact/_lib.py)

SCENE = os.path.join(ROOT, "input", "neohookean_ball.opts")
RADIUS = 0.05  # meshes/ball_5cm.msh
G = 9.81
TIME_STEP = 0.002  # the scene's
HEIGHTS = (0.05, 0.1, 0.2)
YOUNG = (5e4, 1e5)


def run_name(height, young):
    return "ball_h%.3f_E%.0e.h5" % (height, young)


def run_campaign(directory="out/campaign", heights=HEIGHTS, young=YOUNG, comm=None, log=None):
    """One run of input/neohookean_ball.opts per (height, young), each written to directory/run_name():
    the list of the files written"""
    os.makedirs(directory, exist_ok=True)
    say = log or (lambda *a: None)
    files = []
    for E in young:
        for hgt in heights:
            f = os.path.join(directory, run_name(hgt, E))
            fall = np.sqrt(2 * hgt / G)
            # the fall, the impact and the rebound to its apex (at most as long as the fall), with a margin
            steps = int(np.ceil((2 * fall + 0.05) / TIME_STEP))
            opts = {"ball_dm_plex_filename": os.path.join(ROOT, "meshes", "ball_5cm.msh"),
                    "ball_translate": (0.0, 0.0, RADIUS + hgt), "ball_young": E, "time_step": TIME_STEP,
                    "time_steps": steps, "output_file": f, "quiet": None}
            t0 = time.time()
            with fecontact.Scene(options_file=SCENE, options=opts, comm=comm) as scene:
                scene.run()
            say("%s: %d steps in %.1f s" % (f, steps, time.time() - t0))
            files.append(f)
    return files


def summarize(files):
    """The figures of each run, read from its file alone: a list of dicts"""
    rows = []
    for f in files:
        with fecontact.Output(f) as o:
            opts = o.options
            height = float(opts["ball_translate"].split(",")[2]) - RADIUS
            z = o.body("ball").centroid[:, 2]
            z0 = o.body("ball").initial_centroid[2]
            zs = np.concatenate([[z0], z])
            ground = o.pair_normal_forces()[("ball", "ground")]
            low = int(np.argmin(zs))
            rows.append(dict(file=os.path.basename(f), height=height, young=float(opts["ball_young"]),
                             steps=o.nsteps, impact_speed=float(-np.diff(zs).min() / o.time_step),
                             free_fall_speed=float(np.sqrt(2 * G * height)), peak_force=float(ground.max()),
                             compression=float(RADIUS - zs[low]), rebound=float(zs[low:].max() - RADIUS),
                             wall_time=float(o.steps.wall_time[-1]) if "wall_time" in o.steps else float("nan")))
    return rows


def print_table(rows, out=print):
    out("%-24s %6s %8s %16s %10s %12s %10s %8s" % ("run", "h (m)", "E (kPa)", "impact (m/s)", "peak F (N)",
                                                   "centre down", "rebound", "e"))
    for r in rows:
        out("%-24s %6.3f %8.0f %7.3f / %6.3f %10.2f %9.2f mm %7.2f mm %8.3f" %
            (r["file"], r["height"], r["young"] / 1e3, r["impact_speed"], r["free_fall_speed"], r["peak_force"],
             1e3 * r["compression"], 1e3 * r["rebound"], np.sqrt(max(r["rebound"], 0.0) / r["height"])))
    out("impact: the largest downward speed of the centre / sqrt(2 g h); centre down: the ball's radius less the "
        "lowest height of its centre; rebound: the apex of its centre after the impact, above the radius; "
        "e = sqrt(rebound / h)")


def floats(text):
    return [float(x) for x in text.split(",") if x]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("directory", nargs="?", default="out/campaign", help="where the runs' files go (out/campaign)")
    ap.add_argument("--heights", type=floats, default=list(HEIGHTS), help="drop heights (m), comma-separated")
    ap.add_argument("--young", type=floats, default=list(YOUNG), help="Young's moduli (Pa), comma-separated")
    a = ap.parse_args()
    from petsc4py import PETSc
    rank = PETSc.COMM_WORLD.rank
    say = print if rank == 0 else (lambda *x: None)
    files = run_campaign(a.directory, a.heights, a.young, log=say)
    if rank == 0:  # the files are closed: any process can read them, with h5py alone
        print_table(summarize(files))


if __name__ == "__main__":
    main()
