/* What the fast scheme's files share (src/scheme/fast.c: options and the step; fast_wk.c: the products of
   Algorithm 3, W_k = C_k W_H C_k^T and the proximity update) */
#pragma once

#include "schemeimpl.h"

/* The scheme's data, kept from step to step */
typedef struct {
  char      wh_mat_type[FC_MAX_NAME], frames_mat_type[FC_MAX_NAME], vec_type[FC_MAX_NAME];
  PetscBool sweep_update; /* -fast_update sweep */
  PetscBool host;         /* W_H seqdense and C seqaij (the default types): W_k by CongruenceHost */
  PetscBool by_rows;      /* -fast_wk_rows */
  PetscInt  dist_min;     /* -fast_distributed_contacts: W_H by block rows from this many contacts */
  /* W_H and W_k kept from step to step, and what they were built from: W_H is built again only when
     a body's part changed (FCSchemeCompliance), W_k only when W_H or the frames did (on the host) */
  Mat        WH, Wk;
  PetscInt   wh_n3;        /* W_H's size: 3 x the contacts (h, in W_H, is fixed at set-up) */
  PetscInt   wh_c0, wh_c1; /* the contacts whose rows of W_H this rank holds (all: 0, nc) */
  PetscBool  wh_valid;     /* it holds the last build, complete and checked */
  PetscInt   wh_state;     /* counts the builds of W_H that changed it */
  PetscInt   wk_state;     /* the W_H state W_k was formed from (-1: none) */
  PetscInt   wk_c0, wk_c1; /* the contacts whose rows W_k holds (all: 0, nc) */
  PetscInt   wk_nc;        /* the frames W_k was formed with: per contact its row, dim and n, t1, t2 */
  PetscInt  *wk_rows;
  PetscReal *wk_frames;
} Fast;

/* What one step of the scheme works on */
typedef struct {
  FCScheme      scheme;
  FCContactSet *set, H; /* the contacts, and the same in identity frames (W_H's rows) */
  PetscInt      nc, n3, M;
  Mat           WHm, C, U, Ut, Wk;
  Vec           F, dvec, lam; /* world forces, W_H F, forces in the frames */
  PetscReal    *dfree, *d0, *q, *qold, *d;
  PetscInt      rebuilds; /* W_k rebuilt inside the contact solver (-fast_update sweep) */
  PetscBool     host;     /* W_H dense and C AIJ on the host: W_k by CongruenceHost */
  PetscBool     rows;     /* W_k holds the rows [rlo, rhi) of contacts [c0, c1) only (RowBlock) */
  PetscInt      c0, c1, rlo, rhi;
  PetscBool     dist;     /* W_H too held by the rows of contacts [c0, c1): WHm is n3 x 3 (c1 - c0), its
                             columns those rows (W_H symmetric) */
  PetscReal *mu, *lambda; /* friction per contact; forces in the frames (M) */
  PetscInt  *dims;        /* rows per contact */
} FastStep;

/* W_k = C_k W_H C_k^T for the frames of the contact set (FCPhase rebuild_w) */
PETSC_INTERN PetscErrorCode FCFastRebuildW(FastStep *);
/* F = C_k^T lambda and the proximity update d = d_free + h^2 W_H F (eq. 31) */
PETSC_INTERN PetscErrorCode FCFastProximityUpdate(FastStep *, const PetscReal lambda[]);
/* lambda = C_k F: the world forces in the current frames */
PETSC_INTERN PetscErrorCode FCFastForcesInFrames(FastStep *, PetscReal lambda[]);
/* each contact's n^T W_H[k,k] n, where W_k is held by block rows */
PETSC_INTERN PetscErrorCode FCFastNormalComplianceFromWH(FastStep *, const PetscScalar *wh);
/* -fast_update sweep: the solver's update after every sweep (FCContactSolverSetUpdate) */
PETSC_INTERN PetscErrorCode FCFastUpdateAfterSweep(void *ctx, FCContactProblem, PetscReal r[], PetscBool *changed);
