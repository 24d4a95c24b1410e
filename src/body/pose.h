/* The pose of a body that moves rigidly (rigid and kinematic bodies): its shape, the position
   x of its centre, its orientation q (unit quaternion, body to world) and their rates. */
#pragma once
#include "bodyimpl.h"

typedef struct {
  FCShape            shape;
  PetscReal          x[3], q[4], v[3], w[3]; /* centre, orientation, velocity, angular velocity (world) */
  PetscReal          x0[3], q0[4];           /* at t = 0 */
  PetscReal          volume, J[9];           /* volume and inertia per unit density, body frame */
  PetscReal         *bodyVerts;              /* visual vertices in the body frame (nv x 3) */
  PetscReal          xf[3], qf[4];           /* after the free motion of the current step */
  PetscReal          pivot_body[3]; /* the body-frame point the rotation of a step turns about (0: the centre) */
  PetscInt           npts;          /* contact points (the picture's vertices), rank 0 */
  FCProximity       *prox;
  PetscReal         *px0, *pxf, *pkey;
  PetscInt           ntri; /* mesh shape: boundary triangles in the body frame (every rank) */
  PetscReal         *tri9;
  FCSurfaceTriangle *tri; /* their world positions of the step (rank 0) */
} FCPose;

PETSC_INTERN PetscErrorCode FCPoseSetUp(FCBody, FCPose *);
PETSC_INTERN PetscErrorCode FCPoseVisualPositions(FCBody, FCPose *, PetscReal[]);
PETSC_INTERN PetscErrorCode FCPoseDestroy(FCPose *);
/* displacement and velocity of the picture's vertices; pivot: the point the velocity P->v moves
   (NULL: the centre) */
PETSC_INTERN PetscErrorCode FCPoseVisualField(FCBody, FCPose *, const PetscReal pivot[3], FCVisualField, PetscReal[],
                                              PetscBool *);
/* Body ops shared by rigid and kinematic bodies, whose data begins with an FCPose */
PETSC_INTERN PetscErrorCode FCPoseGetCentroid(FCBody, PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPoseGetVelocity(FCBody, PetscReal v[3], PetscReal w[3]);
PETSC_INTERN PetscErrorCode FCPoseGetRotation(FCBody, PetscReal[4], PetscBool *);
PETSC_INTERN PetscErrorCode FCPoseGetVisualPositions(FCBody, PetscReal[]);
PETSC_INTERN PetscErrorCode FCPoseContactPoints(FCBody, PetscInt *, FCProximity **, PetscReal **, PetscReal **,
                                                PetscReal **);
PETSC_INTERN PetscErrorCode FCPoseProximityPosition(FCBody, const FCProximity *, PetscInt, PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPoseSurfaceTriangles(FCBody, PetscInt *, FCSurfaceTriangle **);
PETSC_INTERN PetscErrorCode FCPoseToBody(FCBody, PetscInt, const PetscReal[3], PetscBool, PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPoseStepRotation(FCBody, PetscReal *, PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPosePartialPosition(FCBody, const FCProximity *, PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPoseShapeDistanceFree(FCBody, const PetscReal[3], PetscReal *, PetscReal[3],
                                                    PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPoseShapeDistance(FCBody, const PetscReal[3], PetscReal *, PetscReal[3], PetscReal[3]);
PETSC_INTERN PetscErrorCode FCPoseGetState(FCBody, PetscReal[]);
PETSC_INTERN PetscErrorCode FCPoseSetState(FCBody, const PetscReal[]);
