/* What the files of src/collision/ share: the spatial hash of surface triangles (surface.c),
   the closest-point kernels (geometry.c), the continuous tests (ccd.c) and the edges of a
   surface (edges.c). */
#pragma once
#include "../fcimpl.h"
#include "topology.h"
#include <stdint.h>

typedef struct {
  int64_t  key;
  PetscInt tri;
} FCCellEntry;

typedef struct _FCSelfRing  FCSelfRing;                               /* selfcontact.c */
PETSC_INTERN PetscErrorCode FCCellEntrySort(PetscInt, FCCellEntry[]); /* surface.c: by key, stably */

struct _FCSurface {
  PetscInt           n, nentries;
  FCSurfaceTriangle *tri;
  FCCellEntry       *cells;
  PetscReal         *nrm;     /* 3 n: each triangle's unit normal at the start of the step */
  PetscReal          h;       /* cell size */
  PetscBool          swept;   /* triangles hashed by their boxes over the step (x0 and xf) */
  PetscInt          *stamp;   /* per triangle: the last box query that visited it (FCSurfaceQueryBox) */
  PetscInt           nquery;  /* swept queries so far */
  PetscReal          inflate; /* what each triangle's box was inflated by */
  PetscReal          arc;     /* SurfaceBuild: how far a turning mesh's vertices leave their chords (FCCCDArcMargin) */
  /* self-contact (selfcontact.c): the current vertex, whose ring of triangles it may not land on is
     found at the first triangle it is tested against, and no start-inside fallback (a vertex of the
     surface is on it, not inside it) */
  PetscBool   self;
  PetscReal   selfX[3];  /* the current vertex's reference position */
  PetscReal   selfdepth; /* behind a triangle now: deeper than this (-contact_intersection_depth) */
  PetscBool   selfstart; /* the start-inside rule applies (the body may be inside itself) */
  FCSelfRing *ring;
};

/* The surface triangles of a body (FE or mesh shape) as they are now, gathered on every rank
   (*tri to be freed, or handed to FCSurfaceCreate) */
PETSC_INTERN PetscErrorCode FCSurfaceGather(MPI_Comm, FCBody, PetscInt *ntri, FCSurfaceTriangle **tri);
/* A surface hashed by the boxes of its triangles over the whole step (start and free-motion
   positions), inflated by `inflate`: the broad phase of continuous detection. Takes tri over. */
PETSC_INTERN PetscErrorCode FCSurfaceCreateSwept(PetscInt n, FCSurfaceTriangle *tri, PetscReal inflate, FCSurface **);
typedef struct _FCSurface   Surface;
/* The hashed entries of the cell of x: S->cells[*begin .. *end) */
PETSC_INTERN void FCSurfaceQueryPoint(const FCSurface *, const PetscReal x[3], PetscInt *begin, PetscInt *end);
/* The triangles whose swept boxes overlap the box [lo, hi], each once: cand gets their indices
   (at most S->n), ncand their number */
PETSC_INTERN void FCSurfaceQueryBox(FCSurface *, const PetscReal lo[3], const PetscReal hi[3], PetscInt cand[],
                                    PetscInt *ncand);

/* intersection.c: the triangles of a closed surface bucketed across a fixed ray direction; a
   point is inside when the ray from it crosses the surface an odd number of times (start-of-step
   positions x0 of the surface) */
typedef struct {
  PetscReal    u[3], v[3], h; /* the grid's axes across the ray and its cell size */
  PetscInt     n;
  FCCellEntry *cells;
  PetscReal   *along;        /* 2 per triangle: its extent along the ray, lowest and highest */
  PetscReal    lo[3], hi[3]; /* bounding box of the surface */
} FCRayGrid;
PETSC_INTERN PetscErrorCode FCRayGridCreate(const FCSurface *, FCRayGrid *);
PETSC_INTERN PetscErrorCode FCRayGridDestroy(FCRayGrid *);
PETSC_INTERN PetscBool      FCRayGridInside(const FCSurface *, const FCRayGrid *, const PetscReal x[3]);
/* Whether x on the closed surface S (outward normal n) is inside another part of its body (winding number >= 1); the
   squared distance from x to S's nearest triangle outside ring (NULL: none) hashed in x's cell (PETSC_MAX_REAL: none)
 */
PETSC_INTERN PetscBool FCRayGridSelfInside(const FCSurface *, const FCRayGrid *, const PetscReal x[3],
                                           const PetscReal n[3]);
PETSC_INTERN PetscReal FCSurfaceNearestOutsideRing(const FCSurface *, FCSelfRing *ring, const PetscReal x[3]);
/* collision.c, what the vertex contacts share with the shape points (shapepoints.c): the triangle
   of S a point moving x0 -> xf lands on (nv: the normal of the point's own surface, for
   -contact_facing; *best -1 if none; w, cp: weights and closest point at the start); the FE
   material point at weights w of a triangle; the points of body P against the surface S of body
   Sb (vn: the vertex normals of P's surface, or NULL) */
typedef struct {
  PetscReal X[3], n[3]; /* a vertex's reference position (the sort key) and outward normal */
} FCVertexNormal;
/* -contact_facing: a surface faces a vertex when its normal n and the vertex's normal n_v have
   n . n_v <= -FC_FACING_COS (opposed within 75 degrees) */
#define FC_FACING_COS 0.25881904510252074
PETSC_INTERN PetscErrorCode FCCollisionLandingTriangle(Surface *, const PetscReal x0[3], const PetscReal xf[3],
                                                       const PetscReal nv[3], PetscReal distance, PetscBool continuous,
                                                       PetscReal tau, PetscInt cand[], FCRayGrid *, PetscInt *best,
                                                       PetscReal w[3], PetscReal cp[3]);
PETSC_INTERN void           FCCollisionTrianglePoint(const FCSurfaceTriangle *, const PetscReal w[3], FCProximity *,
                                                     PetscReal xf[3]);
/* collision.c: a body's surface gathered and hashed for the step; topology.c: the vertex normals of
   the triangles tri of topology T, in its vertex order */
PETSC_INTERN PetscErrorCode FCCollisionSurfaceBuild(MPI_Comm, FCBody, const FCContactPairs *, Surface **);
PETSC_INTERN PetscErrorCode FCCollisionVertexNormals(const FCSurfaceTopology *T, const FCSurfaceTriangle tri[],
                                                     PetscInt *nvn, FCVertexNormal **vn);
/* selfcontact.c: an FE body against its own surface (a pair a:a): its vertices, then its sharp edges (edges.c) */
PETSC_INTERN PetscErrorCode FCCollisionSelfPair(MPI_Comm, FCBody, PetscInt ib, PetscInt pair, const FCContactPairs *,
                                                PetscMPIInt rank, FCContactSet *);
/* selfcontact.c: the ring of the current vertex (the triangles it may not land on) over topology T:
   RingVertex sets the current vertex X; RingHas: whether triangle t is on its ring; RingEdgeIn:
   whether edge b (reference ends Xb) has a vertex on a triangle of the ring of either end of edge a */
PETSC_INTERN PetscErrorCode FCSelfRingCreate(const FCSurfaceTopology *T, PetscInt k, FCSelfRing **);
PETSC_INTERN PetscErrorCode FCSelfRingDestroy(FCSelfRing **);
PETSC_INTERN void           FCSelfRingVertex(FCSelfRing *, const PetscReal X[3]);
PETSC_INTERN PetscBool      FCSelfRingHas(FCSelfRing *, PetscInt t);
PETSC_INTERN PetscBool      FCSelfRingEdgeIn(FCSelfRing *, const PetscReal Xa[2][3], const PetscReal Xb[2][3]);
/* selfcontact.c: before vertex X's landing, X is the current vertex; then whether triangle t is not a
   landing place for it at x (its ring, or across the body's own thickness) */
PETSC_INTERN void      FCCollisionSelfVertex(Surface *, const PetscReal X[3]);
PETSC_INTERN PetscBool FCCollisionSelfExcludes(const Surface *, PetscInt t, const PetscReal x[3]);
/* the self-contacts another one holds (barycentric weight > w) made dormant */
PETSC_INTERN PetscErrorCode FCCollisionSelfHeld(PetscReal w, FCContactSet *);
PETSC_INTERN PetscErrorCode FCCollisionVerticesAgainstSurface(FCBody P, FCBody Sb, PetscInt ipts, PetscInt ishp,
                                                              Surface *S, PetscInt nvn, const FCVertexNormal *vn,
                                                              PetscInt pair, const FCContactPairs *, PetscMPIInt rank,
                                                              FCContactSet *);
/* pointshape.c: the candidate points of P (an FE body's owned boundary vertices, a shape's picture points, body ipts)
   against the signed distance of the shape of S (body ishp); vn: the vertex normals of an FE P's surface
   (-contact_facing), or NULL; atfree: an FE P against a rounded S whose surface points are taken after the free
   motion (FCCollisionRoundedFollows), its vertices' contacts too */
PETSC_INTERN PetscErrorCode FCCollisionPointsAgainstShape(FCBody P, FCBody S, PetscInt ipts, PetscInt ishp, PetscInt p,
                                                          PetscInt nvn, const FCVertexNormal *vn, PetscBool atfree,
                                                          const FCContactPairs *, PetscMPIInt rank, FCContactSet *);
/* shapepoints.c: the points of bounded shape Sh (body ish) against the surface S of FE body F
   (body ife), -contact_shape_points */
PETSC_INTERN PetscErrorCode FCCollisionShapePoints(FCBody Sh, FCBody F, PetscInt ish, PetscInt ife, Surface *S,
                                                   PetscBool follows, PetscBool lies, PetscInt pair,
                                                   const FCContactPairs *, PetscMPIInt rank, FCContactSet *);

/* shapepoints.c: the contact of the FE material point tp (key X, at bcp now and yf after the free motion) of body ife
   against the shape of body ish (its point r1, body frame), normal n, start gap gap0 */
PETSC_INTERN PetscErrorCode FCCollisionSurfaceShapeContact(FCBody Sh, PetscInt ish, PetscInt ife, PetscInt pair,
                                                           const FCContactPairs *, PetscMPIInt rank,
                                                           const FCProximity *tp, const PetscReal X[3],
                                                           const PetscReal bcp[3], const PetscReal yf[3],
                                                           const PetscReal n[3], const PetscReal r1[3], PetscReal gap0,
                                                           FCContact *c);
/* shapepoints.c: whether the surface points of rounded shape Sh against the FE surface S (and the FE vertices'
   contacts with it) are taken after the free motion (-contact_rounded_surface exact, and the shape's core follows its
   free motion: no impact, no surface turning its normal); the same on every rank */
PETSC_INTERN PetscErrorCode FCCollisionRoundedFollows(FCBody Sh, Surface *S, const FCContactPairs *,
                                                      PetscBool *follows);
/* shapepoints.c: each point of the picture of shape Sh that lands on surface S inside a triangle (not at an FE
   vertex: that vertex's own contact), once per FE material point (by its reference position X): fn gets the
   triangle, the weights bw, the point's start position bcp and X, and says whether it made a contact there (a
   later picture point landing on the same X is then skipped) */
typedef PetscErrorCode (*FCLandingFn)(const FCSurfaceTriangle *T, const PetscReal bw[3], const PetscReal bcp[3],
                                      const PetscReal X[3], void *ctx, PetscBool *made);
PETSC_INTERN PetscErrorCode FCCollisionPictureLandings(FCBody Sh, Surface *S, const FCContactPairs *, FCLandingFn fn,
                                                       void *ctx);
/* roundedsurface.c: the points of the FE surface S (of body ife) nearest the core of the sphere or capsule Sh (body
   ish), taken after the free motion, and the FE points a sphere's picture points land on (rank 0) */
PETSC_INTERN PetscErrorCode FCCollisionRoundedOnSurface(FCBody Sh, PetscInt ish, PetscInt ife, Surface *S,
                                                        PetscInt pair, const FCContactPairs *, PetscMPIInt rank,
                                                        FCContactSet *);
/* roundedsurface.c: whether the FE surface S's own free motion turns the normal of the sphere or capsule Sh at the
   surface's points nearest its core by more than -contact_intersection_depth allows (the same answer on every rank) */
PETSC_INTERN PetscErrorCode FCCollisionRoundedSurfaceTurns(FCBody Sh, Surface *S, const FCContactPairs *,
                                                           PetscBool *turns);
/* roundedsurface.c: whether the side of cylinder Sh lies on the FE surface S after the free motion (the same on every
   rank) */
PETSC_INTERN PetscErrorCode FCCollisionCylinderLies(FCBody Sh, Surface *S, const FCContactPairs *, PetscBool *lies);
/* smooth.c: a rounded shape P (sphere, capsule, cylinder; body ip) against the analytic shape of S
   (body is), from their exact closest points (rank 0) */
PETSC_INTERN PetscErrorCode FCCollisionRoundedShape(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                                    const FCContactPairs *, PetscMPIInt rank, FCContactSet *);
/* smooth.c: the contact of point x (world, now) of rigid or kinematic body P (body ip) with the shape of S (body is)
   at signed distance d, with S's outward normal n there and closest point cpb (S's body frame), keyed by key; from
   the alarm distance on, only where the point's motion over the step reaches S (continuous detection) */
PETSC_INTERN PetscErrorCode FCCollisionAddShapeContact(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                                       const PetscReal x[3], PetscReal d, const PetscReal n[3],
                                                       const PetscReal cpb[3], const PetscReal key[3],
                                                       const FCContactPairs *, PetscMPIInt     rank, FCContactSet *);
/* boxbox.c: two boxes (P body ip, S body is) that have a face each parallel to the other's: the corners of each
   over the other's face in contact, along that face's normal (*done); otherwise nothing (*done false) */
PETSC_INTERN PetscErrorCode FCCollisionBoxBox(FCBody P, FCBody S, PetscInt ip, PetscInt is, PetscInt pair,
                                              const FCContactPairs *, PetscMPIInt rank, FCContactSet *,
                                              PetscBool *done);
/* edges.c: the edge-edge contacts of the sharp edges of A (FE) against those of B (FE or mesh), from their
   gathered surface triangles (the detection's: nta of ta, ntb of tb; a self pair passes A's twice) */
PETSC_INTERN PetscErrorCode FCCollisionEdgeEdge(MPI_Comm, FCBody A, FCBody B, PetscInt ia, PetscInt ib, PetscInt nta,
                                                const FCSurfaceTriangle *ta, PetscInt ntb, const FCSurfaceTriangle *tb,
                                                PetscInt pair, const FCContactPairs *, FCContactSet *);

/* The sharp edges of a closed surface (as edge-edge contacts take them: -contact_edge_angle) by their two ends'
   positions x0: ends[6 k .. 6 k + 5]; full: 15 a row, then the ends' reference positions X and the sum of the two
   adjacent triangles' outward normals (to be freed) */
PETSC_INTERN PetscErrorCode FCSurfaceSharpEdgeEnds(const FCSurfaceTopology *, const FCSurfaceTriangle *,
                                                   PetscReal angle, PetscBool full, PetscInt *ne, PetscReal **ends);

/* geometry.c: closest point to p on triangle (a, b, c) with its barycentric weights (Ericson,
   5.1.5); the unit normal of a triangle (x[0], x[1], x[2]), counter-clockwise = outward; the
   closest points of segments (p0, p1) and (q0, q1): p0 + s (p1 - p0), q0 + t (q1 - q0), with
   the squared distance (Ericson, 5.1.9) */
PETSC_INTERN void FCClosestPointTriangle(const PetscReal p[3], const PetscReal a[3], const PetscReal b[3],
                                         const PetscReal c[3], PetscReal cp[3], PetscReal w[3]);
PETSC_INTERN void FCTriangleNormal(const PetscReal x[3][3], PetscReal n[3]);
/* a direction fixed in a rigid or kinematic body's frame, in the world at `when` (FC_AT_NOW, FC_AT_FREE; endgaps.c) */
PETSC_INTERN PetscErrorCode FCCollisionBodyDirection(FCBody, PetscInt when, const PetscReal nb[3], PetscReal n[3]);
PETSC_INTERN void FCSurfaceClosestFacing(const FCSurface *, const PetscReal x[3], const PetscReal nv[3], PetscInt *tri,
                                         PetscReal w[3], PetscReal cp[3], PetscReal *d2);
PETSC_INTERN PetscReal FCClosestSegmentSegment(const PetscReal p0[3], const PetscReal p1[3], const PetscReal q0[3],
                                               const PetscReal q1[3], PetscReal *s, PetscReal *t);
/* The t in [0, 1] where f(t, ctx) is smallest, f convex on [0, 1] (the distance to a convex shape along a segment):
   golden-section search, FC_GOLDEN_IT steps, the bracket shrinking by 0.618 each, below round-off; the middle of the
   last bracket */
#define FC_GOLDEN_IT 60
PETSC_INTERN PetscErrorCode FCGoldenMinimum(PetscErrorCode (*f)(PetscReal t, void *ctx, PetscReal *ft), void *ctx,
                                            PetscReal *t);
/* The point at barycentric weights w of nv (2, 3) reference positions, exact where they share a
   coordinate: a contact's sort key */
PETSC_INTERN void FCReferencePoint(PetscInt nv, const PetscReal Xv[][3], const PetscReal w[], PetscReal X[3]);
/* qsort/bsearch order of records that start with a point (3 reals): lexicographic in x, y, z */
PETSC_INTERN int FCComparePoint(const void *, const void *);
/* The point of the triangle x (reference positions Xr) nearest the world point c: its weights w, its reference
   position X, and 1 (a vertex), 2 (an edge: recomputed from the edge alone, the same from both its triangles) or 3
   (the face) */
PETSC_INTERN PetscInt FCTriangleNearestFeature(const PetscReal x[3][3], const PetscReal Xr[3][3], const PetscReal c[3],
                                               PetscReal w[3], PetscReal X[3]);
/* The distance from the world point x to the triangle t */
PETSC_INTERN PetscReal FCTriangleDistance(const PetscReal t[3][3], const PetscReal x[3]);
PETSC_INTERN void      FCCylinderSideDistance(const PetscReal a[3], const PetscReal u[3], PetscReal L, PetscReal r,
                                              const PetscReal y[3], const PetscReal nv[3], PetscReal *d, PetscReal n[3],
                                              PetscBool *side);
/* Whether the ray x + s dir, s > 0, crosses triangle (a, b, c) (Moeller-Trumbore) */
PETSC_INTERN PetscBool FCRayHitsTriangle(const PetscReal x[3], const PetscReal dir[3], const PetscReal a[3],
                                         const PetscReal b[3], const PetscReal c[3]);

/* ccd.c: conservative continuous tests over the step, all points moving linearly from their
   start to their free-motion positions. Each returns whether the two features come closer than
   tau at some time of the step (never a miss; a near miss within tau counts as a hit) and the
   earliest such time found. */
PETSC_INTERN PetscErrorCode FCCCDPointShape(FCBody shape, const PetscReal x0[3], const PetscReal xf[3], PetscReal d0,
                                            PetscReal tau, PetscBool *hit);
PETSC_INTERN PetscBool      FCCCDPointTriangle(const PetscReal p0[3], const PetscReal pf[3], const PetscReal a0[3][3],
                                               const PetscReal af[3][3], PetscReal tau, PetscReal *thit);
/* edges a and b as their two ends, flat: a0 = (start of end 0, start of end 1), af the same after the free motion */
PETSC_INTERN PetscBool FCCCDEdgeEdge(const PetscReal *a0, const PetscReal *af, const PetscReal *b0, const PetscReal *bf,
                                     PetscReal tau, PetscReal *thit);
/* crossing.c's exact tests: point p0 -> p1 through triangle a0 -> a1 from its outer side (counter-clockwise) to its
   inner side, the triangle facing the same way throughout (*behind: how far p ends behind its plane); segments a, b
   meet */
PETSC_INTERN PetscBool FCCCDPointCrossesTriangle(const PetscReal p0[3], const PetscReal p1[3], const PetscReal a0[3][3],
                                                 const PetscReal a1[3][3], PetscReal *behind);
PETSC_INTERN PetscBool FCCCDEdgesMeet(const PetscReal a0[2][3], const PetscReal a1[2][3], const PetscReal b0[2][3],
                                      const PetscReal b1[2][3]);
/* How far the vertices of a body that turns over the step (a rigid or kinematic mesh) leave the
   chords the continuous tests follow: theta^2 / 8 times the largest distance of a vertex of tri
   (body-frame positions X) from the point the body turns about; 0 for FE bodies */
PETSC_INTERN PetscErrorCode FCCCDArcMargin(FCBody, PetscInt ntri, const FCSurfaceTriangle *tri, PetscReal *margin);
/* The distance below which a continuous test reports a hit: a tenth of the alarm distance (a
   point whose free motion ends that close was going to touch), never 0 */
PETSC_INTERN PetscReal FCCCDThreshold(PetscReal distance);
