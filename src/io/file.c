/* file.c: result files written atomically: the ".part" protocol (begin, open, close, commit, abandon), its clean-up on
   a signal or an error exit, and the check before any work that each file of a run can be written. */
#include "io/ioimpl.h"
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

/* Every result file is written to "<name>.part" (an HDF5 file: "<name>.<tag>.part", SgFileBeginHDF5) and renamed once
   complete: a failed or killed run leaves the previous result intact and never a half-written file under the final
   name.
   The files of a run are registered before any work (registry.c, SgFileCheckWritable): a registered name may be
   written elsewhere (SgFileResolve: the target of a symbolic link, or a device written directly). */

/* ".part" files being written, with the file each becomes: removed by SgFileCleanup on a signal or an error exit
   (async-signal-safe: static storage, unlink only); SgFileCommit and SgFileAbandon find a file's temporary name here. */
#define SG_PENDING_MAX 16
static char                  Pending[SG_PENDING_MAX][PETSC_MAX_PATH_LEN];
static char                  PendingPath[SG_PENDING_MAX][PETSC_MAX_PATH_LEN];
static volatile sig_atomic_t PendingUsed[SG_PENDING_MAX];

static PetscBool PendingAdd(const char path[], const char tmp[])
{
  for (int i = 0; i < SG_PENDING_MAX; i++)
    if (!PendingUsed[i]) {
      size_t n = strlen(tmp);
      if (n > PETSC_MAX_PATH_LEN - 1) n = PETSC_MAX_PATH_LEN - 1;
      memcpy(Pending[i], tmp, n);
      Pending[i][n] = 0;
      strncpy(PendingPath[i], path, PETSC_MAX_PATH_LEN - 1);
      PendingPath[i][PETSC_MAX_PATH_LEN - 1] = 0;
      PendingUsed[i]                         = 1;
      return PETSC_TRUE;
    }
  return PETSC_FALSE;
}

static void PendingRemove(const char tmp[])
{
  for (int i = 0; i < SG_PENDING_MAX; i++)
    if (PendingUsed[i] && !strcmp(Pending[i], tmp)) PendingUsed[i] = 0;
}

/* the temporary file of path being written on this rank, or NULL */
static const char *PendingFind(const char path[])
{
  for (int i = 0; i < SG_PENDING_MAX; i++)
    if (PendingUsed[i] && !strcmp(PendingPath[i], path)) return Pending[i];
  return NULL;
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

/* The temporary file of name: the one being written (SgFileBegin, SgFileBeginHDF5), else "<name>.part" (a device is
   written directly). */
PetscErrorCode SgFileTmpName(const char name[], char tmp[], size_t len)
{
  const char *path, *pending;
  PetscBool   direct;

  PetscFunctionBeginUser;
  SgFileResolve(name, &path, &direct);
  pending = direct ? NULL : PendingFind(path);
  if (direct) PetscCall(PetscStrncpy(tmp, path, len));
  else if (pending) PetscCall(PetscStrncpy(tmp, pending, len));
  else PetscCall(PetscSNPrintf(tmp, len, "%s.part", path));
  PetscFunctionReturn(0);
}

static PetscErrorCode BeginTmp(const char path[], const char tmp[])
{
  PetscFunctionBeginUser;
  while (Dying) pause(); /* a signal is ending the process: start no new file */
  PetscCheck(PendingAdd(path, tmp), PETSC_COMM_SELF, PETSC_ERR_SUP, "cannot write '%s': %d result files are being written already (the most at once)", path, SG_PENDING_MAX);
  PetscFunctionReturn(0);
}

/* Note that the temporary file of name ("<name>.part") is being written (rank-local; removed on a signal or an error
   exit). */
PetscErrorCode SgFileBegin(const char name[])
{
  const char *path;
  PetscBool   direct;
  char        tmp[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  SgFileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
  PetscCall(BeginTmp(path, tmp));
  PetscFunctionReturn(0);
}

/* Begin an HDF5 file of name on comm (collective): its temporary file is "<name>.<tag>.part", with a tag new for each
   write, the same on every rank (rank 0's, broadcast). OpenMPI's MPI-IO (OMPIO, sharedfp/sm) guards every file it
   opens with a POSIX semaphore named after the file's base name alone, "OMPIO_<base name>", in /dev/shm, shared by
   every process of the machine: a process that dies between the semaphore's wait and post leaves it taken, and every
   later open of a file of that base name then waits for ever (a killed run of the test suite hung every later run
   writing a checkpoint "ck.h5"). A base name of its own for each write never meets such a semaphore again. */
/* a tag of 8 hex digits for a new file name: this process's id, the clock and a count of the tags made */
static unsigned NewTag(void)
{
  static unsigned count = 0;
  struct timespec ts;

  (void)clock_gettime(CLOCK_REALTIME, &ts);
  return (unsigned)getpid() * 2654435761u ^ (unsigned)ts.tv_nsec ^ ((unsigned)ts.tv_sec << 9) ^ (++count * 0x9e3779b9u);
}

PetscErrorCode SgFileBeginHDF5(MPI_Comm comm, const char name[], char tmp[], size_t len)
{
  const char *path;
  PetscBool   direct;
  PetscMPIInt rank;
  unsigned    tag = 0;

  PetscFunctionBeginUser;
  SgFileResolve(name, &path, &direct);
  if (direct) {
    PetscCall(PetscStrncpy(tmp, path, len));
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) tag = NewTag();
  PetscCallMPI(MPI_Bcast(&tag, 1, MPI_UNSIGNED, 0, comm));
  PetscCall(PetscSNPrintf(tmp, len, "%s.%08x.part", path, tag));
  PetscCall(BeginTmp(path, tmp));
  PetscFunctionReturn(0);
}

/* The name this rank opens an HDF5 file to be read under (rank-local). OMPIO's semaphore (SgFileBeginHDF5) is taken
   by the open of a file read too: a run killed while it opened its restart file "ck.h5" would hold every later run
   reading "ck.h5". The file is opened through a symbolic link of its own, "<dir>/.<base name>.<tag>.read", made here:
   *made says so, and SgFileReadAliasEnd removes the link once the file is open (a signal or an error exit before
   removes it too). No link (*made false, alias = path): the directory is not writable, the file system has no
   symbolic links, or the link's name would be longer than maxlen (the longest name HDF5 may open here). */
PetscErrorCode SgFileReadAliasBegin(const char path[], size_t maxlen, char alias[], size_t len, PetscBool *made)
{
  const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
  const int   dl = slash ? (int)(slash - path) + 1 : 0;

  PetscFunctionBeginUser;
  *made = PETSC_FALSE;
  PetscCall(PetscStrncpy(alias, path, len));
  if (!base[0] || strlen(path) + strlen("/..XXXXXXXX.read") > PetscMin(maxlen, len - 1)) PetscFunctionReturn(0);
  while (Dying) pause();                  /* a signal is ending the process: make no new link */
  for (int k = 0; k < 4 && !*made; k++) { /* another tag if the name is taken */
    PetscCall(PetscSNPrintf(alias, len, "%.*s.%s.%08x.read", dl, path, base, NewTag()));
    if (!PendingAdd(alias, alias)) break;
    if (!symlink(base, alias)) *made = PETSC_TRUE;
    else PendingRemove(alias);
    if (!*made && errno != EEXIST) break;
  }
  if (!*made) PetscCall(PetscStrncpy(alias, path, len));
  PetscFunctionReturn(0);
}

/* Remove the link SgFileReadAliasBegin made (the file opened through it stays open). */
PetscErrorCode SgFileReadAliasEnd(const char alias[])
{
  PetscFunctionBeginUser;
  (void)unlink(alias);
  PendingRemove(alias);
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
