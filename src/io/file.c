/* file.c: result files written atomically: the ".part" protocol (begin, open, close, commit, abandon), its clean-up on
   a signal or an error exit, and the check before any work that each file of a run can be written. */
#include "io/ioimpl.h"
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/statvfs.h>
#include <unistd.h>

/* Every result file is written to "<name>.part" and renamed once complete: a failed or killed run leaves
   the previous result intact and never a half-written file under the final name.
   The files of a run are registered before any work (registry.c, SgFileCheckWritable): a registered name may be
   written elsewhere (SgFileResolve: the target of a symbolic link, or a device written directly). */

/* ".part" files being written: removed by SgFileCleanup on a signal or an error exit (async-signal-safe: static
   storage, unlink only). */
#define SG_PENDING_MAX 16
static char                  Pending[SG_PENDING_MAX][PETSC_MAX_PATH_LEN];
static volatile sig_atomic_t PendingUsed[SG_PENDING_MAX];

static void PendingAdd(const char tmp[])
{
  for (int i = 0; i < SG_PENDING_MAX; i++)
    if (!PendingUsed[i]) {
      size_t n = strlen(tmp);
      if (n > PETSC_MAX_PATH_LEN - 1) n = PETSC_MAX_PATH_LEN - 1;
      memcpy(Pending[i], tmp, n);
      Pending[i][n]  = 0;
      PendingUsed[i] = 1;
      return;
    }
}

static void PendingRemove(const char tmp[])
{
  for (int i = 0; i < SG_PENDING_MAX; i++)
    if (PendingUsed[i] && !strcmp(Pending[i], tmp)) PendingUsed[i] = 0;
}

/* Remove every ".part" file still being written (called from signal handlers and at exit). */
void SgFileCleanup(void)
{
  for (int i = 0; i < SG_PENDING_MAX; i++)
    if (PendingUsed[i]) {
      (void)unlink(Pending[i]);
      PendingUsed[i] = 0;
    }
}

static struct sigaction      OldAction[2];
static const int             CaughtSignals[2] = {SIGINT, SIGTERM};
static volatile sig_atomic_t Dying            = 0;

/* SIGINT, SIGTERM: remove the ".part" files, then let the handler that was there before (PETSc's, or the default)
   end the process as it would have. The signal may run on another thread (MPI's progress threads) while the main
   thread goes on: Dying stops it from starting a new ".part" file, and the signal is unblocked before it is raised
   again, so that the process ends at once. */
static void SignalCleanup(int sig)
{
  sigset_t set;

  Dying = 1;
  SgFileCleanup();
  for (int i = 0; i < 2; i++)
    if (CaughtSignals[i] == sig) {
      (void)sigaction(sig, &OldAction[i], NULL);
      (void)sigemptyset(&set);
      (void)sigaddset(&set, sig);
      (void)pthread_sigmask(SIG_UNBLOCK, &set, NULL);
      (void)raise(sig);
    }
  /* the handler before ours returned (PETSc's, run on an MPI progress thread, may print and return): the process
     still has to end, or the main thread waits in SgFileBegin for ever (seen in the suite's killed runs) */
  _exit(128 + sig);
}

PetscErrorCode SgFileInstallCleanup(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0); /* a second call would chain our handler to itself */
  done = PETSC_TRUE;
  for (int i = 0; i < 2; i++) {
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = SignalCleanup;
    sigemptyset(&sa.sa_mask);
    PetscCheck(!sigaction(CaughtSignals[i], &sa, &OldAction[i]), PETSC_COMM_SELF, PETSC_ERR_SYS, "cannot install the handler of signal %d: %s", CaughtSignals[i], strerror(errno));
  }
  /* an error returned from main (PETSc's error path) also ends with no ".part" left */
  PetscCheck(!atexit(SgFileCleanup), PETSC_COMM_SELF, PETSC_ERR_SYS, "atexit failed");
  PetscFunctionReturn(0);
}

PetscErrorCode SgFileTmpName(const char name[], char tmp[], size_t len)
{
  const char *path;
  PetscBool   direct;

  PetscFunctionBeginUser;
  SgFileResolve(name, &path, &direct);
  if (direct) PetscCall(PetscStrncpy(tmp, path, len));
  else PetscCall(PetscSNPrintf(tmp, len, "%s.part", path));
  PetscFunctionReturn(0);
}

/* Note that the temporary file of name is being written (rank-local; removed on a signal or an error exit). */
PetscErrorCode SgFileBegin(const char name[])
{
  const char *path;
  PetscBool   direct;
  char        tmp[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  SgFileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0);
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  while (Dying) pause(); /* a signal is ending the process: start no new file */
  PendingAdd(tmp);
  PetscFunctionReturn(0);
}

PetscErrorCode SgFileCommit(MPI_Comm comm, const char name[])
{
  PetscMPIInt rank;
  char        tmp[PETSC_MAX_PATH_LEN];
  const char *path;
  PetscBool   direct;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Barrier(comm));
  SgFileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  if (rank == 0 && rename(tmp, path)) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  if (err && rank == 0) (void)unlink(tmp);
  PendingRemove(tmp);
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s: %s", tmp, path, strerror(err));
  PetscFunctionReturn(0);
}

/* Remove a temporary file left by a failed write (rank 0; the other ranks only forget it). */
PetscErrorCode SgFileAbandon(MPI_Comm comm, const char name[])
{
  PetscMPIInt rank;
  char        tmp[PETSC_MAX_PATH_LEN];
  const char *path;
  PetscBool   direct;

  PetscFunctionBeginUser;
  SgFileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  if (rank == 0) (void)unlink(tmp);
  PendingRemove(tmp);
  PetscFunctionReturn(0);
}

/* The directory of path (its file system is asked for the free space): "." for a bare name, "/" for a file in it. */
void SgFileDirectory(const char path[], char dir[PETSC_MAX_PATH_LEN])
{
  char *slash;

  strncpy(dir, path, PETSC_MAX_PATH_LEN - 1);
  dir[PETSC_MAX_PATH_LEN - 1] = 0;
  slash                       = strrchr(dir, '/');
  if (slash) *(slash == dir ? slash + 1 : slash) = 0;
  else strcpy(dir, ".");
}

/* The cause of a failed write, for the message: errno if it says something, else a full file system. */
const char *SgFileErrorCause(int err, const char path[])
{
  struct statvfs sv;
  char           dir[PETSC_MAX_PATH_LEN];

  if (err == ENOSPC) return "no space left on device";
  if (err && err != EIO) return strerror(err);
  SgFileDirectory(path, dir);
  if (!statvfs(dir, &sv) && sv.f_bavail == 0) return "no space left on device";
  return err ? strerror(err) : "the HDF5 library reported a write error";
}

/* Open the file to write for name ("<name>.part", or a device directly) on rank 0 (NULL elsewhere); an error names
   the option that gave the file. */
PetscErrorCode SgFileOpen(MPI_Comm comm, const char option[], const char name[], FILE **fp)
{
  PetscMPIInt rank;
  char        tmp[PETSC_MAX_PATH_LEN];
  int         err = 0;

  PetscFunctionBeginUser;
  *fp = NULL;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  if (rank == 0) {
    PetscCall(SgFileBegin(name));
    *fp = fopen(tmp, "w");
    if (!*fp) {
      err = errno;
      PendingRemove(tmp);
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "%s: cannot write '%s': %s", option, name, strerror(err));
  PetscFunctionReturn(0);
}

/* Close the file; then commit (rename the .part), keep the .part for a later SgFileCommit, or abandon (remove) it.
   A write error always removes it. */
PetscErrorCode SgFileFinish(MPI_Comm comm, const char name[], FILE **fp, SgFileEnd end)
{
  int         err = 0;
  const char *path, *cause;
  PetscBool   direct;

  PetscFunctionBeginUser;
  if (*fp) {
    errno = 0;
    if (fflush(*fp) || ferror(*fp)) err = errno ? errno : EIO;
    if (fclose(*fp) && !err) err = errno;
    *fp = NULL;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm));
  SgFileResolve(name, &path, &direct);
  cause = err ? SgFileErrorCause(err, path) : NULL; /* before the .part is removed (and the space freed) */
  if (err || end == SG_FILE_ABANDON) PetscCall(SgFileAbandon(comm, name));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "error writing '%s': %s", name, cause);
  if (end == SG_FILE_COMMIT) PetscCall(SgFileCommit(comm, name));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFileClose(MPI_Comm comm, const char name[], FILE **fp)
{
  PetscFunctionBeginUser;
  PetscCall(SgFileFinish(comm, name, fp, SG_FILE_COMMIT));
  PetscFunctionReturn(0);
}

static PetscBool OptionIsHDF5(const char option[])
{
  return (PetscBool)(!strcmp(option, "-output_file") || !strcmp(option, "-checkpoint_file") || !strcmp(option, "-restart_file"));
}

/* Fail early (before any solve) if an output location cannot be written, is not ours to replace, or is named twice. */
PetscErrorCode SgFileCheckWritable(MPI_Comm comm, const char option[], const char name[])
{
  FILE       *fp;
  PetscBool   direct;
  const char *path;

  PetscFunctionBeginUser;
  PetscCheck(comm != MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SgFileCheckWritable: the communicator is MPI_COMM_NULL");
  PetscCheck(option && option[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgFileCheckWritable: argument 2 (the option naming the file) is NULL or empty");
  if (!name) name = ""; /* no file */
  PetscCall(SgFileRegister(comm, option, name, PETSC_FALSE, OptionIsHDF5(option)));
  if (!strcmp(option, "-output_file")) {
    char xname[PETSC_MAX_PATH_LEN + 8];
    PetscCall(SgOutputXdmfName(name, xname, sizeof(xname)));
    PetscCall(SgFileRegister(comm, "-output_file (its .xmf file)", name[0] ? xname : NULL, PETSC_FALSE, PETSC_FALSE));
  }
  if (!name[0]) PetscFunctionReturn(0);
  SgFileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0); /* opening a FIFO would wait for its reader; access() was checked */
  PetscCall(SgFileOpen(comm, option, name, &fp));
  PetscCall(SgFileFinish(comm, name, &fp, SG_FILE_ABANDON));
  PetscFunctionReturn(0);
}

/* Register an input file (read by the run), so that no result names it. */
PetscErrorCode SgFileCheckInput(MPI_Comm comm, const char option[], const char name[])
{
  PetscFunctionBeginUser;
  PetscCheck(comm != MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SgFileCheckInput: the communicator is MPI_COMM_NULL");
  PetscCheck(option && option[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgFileCheckInput: argument 2 (the option naming the file) is NULL or empty");
  PetscCall(SgFileRegister(comm, option, name, PETSC_TRUE, OptionIsHDF5(option)));
  PetscFunctionReturn(0);
}
