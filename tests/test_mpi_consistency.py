"""MPI: the same FE scenes on 1 and N ranks give the same vertex positions (matched through their
reference coordinates, since vertex numbering follows the partition) to 1e-10 relative, and the
same centroids and energies. Scenes: a co-rotational spinning cube with a rigid and a kinematic
body (input/cube_fall.opts), and a damped cantilever with fixed vertices.
Usage: test_mpi_consistency.py --np N"""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv, sorted_positions

NP = np_from_argv(2)
c = Checker("mpi consistency 1 vs %d ranks" % NP)
scenes = {
    "cube_fall": ["-options_file", "input/cube_fall.opts", "-time_steps", "30"],
    "beam": ["-scene_bodies", "beam", "-beam_type", "fem", "-beam_dm_plex_filename", "meshes/beam_n4.msh",
             "-beam_young", "2e6", "-beam_density", "1000", "-beam_fixed_box", "-1,-1,-1,1e-9,1,1",
             "-beam_material", "corotational", "-beam_rayleigh_stiffness", "0.01", "-beam_mass_type", "lumped",
             "-time_step", "0.01", "-time_steps", "30", "-output_every", "10"],
}
for name, opts in scenes.items():
    files = []
    for np_ in [1, NP]:
        f = out("mpi_%s_np%d.h5" % (name, np_))
        run(opts + ["-output_file", f, "-quiet"], np_=np_)
        files.append(h5py.File(f, "r"))
    a, b = files
    c.check(b.attrs["mpi_ranks"] == NP, "%s ran on %d ranks" % (name, NP))
    # the step's wall time on N ranks: every phase (the largest time of a rank) lies inside it, and
    # /complete names the whole run (2e-4 s for the clock reads)
    wall = b["steps/wall_time"][:]
    worst = np.max([b["steps/timing/" + p][:] for p in b["steps/timing"]], axis=0)
    c.check(wall.shape == (30,) and np.all(wall > 0) and np.all(wall >= worst - 2e-4),
            "%s: /steps/wall_time on %d ranks holds every phase (largest shortfall %.1e s)" % (name, NP, np.max(worst - wall)))
    c.check(list(b["complete"][:]) == [30, len(b["frames/step"])], "%s: /complete on %d ranks is %s" % (
        name, NP, list(b["complete"][:])))
    for body in a["bodies"]:
        ra, pa = sorted_positions(a, body)
        rb, pb = sorted_positions(b, body)
        c.check(np.abs(ra - rb).max() < 1e-12, "%s/%s: same vertex set" % (name, body))
        scale = np.abs(pa - ra).max() + 1e-300
        err = np.abs(pa - pb).max() / np.abs(pa).max()
        errd = np.abs(pa - pb).max() / scale
        c.check(err < 1e-10, "%s/%s: positions rel. diff %.2e (displacement-relative %.2e) < 1e-10" % (name, body, err, errd))
        ce = np.abs(a["bodies/%s/centroid" % body][:] - b["bodies/%s/centroid" % body][:]).max()
        c.check(ce < 1e-10 * max(1.0, np.abs(a["bodies/%s/centroid" % body][:]).max()), "%s/%s: centroids differ by %.2e" % (name, body, ce))
    ee = np.abs(a["steps/energy"][:] - b["steps/energy"][:]).max() / np.abs(a["steps/energy"][:]).max()
    c.check(ee < 1e-10, "%s: energies rel. diff %.2e" % (name, ee))
c.done()
