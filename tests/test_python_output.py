"""fecontact.Output (python/fecontact/output.py), the reader of the HDF5 output, against h5py reading
the same datasets directly, on files of short runs:

- the grasp (input/grasp_rotate.opts, 12 steps: an FE cube held by two kinematic spheres, pairs
  object:finger1 and object:finger2, contacts from step 1), whose scene order object,finger1,finger2
  is not the alphabetical order of /bodies: every per-step array, timing, frame, field and mesh the
  same arrays exactly; the contacts of every step are the /contacts/offset slices, all of them the
  whole datasets; the pairs' names those of -scene_bodies; pair_forces and pair_normal_forces a
  direct sum; the same run with -scene_bodies finger2,object,finger1 gives other indices in
  /contacts/bodies and the same names; without the root attribute scene_bodies (older files) the
  names come from the options; without either, the alphabetical order;
- the pressed balls (input/pressed.opts, 3 steps: an FE-FE pair with records both ways): reactions,
  and the pair force on the ball counting the records whose side 1 is the block with the opposite
  sign (the vertical force equal to the sum of the normal forces);
- a scene without contact pairs (input/cube_fall.opts): no contacts, no pair forces;
- a run of 0 steps, and a file cut at /complete (a run that stopped early: /complete says fewer
  steps and frames than the datasets hold): only what /complete says is read;
- errors: a missing body (KeyError naming it and listing the bodies), a missing dataset or field, a
  step out of range;
- scripts/plot_run.py writes a PNG for each of these files.
Runs on 1 rank (the reader reads files; test_output.py and test_mpi_consistency.py check the files)."""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from fctest import run, out, Checker, np_from_argv, ROOT

sys.path.insert(0, os.path.join(ROOT, "python"))
from fecontact.output import Output  # noqa: E402

NP = np_from_argv()
c = Checker("python_output np%d" % NP)
PLOT = os.path.join(ROOT, "scripts", "plot_run.py")


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a, b)


def raises(fn, exc):
    """The exception fn() raises if it is an exc, else None."""
    try:
        fn()
    except exc as e:
        return e
    return None


def is_png(path):
    return os.path.exists(path) and open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"


# --- the grasp: three bodies, two pairs, scene order not alphabetical
grasp = ["-options_file", "input/grasp_rotate.opts", "-time_steps", 12, "-output_every", 5, "-quiet"]
fa, fb = out("grasp.h5"), out("grasp_order.h5")
run(grasp + ["-output_file", fa], np_=NP)
run(grasp + ["-scene_bodies", "finger2,object,finger1", "-output_file", fb], np_=NP)

H = h5py.File(fa, "r")
o = Output(fa)
scene = ["object", "finger1", "finger2"]
c.check(o.bodies == scene and sorted(H["bodies"]) != scene,
        "bodies in scene order %s (/bodies lists %s)" % (o.bodies, list(H["bodies"])))
c.check(o.options["scene_bodies"] == "object,finger1,finger2" and o.options["contact_mu"] == "0.8"
        and o.options["quiet"] == "", "options as a dict: scene_bodies, contact_mu, a flag without value")
c.check(o.time_step == 0.01 and o.time_steps == 12 and o.output_every == 5 and o.mpi_ranks == NP,
        "time_step %g, time_steps %d, output_every %d, mpi_ranks %d" % (o.time_step, o.time_steps, o.output_every,
                                                                        o.mpi_ranks))
c.check((o.nsteps, o.nframes, o.first_step, o.last_step) == (12, 4, 0, 12) and o.complete and o.finished,
        "12 steps, 4 frames (0, 5, 10, 12), complete and finished")
c.check(o.contact_pairs == [("object", "finger1"), ("object", "finger2")], "contact_pairs from -contact_pairs")

# /steps: every dataset and every phase, the same arrays
ok = sorted(o.steps.keys()) == sorted(k for k in H["steps"] if isinstance(H["steps"][k], h5py.Dataset))
ok &= all(same(o.steps[k], H["steps"][k][:]) and same(getattr(o.steps, k), H["steps"][k][:]) for k in o.steps)
c.check(ok and len(o.steps.keys()) >= 15, "steps: all %d datasets as h5py reads them" % len(o.steps.keys()))
c.check(all(same(o.steps[k], H["steps"][k][:]) for k in ["time", "step", "wall_time", "contacts", "intersections",
                                                          "residual", "energy"]),
        "steps.time, step, wall_time, contacts, intersections, residual, energy")
tim = o.steps.timing
c.check(sorted(tim) == sorted(H["steps/timing"]) and all(same(tim[p], H["steps/timing"][p][:]) for p in tim),
        "steps.timing: %d phases" % len(tim))
c.check(not hasattr(o.steps, "no_such_column") and isinstance(raises(lambda: o.steps["no_such_column"], KeyError),
                                                               KeyError), "a missing /steps dataset: KeyError")
c.check(same(o.frames, H["frames/time"][:]) and same(o.frame_steps, H["frames/step"][:]), "frames and frame steps")

# bodies: per-step data, frames, fields, mesh
ok = True
for name in scene:
    b, g = o.body(name), H["bodies"][name]
    ok &= b.name == name and b.type == g.attrs["type"].decode()
    ok &= same(b.centroid, g["centroid"][:]) and same(b.positions, g["positions"][:])
    ok &= same(np.stack([b.energy[k] for k in ["kinetic", "elastic", "gravity"]], axis=1), g["energy"][:])
    ok &= np.allclose(b.energy_total, g["energy"][:].sum(axis=1), rtol=0, atol=0)
    ok &= same(b.initial_centroid, g.attrs["initial_centroid"]) and same(b.frames, H["frames/time"][:])
    ok &= same(b.mesh.reference, g["mesh/reference"][:]) and same(b.mesh.cells, g["mesh/cells"][:])
    ok &= b.mesh.cell_type == g["mesh"].attrs["cell_type"].decode()
    fields = [k for k in g if isinstance(g[k], h5py.Dataset) and k not in ("centroid", "rotation", "energy",
                                                                           "positions")]
    ok &= sorted(b.fields) == sorted(fields) and all(same(b.field(k), g[k][:]) for k in fields)
    if "rotation" in g:
        ok &= same(b.rotation, g["rotation"][:]) and same(b.initial_rotation, g.attrs["initial_rotation"])
    ok &= b.reactions == {}
    if "inverted" in g:
        inv = b.inverted
        ok &= sorted(inv) == ["elements", "min_volume_ratio"] and all(same(inv[k], g["inverted"][k][:]) for k in inv)
    else:
        ok &= b.type != "fem" and isinstance(raises(lambda: b.inverted, KeyError), KeyError)
c.check(ok, "bodies: type, centroid, energy, positions, fields, mesh, rotation, inverted as h5py reads them")
c.check(sorted(o.body("object").fields) == ["displacement", "velocity", "von_mises"]
        and o.body("object").mesh.cell_type == "tetrahedron" and o.body("finger1").type == "kinematic",
        "object's fields %s, a tetrahedral mesh; finger1 kinematic" % o.body("object").fields)

# errors
e = raises(lambda: o.body("hand"), KeyError)
c.check(e is not None and "hand" in str(e) and all(n in str(e) for n in scene), "a missing body: KeyError: %s" % e)
e = raises(lambda: o.body("object").rotation, KeyError)
c.check(e is not None and "rotation" in str(e) and "object" in str(e), "an FE body's rotation: KeyError: %s" % e)
e = raises(lambda: o.body("object").field("energy_density"), KeyError)
c.check(e is not None and "energy_density" in str(e), "a field not written: KeyError: %s" % e)
c.check(isinstance(raises(lambda: o.contacts(12), IndexError), IndexError)
        and isinstance(raises(lambda: o.contacts(-13), IndexError), IndexError), "a step row out of range: IndexError")

# contacts: all of them, then step by step through /contacts/offset
allc, off = o.contacts(), H["contacts/offset"][:]
keys = ["point", "normal", "force", "force_world", "gap", "gap_end", "state", "bodies", "point_end", "force_tangential"]
c.check(all(same(allc[k], H["contacts"][k][:]) for k in keys) and len(allc) == off[-1] > 0,
        "contacts(): the %d records of every dataset" % len(allc))
ok = True
for i in range(o.nsteps):
    ci = o.contacts(i)
    ok &= len(ci) == o.steps.contacts[i] == off[i + 1] - off[i]
    ok &= all(same(ci[k], H["contacts"][k][off[i]:off[i + 1]]) for k in keys)
    ok &= (ci.step == i + 1).all() and (ci.row == i).all() and same(ci.force_normal, ci.force[:, 0])
c.check(ok, "contacts(i) for each of the %d steps: the records offset[i]:offset[i+1]" % o.nsteps)
last = o.contacts(-1)
c.check(same(last.force_world, o.contacts(o.nsteps - 1).force_world) and len(last) > 0,
        "contacts(-1) is the last step's (%d contacts)" % len(last))
names = H.attrs["options"].decode().split("-scene_bodies ")[1].split()[0].split(",")
expect = [(names[i], names[j]) for i, j in H["contacts/bodies"][:]]
c.check(allc.pairs == expect and set(expect) == {("object", "finger1"), ("object", "finger2")}
        and same(allc.pair_names.astype(str), np.array(expect)),
        "pair names from -scene_bodies: %s" % sorted(set(expect)))

# forces per pair against a direct sum over the records
pf, pn, pc = o.pair_forces(), o.pair_normal_forces(), o.pair_contacts()
fw, fn, bod = H["contacts/force_world"][:], H["contacts/force"][:, 0], H["contacts/bodies"][:]
ok = list(pf) == list(pn) == list(pc) == o.contact_pairs
err = 0.0
for (a, b), F in pf.items():
    ia, ib = scene.index(a), scene.index(b)
    direct = np.zeros((o.nsteps, 3))
    normal, count = np.zeros(o.nsteps), np.zeros(o.nsteps, dtype=int)
    for i in range(o.nsteps):
        for r in range(off[i], off[i + 1]):
            if (bod[r] == [ia, ib]).all():
                direct[i] += fw[r]
                normal[i] += fn[r]
                count[i] += 1
    ok &= F.shape == (12, 3) and same(count, pc[(a, b)]) and count.sum() > 0
    err = max(err, np.abs(F - direct).max() / np.abs(direct).max(), np.abs(pn[(a, b)] - normal).max() / normal.max())
c.check(ok and err < 1e-14, "pair_forces, pair_normal_forces, pair_contacts: a direct sum (relative %.1e)" % err)
o.close()
H.close()

# the same run, other scene order: other indices, the same names
with h5py.File(fb, "r") as HB, Output(fb) as ob, Output(fa) as oa:
    c.check(ob.bodies == ["finger2", "object", "finger1"] and HB.attrs["scene_bodies"] == b"finger2,object,finger1",
            "-scene_bodies finger2,object,finger1: bodies %s" % ob.bodies)
    ca, cb = oa.contacts(), ob.contacts()
    c.check(not same(ca.bodies, cb.bodies) and ca.pairs == cb.pairs and same(ca.force_world, cb.force_world),
            "other indices in /contacts/bodies, the same pairs and forces")
    c.check(all(same(oa.pair_forces()[k], ob.pair_forces()[k]) for k in oa.pair_forces()), "the same pair forces")
# an older file: no root attribute scene_bodies, the names from the options; neither: alphabetical
fo = out("grasp_old.h5")
shutil.copy(fb, fo)
with h5py.File(fo, "r+") as h:
    del h.attrs["scene_bodies"]
with Output(fo) as oo:
    c.check(oo.bodies == ["finger2", "object", "finger1"] and oo.contacts().pairs == cb.pairs,
            "without the attribute scene_bodies: the scene order of the options (%s)" % oo.bodies)
with h5py.File(fo, "r+") as h:
    opts = h.attrs["options"].decode().replace("-scene_bodies finger2,object,finger1 ", "")
    h.attrs["options"] = np.bytes_(opts)
with Output(fo) as oo:
    c.check(oo.bodies == ["finger1", "finger2", "object"] and "scene_bodies" not in oo.options,
            "without either: the alphabetical order of /bodies (%s)" % oo.bodies)

# --- FE-FE: reactions, records both ways
fp = out("pressed.h5")
run(["-options_file", "input/pressed.opts", "-time_steps", 3, "-quiet", "-output_file", fp], np_=NP)
with h5py.File(fp, "r") as H, Output(fp) as op:
    ok = True
    for name in ["ball", "block"]:
        g = H["bodies"][name]["reactions"]
        r = op.body(name).reactions
        ok &= sorted(r) == sorted(g) and len(r) == 1 and all(same(r[k], g[k][:]) for k in g)
    c.check(ok, "reactions: %s" % {n: list(op.body(n).reactions) for n in ["ball", "block"]})
    bod, fw = H["contacts/bodies"][:], H["contacts/force_world"][:]
    both = {tuple(x) for x in bod}
    F, N = op.pair_forces()[("ball", "block")], op.pair_normal_forces()[("ball", "block")]
    off = H["contacts/offset"][:]
    direct = np.array([fw[off[i]:off[i + 1]][(bod[off[i]:off[i + 1], 0] == 0)].sum(axis=0)
                       - fw[off[i]:off[i + 1]][(bod[off[i]:off[i + 1], 0] == 1)].sum(axis=0) for i in range(3)])
    c.check(both == {(0, 1), (1, 0)} and list(op.pair_forces()) == [("ball", "block")]
            and np.abs(F - direct).max() <= 1e-12 * np.abs(direct).max(),
            "an FE-FE pair with records both ways: the force on the ball, the block's records with opposite sign")
    c.check(np.allclose(F[:, 2], N, rtol=1e-3) and (N > 0).all(),
            "the ball pushed down: the vertical force on it is the sum of the normal forces (%s N)" % np.round(N, 1))

# --- no contact pairs
ff = out("fall.h5")
run(["-options_file", "input/cube_fall.opts", "-time_steps", 3, "-quiet", "-output_file", ff], np_=NP)
with Output(ff) as of:
    cf = of.contacts()
    c.check(of.bodies == ["cube", "ball", "ground"] and len(cf) == 0 and cf.force_world.shape == (0, 3)
            and cf.pairs == [] and len(of.contacts(-1)) == 0 and of.pair_forces() == {} and of.contact_pairs == [],
            "no contact pairs: empty contacts, no pair forces")

# --- 0 steps; a file cut at /complete as a run stopped early leaves it
fz = out("zero.h5")
run(grasp + ["-time_steps", 0, "-output_file", fz], np_=NP)
with Output(fz) as oz:
    ok = oz.nsteps == 0 and oz.nframes == 1 and len(oz.time) == 0 and oz.body("object").centroid.shape == (0, 3)
    ok &= len(oz.contacts()) == 0 and all(v.shape == (0, 3) for v in oz.pair_forces().values())
    c.check(ok and oz.body("object").positions.shape[0] == 1, "0 steps: no rows, frame 0, no contacts")
fe = out("early.h5")
shutil.copy(fa, fe)
with h5py.File(fe, "r+") as h:
    h["complete"][:] = [5, 2]  # what a run stopped after the frame of step 5 has safely on disk
with h5py.File(fa, "r") as H, Output(fe) as oe:
    off = H["contacts/offset"][:]
    ok = (oe.nsteps, oe.nframes, oe.complete) == (5, 2, False) and same(oe.time, H["steps/time"][:5])
    ok &= same(oe.body("object").positions, H["bodies/object/positions"][:2]) and same(oe.frame_steps, [0, 5])
    ok &= same(oe.contacts().force, H["contacts/force"][:off[5]])
    ok &= oe.pair_forces()[("object", "finger1")].shape == (5, 3)
    ok &= all(len(v) == 5 for v in oe.steps.timing.values()) and len(oe.body("finger1").rotation) == 5
    c.check(ok, "a file whose /complete says 5 steps, 2 frames: only those are read")

# --- scripts/plot_run.py: the CLI on the grasp, then in one process on the other files
png = out("grasp.png")
p = subprocess.run([sys.executable, PLOT, fb, "-o", png], capture_output=True, text=True, cwd=ROOT)
c.check(p.returncode == 0 and p.stdout.strip() == png and is_png(png), "plot_run.py writes %s" % png)
q = subprocess.run([sys.executable, "-c", "import sys, runpy; m = runpy.run_path(sys.argv[1]); "
                    "[m['plot'](f, f[:-3] + '.png') for f in sys.argv[2:]]", PLOT, ff, fz, fe, fp],
                   capture_output=True, text=True, cwd=ROOT)
c.check(q.returncode == 0 and all(is_png(f[:-3] + ".png") for f in [ff, fz, fe, fp]),
        "plot_run.py: no contact pairs, 0 steps, stopped early, FE-FE pair%s"
        % (q.stderr[-400:] if q.returncode else ""))
c.done()
