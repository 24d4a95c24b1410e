/* The inside of a body (src/body/ only): its operations, filled by each type, and its structure */
#pragma once

#include "../fcimpl.h"

typedef struct {
  PetscErrorCode (*setfromoptions)(FCBody);
  PetscErrorCode (*setup)(FCBody);
  PetscErrorCode (*freemotion)(FCBody, PetscReal t);
  PetscErrorCode (*integrate)(FCBody, PetscReal t);
  PetscErrorCode (*getcentroid)(FCBody, PetscReal[3]);
  PetscErrorCode (*getrotation)(FCBody, PetscReal[4], PetscBool *);
  PetscErrorCode (*getenergy)(FCBody, FCEnergy *);
  PetscErrorCode (*getvisualpositions)(FCBody, PetscReal[]);
  /* a field of the picture (FCVisualField): per owned visual vertex (3 values) or per owned visual
     cell (1 value), in the visual order; *has = PETSC_FALSE when the type has no such field */
  PetscErrorCode (*getvisualfield)(FCBody, FCVisualField, PetscReal[], PetscBool *has);
  PetscErrorCode (*checkstate)(FCBody, PetscInt);
  /* restart: FE bodies 6 values (u, v) per owned vertex in the visual order; rigid and kinematic
     bodies 13 values (x, q, v, w), the same on every rank */
  PetscErrorCode (*getstate)(FCBody, PetscReal[]);
  PetscErrorCode (*setstate)(FCBody, const PetscReal[]);
  PetscErrorCode (*destroy)(FCBody);
  /* contact: candidate points of this body (owned FE boundary vertices, or points of a rigid
     shape), each with its proximity map, start and free-motion positions */
  PetscErrorCode (*contactpoints)(FCBody, PetscInt *n, FCProximity **prox, PetscReal **x0, PetscReal **xfree,
                                  PetscReal **key);
  /* world position of a proximity point: at the start of the step, after free motion, now */
  PetscErrorCode (*proximityposition)(FCBody, const FCProximity *, PetscInt when, PetscReal x[3]);
  /* W += J_b A_b^-1 J_b^T for the contacts touching this body (W: nrows x nrows, replicated) */
  PetscErrorCode (*addcompliance)(FCBody, PetscInt self, const FCContactSet *, const FCRows *, PetscReal W[]);
  /* optional: builds that W_b for the next addcompliance and tells whether it is the last one, on
     the same rows of W (NULL: a body that adds something is never known to be unchanged; one that
     has it is always called before addcompliance, by FCSchemeCompliance) */
  PetscErrorCode (*buildcompliance)(FCBody, PetscInt self, const FCContactSet *, const FCRows *, PetscBool *same);
  /* signed distance of a world point to this body's shape now: outward normal (world) and the
     closest point (body frame) */
  PetscErrorCode (*shapedistance)(FCBody, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cpb[3]);
  /* the same against the shape at its pose after the free motion (end of the step for a kinematic body) */
  PetscErrorCode (*shapedistancefree)(FCBody, const PetscReal x[3], PetscReal *d, PetscReal n[3], PetscReal cpb[3]);
  /* FE: the boundary triangles this rank holds (start and free positions of this step) */
  PetscErrorCode (*surfacetriangles)(FCBody, PetscInt *n, FCSurfaceTriangle **);
  /* rigid and kinematic: a world point or direction in the body frame, at the pose now (start of
     the step during detection) or after the free motion (when = FC_AT_NOW, FC_AT_FREE) */
  PetscErrorCode (*tobody)(FCBody, PetscInt when, const PetscReal x[3], PetscBool direction, PetscReal r[3]);
  /* the rotation of the body frame over the step (start to free motion): its angle and the
     body-frame point it turns about (rigid and kinematic bodies; none: no rotation) */
  PetscErrorCode (*steprotation)(FCBody, PetscReal *theta, PetscReal center[3]);
  /* add w x (current position) of the vertices of a proximity point this rank owns (FE), or
     the point on rank 0 (rigid, kinematic) */
  PetscErrorCode (*partialposition)(FCBody, const FCProximity *, PetscReal x[3]);
  /* a body named in a contact pair: what its response needs (FE: the compliance builder) */
  PetscErrorCode (*setupcontact)(FCBody);
  /* recursive schemes: keep dv_free, go back to it, and add w x of a proximity point at the
     trial state q + h (v + dv) (owned FE vertices; rigid on rank 0) */
  PetscErrorCode (*savefree)(FCBody);
  PetscErrorCode (*restorefree)(FCBody);
  PetscErrorCode (*trialposition)(FCBody, const FCProximity *, PetscReal x[3]);
  /* dv += h A_b^-1 J_b^T lambda */
  PetscErrorCode (*applycorrection)(FCBody, PetscInt self, const FCContactSet *, const PetscReal lambda[]);
  /* optional: after the scheme, the body's nonlinear equilibrium with the set's final forces (a
     failure is a failed step; held: the force its stabilizing springs still carry, relative to its
     largest contact force); a body without it keeps its corrected motion. relinearize: the free
     motion linearized at the settled state, for the scheme to solve again (src/scene/settle.c) */
  PetscErrorCode (*settle)(FCBody, const FCContactSet *, PetscReal t, PetscReal *held);
  PetscErrorCode (*relinearize)(FCBody);
  /* the contacts a proximity query at the start of a run expects, before the body's first
     factorization: a body whose factorization depends on its contact DOFs prepares for them
     (set by the body at contact set-up, with `expects`) */
  PetscErrorCode (*expectcontacts)(FCBody, PetscInt self, const FCContactSet *);
  /* optional: the constrained regions and their reactions of the last step (6 values each: the
     supports' force on the body and its moment about the region's centroid), the same on every rank */
  /* optional: the magnitude of the work done on the body by its prescribed motions and loads so far */
  PetscErrorCode (*getexternalwork)(FCBody, PetscReal *);
  /* optional: a prescribed body's fastest velocity and angular velocity (else its initial ones) */
  void (*prescribedmotion)(FCBody, PetscReal v[3], PetscReal w[3]);
  /* optional: a prescribed body's pose at any time t (kinematic) */
  PetscErrorCode (*poseat)(FCBody, PetscReal t, PetscReal x[3], PetscReal q[4]);
  /* optional: the scene's time, at set-up (0) and at a restart, before any step */
  PetscErrorCode (*settime)(FCBody, PetscReal t);
  /* optional: body->h changed after set-up (step control): what was formed with the old h */
  PetscErrorCode (*changetimestep)(FCBody);
  /* optional (kinematic): a program's motion from now on (FCBodySetKinematicPose, -Velocity) */
  PetscErrorCode (*setkinematicpose)(FCBody, const PetscReal x[3], const PetscReal q[4]);
  PetscErrorCode (*setkinematicvel)(FCBody, const PetscReal v[3], const PetscReal w[3]);
  /* optional (rigid, kinematic): the velocity and angular velocity over the last step */
  PetscErrorCode (*getvelocity)(FCBody, PetscReal v[3], PetscReal w[3]);
  PetscErrorCode (*getreactions)(FCBody, PetscInt *n, const char ***names, const PetscReal **values);
  /* optional (fem): what identifies its regions across runs (FCBodyGetRegions) */
  PetscErrorCode (*getregions)(FCBody, PetscInt *n, char **names, PetscReal **values);
  /* optional: factorizations and Krylov iterations so far */
  PetscErrorCode (*getsolvercounts)(FCBody, PetscInt *nfactor, PetscInt *nkrylov, PetscInt *nnewton);
  PetscErrorCode (*getcontactmemory)(FCBody, PetscReal bytes[3]); /* W_b, Sigma / C, factor on this rank */
  /* optional (fem): the elements turned inside out (FCBodyGetInverted) */
  PetscErrorCode (*getinverted)(FCBody, FCInverted *, PetscBool *has);
} FCBodyOps;

struct _p_FCBody {
  MPI_Comm  comm;
  PetscBool deformable;       /* set by the type: DOFs at mesh vertices, a surface that deforms (fem) */
  PetscBool prescribed;       /* set by the type: motion given, takes no force (kinematic)           */
  PetscInt  state_cols;       /* set by the type: restart values per row ...                     */
  PetscBool state_per_vertex; /* ... one row per visual vertex (else one row, on rank 0)          */
  char      name[FC_MAX_NAME];
  char      prefix[FC_MAX_NAME + 1]; /* "<name>_" */
  char      type[FC_MAX_NAME];
  FCBodyOps ops;
  void     *data;
  PetscBool setupcalled;
  PetscBool expects; /* its first factorization depends on its contacts: FCBodyExpectContacts before the free motion */
  PetscReal h, gravity[3];
  PetscBool quasistatic;        /* -time_integration static: no inertia, each step an equilibrium */
  PetscInt  nscene;             /* the scene's bodies, for a body that refers to another (-<name>_attach) */
  PetscInt  self;               /* its index among them */
  const FCContactSet *contacts; /* the scene's contacts of the last step (the contact_pressure field) */
  FCBody             *scene;
  /* placement and initial motion, common to every type */
  PetscReal    translate[3], rotate[4], center[3], velocity[3], angular_velocity[3];
  PetscBool    center_set;
  PetscReal    density;
  PetscReal    mass; /* set by the type at set-up (fem, rigid); 0: kinematic */
  FCBodyVisual visual;
  FCShape      shape; /* rigid and kinematic bodies: their shape (owned by the pose) */
};
