/* An interruption during a library call that traps SIGTERM itself: METIS (GKlib turns the signal into
   its error return, METIS_ERROR, by a handler that it installs for the call; MUMPS orders with
   METIS). The executable blocks SIGINT and SIGTERM in every thread before MPI starts its own, and
   takes them in a thread of its own (FCSignalsBlock, src/util/signals.c): so METIS_NodeND, sent
   SIGTERM by another thread while it runs in a process with MPI's threads, completes, and the signal
   is recorded for the run to stop after its step. The same call in a process without that mode
   (a child, one thread) must fail, so that the test can see the difference. */
#include "util/util.h"
#include <metis.h>
#include <pthread.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#define NG 48 /* NG^3 vertices: METIS_NodeND runs longer than the 20 ms before the signal */

static void *Kill(void *arg)
{
  (void)arg;
  usleep(20000);
  kill(getpid(), SIGTERM);
  return NULL;
}

/* METIS_NodeND of the 7-point grid graph, SIGTERM sent to the process 20 ms after it starts */
static int Order(idx_t *xadj, idx_t *adj, idx_t n)
{
  idx_t    *perm = malloc(n * sizeof(idx_t)), *iperm = malloc(n * sizeof(idx_t)), opts[METIS_NOPTIONS];
  pthread_t th;
  int       err;

  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_NUMBERING] = 0;
  { /* the sending thread blocks SIGTERM, so that the process's signal is the main thread's (or, in
       the executable's mode, its waiting thread's): GKlib's longjmp from another thread would crash */
    sigset_t set, old;
    sigemptyset(&set);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, &old);
    pthread_create(&th, NULL, Kill, NULL);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
  }
  err = METIS_NodeND(&n, xadj, adj, NULL, opts, perm, iperm);
  pthread_join(th, NULL);
  free(perm);
  free(iperm);
  return err;
}

int main(int argc, char **argv)
{
  idx_t n = NG * NG * NG, *xadj = malloc((NG * NG * NG + 1) * sizeof(idx_t)), *adj = malloc(6 * n * sizeof(idx_t));
  idx_t k     = 0;
  int   fails = 0, err, st = 0;
  pid_t pid;

  for (idx_t i = 0; i < NG; i++)
    for (idx_t j = 0; j < NG; j++)
      for (idx_t l = 0; l < NG; l++) {
        idx_t v = (i * NG + j) * NG + l;
        xadj[v] = k;
        if (i > 0) adj[k++] = v - NG * NG;
        if (i < NG - 1) adj[k++] = v + NG * NG;
        if (j > 0) adj[k++] = v - NG;
        if (j < NG - 1) adj[k++] = v + NG;
        if (l > 0) adj[k++] = v - 1;
        if (l < NG - 1) adj[k++] = v + 1;
      }
  xadj[n] = k;
  /* without the mode: GKlib's handler takes the signal and METIS fails */
  pid = fork();
  if (!pid) {
    alarm(60); /* a hang is a failure (SIGALRM ends the child) */
    _exit(Order(xadj, adj, n) == METIS_ERROR ? 0 : 1);
  }
  waitpid(pid, &st, 0);
  printf("%s: without the executable's signal mode, METIS_NodeND sent SIGTERM returns METIS_ERROR (child %s %d)\n",
         WIFEXITED(st) && WEXITSTATUS(st) == 0 ? "PASS" : "FAIL", WIFEXITED(st) ? "exit" : "signal",
         WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
  fails += !(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  /* the executable's mode, MPI's threads started after it */
  alarm(120); /* a hang is a failure */
  if (FCSignalsBlock()) return 2;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(FCSignalsInstall());
  err = Order(xadj, adj, n);
  for (int w = 0; w < 100 && !FCSignalsCaught(); w++) usleep(10000); /* the waiting thread records it */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "%s: with it, METIS_NodeND completes (status %d, METIS_OK %d) and the signal is recorded "
                        "(%d, SIGTERM %d)\n",
                        err == METIS_OK && FCSignalsCaught() == SIGTERM ? "PASS" : "FAIL", err, METIS_OK,
                        FCSignalsCaught(), SIGTERM));
  fails += !(err == METIS_OK && FCSignalsCaught() == SIGTERM);
  free(xadj);
  free(adj);
  PetscCall(PetscFinalize());
  return fails ? 1 : 0;
}
