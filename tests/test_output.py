"""Output: the HDF5 schema of docs/output.md (datasets, shapes, attributes), frames every
-output_every steps plus the last, the XDMF index (valid XML pointing at existing datasets with
consistent sizes), and that a file from an interrupted run (-time_steps reached early by a
diverging step) keeps every completed step."""
import os
import xml.etree.ElementTree as ET
import numpy as np
import h5py
from fctest import run, out, Checker, ROOT

c = Checker("output")
f = out("schema.h5")
run(["-options_file", "input/cube_fall.opts", "-time_steps", "23", "-output_every", "5", "-output_file", f, "-quiet"])
H = h5py.File(f, "r")
c.check(H["steps/time"].shape == (23,) and H["steps/step"][-1] == 23, "/steps has one row per step")
for p in ["assembly", "factorization", "free_motion", "integration", "output"]:
    ok = H["steps/timing/" + p].shape == (23,) and np.all(H["steps/timing/" + p][:] >= 0)
    c.check(ok, "/steps/timing/%s per step, non-negative" % p)
# the step's wall time covers its phases (one rank: they are nested in it; 2e-4 s for the clock reads)
wall = H["steps/wall_time"][:]
phases = sum(H["steps/timing/" + p][:] for p in H["steps/timing"])
c.check(wall.shape == (23,) and np.all(wall > 0) and np.all(wall >= phases - 2e-4),
        "/steps/wall_time per step, at least the sum of its phases (largest shortfall %.1e s)" % np.max(phases - wall))
c.check(list(H["complete"][:]) == [23, 6], "/complete of a finished run: its last step and its frames (%s)" % list(H["complete"][:]))
c.check(list(H["frames/step"][:]) == [0, 5, 10, 15, 20, 23], "frames at 0, every 5 steps and the last: %s" % list(H["frames/step"][:]))
c.check("-cube_young 1e5" in H.attrs["options"].decode() if isinstance(H.attrs["options"], bytes) else "-cube_young 1e5" in H.attrs["options"],
        "root attribute 'options' holds the options")
for k in ["fecontact_version", "mpi_ranks", "time_step", "time_steps", "output_every", "created"]:
    c.check(k in H.attrs, "root attribute %s" % k)
for b, typ in [("cube", "fem"), ("ball", "rigid"), ("ground", "kinematic")]:
    g = H["bodies/" + b]
    nv = g["mesh/reference"].shape[0]
    c.check(g.attrs["type"].decode() == typ if isinstance(g.attrs["type"], bytes) else g.attrs["type"] == typ, "%s type %s" % (b, typ))
    c.check(g["centroid"].shape == (23, 3) and g["energy"].shape == (23, 3), "%s centroid and energy (steps x 3)" % b)
    c.check(g["positions"].shape == (6, nv, 3), "%s positions (frames x vertices x 3): %s" % (b, g["positions"].shape))
    c.check(np.allclose(g["positions"][0], g["mesh/reference"][:]), "%s frame 0 is the reference placement" % b)
    cells = g["mesh/cells"][:]
    c.check(cells.min() >= 0 and cells.max() < nv, "%s cells index existing vertices" % b)
    if typ != "fem":
        q = g["rotation"][:]
        c.check(q.shape == (23, 4) and np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12), "%s rotation unit quaternions" % b)
xmf = f[:-3] + ".xmf"
c.check(os.path.exists(xmf), "XDMF file written beside the HDF5 file")
root = ET.parse(xmf).getroot()
grids = root.findall("./Domain/Grid")
c.check(len(grids) == 3 and all(len(g.findall("Grid")) == 6 for g in grids), "XDMF: one temporal collection per body, 6 frames each")
ok = True
for item in root.iter("DataItem"):
    if item.get("Format") == "HDF":
        fname, path = item.text.strip().split(":")
        dims = tuple(int(x) for x in item.get("Dimensions").split())
        ok &= fname == os.path.basename(f) and path in H and H[path].shape == dims
c.check(ok, "XDMF: every HDF reference exists with the declared dimensions")
c.done()
