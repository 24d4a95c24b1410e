/* Body: what a body is and what code outside src/body/ may ask of it (src/body/body_ops.c). Its
   structure and operations are in src/body/bodyimpl.h, which only src/body/ includes. */
#pragma once

#include "../contact/contact.h"
#include "../shape/shape.h"

/* Fields of a body's picture written at output frames (-output_fields, src/io/fields.c): point
   fields have 3 values per visual vertex, cell fields 1 value per visual cell */
typedef enum {
  FC_FIELD_DISPLACEMENT,     /* point: x - X (m)                                               */
  FC_FIELD_VELOCITY,         /* point: dx/dt (m/s)                                             */
  FC_FIELD_VON_MISES,        /* cell, FE: von Mises stress of the material's linear stress (Pa) */
  FC_FIELD_ENERGY_DENSITY,   /* cell, FE: elastic energy / reference volume (J/m^3 = Pa)        */
  FC_FIELD_CONTACT_PRESSURE, /* point, FE: the step's normal contact force per vertex area (Pa) */
  FC_FIELD_NUM
} FCVisualField;
PETSC_INTERN const char *const FCVisualFieldNames[FC_FIELD_NUM];
PETSC_INTERN PetscBool         FCVisualFieldIsCell(FCVisualField);
PETSC_INTERN PetscBool         FCVisualFieldIsScalar(FCVisualField); /* one value (else 3) per vertex or cell */
enum { FC_AT_START, FC_AT_FREE, FC_AT_NOW };

/* What a body is, and what code outside src/body/ may ask of it (src/body/body_ops.c): no other
   file reads body->ops or compares body type names. */
PETSC_INTERN PetscBool FCBodyIsDeformable(FCBody);    /* FE: vertex DOFs, a deforming surface     */
PETSC_INTERN PetscBool FCBodyIsPrescribed(FCBody);    /* kinematic: given motion, takes no force  */
PETSC_INTERN PetscBool FCBodyHasShape(FCBody);        /* a signed distance (rigid, kinematic)     */
PETSC_INTERN PetscBool FCBodyHasBoundedShape(FCBody); /* ... of a closed shape (not a plane)      */
PETSC_INTERN PetscBool FCBodyHasShapeCore(FCBody);    /* ... rounded, with a core (sphere, capsule, cylinder) */
/* the core of a rounded shape (FCShape: a point or a segment, body frame), its radius and whether
   its ends are flat (cylinder); *ncore 0 for a body without one */
PETSC_INTERN void FCBodyGetShapeCore(FCBody, PetscInt *ncore, PetscReal core[2][3], PetscReal *radius, PetscBool *flat);
PETSC_INTERN PetscBool   FCBodyHasSmoothShape(FCBody);      /* ... without edges (sphere, capsule)      */
PETSC_INTERN PetscBool   FCBodyHasSurfaceTriangles(FCBody); /* FE bodies and mesh shapes           */
PETSC_INTERN PetscBool   FCBodyIsBox(FCBody);               /* a rigid or kinematic box              */
PETSC_INTERN void        FCBodyGetBoxHalfExtents(FCBody, PetscReal h[3]);
PETSC_INTERN PetscReal   FCBodyGetMass(FCBody);  /* after set-up; 0 for kinematic bodies */
PETSC_INTERN const char *FCBodyName(FCBody);     /* for messages */
PETSC_INTERN const char *FCBodyTypeName(FCBody); /* for messages */
PETSC_INTERN PetscReal   FCBodyTimeStep(FCBody);
/* A time step after set-up, for the steps from now on (the scene's step control) */
PETSC_INTERN PetscErrorCode FCBodyChangeTimeStep(FCBody, PetscReal h);
PETSC_INTERN void           FCBodyGetGravity(FCBody, PetscReal g[3]);
/* the velocity and angular velocity of -<name>_velocity, -<name>_angular_velocity (a kinematic body's motion) */
PETSC_INTERN void FCBodyGetPrescribedMotion(FCBody, PetscReal v[3], PetscReal w[3]);
/* Restart state: `cols` values per visual vertex (pervertex, distributed like the visual) or one
   row of `cols` values on rank 0 */
PETSC_INTERN PetscErrorCode FCBodyGetStateLayout(FCBody, PetscInt *cols, PetscBool *pervertex);
PETSC_INTERN PetscErrorCode FCBodyGetState(FCBody, PetscReal[]);
/* A field of the body's picture (see FCBodyOps.getvisualfield); *has = PETSC_FALSE when the body has none */
PETSC_INTERN PetscErrorCode FCBodySetStepContacts(FCBody, PetscInt self, const FCContactSet *);
PETSC_INTERN PetscErrorCode FCBodyGetVisualField(FCBody, FCVisualField, PetscReal[], PetscBool *has);
PETSC_INTERN PetscErrorCode FCBodySetState(FCBody, const PetscReal[]);
/* Contact geometry (see FCBodyOps for the meaning of each) */
PETSC_INTERN PetscErrorCode FCBodyGetContactPoints(FCBody, PetscInt *n, FCProximity **prox, PetscReal **x0,
                                                   PetscReal **xfree, PetscReal **key);
PETSC_INTERN PetscErrorCode FCBodyGetSurfaceTriangles(FCBody, PetscInt *n, FCSurfaceTriangle **);
PETSC_INTERN PetscErrorCode FCBodyProximityPosition(FCBody, const FCProximity *, PetscInt when, PetscReal x[3]);
/* when: FC_AT_NOW (the shape's pose now) or FC_AT_FREE (after the free motion) */
PETSC_INTERN PetscErrorCode FCBodyShapeDistance(FCBody, PetscInt when, const PetscReal x[3], PetscReal *d,
                                                PetscReal n[3], PetscReal cpb[3]);
/* Whether a contact keeps its normal n at x where the shape's distance gave gap and the normal nx:
   on an edge of the shape, where n is still nearly one of its normals there; move: how far the point
   moved, the probe's scale (src/body/body_ops.c) */
PETSC_INTERN PetscErrorCode FCBodyShapeKeepsNormal(FCBody, PetscInt when, const PetscReal x[3], PetscReal gap,
                                                   const PetscReal nx[3], const PetscReal n[3], PetscReal move,
                                                   PetscBool *keep);
/* when: FC_AT_NOW (the pose now) or FC_AT_FREE (after the free motion) */
/* The angle the body frame turns by over the step and the body-frame point it turns about (0 for
   bodies that do not rotate rigidly): continuous detection bounds the arc a point follows in it */
PETSC_INTERN PetscErrorCode FCBodyStepRotation(FCBody, PetscReal *theta, PetscReal center[3]);
PETSC_INTERN PetscErrorCode FCBodyToBodyFrame(FCBody, PetscInt when, const PetscReal x[3], PetscBool direction,
                                              PetscReal r[3]);
/* signed distance of a body-frame point to the body's shape: outward normal and closest point, body frame */
PETSC_INTERN PetscErrorCode FCBodyShapeDistanceLocal(FCBody, const PetscReal r[3], PetscReal *d, PetscReal n[3],
                                                     PetscReal cp[3]);
PETSC_INTERN PetscErrorCode FCBodyAddPartialPosition(FCBody, const FCProximity *, PetscReal x[3]);
/* bytes on this rank: W_b, Sigma / C, the factorization of A (0 where the body has none) */
PETSC_INTERN PetscErrorCode FCBodyGetContactMemory(FCBody, PetscReal bytes[3]);
PETSC_INTERN PetscErrorCode FCBodyGetRegions(FCBody, PetscInt *n, char **names, PetscReal **values);
/* Contact response */
PETSC_INTERN PetscErrorCode FCBodySetUpContact(FCBody); /* a body named in a contact pair, after FCBodySetUp */
/* W += the body's part, on this rank's rows of W (NULL: all) */
PETSC_INTERN PetscErrorCode FCBodyAddCompliance(FCBody, PetscInt self, const FCContactSet *, const FCRows *,
                                                PetscReal W[]);
/* before FCBodyAddCompliance with the same set and rows: whether the body's part of W is the one it
   added last (on the same rows): a W summed from the bodies' last parts still holds when every one is */
PETSC_INTERN PetscErrorCode FCBodyBuildCompliance(FCBody, PetscInt self, const FCContactSet *, const FCRows *,
                                                  PetscBool *same);
/* before the first free motion of a run: whether the body's factorization depends on its contacts,
   and the contacts a proximity query at the start positions gives it */
PETSC_INTERN PetscBool      FCBodyExpectsContacts(FCBody);
PETSC_INTERN PetscErrorCode FCBodyExpectContacts(FCBody, PetscInt self, const FCContactSet *);
/* a nonlinear body's equilibrium with the forces of the set (held: 0 for other bodies), and its
   free motion linearized there (src/scene/settle.c) */
PETSC_INTERN PetscErrorCode FCBodySettle(FCBody, const FCContactSet *, PetscReal t, PetscReal *held);
PETSC_INTERN PetscErrorCode FCBodyRelinearize(FCBody);
PETSC_INTERN PetscErrorCode FCBodyApplyCorrection(FCBody, PetscInt self, const FCContactSet *,
                                                  const PetscReal lambda[]);
PETSC_INTERN PetscErrorCode FCBodySaveFreeMotion(FCBody);
PETSC_INTERN PetscErrorCode FCBodyRestoreFreeMotion(FCBody);
PETSC_INTERN PetscErrorCode FCBodyAddTrialPosition(FCBody, const FCProximity *, PetscReal x[3]);

PETSC_INTERN PetscErrorCode FCBodyRegisterAll(void);
/* Reads the placement options of a body: -<name>_translate, _rotate, _center, _velocity,
   _angular_velocity. */
PETSC_INTERN PetscErrorCode FCBodyReadPlacement(FCBody);
/* Rotation matrix of -<name>_rotate */
PETSC_INTERN void           FCBodyPlacementRotation(FCBody, PetscReal R[9]);
PETSC_INTERN PetscErrorCode FCBodyVisualFromShape(FCBody, FCShape);
PETSC_INTERN PetscErrorCode FCBodyVisualDestroy(FCBodyVisual *);
