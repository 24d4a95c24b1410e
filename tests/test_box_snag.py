"""A frictionless rigid box sliding on a stiff FE slab keeps its speed, whatever its size against the
elements, with -contact_facing_face (issue 57; scripts/box_snag.py, the same scene; docs/validation.md):
the slab's vertices take the box face that faces them (src/collision/pointshape.c, FacingFace). Without
it (the default), a vertex at the box's front edge is a contact along the edge's or the front face's
normal, a wall: the box hops and loses speed, checked here on one case.
  - 1 rank: on the 5 and 2.5 cm slabs (meshes/slide_slab_coarse.msh, slide_slab.msh), box edges of 1
    and 4 elements, launched at 0.5 and 2 m/s: at least 98 % of the speed kept, hop below 1 mm, no
    crossing, no intersection;
  - 2 ranks: two of those cases, the same speed kept and hop as on 1 rank (1e-6)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import box_snag  # noqa: E402
from fctest import Checker, TMP, np_from_argv  # noqa: E402

NP = np_from_argv(1)
c = Checker("box snag np%d" % NP)
CASES = [(m, e, v) for m in ("coarse", "medium") for e in (1, 4) for v in (0.5, 2.0)]
if NP > 1:
    CASES = [("coarse", 1, 2.0), ("medium", 4, 0.5)]
for m, e, v in CASES:
    mesh, el = box_snag.MESHES[m]
    kept, hop, low, cr, it = box_snag.slide(mesh, 0.5 * e * el, v, NP, tmp=TMP)
    what = "%s slab (%g cm), box edge %d element(s), %g m/s: %.4f of the speed kept, hop %.1e m, crossings %d, " \
           "intersections %d" % (m, 100 * el, e, v, kept, hop, cr, it)
    ok = kept >= 0.98 and hop < 1e-3 and cr == 0 and it == 0
    if NP > 1:
        k1, h1, _, _, _ = box_snag.slide(mesh, 0.5 * e * el, v, 1, tmp=TMP)
        ok = ok and abs(kept - k1) < 1e-6 and abs(hop - h1) < 1e-6
        what += "; 1 rank: %.4f, hop %.1e m" % (k1, h1)
    c.check(ok, what)
box_snag.FACE = False
kept, hop, low, cr, it = box_snag.slide("slide_slab", 0.05, 0.5, NP, tmp=TMP)
c.check(kept < 0.98 or hop > 1e-3, "without -contact_facing_face (the default): medium slab, box edge 4 elements, 0.5 m/s: "
        "%.4f of the speed kept, hop %.1e m (the snag)" % (kept, hop))
c.done()
