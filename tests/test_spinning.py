"""Spinning co-rotational bodies (src/body/fem_rotation.c, -<body>_rotation exact, the default).

- A free FE ball (r = 5 cm, rho = 1000, meshes/ball_5cm.msh) spinning at 20 rad/s with h = 0.005
  (omega h = 0.1) keeps its energy within 1 % over 100 steps, at E = 1e6 and 1e8; with eq. 2 as it
  is (-ball_rotation linear) the same ball gains more than 10 % in its first step at E = 1e6 (the
  stretch of the tangent step taken as strain), so the check can fail.
- The spinning ball keeps its angular momentum: the velocity field after 100 steps turns at
  20 rad/s about z within 0.2 % (from the output positions and velocities, omega = I^-1 L with the
  vertices' lumped masses).
- A stiff FE bar (E = 1e9) tumbling about a non-principal axis turns as the rigid box of the same
  shape does (Euler's equations, src/body/rigid.c): orientations within 0.5 degrees after 1 s
  (h = 0.005; the two first-order integrators differ by O(h)), energies within 0.1 %.
On 1 and 2 ranks."""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("spinning np%d" % NP)
H, N, W = 0.005, 100, 20.0


def ball(E, rotation, steps=N):
    f = out("spin_%s_%s_np%d.h5" % (E, rotation, NP))
    run(["-scene_bodies", "ball", "-ball_type", "fem", "-ball_dm_plex_filename", "meshes/ball_5cm.msh",
         "-ball_material", "corotational", "-ball_young", E, "-ball_density", "1000", "-ball_rotation", rotation,
         "-ball_angular_velocity", "0,0,%g" % W, "-gravity", "0,0,0", "-time_step", H, "-time_steps", steps,
         "-output_every", steps, "-output_file", f, "-quiet"], np_=NP)
    return h5py.File(f, "r")


for E in ["1e6", "1e8"]:
    f = ball(E, "exact")
    e0 = float(np.ravel(f.attrs["initial_energy"])[0])
    e = f["steps/energy"][:] / e0
    c.check(np.abs(e - 1).max() < 0.01, "E = %s, omega h = 0.1: energy within 1 %% over %d steps (range %.5f .. %.5f "
            "of the initial %.4f J)" % (E, N, e.min(), e.max(), e0))
    if E == "1e6":
        g = f["bodies/ball"]
        x, v = g["positions"][-1], g["velocity"][-1]
        # lumped vertex masses from the mesh: rho V / 4 per cell and vertex
        X, cells = g["mesh/reference"][:], g["mesh/cells"][:]
        P = X[cells]
        vol = np.abs(np.einsum("ij,ij->i", P[:, 1] - P[:, 0], np.cross(P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]))) / 6
        m = np.zeros(len(X))
        np.add.at(m, cells.ravel(), np.repeat(1000 * vol / 4, 4))
        r = x - (m[:, None] * x).sum(0) / m.sum()
        L = (m[:, None] * np.cross(r, v)).sum(0)
        I = (m[:, None, None] * (np.einsum("ij,ij->i", r, r)[:, None, None] * np.eye(3) - r[:, :, None] * r[:, None, :])).sum(0)
        w = np.linalg.solve(I, L)
        c.check(abs(w[2] - W) / W < 2e-3 and np.abs(w[:2]).max() < 1e-3 * W,
                "E = 1e6: after %d steps the ball turns at (%.4f, %.4f, %.4f) rad/s (20 about z)" % (N, w[0], w[1], w[2]))

f = ball("1e6", "linear", 1)
e0 = float(np.ravel(f.attrs["initial_energy"])[0])
gain = f["steps/energy"][0] / e0 - 1
c.check(gain > 0.1, "-ball_rotation linear (eq. 2 as it is), E = 1e6: the first step adds %.1f %% of the energy" % (100 * gain))


def quat_matrix(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


# a stiff bar tumbling about a non-principal axis against the rigid box of its shape (meshes/bar.msh:
# 0.55 x 0.1 x 0.1 m, centred on its centroid by both bodies)
steps, w = 200, "3,1,0.5"
common = ["-gravity", "0,0,0", "-time_step", H, "-time_steps", steps, "-output_every", steps, "-quiet"]
fr, ff = out("tumble_rigid_np%d.h5" % NP), out("tumble_fe_np%d.h5" % NP)
run(["-scene_bodies", "box", "-box_type", "rigid", "-box_shape", "box", "-box_half_extents", "0.275,0.05,0.05",
     "-box_density", "1000", "-box_angular_velocity", w, "-output_file", fr] + common, np_=NP)
run(["-scene_bodies", "bar", "-bar_type", "fem", "-bar_dm_plex_filename", "meshes/bar.msh", "-bar_material",
     "corotational", "-bar_young", "1e9", "-bar_density", "1000", "-bar_angular_velocity", w, "-output_file", ff] + common,
    np_=NP)
R, F = h5py.File(fr, "r"), h5py.File(ff, "r")
Rr = quat_matrix(R["bodies/box/rotation"][-1])
X, P = F["bodies/bar/mesh/reference"][:], F["bodies/bar/positions"][-1]
U, _, Vt = np.linalg.svd((P - P.mean(0)).T @ (X - X.mean(0)))
Rf = U @ np.diag([1, 1, np.linalg.det(U @ Vt)]) @ Vt
ang = np.degrees(np.arccos(np.clip((np.trace(Rf.T @ Rr) - 1) / 2, -1, 1)))
turned = np.degrees(np.arccos(np.clip((np.trace(Rr) - 1) / 2, -1, 1)))
er, ef = R["steps/energy"][-1], F["steps/energy"][-1]
c.check(ang < 0.5 and abs(ef - er) / er < 1e-3,
        "stiff bar tumbling about a non-principal axis, 1 s: %.3f degrees from the rigid box (which turned %.1f), energy "
        "%.6g J against %.6g" % (ang, turned, ef, er))
c.done()
