/* The contact solver's sweeps split over the ranks (-pgs_ranks split, src/contact/pgs.c): each rank
   owns a contiguous block of contacts (balanced by rows; contacts are sorted by their reference
   position, so a block is a patch of the contact zone) and sweeps only those, Gauss-Seidel inside
   its block with the velocities of its own rows, u_b = q_b + W_b: r; between blocks the sweep is
   Jacobi: after each sweep the ranks exchange the forces of their blocks (one MPI_Allgatherv of
   the changed forces) and each adds to its u_b what the other blocks' changes did,
   W_b,other (r - r_prev), one pass over the off-block columns of its rows. Each block's step is damped
   (-pgs_split_damping theta: r_b <- r_b_prev + theta (r_b_swept - r_b_prev), a convex combination, so it stays in the
   cones) against the overshoot of blocks that all move at once. A sweep then costs n_b n flops per rank instead of n^2
   (the product with W of the replicated sweep, split p ways); the price is the Jacobi coupling between blocks, which
   can need more sweeps (docs/contact-solver.md measures both). The residual is the same natural-map residual as the
   replicated solver's, summed over the blocks (an MPI_Allreduce), so every rank stops at the same sweep with the same
   forces. Dense W only (what the schemes build), whole or held by block rows (each rank its block's,
   problem.c: the sweeps read no other); the stopping test and the exact recomputation of u every FC_PGS_EXACT
   sweeps follow the replicated solver. With giveup (-pgs_ranks auto) the exact residuals FC_SPLIT_EXACT sweeps apart
   give the rate of convergence, and the sweeps stop, unconverged, as soon as it says max_it will not be enough (the
   same decision on every rank: the residual is reduced). */
#include "contactimpl.h"
#include <petscblaslapack.h>

#define FC_SPLIT_EXACT 16

void FCContactSplitBlocks(PetscInt nc, const PetscInt off[], PetscMPIInt size, PetscInt cfirst[])
{
  PetscInt c = 0, n = off[nc];
  for (PetscMPIInt b = 0; b < size; b++) {
    cfirst[b] = c;
    while (c < nc && off[c] < (b + 1) * n / size) c++;
  }
  cfirst[size] = nc;
}

/* u_b = q_b + W_b: r for the rows [lo, hi): W row-major is W^T = W column-major, whose columns
   [lo, hi) are W's rows (one BLAS gemv, transposed); a problem by rows holds just these */
static PetscErrorCode BlockVelocity(FCContactProblem p, PetscInt lo, PetscInt hi, const PetscReal r[], PetscReal ub[])
{
  PetscBLASInt n, nb, one = 1;
  PetscReal    alpha = 1.0, beta = 1.0;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(p->n, &n));
  PetscCall(PetscBLASIntCast(hi - lo, &nb));
  for (PetscInt k = lo; k < hi; k++) ub[k - lo] = p->q[k];
  if (nb && n)
    PetscCallBLAS("BLASgemv",
                  BLASgemv_("T", &n, &nb, &alpha, FCContactProblemRow(p, lo), &n, r, &one, &beta, ub, &one));
  PetscFunctionReturn(0);
}

/* u_b += W_b,other dr: the off-block columns of the block's rows, [0, lo) and [hi, n), as two BLAS
   gemv on W^T (row-major W seen column-major): a hand loop would be a chain of dependent adds
   (no reassociation without -ffast-math), which gemv is not */
static PetscErrorCode AddOffBlock(FCContactProblem p, PetscInt lo, PetscInt hi, const PetscReal dr[], PetscReal ub[])
{
  PetscBLASInt n, nb, m0, m1, one = 1;
  PetscReal    alpha = 1.0, beta = 1.0;

  PetscFunctionBegin;
  PetscCall(PetscBLASIntCast(p->n, &n));
  PetscCall(PetscBLASIntCast(hi - lo, &nb));
  PetscCall(PetscBLASIntCast(lo, &m0));
  PetscCall(PetscBLASIntCast(p->n - hi, &m1));
  if (nb && m0)
    PetscCallBLAS("BLASgemv",
                  BLASgemv_("T", &m0, &nb, &alpha, FCContactProblemRow(p, lo), &n, dr, &one, &beta, ub, &one));
  if (nb && m1)
    PetscCallBLAS("BLASgemv", BLASgemv_("T", &m1, &nb, &alpha, FCContactProblemRow(p, lo) + hi, &n, dr + hi, &one,
                                        &beta, ub, &one));
  PetscFunctionReturn(0);
}

/* The natural-map residual / ||q|| of the whole problem: this block's contacts [c0, c1), summed
   over the blocks (every rank gets the same value, so all stop at the same sweep) */
static PetscErrorCode Residual(MPI_Comm comm, FCContactProblem p, PetscInt c0, PetscInt c1, PetscInt lo,
                               const PetscReal r[], const PetscReal ub[], PetscReal *residual)
{
  PetscReal sum = 0.0;

  PetscFunctionBegin;
  for (PetscInt i = c0; i < c1; i++) /* the awake contacts (a dormant one is checked by SolveLazy, pgs.c) */
    if (!p->dormant || !p->dormant[i])
      sum += FCContactNaturalMapError2(p->dim[i], p->mu[i], &r[p->off[i]], &ub[p->off[i] - lo]);
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, comm));
  *residual = PetscSqrtReal(sum) / PetscMax(p->qnorm, PETSC_MACHINE_EPSILON);
  PetscFunctionReturn(0);
}

PetscErrorCode FCContactSolveSplit(MPI_Comm comm, FCContactProblem p, PetscReal tol, PetscInt max_it, PetscReal omega,
                                   PetscReal proximal, PetscReal damping, PetscBool giveup, PetscReal r[],
                                   PetscInt *sweeps, PetscReal *residual)
{
  PetscMPIInt size, rank, *counts, *displs;
  PetscInt   *cfirst, c0, c1, lo, hi, nb, n = p->n;
  PetscReal  *ub, *rprev, *ustart, checkpoint = 0.0; /* giveup: the exact residual FC_SPLIT_EXACT sweeps ago */

  PetscFunctionBegin;
  PetscCheck(p->Wd, comm, PETSC_ERR_SUP, "Option -pgs_ranks split needs a dense W (the schemes' problems)");
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMalloc3(size + 1, &cfirst, size, &counts, size, &displs));
  { /* contiguous blocks of contacts, about n / size rows each */
    FCContactSplitBlocks(p->nc, p->off, size, cfirst);
    for (PetscMPIInt b = 0; b < size; b++) {
      counts[b] = (PetscMPIInt)(p->off[cfirst[b + 1]] - p->off[cfirst[b]]);
      displs[b] = (PetscMPIInt)p->off[cfirst[b]];
    }
  }
  { /* one non-empty block is plain Gauss-Seidel: nothing to damp */
    PetscInt nonempty = 0;
    for (PetscMPIInt b = 0; b < size; b++) nonempty += cfirst[b + 1] > cfirst[b];
    if (nonempty < 2) damping = 1.0;
  }
  c0 = cfirst[rank];
  c1 = cfirst[rank + 1];
  PetscCheck(p->rowcomm == MPI_COMM_NULL || (p->c0 == c0 && p->c1 == c1), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
             "The contact problem holds the rows of contacts [%" PetscInt_FMT ", %" PetscInt_FMT
             ") on this rank, the split sweeps need [%" PetscInt_FMT ", %" PetscInt_FMT ") (FCContactSolverRowBlock)",
             p->c0, p->c1, c0, c1);
  lo = p->off[c0];
  hi = p->off[c1];
  nb = hi - lo;
  PetscCall(PetscMalloc3(nb + 1, &ub, n + 1, &rprev, nb + 1, &ustart));
  PetscCall(BlockVelocity(p, lo, hi, r, ub));
  PetscCall(Residual(comm, p, c0, c1, lo, r, ub, residual));
  *sweeps = 0;
  while (*residual > tol && *sweeps < max_it) {
    PetscCall(PetscArraycpy(rprev, r, n));
    PetscCall(PetscArraycpy(ustart, ub, nb));
    for (PetscInt i = c0; i < c1; i++) { /* Gauss-Seidel inside the block */
      PetscInt  d = p->dim[i], o = p->off[i];
      PetscReal delta[3];
      PetscBool changed;
      PetscCall(FCContactLocalUpdate(p, i, &ub[o - lo], omega, proximal, r, delta, &changed));
      if (changed) { /* u_b += W_b,i delta: the rows of contact i restricted to the block (W symmetric) */
        const PetscReal *w = FCContactProblemRow(p, o) + lo;
        if (d == 3)
          FCContactAddRows3(nb, w, w + n, w + 2 * n, delta[0], delta[1], delta[2], ub);
        else
          for (PetscInt a = 0; a < d; a++)
            FCContactAddRows3(nb, w + a * n, w + a * n, w + a * n, delta[a], 0.0, 0.0, ub);
      }
    }
    if (damping != 1.0) /* r_b and u_b moved by damping times the block's step (a convex combination: in the cones) */
      for (PetscInt k = lo; k < hi; k++) {
        r[k]       = rprev[k] + damping * (r[k] - rprev[k]);
        ub[k - lo] = ustart[k - lo] + damping * (ub[k - lo] - ustart[k - lo]);
      }
    /* Jacobi between blocks: every block's new forces to every rank, and their effect on u_b */
    PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, r, counts, displs, MPIU_REAL, comm));
    (*sweeps)++;
    if (*sweeps % FC_SPLIT_EXACT == 0) {
      PetscCall(BlockVelocity(p, lo, hi, r, ub));
      if (giveup) { /* from the exact residuals FC_SPLIT_EXACT sweeps apart: the sweeps still needed */
        PetscReal now, rate;
        PetscCall(Residual(comm, p, c0, c1, lo, r, ub, &now));
        rate = checkpoint > 0.0 ? now / checkpoint : 0.0;
        if (checkpoint > 0.0 && now > tol &&
            (rate >= 1.0 || *sweeps + FC_SPLIT_EXACT * PetscLogReal(tol / now) / PetscLogReal(rate) > max_it)) {
          *residual = now;
          break;
        }
        checkpoint = now;
      }
    } else {
      for (PetscInt j = 0; j < n; j++) rprev[j] = r[j] - rprev[j];
      PetscCall(AddOffBlock(p, lo, hi, rprev, ub));
    }
    PetscCall(Residual(comm, p, c0, c1, lo, r, ub, residual));
    if (*residual <= tol && *sweeps % FC_SPLIT_EXACT) { /* converged on the carried u: confirm on the exact one */
      PetscCall(BlockVelocity(p, lo, hi, r, ub));
      PetscCall(Residual(comm, p, c0, c1, lo, r, ub, residual));
    }
    PetscCheck(!PetscIsInfOrNanReal(*residual), comm, PETSC_ERR_FP,
               "Contact solver (-pgs_ranks split) diverged (NaN residual) after %" PetscInt_FMT " sweeps", *sweeps);
  }
  if (*residual > tol && *sweeps % FC_SPLIT_EXACT) { /* stopped by max_it: the exact residual */
    PetscCall(BlockVelocity(p, lo, hi, r, ub));
    PetscCall(Residual(comm, p, c0, c1, lo, r, ub, residual));
  }
  PetscCall(PetscFree3(ub, rprev, ustart));
  PetscCall(PetscFree3(cfirst, counts, displs));
  PetscFunctionReturn(0);
}
