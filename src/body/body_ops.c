/* The body as the rest of the code sees it: facts about what a body is, and one wrapper per
   operation of its type (FCBodyOps). Collision, schemes, output and restart go through these;
   an operation a type does not have is either a no-op (responses of bodies that take no force)
   or an error naming the body. */
#include "bodyimpl.h"

PetscBool FCBodyIsDeformable(FCBody body)
{
  return body->deformable;
}

PetscBool FCBodyIsPrescribed(FCBody body)
{
  return body->prescribed;
}

PetscBool FCBodyHasShape(FCBody body)
{
  return body->ops.shapedistance ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCBodyHasBoundedShape(FCBody body)
{
  return body->shape && body->shape->bounded ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCBodyHasSmoothShape(FCBody body)
{
  return body->shape && body->shape->smooth ? PETSC_TRUE : PETSC_FALSE;
}

PetscBool FCBodyHasShapeCore(FCBody body)
{
  return body->shape && body->shape->ncore > 0 ? PETSC_TRUE : PETSC_FALSE;
}

void FCBodyGetShapeCore(FCBody body, PetscInt *ncore, PetscReal core[2][3], PetscReal *radius, PetscBool *flat)
{
  *ncore  = body->shape ? body->shape->ncore : 0;
  *radius = *ncore ? body->shape->radius : 0.0;
  *flat   = *ncore ? body->shape->flat : PETSC_FALSE;
  for (PetscInt k = 0; k < *ncore; k++)
    for (int i = 0; i < 3; i++) core[k][i] = body->shape->core[k][i];
}

PetscBool FCBodyIsBox(FCBody body)
{
  PetscBool box = PETSC_FALSE;
  if (body->shape) PetscStrcmp(body->shape->type, FCSHAPEBOX, &box);
  return box;
}

void FCBodyGetBoxHalfExtents(FCBody body, PetscReal h[3])
{
  for (int i = 0; i < 3; i++) h[i] = body->shape ? body->shape->half_extents[i] : 0.0;
}

PetscBool FCBodyHasSurfaceTriangles(FCBody body)
{
  return body->ops.surfacetriangles ? PETSC_TRUE : PETSC_FALSE;
}

PetscReal FCBodyGetMass(FCBody body)
{
  return body->prescribed ? 0.0 : body->mass;
}

const char *FCBodyName(FCBody body)
{
  return body->name;
}

const char *FCBodyTypeName(FCBody body)
{
  return body->type;
}

PetscReal FCBodyTimeStep(FCBody body)
{
  return body->h;
}

void FCBodyGetGravity(FCBody body, PetscReal g[3])
{
  for (int d = 0; d < 3; d++) g[d] = body->gravity[d];
}

void FCBodyGetPrescribedMotion(FCBody body, PetscReal v[3], PetscReal w[3])
{
  if (body->ops.prescribedmotion) {
    body->ops.prescribedmotion(body, v, w);
    return;
  }
  for (int d = 0; d < 3; d++) {
    v[d] = body->velocity[d];
    w[d] = body->angular_velocity[d];
  }
}

/* An operation the body's type lacks, asked for anyway */
static PetscErrorCode Missing(FCBody body, const char what[])
{
  SETERRQ(body->comm, PETSC_ERR_SUP, "Body '%s' (type %s) cannot %s", body->name, body->type, what);
}

PetscErrorCode FCBodyGetStateLayout(FCBody body, PetscInt *cols, PetscBool *pervertex)
{
  PetscFunctionBegin;
  *cols      = body->state_cols;
  *pervertex = body->state_per_vertex;
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetState(FCBody body, PetscReal s[])
{
  PetscFunctionBegin;
  if (!body->ops.getstate) PetscCall(Missing(body, "report its state"));
  PetscCall((*body->ops.getstate)(body, s));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySetState(FCBody body, const PetscReal s[])
{
  PetscFunctionBegin;
  if (!body->ops.setstate) PetscCall(Missing(body, "take a state"));
  PetscCall((*body->ops.setstate)(body, s));
  PetscFunctionReturn(0);
}

/* A type without fields has none (*has = PETSC_FALSE) */
PetscErrorCode FCBodyGetVisualField(FCBody body, FCVisualField field, PetscReal out[], PetscBool *has)
{
  PetscFunctionBegin;
  *has = PETSC_FALSE;
  if (body->ops.getvisualfield) PetscCall((*body->ops.getvisualfield)(body, field, out, has));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetContactPoints(FCBody body, PetscInt *n, FCProximity **prox, PetscReal **x0, PetscReal **xf,
                                      PetscReal **key)
{
  PetscFunctionBegin;
  if (!body->ops.contactpoints) PetscCall(Missing(body, "give contact points"));
  PetscCall((*body->ops.contactpoints)(body, n, prox, x0, xf, key));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyGetSurfaceTriangles(FCBody body, PetscInt *n, FCSurfaceTriangle **tri)
{
  PetscFunctionBegin;
  if (!body->ops.surfacetriangles) PetscCall(Missing(body, "give surface triangles"));
  PetscCall((*body->ops.surfacetriangles)(body, n, tri));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyProximityPosition(FCBody body, const FCProximity *p, PetscInt when, PetscReal x[3])
{
  PetscFunctionBegin;
  if (!body->ops.proximityposition) PetscCall(Missing(body, "place a proximity point"));
  PetscCall((*body->ops.proximityposition)(body, p, when, x));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyShapeDistance(FCBody body, PetscInt when, const PetscReal x[3], PetscReal *d, PetscReal n[3],
                                   PetscReal cpb[3])
{
  PetscErrorCode (*f)(FCBody, const PetscReal[3], PetscReal *, PetscReal[3], PetscReal[3]);

  PetscFunctionBegin;
  f = when == FC_AT_FREE ? body->ops.shapedistancefree : body->ops.shapedistance;
  if (!f) PetscCall(Missing(body, "measure a distance to its shape"));
  PetscCall((*f)(body, x, d, n, cpb));
  PetscFunctionReturn(0);
}

/* On an edge of a shape with edges the normal is any of the edge's wedge (a box's corner resting on the
   lower box's edge: the top face's, a side's, or anything between, which the distance then takes from
   offsets of round-off size). The normal the distance gave at x (nx, with gap) is then not to be taken
   for a normal n that the contact already has: where nx turns by more than 10 degrees from n while n is
   still nearly the shape's at x (the distance grows at 0.99 of the full rate along n: on a smooth shape a
   normal 10 degrees off grows at cos 10 = 0.985, so the rule holds on edges only; probed over a
   thousandth of the point's motion (move) or of its gap, at least 1e-8 |x|: well above the round-off of
   positions), *keep says to keep n. A point that has passed under another
   face (a punch's front face sliding over a vertex) gets that face's normal */
PetscErrorCode FCBodyShapeKeepsNormal(FCBody body, PetscInt when, const PetscReal x[3], PetscReal gap,
                                      const PetscReal nx[3], const PetscReal n[3], PetscReal move, PetscBool *keep)
{
  PetscReal xp[3], gp, np[3], cpb[3], eta;

  PetscFunctionBegin;
  *keep = PETSC_FALSE;
  if (FCDot(nx, n) >= 0.985) PetscFunctionReturn(0);
  eta = PetscMax(1e-3 * PetscMax(move, PetscAbsReal(gap)), 1e-8 * PetscSqrtReal(FCDot(x, x))) + 1e-300;
  for (int i = 0; i < 3; i++) xp[i] = x[i] + eta * n[i];
  PetscCall(FCBodyShapeDistance(body, when, xp, &gp, np, cpb));
  *keep = (PetscBool)(gp - gap >= 0.99 * eta);
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyStepRotation(FCBody body, PetscReal *theta, PetscReal center[3])
{
  PetscFunctionBegin;
  *theta = 0.0;
  for (int d = 0; d < 3; d++) center[d] = 0.0;
  if (body->ops.steprotation) PetscCall((*body->ops.steprotation)(body, theta, center));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyToBodyFrame(FCBody body, PetscInt when, const PetscReal x[3], PetscBool direction, PetscReal r[3])
{
  PetscFunctionBegin;
  if (!body->ops.tobody) PetscCall(Missing(body, "express a point in a body frame"));
  PetscCall((*body->ops.tobody)(body, when, x, direction, r));
  PetscFunctionReturn(0);
}

/* The shape's own signed distance, in its body frame: what continuous detection follows along
   a point's motion relative to the shape */
PetscErrorCode FCBodyShapeDistanceLocal(FCBody body, const PetscReal r[3], PetscReal *d, PetscReal n[3],
                                        PetscReal cp[3])
{
  PetscFunctionBegin;
  if (!body->shape || !body->shape->distance) PetscCall(Missing(body, "measure a distance to its shape"));
  PetscCall((*body->shape->distance)(body->shape, r, d, n, cp));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyAddPartialPosition(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscFunctionBegin;
  if (!body->ops.partialposition) PetscCall(Missing(body, "place a proximity point"));
  PetscCall((*body->ops.partialposition)(body, p, x));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyAddTrialPosition(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscFunctionBegin;
  if (!body->ops.trialposition) PetscCall(Missing(body, "report trial positions"));
  PetscCall((*body->ops.trialposition)(body, p, x));
  PetscFunctionReturn(0);
}

/* Responses: a body that takes no force (kinematic) adds nothing and is not corrected */
PetscErrorCode FCBodySetUpContact(FCBody body)
{
  PetscFunctionBegin;
  if (body->ops.setupcontact) PetscCall((*body->ops.setupcontact)(body));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyAddCompliance(FCBody body, PetscInt self, const FCContactSet *set, const FCRows *rows,
                                   PetscReal W[])
{
  PetscFunctionBegin;
  if (body->ops.addcompliance) PetscCall((*body->ops.addcompliance)(body, self, set, rows, W));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyBuildCompliance(FCBody body, PetscInt self, const FCContactSet *set, const FCRows *rows,
                                     PetscBool *same)
{
  PetscFunctionBegin;
  if (body->ops.buildcompliance)
    PetscCall((*body->ops.buildcompliance)(body, self, set, rows, same));
  else { /* unchanged only when it adds nothing: no compliance, or no contact on it */
    *same = PETSC_TRUE;
    if (body->ops.addcompliance)
      for (PetscInt k = 0; k < set->n && *same; k++)
        *same = (PetscBool)(set->c[k].body[0] != self && set->c[k].body[1] != self);
  }
  PetscFunctionReturn(0);
}

PetscBool FCBodyExpectsContacts(FCBody body)
{
  return body->expects;
}

PetscErrorCode FCBodyExpectContacts(FCBody body, PetscInt self, const FCContactSet *set)
{
  PetscFunctionBegin;
  if (body->expects && body->ops.expectcontacts) PetscCall((*body->ops.expectcontacts)(body, self, set));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyApplyCorrection(FCBody body, PetscInt self, const FCContactSet *set, const PetscReal lambda[])
{
  PetscFunctionBegin;
  if (body->ops.applycorrection) PetscCall((*body->ops.applycorrection)(body, self, set, lambda));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySettle(FCBody body, const FCContactSet *set, PetscReal t, PetscReal *held)
{
  PetscFunctionBegin;
  *held = 0.0;
  if (body->ops.settle) PetscCall((*body->ops.settle)(body, set, t, held));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyRelinearize(FCBody body)
{
  PetscFunctionBegin;
  if (body->ops.relinearize) PetscCall((*body->ops.relinearize)(body));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodySaveFreeMotion(FCBody body)
{
  PetscFunctionBegin;
  if (body->ops.savefree) PetscCall((*body->ops.savefree)(body));
  PetscFunctionReturn(0);
}

PetscErrorCode FCBodyRestoreFreeMotion(FCBody body)
{
  PetscFunctionBegin;
  if (body->ops.restorefree) PetscCall((*body->ops.restorefree)(body));
  PetscFunctionReturn(0);
}
