#!/usr/bin/python3
"""Sliding over FE slabs of three element sizes, along and across the mesh, at three speeds, against
the same slider on a kinematic plane (issue 32; tests/test_sliding.py runs a few of these cases in
ctest). The slab is that of input/sliding.opts (1 m x 0.3 m x 5 cm, E = 1e8, bottom fixed) meshed by
meshes/slide_slab_coarse.msh (5 cm elements), slide_slab.msh (2.5 cm) and slide_slab_fine.msh
(1.25 cm); mu = 0.5, h = 0.005, 100 steps (60 for the FE block). Sliders: a rigid box (0.1 m), an
upright rigid cylinder (r 5 cm, 0.1 m), an FE block (meshes/small_cube.msh, 0.15 m, co-rotational,
E = 1e7). Directions 0, 30 and 45 degrees to the mesh at 0.5 and 1 m/s, along it at 2 m/s (across
at 2 m/s the slider would leave the slab's side). Prints a markdown table: the distance on the slab
and on the plane, their relative difference, the height range (hop) and the sideways drift, and
writes a plot of the relative differences (--plot FILE).
  /usr/bin/python3 scripts/sliding_matrix.py [--exe build/fecontact] [--plot docs/figures/sliding_matrix.png]"""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--exe", default=os.path.join(ROOT, "build", "fecontact"))
ap.add_argument("--plot", default=None)
a = ap.parse_args()
env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
tmp = tempfile.mkdtemp(prefix="sliding-matrix-")
COMMON = ["-time_step", "0.005", "-time_steps", "100", "-contact_mu", "0.5", "-contact_distance", "0.005",
          "-scene_bodies", "slab,box", "-contact_pairs", "slab:box", "-quiet"]
MESHES = [("5 cm", "slide_slab_coarse"), ("2.5 cm", "slide_slab"), ("1.25 cm", "slide_slab_fine")]
PLANE = ["-slab_type", "kinematic", "-slab_shape", "plane", "-slab_length", "3"]


def slab(mesh):
    return ["-slab_type", "fem", "-slab_dm_plex_filename", "meshes/%s.msh" % mesh, "-slab_material", "linear",
            "-slab_young", "1e8", "-slab_density", "1000", "-slab_translate", "0.4,0,-0.05",
            "-slab_fixed_box", "-3,-3,-1,3,3,-0.049"]


def slider(kind, y):
    if kind == "rigid box":
        return ["-box_type", "rigid", "-box_shape", "box", "-box_half_extents", "0.05,0.05,0.05", "-box_density",
                "1000", "-box_center", "0.1125,%g,0.05" % y]
    if kind == "rigid cylinder":
        return ["-box_type", "rigid", "-box_shape", "cylinder", "-box_radius", "0.05", "-box_length", "0.1",
                "-box_density", "1000", "-box_center", "0.1125,%g,0.05" % y]
    return ["-box_type", "fem", "-box_dm_plex_filename", "meshes/small_cube.msh", "-box_material", "corotational",
            "-box_young", "1e7", "-box_density", "1000", "-box_translate", "0.1125,%g,0.0" % y,
            "-time_steps", "60"]


seq = [0]


def go(ground, body, v):
    seq[0] += 1
    f = os.path.join(tmp, "s%d.h5" % seq[0])
    subprocess.run([a.exe] + COMMON + ground + body + ["-box_velocity", "%.17g,%.17g,0" % (v[0], v[1]),
                                                       "-output_file", f], cwd=ROOT, env=env, check=True)
    h = h5py.File(f, "r")
    return h["bodies/box/centroid"][:], int(h["steps/intersections"][:].max())


cases = [(d, s) for d in (0, 30, 45) for s in (0.5, 1.0)] + [(0, 2.0)]
rows = []
print("| slider | direction | speed | element | on the slab (m) | on the plane (m) | rel. | hop (m) | sideways (m) | intersections |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for kind in ("rigid box", "rigid cylinder", "FE block"):
    for d, s in cases:
        u = np.array([np.cos(np.radians(d)), np.sin(np.radians(d)), 0.0])
        y0 = 0.0125 if d == 0 else -0.07  # the slab spans y in [-0.15, 0.15]: every slider starts and stays on it
        ref, _ = go(PLANE, slider(kind, y0), s * u)
        dref = (ref[-1] - ref[0]) @ u
        for label, mesh in MESHES:
            x, ni = go(slab(mesh), slider(kind, y0), s * u)
            dx = (x[-1] - x[0]) @ u
            side = np.abs(np.cross(x - x[0], u)[:, 2]).max()
            hop = x[:, 2].max() - x[:, 2].min()
            rel = dx / dref - 1
            rows.append((kind, d, s, label, rel))
            print("| %s | %d | %.1f | %s | %.5f | %.5f | %+.1e | %.1e | %.1e | %d |" % (
                kind, d, s, label, dx, dref, rel, hop, side, ni), flush=True)
if a.plot:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4))
    labels = ["%s %d deg %.1f m/s" % (k, d, s) for k, d, s in dict.fromkeys((r[0], r[1], r[2]) for r in rows)]
    for j, (label, _) in enumerate(MESHES):
        vals = [abs(r[4]) for r in rows if r[3] == label]
        ax.semilogy(range(len(vals)), np.maximum(vals, 1e-8), "o", label="elements " + label)
    ax.axhline(0.03, color="k", ls="--", lw=0.8, label="3 % (issue 32)")
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, rotation=90, fontsize=6)
    ax.set_ylabel("|distance on FE slab / on plane - 1|")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.plot, dpi=120)
