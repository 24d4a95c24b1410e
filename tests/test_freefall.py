"""Free fall: an FE body (linear and co-rotational) and rigid bodies under gravity follow the
closed form of the discrete implicit Euler recurrence, v_n = v0 + n h g,
x_n = x0 + n h v0 + h^2 g n (n+1) / 2, to 1e-12 (relative to the travelled distance scale);
a rigid sphere spinning about an axis keeps q_n = exp(n h w / 2) q0; a kinematic body moves
exactly as prescribed. Usage: test_freefall.py [--np N]"""
import numpy as np
import h5py
from fctest import run, out, Checker, np_from_argv

NP = np_from_argv()
c = Checker("freefall np%d" % NP)
h, N, g = 0.01, 40, np.array([0.3, -0.2, -9.81])
v0 = np.array([0.5, 0.0, 1.0])
f = out("freefall_np%d.h5" % NP)
run(["-scene_bodies", "lin,cor,box,ball,kin,mcube,bcube",
     "-mcube_type", "rigid", "-mcube_shape", "mesh", "-mcube_dm_plex_filename", "meshes/cube_coarse.msh",
     "-mcube_density", "100", "-mcube_angular_velocity", "0,0,2", "-mcube_velocity", "0.5,0,1", "-mcube_translate", "0,0,5",
     "-bcube_type", "rigid", "-bcube_shape", "box", "-bcube_half_extents", "0.5,0.5,0.5", "-bcube_density", "100",
     "-bcube_angular_velocity", "0,0,2", "-bcube_velocity", "0.5,0,1", "-bcube_center", "0,0,-5", "-time_step", h, "-time_steps", N, "-gravity", "0.3,-0.2,-9.81",
     "-output_file", f, "-quiet",
     "-lin_type", "fem", "-lin_dm_plex_filename", "meshes/cube_coarse.msh", "-lin_young", "1e6", "-lin_density", "800",
     "-lin_velocity", "0.5,0,1",
     "-cor_type", "fem", "-cor_dm_plex_filename", "meshes/cube_coarse.msh", "-cor_young", "1e6", "-cor_density", "800",
     "-cor_material", "corotational", "-cor_mass_type", "lumped", "-cor_velocity", "0.5,0,1", "-cor_translate", "3,0,0",
     "-box_type", "rigid", "-box_shape", "box", "-box_half_extents", "0.2,0.3,0.4", "-box_density", "100",
     "-box_velocity", "0.5,0,1", "-box_center", "0,3,0",
     "-ball_type", "rigid", "-ball_shape", "sphere", "-ball_radius", "0.3", "-ball_density", "100",
     "-ball_velocity", "0.5,0,1", "-ball_center", "0,-3,0", "-ball_angular_velocity", "1,2,3",
     "-kin_type", "kinematic", "-kin_shape", "capsule", "-kin_radius", "0.2", "-kin_length", "1",
     "-kin_velocity", "1,2,3", "-kin_angular_velocity", "0,0,5", "-kin_center", "5,5,5"], np_=NP)
H = h5py.File(f, "r")
n = np.arange(1, N + 1)[:, None]
scale = np.abs(h * h * g * N * (N + 1) / 2).max()
for b in ["lin", "cor", "box", "ball"]:
    x0 = H["bodies/%s" % b].attrs["initial_centroid"]
    exact = x0 + n * h * v0 + h * h * g * n * (n + 1) / 2
    err = np.abs(H["bodies/%s/centroid" % b][:] - exact).max() / scale
    c.check(err < 1e-12, "%s centroid vs closed form: rel err %.2e < 1e-12" % (b, err))
for b in ["lin", "cor"]:  # every vertex moves rigidly with the closed form
    ref, pos = H["bodies/%s/mesh/reference" % b][:], H["bodies/%s/positions" % b][-1]
    disp = N * h * v0 + h * h * g * N * (N + 1) / 2
    err = np.abs(pos - ref - disp).max() / scale
    c.check(err < 1e-12, "%s every vertex displacement vs closed form: rel err %.2e" % (b, err))
w = np.array([1.0, 2.0, 3.0])
ang = np.linalg.norm(w) * h * N
q_exact = np.concatenate([[np.cos(ang / 2)], np.sin(ang / 2) * w / np.linalg.norm(w)])
q = H["bodies/ball/rotation"][-1]
err = min(np.abs(q - q_exact).max(), np.abs(q + q_exact).max())
c.check(err < 1e-12, "spinning sphere quaternion after %d steps: err %.2e" % (N, err))
kx = H["bodies/kin/centroid"][:]
err = np.abs(kx - (np.array([5, 5, 5]) + n * h * np.array([1, 2, 3]))).max()
c.check(err < 1e-12, "kinematic body follows its prescribed twist: err %.2e" % err)
qk = H["bodies/kin/rotation"][-1]
c.check(abs(qk[0] - np.cos(5 * h * N / 2)) < 1e-12 and abs(qk[3] - np.sin(5 * h * N / 2)) < 1e-12,
        "kinematic rotation exp(t w/2): %s" % qk)
# mass properties: a rigid body shaped by the tet mesh of the unit cube and an analytic unit box,
# both spinning about z: kinetic energy 1/2 m |v|^2 + 1/2 (m/6) w^2 at every step
m, wz = 100.0, 2.0
for b in ["mcube", "bcube"]:
    v = v0 + n * h * g
    Ek = 0.5 * m * (v * v).sum(axis=1) + 0.5 * (m / 6.0) * wz * wz
    err = np.abs(H["bodies/%s/energy" % b][:, 0] - Ek).max() / Ek.max()
    c.check(err < 1e-12, "%s (rigid %s) kinetic energy vs 1/2 m v^2 + 1/2 (m/6) w^2: rel err %.2e" % (b, "mesh" if b == "mcube" else "box", err))
    x0 = H["bodies/%s" % b].attrs["initial_centroid"]
    err = np.abs(H["bodies/%s/centroid" % b][:] - (x0 + n * h * v0 + h * h * g * n * (n + 1) / 2)).max() / scale
    c.check(err < 1e-12, "%s centroid vs closed form: rel err %.2e" % (b, err))
c.check(np.abs(H["bodies/mcube"].attrs["initial_centroid"] - [0, 0, 5]).max() < 1e-12, "mesh shape: centroid of the mesh, translated")
c.check(H["steps/time"].shape == (N,) and abs(H["steps/time"][-1] - N * h) < 1e-14, "one /steps row per step")
c.done()
