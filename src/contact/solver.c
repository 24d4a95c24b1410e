/* FCContactSolver: the contact solver of a scene, FC(W, q, mu) -> r (eq. 19). Its type
   (-contact_solver, a registry: pgs.c's sweeps, newton.c's Newton steps and auto) solves a problem
   on one rank; this file places that solve over the ranks (-pgs_ranks: every rank, rank 0 and a
   broadcast, or the sweeps split into blocks of contacts, pgs_split.c), runs the wake loop of the
   dormant contacts around it (SolveLazy) and dumps problems (-pgs_dump_problem). Each option is
   described by its help string here and in docs/options.md. */
#include "contactimpl.h"

typedef enum { PGS_AUTO, PGS_ALL, PGS_ROOT, PGS_SPLIT } PGSPlacement; /* -pgs_ranks, in this order */
static const char *const PGSPlacements[] = {"auto", "all", "root", "split"};

PetscFunctionList FCContactSolverList = NULL;

PetscErrorCode FCContactSolverRegister(const char name[], PetscErrorCode (*create)(FCContactSolver))
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&FCContactSolverList, name, create));
  PetscFunctionReturn(0);
}

/* The built-in types: a new type is one file with its create function, declared and registered here */
PETSC_INTERN PetscErrorCode FCContactSolverCreate_PGS(FCContactSolver);
PETSC_INTERN PetscErrorCode FCContactSolverCreate_Newton(FCContactSolver);
PETSC_INTERN PetscErrorCode FCContactSolverCreate_Auto(FCContactSolver);

PetscErrorCode FCContactSolverRegisterAll(void)
{
  PetscFunctionBegin;
  PetscCall(FCContactSolverRegister(FCCONTACTSOLVERAUTO, FCContactSolverCreate_Auto));
  PetscCall(FCContactSolverRegister(FCCONTACTSOLVERPGS, FCContactSolverCreate_PGS));
  PetscCall(FCContactSolverRegister(FCCONTACTSOLVERNEWTON, FCContactSolverCreate_Newton));
  PetscFunctionReturn(0);
}

/* The type's create function sets how it solves on one rank and whether its sweeps may be split */
static PetscErrorCode SetType(FCContactSolver s, const char type[])
{
  PetscErrorCode (*create)(FCContactSolver) = NULL;

  PetscFunctionBegin;
  PetscCall(FCRegistryFind(s->comm, FCContactSolverList, "contact solver", "-contact_solver", type,
                           (void (**)(void)) & create));
  PetscCall(PetscStrncpy(s->type, type, sizeof(s->type)));
  s->solve  = NULL;
  s->splits = s->newton = PETSC_FALSE;
  PetscCall((*create)(s));
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolverCreate(MPI_Comm comm, FCContactSolver *solver)
{
  PetscFunctionBegin;
  PetscCall(FCInitializePackage());
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
  (*solver)->newton_max_it  = 300;
  PetscCall(SetType(*solver, "auto")); /* docs/contact-solver.md */
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
    PetscCall(FCOptionsEList(PetscOptionsObject, "-pgs_acceleration", "Acceleration of the sweeps", acc, 2, &a, NULL));
    s->nncg = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(FCOptionsEList(PetscOptionsObject, "-pgs_ranks",
                           "Where the contact solver runs: by size, every rank, rank 0, or split by blocks",
                           PGSPlacements, 4, &s->placement, NULL));
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
  {
    char      type[FC_MAX_NAME];
    PetscBool set;
    PetscCall(PetscStrncpy(type, s->type, sizeof(type)));
    PetscCall(PetscOptionsFList("-contact_solver",
                                "The contact solver: auto (sweeps, then Newton where they stall), pgs (projected "
                                "Gauss-Seidel) or newton (nonsmooth Newton)",
                                "FCContactSolverRegister", FCContactSolverList, type, type, sizeof(type), &set));
    if (set) PetscCall(SetType(s, type));
  }
  if (s->newton) {
    const char *lus[] = {"auto", "dense", "sparse"};
    PetscCall(FCOptionsInt(PetscOptionsObject, "-contact_newton_max_it",
                           "Newton steps at most (-contact_solver auto or newton)", &s->newton_max_it, NULL));
    PetscCall(FCOptionsEList(PetscOptionsObject, "-contact_newton_lu",
                             "The LU of a Newton step: by W's fill, LAPACK's dense LU, or MUMPS' sparse LU", lus, 3,
                             &s->newton_lu, NULL));
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
  PetscCall((*s->solve)(s, p, r));
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
  *split = (PetscBool)(size > 1 && !s->update && s->splits &&
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
  splittable = (PetscBool)(size > 1 && p->Wd && !s->update && s->splits);
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
