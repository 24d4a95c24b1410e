/* Contact pairs and collision detection (src/collision/) */
#pragma once

#include "../body/body.h"

/* the topology of a body's gathered surface, kept per body for the run (src/collision/topology.c) */
typedef struct _FCSurfaceTopology FCSurfaceTopology;

typedef struct {
  PetscInt n;
  PetscInt (*body)[2]; /* scene body indices */
  PetscReal *mu;
  PetscReal  distance;      /* alarm distance */
  PetscInt   passes;        /* FE-FE and FE-mesh pairs: 2 both ways, 1 first body's vertices only */
  PetscReal  pass2_drop;    /* -contact_fe_pass2_drop: drop 2nd-pass vertices held by the 1st pass (< 0: off) */
  PetscReal  pass2_dormant; /* -contact_fe_pass2_dormant: such contacts dormant instead (< 0: off) */
  PetscReal  dormant_depth; /* -contact_dormant_depth: a dormant contact wakes when left deeper than this (m) */
  PetscBool  facing;        /* -contact_facing: a vertex lands only on triangles that face its own surface */
  PetscBool  facing_face;   /* -contact_facing_face: a vertex near a shape's edge takes the shape's face facing it */
  PetscBool  continuous;    /* -contact_detection continuous (default) or discrete */
  PetscBool  edges;         /* -contact_edge_edge: edge-edge contacts of meshed pairs (default) */
  PetscReal  edge_angle;    /* -contact_edge_angle: an edge is a candidate where its triangles turn more (deg; 0 all) */
  PetscInt   self_ring;    /* -contact_self_ring: a self-contact vertex leaves out the triangles this many edges near */
  PetscBool  shape_points; /* -contact_shape_points: a bounded shape's points against an FE surface too */
  PetscBool  rounded_exact; /* -contact_rounded_surface exact: a sphere's or capsule's nearest FE surface points */
  PetscReal
      separation_speed; /* -contact_separation_speed: bodies that start inside each other part at most this fast */
  PetscReal           intersection_depth;    /* a point deeper than this inside another body is an intersection */
  PetscBool           fail_on_intersection;  /* -contact_fail_on_intersection: stop the run at the first one */
  PetscInt            crossings;             /* -contact_crossings: FC_CROSSINGS_OFF, _COUNT, _REDO */
  PetscInt            crossing_cuts;         /* -contact_crossings_cuts: the halvings a crossing may cause */
  PetscReal           check_cone;            /* -contact_check_cone: the end-of-step check's cone tolerance (-) */
  PetscReal           check_complementarity; /* -contact_check_complementarity: its natural-map tolerance (m) */
  FCSurfaceTopology **topo; /* per scene body: its surface's topology, built at its first use (NULL: none kept) */
  PetscBool *self_inside;   /* per pair: a self pair's body was inside itself at the last intersection count (PETSC_TRUE
                               before the first; NULL: always), where its start-inside rule is needed */
} FCContactPairs;
/* Discrete collision detection at the start of the step (after the free motion has been
   computed, so that every contact also carries its free-motion positions) */
PETSC_INTERN PetscErrorCode FCCollisionDetectPairs(MPI_Comm, PetscInt nbodies, FCBody bodies[], const FCContactPairs *,
                                                   FCContactSet *);
/* Gap, normal and d = p1 - p2 of every contact at the end of the step, on the real geometry */
PETSC_INTERN PetscErrorCode FCCollisionEndGapsOf(MPI_Comm, PetscInt nbodies, FCBody bodies[], FCContactSet *);
/* The points inside another body at the end of the step (src/collision/intersection.c), the same
   on every rank */
PETSC_INTERN PetscErrorCode FCCollisionCountPairIntersections(MPI_Comm, PetscInt nbodies, FCBody bodies[],
                                                              const FCContactPairs *, PetscInt *count);

/* The crossing audit (src/collision/crossing.c): what went through another body's surface over a step's actual
   motion, from the positions at its start (Start) to those at its end (Count: how many features, and how far the
   deepest ended behind the surface it crossed, the same on every rank) */
enum { FC_CROSSINGS_OFF, FC_CROSSINGS_COUNT, FC_CROSSINGS_REDO };
typedef struct _FCCrossingAudit *FCCrossingAudit;
PETSC_INTERN PetscErrorCode      FCCrossingAuditCreate(PetscInt nbodies, FCCrossingAudit *);
PETSC_INTERN PetscErrorCode FCCrossingAuditStart(FCCrossingAudit, MPI_Comm, FCBody bodies[], const FCContactPairs *);
PETSC_INTERN PetscErrorCode FCCrossingAuditCount(FCCrossingAudit, MPI_Comm, FCBody bodies[], const FCContactPairs *,
                                                 PetscInt *count, PetscReal *deepest);
PETSC_INTERN PetscErrorCode FCCrossingAuditDestroy(FCCrossingAudit *);

/* FCCollision (src/collision/pairs.c): the scene's contact pairs and detection options, read from the
   options database, and the step's detection on them */
typedef struct _p_FCCollision     *FCCollision;
PETSC_INTERN PetscErrorCode        FCCollisionCreate(MPI_Comm, PetscInt nbodies, FCBody bodies[], FCCollision *);
PETSC_INTERN PetscErrorCode        FCCollisionSetFromOptions(FCCollision);
PETSC_INTERN const FCContactPairs *FCCollisionGetPairs(FCCollision);
/* the contacts of the step (continuous: as -contact_detection says; PETSC_FALSE: at the start positions only) */
PETSC_INTERN PetscErrorCode FCCollisionDetect(FCCollision, PetscBool continuous, FCContactSet *);
PETSC_INTERN PetscErrorCode FCCollisionEndGaps(FCCollision, FCContactSet *);
PETSC_INTERN PetscErrorCode FCCollisionCountIntersections(FCCollision, PetscInt *count);
/* the crossing audit of the step (-contact_crossings): its start, before the free motion; its count, after the
   integration (0 when off) */
PETSC_INTERN PetscErrorCode FCCollisionAuditStart(FCCollision);
PETSC_INTERN PetscErrorCode FCCollisionCountCrossings(FCCollision, PetscInt *count, PetscReal *deepest);
PETSC_INTERN PetscErrorCode FCCollisionDestroy(FCCollision *);
