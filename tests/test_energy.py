"""Energy: total energy (kinetic + elastic + gravitational, /steps/energy) of a cantilever released
from rest under gravity. Implicit Euler on a linear model dissipates exactly
  E_{n+1} - E_n = -h v^T B v - dv^T M dv / 2 - du^T K du / 2 <= 0,
so without damping energy never grows, and with Rayleigh damping it decays monotonically (and
faster). Checked for the linear and the co-rotational model (where A is re-factored each step),
and for a rigid box tumbling about a non-principal axis (gyroscopic torque). Tolerance: a growth of
at most 1e-12 of the initial energy scale per step (round-off)."""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("energy np%d" % NP)
base = ["-scene_bodies", "beam", "-beam_type", "fem", "-beam_dm_plex_filename", "meshes/beam_n4.msh",
        "-beam_young", "2e6", "-beam_density", "1000", "-beam_fixed_box", "-1,-1,-1,1e-9,1,1",
        "-time_step", "0.01", "-time_steps", "150", "-output_every", "50", "-quiet"]
for material in ["linear", "corotational"]:
    runs = {}
    for damped in [False, True]:
        f = out("energy_%s_%d_np%d.h5" % (material, damped, NP))
        extra = ["-beam_rayleigh_mass", "0.5", "-beam_rayleigh_stiffness", "0.01"] if damped else []
        run(base + ["-beam_material", material, "-output_file", f] + extra, np_=NP)
        H = h5py.File(f, "r")
        E = H["steps/energy"][:]
        scale = np.abs(H["bodies/beam/energy"][:]).max()
        dE = np.diff(E) / scale
        runs[damped] = E
        what = "damped, decays monotonically" if damped else "undamped, never grows"
        c.check(dE.max() <= 1e-12, "%s %s: max step change %+.2e of scale %.3e" % (material, what, dE.max(), scale))
        moved = np.abs(H["bodies/beam/energy"][:, 0]).max()
        c.check(moved > 1e-3 * scale, "%s: the beam moves (max kinetic %.3e)" % (material, moved))
    c.check(runs[True][-1] < runs[False][-1], "%s: damping dissipates more (%.6e < %.6e)" % (material, runs[True][-1], runs[False][-1]))

f = out("energy_rigid_np%d.h5" % NP)
run(["-scene_bodies", "box", "-box_type", "rigid", "-box_shape", "box", "-box_half_extents", "0.1,0.3,0.6",
     "-box_density", "500", "-box_angular_velocity", "3,1,0.5", "-gravity", "0,0,-9.81",
     "-time_step", "0.01", "-time_steps", "300", "-output_every", "100", "-output_file", f, "-quiet"], np_=NP)
H = h5py.File(f, "r")
E = H["steps/energy"][:]
scale = np.abs(H["bodies/box/energy"][:]).max()
c.check(np.diff(E).max() / scale <= 1e-12, "tumbling rigid box: energy never grows (max step change %+.2e)" % (np.diff(E).max() / scale))
c.done()
