/* FE body: its constrained regions and loads (fem_bc.c, fem_load.c), and where a constraint puts
   its vertices over a step */
#pragma once
#include "bodyimpl.h"

#define FC_MAX_REGIONS 16 /* constraints (fixed, prescribed) and loads of a body, each at most */

/* A constrained region (fem_bc.c): fixed, moved by a table of displacement, or attached to a
   kinematic body. Its vertices' displacement at t - h, t, t + h (FC_BC_BEFORE, _NOW, _END) is
   u(X) = x[when] + RR[when] (X - x0) - X: for a table x0 = 0 and RR = I (a translation), for an
   attachment the body's centre and RR = R(t) R(0)^T */
enum { FC_BC_BEFORE, FC_BC_NOW, FC_BC_END };
typedef struct {
  char      region[256]; /* as given: a group's name or number, or box:... */
  PetscBool moves;       /* prescribed (a table or an attachment); else fixed */
  FCTable   table;       /* -displacement: t -> ux, uy, uz */
  FCBody    body;        /* -attach: the kinematic body it follows */
  PetscBool referenced;  /* its reference pose (x0, R0T) is known */
  PetscBool rotates;
  PetscReal x0[3], R0T[9];     /* the attached body's pose at t = 0 (tables: 0, unused) */
  PetscReal x[3][3], RR[3][9]; /* at t - h, t, t + h */
  PetscInt  nface, *facev;     /* its boundary faces on this rank: the centroid is theirs (else its vertices') */
} FCFEMConstraint;

/* A load on a region (fem_bc.c) */
typedef enum { FC_LOAD_FORCE, FC_LOAD_TRACTION, FC_LOAD_PRESSURE } FCLoadKind;
typedef struct {
  char       region[256];
  FCLoadKind kind;
  FCTable    table;
  PetscInt   nface, *facev; /* boundary faces this rank holds (outward local vertex triples) */
  PetscReal *weight;        /* force: per local vertex, its share of the total (by area, mass or count) */
} FCFEMLoad;

/* Component d of the displacement of a vertex of constraint k (-1: none) with reference X, at
   t - h, t or t + h (when) */
static inline PetscReal FCFEMConstraintU(const FCFEMConstraint *c, const PetscReal X[3], int when, int d)
{
  PetscReal y = 0.0;
  if (!c->moves) return 0.0;
  if (!c->rotates) return c->x[when][d] - c->x0[d];
  for (int j = 0; j < 3; j++) y += c->RR[when][3 * d + j] * (X[j] - c->x0[j]);
  return c->x[when][d] + y - X[d];
}
