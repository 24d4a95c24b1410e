/* Projected (block) Gauss-Seidel on FC(W, q, mu), eq. 19: sweep over contacts; for contact i,
   q_i' = q_i + sum_{j != i} W_ij r_j and r_i is the exact solution of the local problem
   (W_ii, q_i', mu_i) (local.c). Warm-started from the r given. Stops when the natural-map
   residual divided by ||q|| (FCContactProblemResidual, Siconos 4.4's normalization) is at most
   -pgs_tol, or after -pgs_max_it sweeps.
   Options:
     -pgs_tol t            (> 0, default 1e-8)
     -pgs_max_it n         (>= 1, default 1000)
     -pgs_omega w          relaxation of each local update, r_i <- (1 - w) r_i + w r_i^local, then
                           projected on the cone (0 < w < 2, default 1: plain Gauss-Seidel)
     -pgs_proximal rho     proximal damping of the local problems: (W_ii + s I, q_i' - s r_i) with
                           s = rho tr(W_ii)/d_i. A fixed point is a solution of the original problem,
                           and the local problems stay well-posed when W_ii is (nearly) singular or
                           contacts are redundant (>= 0, default 0)
     -pgs_ranks auto|all|root|split
                           on several ranks: every rank solves the replicated problem (all, no
                           communication), rank 0 does and broadcasts the forces (root), or the
                           ranks split the sweeps, each its own block of contacts, damped Jacobi
                           between blocks (split: pgs_split.c; dense W, without NNCG). auto
                           (default): split from -pgs_split_min_rows rows on, and rank 0 goes on
                           from the split iterate when the split sweeps will not converge within
                           -pgs_split_max_it (judged from their rate every 16 sweeps: stacks, where
                           the Jacobi coupling stalls, and hard problems); smaller problems as
                           root, whose forces are the 1-rank solver's to round-off (a split
                           solution differs within the tolerance: on the impact hard case, 711
                           rows, the ball rose 1.1e-8 m after landing on 2 ranks, which
                           tests/test_hard_cases.py bounds by 1e-9 m). A solver with a per-sweep
                           update (the fast scheme's -fast_update sweep, collective) runs on every
                           rank; a sparse W is never split. Measured in docs/contact-solver.md
                           ("Split over the ranks")
     -pgs_split_min_rows n with auto: the smallest problem split (>= 1, default 900)
     -pgs_split_max_it n   with auto: the split sweeps before rank 0 takes over (>= 1, default 200)
     -pgs_split_damping t  with split or auto: each block takes t times its step, in (0, 1]
                           (default 0.8, measured on the 149k box and the cube:
                           docs/contact-solver.md)
     -pgs_acceleration none|nncg
                           nonsmooth nonlinear conjugate gradient on top of the sweeps (Silcowitz,
                           Niebe, Erleben 2010): after a sweep with step g = r_k+1 - r_k,
                           r += beta p, p = beta p + g, beta = |g|^2 / |g_prev|^2, restart when
                           beta > 1; the iterate is projected on the cones, and a step that does
                           not lower the residual is undone (back to the sweep's iterate, restart)
                           (default nncg: 2-5x fewer sweeps on the FCLIB problems,
                           docs/contact-solver.md)
     -pgs_dump_problem f.hdf5
                           write the first contact problem with at least -pgs_dump_rows rows
                           (default 1) in the FCLIB layout, for tools/bench_pgs, tools/fclib_solve
                           or Siconos (rank 0; contacts with friction and without cannot be mixed);
                           with -pgs_dump_unconverged, the first such problem the solver does not
                           converge on (the last linearization of the step), for a bug report
     -contact_solver auto|pgs|newton
                           pgs: the sweeps above; newton: rounds of sweeps, then nonsmooth Newton
                           steps on the Alart-Curnier function from their iterate, with an LU of
                           its n x n Jacobian and a line search (newton.c), for ill-conditioned
                           problems where the sweeps stall (mass and stiffness ratios); the same
                           residual and tolerance (-pgs_tol); solved on rank 0 (every rank with
                           -pgs_ranks all or the fast scheme's -fast_update sweep), never split.
                           auto (default): the sweeps, stopped once their rate (every 16 sweeps,
                           from the 64th) says they will not converge within -pgs_max_it, then
                           newton from the solve's warm start with the budget left; placed as pgs (split
                           sweeps, then rank 0, on large problems). A problem the sweeps converge
                           on steadily is solved as by pgs. docs/contact-solver.md
     -contact_newton_max_it n
                           with newton or auto: Newton steps at most (>= 1, default 300)
     -contact_newton_lu auto|dense|sparse
                           with newton or auto: the LU of a Newton step, LAPACK's dense one or
                           MUMPS' sparse one with W's block pattern; auto (default): sparse from
                           300 rows on where W's nonzero blocks hold at most 20 % of it
                           (newton_jacobian.c) */
#include "contactimpl.h"

typedef enum { PGS_AUTO, PGS_ALL, PGS_ROOT, PGS_SPLIT } PGSPlacement; /* -pgs_ranks, in this order */
static const char *const PGSPlacements[] = {"auto", "all", "root", "split"};
typedef enum { SOLVER_AUTO, SOLVER_PGS, SOLVER_NEWTON } SolverType; /* -contact_solver, in this order */
static const char *const SolverTypes[] = {"auto", "pgs", "newton"};

PetscErrorCode FCContactSolverCreate(MPI_Comm comm, FCContactSolver *solver)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(solver));
  (*solver)->comm           = comm;
  (*solver)->tol            = 1e-8;
  (*solver)->max_it         = 1000;
  (*solver)->omega          = 1.0;
  (*solver)->nncg           = PETSC_TRUE;
  (*solver)->placement      = PGS_AUTO; /* docs/contact-solver.md */
  (*solver)->dump_rows      = 1;
  (*solver)->split_damping  = 0.8;
  (*solver)->split_min_rows = 900;
  (*solver)->split_max_it   = 200;
  (*solver)->type           = SOLVER_AUTO; /* docs/contact-solver.md */
  (*solver)->newton_max_it  = 300;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverSetFromOptions(FCContactSolver s)
{
  PetscFunctionBegin;
  PetscOptionsBegin(s->comm, NULL, "Contact solver (projected Gauss-Seidel)", "FCContactSolver");
  PetscCall(FCOptionsReal(PetscOptionsObject, "-pgs_tol", "Stop when the natural-map residual / ||q|| is below this",
                          &s->tol, NULL));
  PetscCall(FCOptionsInt(PetscOptionsObject, "-pgs_max_it", "Maximum number of PGS sweeps", &s->max_it, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-pgs_omega", "Relaxation of the local updates (0, 2)", &s->omega, NULL));
  PetscCall(FCOptionsReal(PetscOptionsObject, "-pgs_proximal", "Proximal damping of the local problems (>= 0)",
                          &s->proximal, NULL));
  {
    const char *acc[] = {"none", "nncg"};
    PetscInt    a     = s->nncg ? 1 : 0; /* default nncg: docs/contact-solver.md */
    PetscCall(PetscOptionsEList("-pgs_acceleration", "Acceleration of the sweeps", NULL, acc, 2, acc[a], &a, NULL));
    s->nncg = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsEList("-pgs_ranks",
                              "Where the contact solver runs: by size, every rank, rank 0, or split by blocks", NULL,
                              PGSPlacements, 4, PGSPlacements[s->placement], &s->placement, NULL));
  if (s->placement == PGS_SPLIT || s->placement == PGS_AUTO)
    PetscCall(FCOptionsReal(PetscOptionsObject, "-pgs_split_damping",
                            "With -pgs_ranks split or auto: the fraction of each block's step taken (0, 1]",
                            &s->split_damping, NULL));
  if (s->placement == PGS_AUTO) {
    PetscCall(FCOptionsInt(PetscOptionsObject, "-pgs_split_min_rows",
                           "With -pgs_ranks auto: split the sweeps from this many rows on, below solve on rank 0",
                           &s->split_min_rows, NULL));
    PetscCall(FCOptionsInt(PetscOptionsObject, "-pgs_split_max_it",
                           "With -pgs_ranks auto: split sweeps before rank 0 takes over an unconverged solve",
                           &s->split_max_it, NULL));
  }
  PetscCall(PetscOptionsEList("-contact_solver",
                              "The contact solver: sweeps then Newton where they stall, projected Gauss-Seidel, or "
                              "nonsmooth Newton",
                              NULL, SolverTypes, 3, SolverTypes[s->type], &s->type, NULL));
  if (s->type != SOLVER_PGS) {
    const char *lus[] = {"auto", "dense", "sparse"};
    PetscCall(FCOptionsInt(PetscOptionsObject, "-contact_newton_max_it",
                           "Newton steps at most (-contact_solver auto or newton)", &s->newton_max_it, NULL));
    PetscCall(PetscOptionsEList("-contact_newton_lu",
                                "The LU of a Newton step: by W's fill, LAPACK's dense LU, or MUMPS' sparse LU", NULL,
                                lus, 3, lus[s->newton_lu], &s->newton_lu, NULL));
  }
  PetscCall(PetscOptionsString("-pgs_dump_problem", "Write a contact problem to this FCLIB file", NULL, s->dump,
                               s->dump, sizeof(s->dump), NULL));
  if (s->dump[0]) {
    PetscCall(FCOptionsInt(PetscOptionsObject, "-pgs_dump_rows", "Dump the first problem with at least this many rows",
                           &s->dump_rows, NULL));
    PetscCall(FCOptionsBool(PetscOptionsObject, "-pgs_dump_unconverged",
                            "Dump the first problem the solver does not converge on", &s->dump_unconverged, NULL));
    PetscCheck(s->dump_rows >= 1, s->comm, PETSC_ERR_USER_INPUT,
               "Option -pgs_dump_rows must be >= 1, got %" PetscInt_FMT, s->dump_rows);
  }
  PetscOptionsEnd();
  if (s->dump[0]) { /* the file can be created: an error now, on every rank, not at the first contact on rank 0 */
    PetscMPIInt rank;
    int         ok = 1;
    PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
    if (!rank) {
      FILE *f = fopen(s->dump, "w");
      ok      = f ? 1 : 0;
      if (f) fclose(f);
    }
    PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
    PetscCheck(ok, s->comm, PETSC_ERR_USER_INPUT, "Option -pgs_dump_problem: cannot create the file '%s'", s->dump);
  }
  PetscCheck(s->omega > 0.0 && s->omega < 2.0, s->comm, PETSC_ERR_USER_INPUT,
             "Option -pgs_omega must lie in (0, 2), got %g", (double)s->omega);
  PetscCheck(s->proximal >= 0.0, s->comm, PETSC_ERR_USER_INPUT, "Option -pgs_proximal must be >= 0, got %g",
             (double)s->proximal);
  PetscCheck(s->tol > 0.0, s->comm, PETSC_ERR_USER_INPUT, "Option -pgs_tol must be > 0, got %g", (double)s->tol);
  PetscCheck(s->split_damping > 0.0 && s->split_damping <= 1.0, s->comm, PETSC_ERR_USER_INPUT,
             "Option -pgs_split_damping must lie in (0, 1], got %g", (double)s->split_damping);
  PetscCheck(s->max_it >= 1, s->comm, PETSC_ERR_USER_INPUT, "Option -pgs_max_it must be >= 1, got %" PetscInt_FMT,
             s->max_it);
  PetscCheck(s->split_min_rows >= 1, s->comm, PETSC_ERR_USER_INPUT,
             "Option -pgs_split_min_rows must be >= 1, got %" PetscInt_FMT, s->split_min_rows);
  PetscCheck(s->newton_max_it >= 1, s->comm, PETSC_ERR_USER_INPUT,
             "Option -contact_newton_max_it must be >= 1, got %" PetscInt_FMT, s->newton_max_it);
  PetscCheck(s->split_max_it >= 1, s->comm, PETSC_ERR_USER_INPUT,
             "Option -pgs_split_max_it must be >= 1, got %" PetscInt_FMT, s->split_max_it);
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverSetUpdate(FCContactSolver s, FCContactSolverUpdateFn f, void *ctx)
{
  PetscFunctionBegin;
  s->update    = f;
  s->updatectx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverSetTolerances(FCContactSolver s, PetscReal tol, PetscInt max_it)
{
  PetscFunctionBegin;
  if (tol > 0) s->tol = tol;
  if (max_it > 0) s->max_it = max_it;
  PetscFunctionReturn(0);
}

/* One sweep over the contacts, in place (eq. 19). u = q + W r is kept current: contact i's local
   problem is (W_ii, u_i - W_ii r_i), and after it u += W[:, i] (r_i^new - r_i), the rows of
   contact i in W (W symmetric: every dense W) or in W^T, read once per sweep with unit stride. */
PetscErrorCode FCContactLocalUpdate(FCContactProblem p, PetscInt i, const PetscReal ui[], PetscReal omega,
                                    PetscReal proximal, PetscReal r[], PetscReal delta[], PetscBool *changed)
{
  PetscInt  d = p->dim[i], o = p->off[i];
  PetscReal qi[3], Wi[9], ri[3], *r0 = &r[o];

  PetscFunctionBegin;
  *changed = PETSC_FALSE;
  if (p->dormant && p->dormant[i]) {
    for (PetscInt a = 0; a < d; a++) delta[a] = 0.0;
    PetscFunctionReturn(0);
  }
  FCContactProblemDiagonalBlock(p, i, Wi);
  for (PetscInt a = 0; a < d; a++) {
    qi[a] = ui[a];
    for (PetscInt b = 0; b < d; b++) qi[a] -= Wi[a * d + b] * r0[b];
  }
  for (PetscInt a = 0; a < d; a++) ri[a] = r0[a];
  if (proximal > 0.0) { /* (W_ii + sigma I) r = -(q_i - sigma r_i): the same fixed points */
    PetscReal tr = 0.0, sigma;
    for (PetscInt a = 0; a < d; a++) tr += Wi[a * d + a];
    sigma = proximal * tr / d;
    for (PetscInt a = 0; a < d; a++) {
      Wi[a * d + a] += sigma;
      qi[a] -= sigma * r0[a];
    }
  }
  PetscCall(FCContactLocalSolve(d, Wi, qi, p->mu[i], ri, NULL));
  if (omega != 1.0) {
    PetscReal x[3];
    for (PetscInt a = 0; a < d; a++) x[a] = (1.0 - omega) * r0[a] + omega * ri[a];
    FCContactProjectCone(d, p->mu[i], x, ri);
  }
  for (PetscInt a = 0; a < d; a++) {
    delta[a] = ri[a] - r0[a];
    *changed = *changed || delta[a] != 0.0;
    r0[a]    = ri[a];
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Sweep(FCContactSolver s, FCContactProblem p, PetscReal r[], PetscReal u[])
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < p->nc; i++) {
    PetscReal delta[3];
    PetscBool changed;
    PetscCall(FCContactLocalUpdate(p, i, &u[p->off[i]], s->omega, s->proximal, r, delta, &changed));
    if (changed) FCContactProblemAddColumns(p, i, delta, u);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SolveSplit(FCContactSolver, FCContactProblem, PetscReal[]);
static PetscErrorCode SolveSplitThenRoot(FCContactSolver, FCContactProblem, PetscReal[]);
static PetscErrorCode SolveLazyHere(FCContactSolver, FCContactProblem, PetscReal[]);
static PetscErrorCode SolveLazy(FCContactSolver, FCContactProblem, PetscReal[],
                                PetscErrorCode (*)(FCContactSolver, FCContactProblem, PetscReal[]));

/* -pgs_dump_problem: rank 0 writes p; its failure (e.g. contacts with and without friction) stops every rank */
static PetscErrorCode Dump(FCContactSolver s, FCContactProblem p)
{
  PetscMPIInt    rank;
  PetscErrorCode werr = 0;

  FCContactProblem whole = NULL;
  PetscReal       *W     = NULL;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (p->rowcomm != MPI_COMM_NULL) PetscCall(FCContactProblemGatherWhole(p, &W, &whole)); /* by rows */
  if (!rank) {
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    werr = FCContactProblemWriteFCLIB(whole ? whole : p, s->dump);
    PetscCall(PetscPopErrorHandler());
  }
  PetscCall(FCContactProblemDestroy(&whole));
  PetscCall(PetscFree(W));
  PetscCallMPI(MPI_Bcast(&werr, 1, MPI_INT, 0, s->comm));
  PetscCheck(!werr, s->comm, PETSC_ERR_FILE_WRITE,
             "Option -pgs_dump_problem: could not write the contact problem to '%s' (FCLIB needs the same rows for "
             "every contact: all with friction or all without)",
             s->dump);
  s->dumped = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Rank 0 runs inner, the others wait for its forces, sweeps, residual and woken dormant contacts */
static PetscErrorCode OnRoot(FCContactSolver s, FCContactProblem p, PetscReal r[],
                             PetscErrorCode (*inner)(FCContactSolver, FCContactProblem, PetscReal[]))
{
  PetscMPIInt rank;
  PetscReal   info[3];

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (!rank) PetscCall((*inner)(s, p, r));
  info[0] = (PetscReal)s->sweeps;
  info[1] = s->residual;
  info[2] = (PetscReal)s->converged;
  PetscCallMPI(MPI_Bcast(info, 3, MPIU_REAL, 0, s->comm));
  PetscCallMPI(MPI_Bcast(r, (PetscMPIInt)p->n, MPIU_REAL, 0, s->comm));
  if (p->dormant) PetscCallMPI(MPI_Bcast(p->dormant, (PetscMPIInt)p->nc, MPIU_BOOL, 0, s->comm)); /* the woken */
  s->sweeps    = (PetscInt)info[0];
  s->residual  = info[1];
  s->converged = info[2] != 0.0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The solver of -contact_solver on this rank */
static PetscErrorCode Here(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscFunctionBegin;
  if (s->type == SOLVER_NEWTON)
    PetscCall(FCContactSolverNewton(s, p, r));
  else if (s->type == SOLVER_AUTO)
    PetscCall(FCContactSolverAuto(s, p, r));
  else
    PetscCall(FCContactSolverSweeps(s, p, r));
  PetscFunctionReturn(0);
}

static PetscErrorCode SolveLazyHere(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscFunctionBegin;
  PetscCall(SolveLazy(s, p, r, Here));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverRowBlock(FCContactSolver s, PetscInt nc, const PetscInt dim[], PetscBool *split,
                                       PetscInt *c0, PetscInt *c1)
{
  PetscMPIInt size, rank;
  PetscInt   *off, *cfirst;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PetscMalloc2(nc + 1, &off, size + 1, &cfirst));
  off[0] = 0;
  for (PetscInt i = 0; i < nc; i++) off[i + 1] = off[i] + dim[i];
  /* the choice of FCContactSolverSolve for a dense W */
  *split = (PetscBool)(size > 1 && !s->update && s->type != SOLVER_NEWTON &&
                       (s->placement == PGS_SPLIT || (s->placement == PGS_AUTO && off[nc] >= s->split_min_rows)));
  FCContactSplitBlocks(nc, off, size, cfirst);
  *c0 = *split ? cfirst[rank] : 0;
  *c1 = *split ? cfirst[rank + 1] : nc;
  PetscCall(PetscFree2(off, cfirst));
  PetscFunctionReturn(0);
}

/* Where the replicated problem is solved (-pgs_ranks): split over the ranks (split; auto from
   -pgs_split_min_rows rows), on every rank (all; on 1 rank; with a per-sweep update, which is
   collective), or on rank 0, which broadcasts the forces (root; auto below that size) */
PetscErrorCode FCContactSolverSolve(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscMPIInt size;
  PetscBool   splittable;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  if (s->dump[0] && !s->dump_unconverged && !s->dumped && p->n >= s->dump_rows) PetscCall(Dump(s, p));
  splittable = (PetscBool)(size > 1 && p->Wd && !s->update && s->type != SOLVER_NEWTON);
  PetscCheck(p->rowcomm == MPI_COMM_NULL ||
                 (splittable && (s->placement == PGS_SPLIT || (s->placement == PGS_AUTO && p->n >= s->split_min_rows))),
             s->comm, PETSC_ERR_ARG_WRONG,
             "A contact problem held by block rows needs split sweeps (FCContactSolverRowBlock says when)");
  if (splittable && s->placement == PGS_SPLIT)
    PetscCall(SolveLazy(s, p, r, SolveSplit));
  else if (splittable && s->placement == PGS_AUTO && p->n >= s->split_min_rows)
    PetscCall(SolveLazy(s, p, r, SolveSplitThenRoot));
  else if (s->placement == PGS_ALL || size == 1 || s->update)
    PetscCall(SolveLazy(s, p, r, Here));
  else
    PetscCall(OnRoot(s, p, r, SolveLazyHere));
  if (s->dump[0] && s->dump_unconverged && !s->dumped && !s->converged && p->n >= s->dump_rows) PetscCall(Dump(s, p));
  PetscFunctionReturn(0);
}

/* The sweeps, with u = q + W r carried along: the residual of the stopping test and NNCG's
   accept/undo decision come from (r, u) without a product with W. NNCG keeps W dir too (the change
   of u over a sweep is W times the sweep's step), so its step costs no product either. u is
   recomputed exactly (one product) every FC_PGS_EXACT sweeps, against the drift of the incremental
   updates, and before the solver stops. */
#define FC_PGS_EXACT 16
/* With s->giveup (-contact_solver auto), the sweeps stop, unconverged, from this many sweeps on, when
   the rate of the residual over the last FC_PGS_EXACT sweeps says they would not converge within max_it; before, NNCG's
   restarts make the rate noisy */
#define FC_PGS_GIVEUP 64
PetscErrorCode FCContactSolverSweeps(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscInt   n = p->n;
  PetscBool  exact;
  PetscReal *u, *rold = NULL, *uold = NULL, *dir = NULL, *wdir = NULL, *rsweep = NULL, *usweep = NULL, gg_old = 0.0;
  PetscReal  checkpoint = 0.0; /* the residual FC_PGS_EXACT sweeps ago (giveup) */

  PetscFunctionBegin;
  s->converged = PETSC_FALSE;
  s->sweeps    = 0;
  for (PetscInt k = 0; k < n; k++)
    PetscCheck(!PetscIsInfOrNanReal(r[k]), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Warm start of the contact solver has NaN/Inf");
  PetscCall(PetscMalloc1(n + 1, &u));
  PetscCall(FCContactProblemVelocity(p, r, u));
  exact       = PETSC_TRUE; /* u is W r + q, not carried */
  s->residual = FCContactProblemResidualFromVelocity(p, r, u);
  if (s->nncg)
    PetscCall(PetscCalloc6(n + 1, &rold, n + 1, &uold, n + 1, &dir, n + 1, &wdir, n + 1, &rsweep, n + 1, &usweep));
  while (s->residual > s->tol && s->sweeps < s->max_it) {
    PetscBool moved    = PETSC_FALSE;
    PetscReal previous = s->residual;
    if (s->nncg) {
      PetscCall(PetscArraycpy(rold, r, n));
      PetscCall(PetscArraycpy(uold, u, n));
    }
    PetscCall(Sweep(s, p, r, u));
    if (s->nncg) { /* NNCG: conjugate the sweep's step with the previous direction */
      PetscReal gg = 0.0, beta;
      for (PetscInt k = 0; k < n; k++) gg += PetscSqr(r[k] - rold[k]);
      beta = gg_old > 0.0 ? gg / gg_old : 2.0;
      if (beta > 1.0) /* restart */
        for (PetscInt k = 0; k < n; k++) {
          dir[k]  = r[k] - rold[k];
          wdir[k] = u[k] - uold[k];
        }
      else {
        PetscCall(PetscArraycpy(rsweep, r, n));
        PetscCall(PetscArraycpy(usweep, u, n));
        for (PetscInt k = 0; k < n; k++) {
          PetscReal g = r[k] - rold[k], wg = u[k] - uold[k];
          r[k] += beta * dir[k];
          u[k] += beta * wdir[k];
          dir[k]  = beta * dir[k] + g;
          wdir[k] = beta * wdir[k] + wg;
        }
        for (PetscInt i = 0; i < p->nc; i++) { /* back into the cones, u following */
          PetscInt  d = p->dim[i], o = p->off[i];
          PetscReal x[3], delta[3];
          PetscBool changed = PETSC_FALSE;
          for (PetscInt a = 0; a < d; a++) x[a] = r[o + a];
          FCContactProjectCone(d, p->mu[i], x, &r[o]);
          for (PetscInt a = 0; a < d; a++) {
            delta[a] = r[o + a] - x[a];
            changed  = changed || delta[a] != 0.0;
          }
          if (changed) FCContactProblemAddColumns(p, i, delta, u);
        }
        moved = PETSC_TRUE;
      }
      gg_old = gg;
    }
    s->sweeps++;
    exact = s->sweeps % FC_PGS_EXACT == 0 ? PETSC_TRUE : PETSC_FALSE;
    if (exact) PetscCall(FCContactProblemVelocity(p, r, u));
    s->residual = FCContactProblemResidualFromVelocity(p, r, u);
    if (moved && !(s->residual < previous)) { /* the step did not pay: back to the sweep's iterate, restart */
      PetscCall(PetscArraycpy(r, rsweep, n));
      PetscCall(PetscArraycpy(u, usweep, n));
      exact = PETSC_FALSE;
      for (PetscInt k = 0; k < n; k++) {
        dir[k]  = r[k] - rold[k];
        wdir[k] = u[k] - uold[k];
      }
      s->residual = FCContactProblemResidualFromVelocity(p, r, u);
    }
    if (s->update) { /* the caller re-linearizes at this iterate: a new problem, the same unknowns */
      PetscBool changed = PETSC_FALSE;
      PetscCall((*s->update)(s->updatectx, p, r, &changed));
      if (changed) {
        PetscCall(FCContactProblemVelocity(p, r, u));
        exact       = PETSC_TRUE;
        s->residual = FCContactProblemResidualFromVelocity(p, r, u);
        gg_old      = 0.0; /* NNCG restarts */
        checkpoint  = 0.0; /* and the rate is the new problem's */
      }
    }
    if (s->giveup && s->sweeps % FC_PGS_EXACT == 0) { /* residuals FC_PGS_EXACT sweeps apart: the sweeps still needed */
      PetscReal rate = checkpoint > 0.0 ? s->residual / checkpoint : 0.0;
      if (s->sweeps >= FC_PGS_GIVEUP && s->residual > s->tol &&
          (rate >= 1.0 ||
           s->sweeps + FC_PGS_EXACT * PetscLogReal(s->tol / s->residual) / PetscLogReal(rate) > s->max_it))
        break;
      checkpoint = s->residual;
    }
    if (s->residual <= s->tol && !exact) { /* converged on the carried u: confirm on the exact one */
      PetscCall(FCContactProblemVelocity(p, r, u));
      exact       = PETSC_TRUE;
      s->residual = FCContactProblemResidualFromVelocity(p, r, u);
    }
    PetscCheck(!PetscIsInfOrNanReal(s->residual), PETSC_COMM_SELF, PETSC_ERR_FP,
               "Contact solver diverged (NaN residual) after %" PetscInt_FMT " sweeps", s->sweeps);
  }
  if (!exact && s->residual > s->tol) { /* stopped by max_it: the exact residual */
    PetscCall(FCContactProblemVelocity(p, r, u));
    s->residual = FCContactProblemResidualFromVelocity(p, r, u);
  }
  if (s->nncg) PetscCall(PetscFree6(rold, uold, dir, wdir, rsweep, usweep));
  PetscCall(PetscFree(u));
  s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* -pgs_ranks split: every rank sweeps its own block (pgs_split.c) */
static PetscErrorCode SolveSplit(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscFunctionBegin;
  PetscCall(FCContactSolveSplit(s->comm, p, s->tol, s->max_it, s->omega, s->proximal, s->split_damping, PETSC_FALSE, r,
                                &s->sweeps, &s->residual));
  s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* -pgs_ranks auto on a large problem: at most -pgs_split_max_it split sweeps, which converge on FE
   contact zones in about as many sweeps as the replicated solver (docs/contact-solver.md); where
   they do not (the Jacobi coupling between blocks: multibody stacks; a hard FE problem that needs
   hundreds of sweeps), rank 0 goes on from the split iterate with the replicated sweeps and
   broadcasts the forces (a problem held by block rows is gathered whole on rank 0 for that). The split sweeps stop as
   soon as their rate says they would not converge within -pgs_split_max_it (pgs_split.c), so such a problem pays a few
   dozen of them, not all. Collective. */
static PetscErrorCode SolveSplitThenRoot(FCContactSolver s, FCContactProblem p, PetscReal r[])
{
  PetscInt  max_it = s->max_it, split_sweeps;
  PetscReal split_residual;

  PetscFunctionBegin;
  PetscCall(FCContactSolveSplit(s->comm, p, s->tol, PetscMin(max_it, s->split_max_it), s->omega, s->proximal,
                                s->split_damping, PETSC_TRUE, r, &s->sweeps, &s->residual));
  s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
  if (s->converged || s->sweeps >= max_it) PetscFunctionReturn(0);
  split_sweeps   = s->sweeps;
  split_residual = s->residual;
  s->max_it      = max_it - split_sweeps;
  if (p->rowcomm != MPI_COMM_NULL) { /* by rows: rank 0 goes on with W gathered whole */
    FCContactProblem whole;
    PetscReal       *W;
    PetscMPIInt      rank;
    PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
    PetscCall(FCContactProblemGatherWhole(p, &W, &whole));
    PetscCall(OnRoot(s, rank ? p : whole, r, Here));
    PetscCall(FCContactProblemDestroy(&whole));
    PetscCall(PetscFree(W));
  } else
    PetscCall(OnRoot(s, p, r, Here));
  s->max_it = max_it;
  s->sweeps += split_sweeps;
  PetscCall(PetscInfo(NULL,
                      "split sweeps: residual %g after %" PetscInt_FMT
                      " (not converging within -pgs_split_max_it); rank 0 went on: %" PetscInt_FMT
                      " sweeps in all, residual %g\n",
                      (double)split_residual, split_sweeps, s->sweeps, (double)s->residual));
  PetscFunctionReturn(0);
}

/* Dormant contacts (FCContactProblemSetDormant): nearly redundant constraints, such as the second
   pass of two-way FE-FE detection where the first pass already holds the vertex. Together with
   the constraints they duplicate they make W nearly singular, on which the sweeps crawl
   (docs/hard-cases.md, "stiffness contrast"); alone, the awake ones converge. So: the sweeps solve
   the awake contacts to the tolerance, with r_i = 0 on the dormant ones; a dormant contact whose
   normal gap u_n (u = W r + q, lengths) is then below -depth wakes, and the sweeps go on from
   there; it ends when none wakes. The residual is the awake contacts'; every dormant one carries
   no force and is left at most depth inside. The decisions depend only on the replicated problem,
   so every rank that runs this makes the same (split: all ranks, collectively). */
static PetscErrorCode SolveLazy(FCContactSolver s, FCContactProblem p, PetscReal r[],
                                PetscErrorCode (*inner)(FCContactSolver, FCContactProblem, PetscReal[]))
{
  PetscInt   total = 0, max_it = s->max_it, nwoke = 0, rounds = 0, nleft = 0;
  PetscReal *u, deepest = 0.0;
  PetscBool *dormant = p->dormant;

  PetscFunctionBegin;
  if (!dormant) {
    PetscCall((*inner)(s, p, r));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < p->nc; i++)
    if (dormant[i])
      for (PetscInt a = 0; a < p->dim[i]; a++) r[p->off[i] + a] = 0.0;
  PetscCall(PetscMalloc1(p->n + 1, &u));
  for (;;) {
    PetscInt woke = 0;
    s->max_it     = max_it - total;
    PetscCall((*inner)(s, p, r));
    total += s->sweeps;
    rounds++;
    PetscCall(FCContactProblemVelocity(p, r, u));
    deepest = 0.0;
    nleft   = 0;
    for (PetscInt i = 0; i < p->nc; i++) {
      if (!dormant[i]) continue;
      if (u[p->off[i]] < -p->wake) {
        dormant[i] = PETSC_FALSE;
        woke++;
      } else {
        nleft++;
        deepest = PetscMin(deepest, u[p->off[i]]);
      }
    }
    nwoke += woke;
    if (!woke || total >= max_it) break;
  }
  PetscCall(PetscFree(u));
  s->max_it    = max_it;
  s->sweeps    = total;
  s->converged = s->residual <= s->tol ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscInfo(NULL,
                      "dormant contacts: %" PetscInt_FMT " woke in %" PetscInt_FMT " rounds, %" PetscInt_FMT
                      " left dormant (deepest normal gap %g m), %" PetscInt_FMT " sweeps, residual %g\n",
                      nwoke, rounds, nleft, (double)deepest, total, (double)s->residual));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverGetConvergence(FCContactSolver s, PetscInt *sweeps, PetscReal *residual,
                                             PetscBool *converged)
{
  PetscFunctionBegin;
  if (sweeps) *sweeps = s->sweeps;
  if (residual) *residual = s->residual;
  if (converged) *converged = s->converged;
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverDestroy(FCContactSolver *s)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(0);
}
