#include "pose.h"

/* Reads the shape, places its centre and orientation from the body's placement options and
   prepares the picture. For analytic shapes the centre is -<body>_center (default origin);
   for a mesh shape it is the mesh centroid, rotated about -<body>_center when given. The
   initial velocity of the centre is v + omega x (x_centre - centre of rotation). */
static int CompareXYZ(const void *a, const void *b)
{
  const PetscReal *x = (const PetscReal *)a, *y = (const PetscReal *)b;
  for (int i = 0; i < 3; i++)
    if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
  return 0;
}

/* Mesh shape: its boundary triangles in the body frame (origin at the centroid c), gathered on
   every rank; the distinct vertices are the contact points, on rank 0 */
static PetscErrorCode MeshBoundary(FCBody body, FCPose *P, const PetscReal c[3])
{
  FCMesh     *mesh = (FCMesh *)P->shape->data;
  PetscInt    nbv, *bv, nt, *tv;
  PetscReal  *loc;
  PetscMPIInt size, rank, n, *counts, *displs, total = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(body->comm, &size));
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  PetscCall(FCMeshGetBoundary(mesh, &nbv, &bv, &nt, &tv));
  PetscCall(PetscMalloc1(9 * nt + 1, &loc));
  for (PetscInt t = 0; t < nt; t++) /* the mesh keeps its file coordinates: body frame = X - centroid */
    for (int a = 0; a < 3; a++)
      for (int k = 0; k < 3; k++) loc[9 * t + 3 * a + k] = mesh->X[3 * tv[3 * t + a] + k] - c[k];
  n = (PetscMPIInt)(9 * nt);
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, body->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  P->ntri = total / 9;
  PetscCall(PetscMalloc1(total + 1, &P->tri9));
  PetscCallMPI(MPI_Allgatherv(loc, n, MPIU_REAL, P->tri9, counts, displs, MPIU_REAL, body->comm));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree(bv));
  PetscCall(PetscFree(tv));
  PetscCall(PetscMalloc1(P->ntri + 1, &P->tri));
  if (rank == 0) { /* distinct vertices: sort the 3 ntri corners and drop repeats */
    PetscReal *v;
    PetscInt   nv = 0;
    PetscCall(PetscMalloc1(9 * P->ntri + 1, &v));
    PetscCall(PetscArraycpy(v, P->tri9, 9 * P->ntri));
    qsort(v, 3 * P->ntri, 3 * sizeof(PetscReal), CompareXYZ);
    for (PetscInt i = 0; i < 3 * P->ntri; i++)
      if (!nv || CompareXYZ(&v[3 * i], &v[3 * (nv - 1)])) {
        for (int k = 0; k < 3; k++) v[3 * nv + k] = v[3 * i + k];
        nv++;
      }
    P->npts = nv;
    PetscCall(PetscCalloc4(nv + 1, &P->prox, 3 * nv + 1, &P->px0, 3 * nv + 1, &P->pxf, 3 * nv + 1, &P->pkey));
    for (PetscInt i = 0; i < nv; i++)
      for (int k = 0; k < 3; k++) P->prox[i].r[k] = P->pkey[3 * i + k] = v[3 * i + k];
    PetscCall(PetscFree(v));
  }
  body->ops.surfacetriangles = FCPoseSurfaceTriangles;
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseSetUp(FCBody body, FCPose *P)
{
  PetscReal R0[9], rot_center[3], c[3];
  PetscBool ismesh;

  PetscFunctionBegin;
  PetscCall(FCShapeCreateFromOptions(body->comm, body->prefix, body->name, &P->shape));
  PetscCall(PetscStrcmp(P->shape->type, FCSHAPEMESH, &ismesh));
  if (P->shape->massproperties) PetscCall((*P->shape->massproperties)(P->shape, &P->volume, P->J));
  FCBodyPlacementRotation(body, R0);
  FCQuatFromAxisAngle(body->rotate, body->rotate[3] * PETSC_PI / 180.0, P->q);
  FCQuatNormalize(P->q);
  if (ismesh) {
    FCMesh   *mesh = (FCMesh *)P->shape->data;
    PetscReal V, J[9];
    PetscCall(FCMeshComputeMassProperties(mesh, &V, c, J));
    for (int d = 0; d < 3; d++) rot_center[d] = body->center_set ? body->center[d] : c[d];
  } else {
    for (int d = 0; d < 3; d++) c[d] = rot_center[d] = body->center[d];
  }
  {
    PetscReal r[3], Rr[3], wr[3];
    for (int d = 0; d < 3; d++) r[d] = c[d] - rot_center[d];
    FCMat3Vec(R0, r, Rr);
    for (int d = 0; d < 3; d++) P->x[d] = rot_center[d] + Rr[d] + body->translate[d];
    FCCross(body->angular_velocity, Rr, wr);
    for (int d = 0; d < 3; d++) {
      P->v[d] = body->velocity[d] + wr[d];
      P->w[d] = body->angular_velocity[d];
    }
  }
  for (int d = 0; d < 3; d++) body->center[d] = rot_center[d] + body->translate[d];
  for (int d = 0; d < 3; d++) P->x0[d] = P->x[d];
  for (int d = 0; d < 4; d++) P->q0[d] = P->q[d];

  /* picture: vertices kept in the body frame */
  if (ismesh) {
    FCMesh *mesh = (FCMesh *)P->shape->data;
    PetscCall(FCMeshCreateVisual(mesh, &body->visual));
    PetscCall(PetscMalloc1(3 * body->visual.nv, &P->bodyVerts));
    for (PetscInt i = 0; i < body->visual.nv; i++)
      for (int d = 0; d < 3; d++) P->bodyVerts[3 * i + d] = body->visual.reference[3 * i + d] - c[d];
  } else {
    PetscCall(FCBodyVisualFromShape(body, P->shape));
    PetscCall(PetscMalloc1(3 * body->visual.nv, &P->bodyVerts));
    PetscCall(PetscArraycpy(P->bodyVerts, body->visual.reference, 3 * body->visual.nv));
  }
  PetscCall(FCPoseVisualPositions(body, P, body->visual.reference)); /* reference = placed at t = 0 */
  body->shape = P->shape;
  for (int d = 0; d < 3; d++) P->xf[d] = P->x[d];
  for (int d = 0; d < 4; d++) P->qf[d] = P->q[d];
  if (ismesh) PetscCall(MeshBoundary(body, P, c));
  /* contact points of the shape: its picture's vertices (box corners exactly), on rank 0 */
  if (!ismesh && P->shape->bounded) {
    P->npts = body->visual.nv;
    PetscCall(PetscCalloc4(P->npts + 1, &P->prox, 3 * P->npts + 1, &P->px0, 3 * P->npts + 1, &P->pxf, 3 * P->npts + 1,
                           &P->pkey));
    for (PetscInt i = 0; i < P->npts; i++)
      for (int d = 0; d < 3; d++) P->prox[i].r[d] = P->pkey[3 * i + d] = P->bodyVerts[3 * i + d];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseVisualPositions(FCBody body, FCPose *P, PetscReal x[])
{
  PetscReal R[9];

  PetscFunctionBegin;
  FCQuatToMat3(P->q, R);
  for (PetscInt i = 0; i < body->visual.nv; i++) {
    FCMat3Vec(R, &P->bodyVerts[3 * i], &x[3 * i]);
    for (int d = 0; d < 3; d++) x[3 * i + d] += P->x[d];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseDestroy(FCPose *P)
{
  PetscFunctionBegin;
  PetscCall(FCShapeDestroy(&P->shape));
  PetscCall(PetscFree(P->tri9));
  PetscCall(PetscFree(P->tri));
  PetscCall(PetscFree4(P->prox, P->px0, P->pxf, P->pkey));
  PetscCall(PetscFree(P->bodyVerts));
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseGetCentroid(FCBody body, PetscReal c[3])
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) c[d] = P->x[d];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseGetVelocity(FCBody body, PetscReal v[3], PetscReal w[3])
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    v[d] = P->v[d];
    w[d] = P->w[d];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseGetRotation(FCBody body, PetscReal q[4], PetscBool *has)
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  for (int d = 0; d < 4; d++) q[d] = P->q[d];
  *has = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseGetVisualPositions(FCBody body, PetscReal x[])
{
  PetscFunctionBegin;
  PetscCall(FCPoseVisualPositions(body, (FCPose *)body->data, x));
  PetscFunctionReturn(0);
}

/* Fields of the picture of a body moving rigidly: displacement x - X of each vertex, and velocity
   v + w x (x - c) with c a point whose velocity is v: the centre for a rigid body (pivot NULL); for a
   kinematic body the pivot, carried along: c = x_centre - R(q q0^-1) (x0_centre - pivot). No cell
   fields (*has = PETSC_FALSE). */
PetscErrorCode FCPoseVisualField(FCBody body, FCPose *P, const PetscReal pivot[3], FCVisualField field, PetscReal out[],
                                 PetscBool *has)
{
  const FCBodyVisual *vis = &body->visual;

  PetscFunctionBegin;
  *has = field == FC_FIELD_DISPLACEMENT || field == FC_FIELD_VELOCITY ? PETSC_TRUE : PETSC_FALSE;
  if (!*has) PetscFunctionReturn(0);
  PetscCall(FCPoseVisualPositions(body, P, out));
  if (field == FC_FIELD_DISPLACEMENT) {
    for (PetscInt i = 0; i < 3 * vis->nv; i++) out[i] -= vis->reference[i];
  } else {
    PetscReal c[3];
    for (int d = 0; d < 3; d++) c[d] = P->x[d];
    if (pivot) {
      PetscReal q0c[4] = {P->q0[0], -P->q0[1], -P->q0[2], -P->q0[3]}, dq[4], R[9], r[3], Rr[3];
      FCQuatMult(P->q, q0c, dq);
      FCQuatToMat3(dq, R);
      for (int d = 0; d < 3; d++) r[d] = P->x0[d] - pivot[d];
      FCMat3Vec(R, r, Rr);
      for (int d = 0; d < 3; d++) c[d] -= Rr[d];
    }
    for (PetscInt i = 0; i < vis->nv; i++) {
      PetscReal r[3], wr[3];
      for (int d = 0; d < 3; d++) r[d] = out[3 * i + d] - c[d];
      FCCross(P->w, r, wr);
      for (int d = 0; d < 3; d++) out[3 * i + d] = P->v[d] + wr[d];
    }
  }
  PetscFunctionReturn(0);
}

static void Transform(const PetscReal x[3], const PetscReal q[4], const PetscReal r[3], PetscReal p[3])
{
  PetscReal R[9];
  FCQuatToMat3(q, R);
  FCMat3Vec(R, r, p);
  for (int d = 0; d < 3; d++) p[d] += x[d];
}

PetscErrorCode FCPoseContactPoints(FCBody body, PetscInt *n, FCProximity **prox, PetscReal **x0, PetscReal **xf,
                                   PetscReal **key)
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < P->npts; i++) {
    Transform(P->x, P->q, P->prox[i].r, &P->px0[3 * i]);
    Transform(P->xf, P->qf, P->prox[i].r, &P->pxf[3 * i]);
  }
  *n    = P->npts;
  *prox = P->prox;
  *x0   = P->px0;
  *xf   = P->pxf;
  *key  = P->pkey;
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseProximityPosition(FCBody body, const FCProximity *p, PetscInt when, PetscReal x[3])
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  if (when == FC_AT_FREE)
    Transform(P->xf, P->qf, p->r, x);
  else
    Transform(P->x, P->q, p->r, x);
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseShapeDistance(FCBody body, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cpb[3])
{
  FCPose   *P = (FCPose *)body->data;
  PetscReal R[9], xb[3], nb[3], dx[3];

  PetscFunctionBegin;
  PetscCheck(P->shape->distance, body->comm, PETSC_ERR_SUP, "Body '%s': contact with a %s shape is not supported yet",
             body->name, P->shape->type);
  FCQuatToMat3(P->q, R);
  for (int i = 0; i < 3; i++) dx[i] = x[i] - P->x[i];
  FCMat3TVec(R, dx, xb);
  PetscCall((*P->shape->distance)(P->shape, xb, d, nb, cpb));
  FCMat3Vec(R, nb, n);
  PetscFunctionReturn(0);
}

/* Mesh shape: its boundary triangles at the start of the step and after the free motion (rank 0
   hands them out; the collision gathers them) */
PetscErrorCode FCPoseSurfaceTriangles(FCBody body, PetscInt *n, FCSurfaceTriangle **tri)
{
  FCPose     *P = (FCPose *)body->data;
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  *n   = rank ? 0 : P->ntri;
  *tri = P->tri;
  for (PetscInt t = 0; t < *n; t++)
    for (int a = 0; a < 3; a++) {
      P->tri[t].gdof[a] = -1;
      for (int k = 0; k < 3; k++) P->tri[t].X[a][k] = P->tri9[9 * t + 3 * a + k];
      Transform(P->x, P->q, &P->tri9[9 * t + 3 * a], P->tri[t].x0[a]);
      Transform(P->xf, P->qf, &P->tri9[9 * t + 3 * a], P->tri[t].xf[a]);
    }
  PetscFunctionReturn(0);
}

/* The angle between the orientations at the start and after the free motion, 2 acos |q . qf| (the
   quaternions' dot product is the cosine of half the relative rotation, whatever their signs) */
PetscErrorCode FCPoseStepRotation(FCBody body, PetscReal *theta, PetscReal center[3])
{
  FCPose   *P = (FCPose *)body->data;
  PetscReal c = 0.0;

  PetscFunctionBegin;
  for (int k = 0; k < 4; k++) c += P->q[k] * P->qf[k];
  *theta = 2.0 * PetscAcosReal(PetscMin(1.0, PetscAbsReal(c)));
  for (int d = 0; d < 3; d++) center[d] = P->pivot_body[d];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseToBody(FCBody body, PetscInt when, const PetscReal x[3], PetscBool direction, PetscReal r[3])
{
  FCPose          *P = (FCPose *)body->data;
  PetscReal        R[9], d[3];
  const PetscReal *c = when == FC_AT_FREE ? P->xf : P->x;

  PetscFunctionBegin;
  FCQuatToMat3(when == FC_AT_FREE ? P->qf : P->q, R);
  for (int k = 0; k < 3; k++) d[k] = direction ? x[k] : x[k] - c[k];
  FCMat3TVec(R, d, r);
  PetscFunctionReturn(0);
}

/* rank 0 adds the current position of the body-frame point (the state is replicated) */
PetscErrorCode FCPosePartialPosition(FCBody body, const FCProximity *p, PetscReal x[3])
{
  PetscMPIInt rank;
  PetscReal   y[3];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(body->comm, &rank));
  if (rank) PetscFunctionReturn(0);
  PetscCall(FCPoseProximityPosition(body, p, FC_AT_NOW, y));
  for (int k = 0; k < 3; k++) x[k] += y[k];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseShapeDistanceFree(FCBody body, const PetscReal x[3], PetscReal *d, PetscReal n[3],
                                       PetscReal cpb[3])
{
  FCPose   *P = (FCPose *)body->data;
  PetscReal R[9], xb[3], nb[3], dx[3];

  PetscFunctionBegin;
  FCQuatToMat3(P->qf, R);
  for (int i = 0; i < 3; i++) dx[i] = x[i] - P->xf[i];
  FCMat3TVec(R, dx, xb);
  PetscCall((*P->shape->distance)(P->shape, xb, d, nb, cpb));
  FCMat3Vec(R, nb, n);
  PetscFunctionReturn(0);
}

/* Restart state of a rigidly moving body: x, q, v, w */
PetscErrorCode FCPoseGetState(FCBody body, PetscReal s[])
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    s[d]      = P->x[d];
    s[7 + d]  = P->v[d];
    s[10 + d] = P->w[d];
  }
  for (int d = 0; d < 4; d++) s[3 + d] = P->q[d];
  PetscFunctionReturn(0);
}

PetscErrorCode FCPoseSetState(FCBody body, const PetscReal s[])
{
  FCPose *P = (FCPose *)body->data;

  PetscFunctionBegin;
  for (int d = 0; d < 3; d++) {
    P->x[d] = s[d];
    P->v[d] = s[7 + d];
    P->w[d] = s[10 + d];
  }
  for (int d = 0; d < 4; d++) P->q[d] = s[3 + d];
  PetscFunctionReturn(0);
}
