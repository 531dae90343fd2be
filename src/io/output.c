/* output.c: result files written atomically: HDF5 fields + XDMF for ParaView, the JSON summary, CSV tables. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>
#include <errno.h>
#include <pthread.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

/* Every result file is written to "<name>.part" and renamed once complete: a failed or killed run leaves
   the previous result intact and never a half-written file under the final name.

   The result and input files of a run are registered here before any work (SgFileCheckWritable, SgFileCheckInput):
   that refuses names too long for the libraries, files that are not regular files where a rename would replace
   them, and two options naming the same file. A registered name may differ from the file written:
   - a symbolic link to a regular file is written through: "<target>.part", renamed onto the target (the link stays);
   - a character device or FIFO (text results only) is written directly, without a ".part" and a rename. */
typedef struct {
  char      option[64];
  char      name[PETSC_MAX_PATH_LEN]; /* as given */
  char      path[PETSC_MAX_PATH_LEN]; /* the file written: name, or the target of a symbolic link */
  char      key[PATH_MAX + NAME_MAX + 2]; /* realpath of the directory + "/" + base name of path */
  PetscBool direct, input, exists;
  dev_t     dev;
  ino_t     ino;
} SgFileEntry;

#define SG_FILE_MAX 48
static SgFileEntry FileTable[SG_FILE_MAX];
static int         FileCount = 0;

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
      Pending[i][n] = 0;
      PendingUsed[i]                     = 1;
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

static struct sigaction    OldAction[2];
static const int           CaughtSignals[2] = {SIGINT, SIGTERM};
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

static SgFileEntry *FileFind(const char name[])
{
  for (int i = 0; i < FileCount; i++)
    if (!strcmp(FileTable[i].name, name) && !FileTable[i].input) return &FileTable[i];
  return NULL;
}

/* The file written for a result name (the target of a symbolic link), and whether it is written directly. */
static void FileResolve(const char name[], const char **path, PetscBool *direct)
{
  const SgFileEntry *e = FileFind(name);
  *path                = e ? e->path : name;
  *direct              = e ? e->direct : PETSC_FALSE;
}

PetscErrorCode SgFileTmpName(const char name[], char tmp[], size_t len)
{
  const char *path;
  PetscBool   direct;

  PetscFunctionBeginUser;
  FileResolve(name, &path, &direct);
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
  FileResolve(name, &path, &direct);
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
  FileResolve(name, &path, &direct);
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
  FileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  if (rank == 0) (void)unlink(tmp);
  PendingRemove(tmp);
  PetscFunctionReturn(0);
}

/* The cause of a failed write, for the message: errno if it says something, else a full file system. */
const char *SgFileErrorCause(int err, const char path[])
{
  struct statvfs sv;
  char           dir[PETSC_MAX_PATH_LEN];
  char          *slash;

  if (err == ENOSPC) return "no space left on device";
  if (err && err != EIO) return strerror(err);
  strncpy(dir, path, sizeof(dir) - 1);
  dir[sizeof(dir) - 1] = 0;
  slash                = strrchr(dir, '/');
  if (slash) *(slash == dir ? slash + 1 : slash) = 0;
  else strcpy(dir, ".");
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
typedef enum { FILE_ABANDON, FILE_COMMIT, FILE_KEEP } FileEnd;
static PetscErrorCode FileFinish(MPI_Comm comm, const char name[], FILE **fp, FileEnd end)
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
  FileResolve(name, &path, &direct);
  cause = err ? SgFileErrorCause(err, path) : NULL; /* before the .part is removed (and the space freed) */
  if (err || end == FILE_ABANDON) PetscCall(SgFileAbandon(comm, name));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "error writing '%s': %s", name, cause);
  if (end == FILE_COMMIT) PetscCall(SgFileCommit(comm, name));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFileClose(MPI_Comm comm, const char name[], FILE **fp)
{
  PetscFunctionBeginUser;
  PetscCall(FileFinish(comm, name, fp, FILE_COMMIT));
  PetscFunctionReturn(0);
}

/* OpenMPI's OMPIO (sharedfp/lockedfile) formats "<name>.locktest.<rank>" into a 256-byte buffer when HDF5 opens a
   file through MPI-IO and aborts the process beyond ("buffer overflow detected"): the longest file name HDF5 may be
   given on a communicator of size ranks. */
PetscErrorCode SgFileHDF5NameMax(MPI_Comm comm, size_t *len)
{
  PetscMPIInt size;
  size_t      digits = 1;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  for (PetscMPIInt r = size - 1; r >= 10; r /= 10) digits++;
  *len = 255 - strlen(".locktest.") - digits;
  PetscFunctionReturn(0);
}

static const char *FileTypeName(mode_t m)
{
  if (S_ISDIR(m)) return "a directory";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

/* Fill an entry (on rank 0: the file system is looked at there; the verdict is broadcast). Returns a message in msg
   (empty: fine). */
static void FileInspect(SgFileEntry *e, PetscBool hdf5, size_t h5max, char msg[], size_t len)
{
  struct stat st, lst;
  char        dir[PETSC_MAX_PATH_LEN], rdir[PATH_MAX];
  const char *base, *slash;
  size_t      n = strlen(e->name);

  msg[0] = 0;
  PetscStrncpy(e->path, e->name, sizeof(e->path));
  if (!e->input && n + strlen(".part") >= PETSC_MAX_PATH_LEN - 1) {
    snprintf(msg, len, "%s: the file name is %zu characters long, at most %d are supported", e->option, n, PETSC_MAX_PATH_LEN - 7);
    return;
  }
  if (!lstat(e->name, &lst) && S_ISLNK(lst.st_mode)) {
    /* a symbolic link is written through: its target is the file replaced, the link stays */
    if (stat(e->name, &st)) {
      snprintf(msg, len, "%s: '%s' is a symbolic link to a missing file", e->option, e->name);
      return;
    }
    if (S_ISREG(st.st_mode) && !realpath(e->name, e->path)) {
      snprintf(msg, len, "%s: cannot resolve the symbolic link '%s': %s", e->option, e->name, strerror(errno));
      return;
    }
  }
  e->exists = (PetscBool)!stat(e->path, &st);
  if (e->exists) {
    e->dev = st.st_dev;
    e->ino = st.st_ino;
    if (S_ISDIR(st.st_mode)) {
      snprintf(msg, len, "%s: '%s' is a directory, not a file name", e->option, e->name);
      return;
    }
    if (!S_ISREG(st.st_mode) && !e->input) {
      /* never rename over a device or FIFO: text is written into it, HDF5 needs a regular file */
      if (hdf5 || !(S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) {
        snprintf(msg, len, "%s: '%s' is %s, not a regular file: %s", e->option, e->name, FileTypeName(st.st_mode), hdf5 ? "HDF5 results need a regular file" : "refusing to replace it");
        return;
      }
      e->direct = PETSC_TRUE;
      if (access(e->path, W_OK)) snprintf(msg, len, "%s: cannot write '%s': %s", e->option, e->name, strerror(errno));
      return;
    }
  } else if (e->input) {
    return; /* a missing input is reported by the code that reads it */
  }
  if (hdf5) {
    const size_t hl = strlen(e->path) + (e->input ? 0 : strlen(".part"));
    if (hl > h5max) {
      snprintf(msg, len, "%s: the file name '%s' is %zu characters long; HDF5 through OpenMPI's MPI-IO accepts at most %zu here (%zu with the \".part\" suffix): use a shorter path (e.g. a relative one or a symbolic link to the directory)", e->option, e->name, n, h5max - (e->input ? 0 : strlen(".part")), h5max);
      return;
    }
  }
  /* the key: the real directory and the base name, so that two spellings of one file compare equal */
  slash = strrchr(e->path, '/');
  base  = slash ? slash + 1 : e->path;
  if (slash) {
    size_t dl = (size_t)(slash - e->path);
    if (dl == 0) dl = 1;
    memcpy(dir, e->path, dl);
    dir[dl] = 0;
  } else strcpy(dir, ".");
  if (!realpath(dir, rdir)) {
    if (!e->input) snprintf(msg, len, "%s: cannot write '%s': %s (the directory '%s')", e->option, e->name, strerror(errno), dir);
    PetscStrncpy(e->key, e->path, sizeof(e->key));
    return;
  }
  snprintf(e->key, sizeof(e->key), "%s/%s", rdir, base);
}

static PetscBool FileSame(const SgFileEntry *a, const SgFileEntry *b)
{
  if (a->direct && b->direct) return PETSC_FALSE; /* two streams into one device (e.g. /dev/null) are fine */
  if (a->exists && b->exists && a->dev == b->dev && a->ino == b->ino) return PETSC_TRUE;
  return (PetscBool)(a->key[0] && !strcmp(a->key, b->key));
}

/* Register the file of an option (replacing an earlier registration of the same option) and check it against the
   others. hdf5: written by HDF5 (the length limit, regular files only). */
static PetscErrorCode FileRegister(MPI_Comm comm, const char option[], const char name[], PetscBool input, PetscBool hdf5)
{
  SgFileEntry *e = NULL;
  PetscMPIInt  rank;
  char         msg[PETSC_MAX_PATH_LEN + 512];
  size_t       h5max;

  PetscFunctionBeginUser;
  for (int i = 0; i < FileCount; i++) /* an option names one file, except -options_file (each is kept) */
    if (!strcmp(FileTable[i].option, option) && strcmp(option, "-options_file")) e = &FileTable[i];
  if (!name || !name[0]) {
    if (e) *e = FileTable[--FileCount];
    PetscFunctionReturn(0);
  }
  if (!e) {
    PetscCheck(FileCount < SG_FILE_MAX, comm, PETSC_ERR_PLIB, "too many files");
    e = &FileTable[FileCount++];
  }
  PetscCall(PetscMemzero(e, sizeof(*e)));
  PetscCall(PetscStrncpy(e->option, option, sizeof(e->option)));
  PetscCall(PetscStrncpy(e->name, name, sizeof(e->name)));
  e->input = input;
  PetscCall(SgFileHDF5NameMax(input ? PETSC_COMM_SELF : comm, &h5max));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMemzero(msg, sizeof(msg)));
  if (!rank) {
    FileInspect(e, hdf5, h5max, msg, sizeof(msg));
    for (int i = 0; !msg[0] && i < FileCount; i++) {
      const SgFileEntry *o = &FileTable[i];
      if (o == e || (o->input && e->input)) continue;
      /* resuming from and rewriting one checkpoint is the normal workflow: the restart is read completely before
         the first checkpoint is written, and the write is atomic */
      if ((!strcmp(o->option, "-restart_file") && !strcmp(e->option, "-checkpoint_file")) || (!strcmp(e->option, "-restart_file") && !strcmp(o->option, "-checkpoint_file"))) continue;
      if (FileSame(e, o)) snprintf(msg, sizeof(msg), "%.64s '%.2000s' and %.64s '%.2000s' name the same file: %s", o->option, o->name, e->option, e->name, o->input || e->input ? "an input would be overwritten" : "one result would overwrite the other");
    }
  }
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCallMPI(MPI_Bcast(e, sizeof(*e), MPI_BYTE, 0, comm));
  if (msg[0]) {
    *e = FileTable[--FileCount];
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", msg);
  }
  PetscFunctionReturn(0);
}

static PetscBool OptionIsHDF5(const char option[])
{
  return (PetscBool)(!strcmp(option, "-output_file") || !strcmp(option, "-checkpoint_file") || !strcmp(option, "-restart_file"));
}

/* The XDMF file written beside an HDF5 result: F.h5 -> F.xmf, else F + ".xmf". */
PetscErrorCode SgOutputXdmfName(const char h5name[], char xname[], size_t len)
{
  size_t n;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(xname, h5name, len));
  PetscCall(PetscStrlen(xname, &n));
  if (n > 3 && !strcmp(xname + n - 3, ".h5")) xname[n - 3] = 0;
  PetscCall(PetscStrlcat(xname, ".xmf", len));
  PetscFunctionReturn(0);
}

/* Fail early (before any solve) if an output location cannot be written, is not ours to replace, or is named twice. */
PetscErrorCode SgFileCheckWritable(MPI_Comm comm, const char option[], const char name[])
{
  FILE     *fp;
  PetscBool direct;
  const char *path;

  PetscFunctionBeginUser;
  PetscCheck(comm != MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SgFileCheckWritable: the communicator is MPI_COMM_NULL");
  PetscCheck(option && option[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgFileCheckWritable: argument 2 (the option naming the file) is NULL or empty");
  if (!name) name = ""; /* no file */
  PetscCall(FileRegister(comm, option, name, PETSC_FALSE, OptionIsHDF5(option)));
  if (!strcmp(option, "-output_file")) {
    char xname[PETSC_MAX_PATH_LEN + 8];
    PetscCall(SgOutputXdmfName(name, xname, sizeof(xname)));
    PetscCall(FileRegister(comm, "-output_file (its .xmf file)", name[0] ? xname : NULL, PETSC_FALSE, PETSC_FALSE));
  }
  if (!name[0]) PetscFunctionReturn(0);
  FileResolve(name, &path, &direct);
  if (direct) PetscFunctionReturn(0); /* opening a FIFO would wait for its reader; access() was checked */
  PetscCall(SgFileOpen(comm, option, name, &fp));
  PetscCall(FileFinish(comm, name, &fp, FILE_ABANDON));
  PetscFunctionReturn(0);
}

/* Register an input file (read by the run), so that no result names it. */
PetscErrorCode SgFileCheckInput(MPI_Comm comm, const char option[], const char name[])
{
  PetscFunctionBeginUser;
  PetscCheck(comm != MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SgFileCheckInput: the communicator is MPI_COMM_NULL");
  PetscCheck(option && option[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgFileCheckInput: argument 2 (the option naming the file) is NULL or empty");
  PetscCall(FileRegister(comm, option, name, PETSC_TRUE, OptionIsHDF5(option)));
  PetscFunctionReturn(0);
}

/* Write the HDF5 file of a result option through body(viewer, ctx) into its ".part" file and commit it (or leave it
   for SgFileCommit when commit is false). A failure (a full disk, say) does not raise an error here: the ".part" is
   removed and ok = PETSC_FALSE with a message naming the option, the file and the cause, so that the caller can
   still record it in the summary. HDF5's own error stack is silenced meanwhile. */
/* errno values a failed write sets (HDF5 leaves errno stale otherwise) */
static PetscBool WriteErrno(int e)
{
  return (PetscBool)(e == ENOSPC || e == EDQUOT || e == EFBIG || e == EROFS || e == EACCES || e == EIO);
}

/* HDF5 cannot always close a file whose write failed in the middle: PETSc's writers return on the error with their
   dataset and group open, and the close's flush fails again while the disk stays full, so the file stays open and
   HDF5's own clean-up at MPI_Finalize crashes (a checkpoint or fields file on a file system that fills during the
   write). A file system with less than this many bytes free is refused before HDF5 writes anything; a disk that fills
   during a larger write can still meet that failure. */
#define SG_HDF5_MIN_FREE (1024.0 * 1024.0)

static PetscBool SpaceBelow(const char path[], double bytes)
{
  struct statvfs sv;
  char           dir[PETSC_MAX_PATH_LEN];
  char          *slash;

  strncpy(dir, path, sizeof(dir) - 1);
  dir[sizeof(dir) - 1] = 0;
  slash                = strrchr(dir, '/');
  if (slash) *(slash == dir ? slash + 1 : slash) = 0;
  else strcpy(dir, ".");
  return (PetscBool)(!statvfs(dir, &sv) && (double)sv.f_bavail * (double)sv.f_frsize < bytes);
}

static PetscBool DiskFull(const char path[])
{
  return (PetscBool)!strcmp(SgFileErrorCause(0, path), "no space left on device");
}

/* A write of tmp (the .part of path) failed: the cause is judged while the disk is still full, then the file, which
   goes anyway, is emptied, so that HDF5 has the space to close it (a file left open in HDF5 crashes HDF5's clean-up
   at PetscFinalize; an unlinked file would keep its blocks while open). */
static void PartFailed(const char tmp[], const char path[], PetscBool direct, PetscMPIInt rank, int *cause)
{
  if (direct) return;
  if (!WriteErrno(*cause) && DiskFull(path)) *cause = ENOSPC;
  if (rank == 0) (void)truncate(tmp, 0);
}

PetscErrorCode SgFileWriteHDF5(MPI_Comm comm, const char option[], const char name[], PetscErrorCode (*body)(PetscViewer, void *), void *ctx, PetscBool commit, PetscBool *ok, char msg[], size_t len)
{
  char           tmp[PETSC_MAX_PATH_LEN];
  PetscViewer    viewer = NULL;
  PetscErrorCode ierr, ierr2;
  H5E_auto2_t    efunc;
  void          *edata;
  int            err[2];
  const char    *path;
  PetscBool      direct;
  PetscMPIInt    rank;

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  FileResolve(name, &path, &direct);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  PetscCall(SgFileBegin(name));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  (void)H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
  (void)H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  errno = 0;
  if (!direct && SpaceBelow(path, SG_HDF5_MIN_FREE)) {
    ierr  = PETSC_ERR_FILE_WRITE; /* refused before HDF5 writes anything */
    errno = ENOSPC;
  } else {
    /* not PetscCall: the error is caught, reported with its cause and the .part removed below */
    ierr = PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &viewer);
  }
  /* collective MPI-IO transfers (PETSc's default is independent): every rank writes its part of each dataset in one
     collective call, which MPI-IO can aggregate on a parallel file system */
  if (!ierr) ierr = PetscViewerHDF5SetCollective(viewer, PETSC_TRUE);
  if (!ierr) ierr = body(viewer, ctx);
  err[1] = errno;
  if (viewer) {
    hid_t fid = -1;
    (void)PetscViewerHDF5GetFileId(viewer, &fid);
    if (ierr) PartFailed(tmp, path, direct, rank, &err[1]);
    ierr2 = PetscViewerDestroy(&viewer);
    if (ierr2 && !ierr) {
      ierr   = ierr2;
      err[1] = errno;
      PartFailed(tmp, path, direct, rank, &err[1]);
      if (fid >= 0) (void)H5Fclose(fid); /* the close failed (its flush): again, with the space freed */
    }
  }
  (void)H5Eset_auto2(H5E_DEFAULT, efunc, edata);
  PetscCall(PetscPopErrorHandler());
  err[0] = ierr ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, err, 2, MPI_INT, MPI_MAX, comm));
  if (err[0]) {
    /* HDF5 leaves errno stale: trust only the codes of a failed write; the cause before the .part is removed */
    if (!WriteErrno(err[1])) err[1] = 0;
    PetscCall(PetscSNPrintf(msg, len, "%s: cannot write '%s': %s", option, name, SgFileErrorCause(err[1], path)));
    PetscCall(SgFileAbandon(comm, name));
    *ok = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  if (commit) PetscCall(SgFileCommit(comm, name));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- JSON summary */
PetscErrorCode SgSummaryCreate(SgSummary *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(s));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummaryDestroy(SgSummary *s)
{
  PetscFunctionBeginUser;
  if (!*s) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < (*s)->n; i++) PetscCall(PetscFree2((*s)->key[i], (*s)->val[i]));
  PetscCall(PetscFree2((*s)->key, (*s)->val));
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(0);
}

/* Set key to an already JSON-encoded value (replacing an earlier value of the key). */
PetscErrorCode SgSummarySetRaw(SgSummary s, const char key[], const char json[])
{
  PetscInt i;
  size_t   lk, lv;

  PetscFunctionBeginUser;
  for (i = 0; i < s->n; i++) {
    PetscBool eq;
    PetscCall(PetscStrcmp(s->key[i], key, &eq));
    if (eq) break;
  }
  if (i == s->n) {
    if (s->n == s->cap) {
      char   **k, **v;
      PetscInt cap = PetscMax(32, 2 * s->cap);
      PetscCall(PetscCalloc2(cap, &k, cap, &v));
      PetscCall(PetscArraycpy(k, s->key, s->n));
      PetscCall(PetscArraycpy(v, s->val, s->n));
      PetscCall(PetscFree2(s->key, s->val));
      s->key = k;
      s->val = v;
      s->cap = cap;
    }
    s->n++;
  } else PetscCall(PetscFree2(s->key[i], s->val[i]));
  PetscCall(PetscStrlen(key, &lk));
  PetscCall(PetscStrlen(json, &lv));
  PetscCall(PetscMalloc2(lk + 1, &s->key[i], lv + 1, &s->val[i]));
  PetscCall(PetscStrcpy(s->key[i], key));
  PetscCall(PetscStrcpy(s->val[i], json));
  PetscFunctionReturn(0);
}

static void JSONReal(char buf[], size_t len, PetscReal v)
{
  if (PetscIsInfOrNanReal(v)) snprintf(buf, len, "null");
  else snprintf(buf, len, "%.17g", (double)v);
}

PetscErrorCode SgSummarySetReal(SgSummary s, const char key[], PetscReal v)
{
  char buf[64];

  PetscFunctionBeginUser;
  JSONReal(buf, sizeof(buf), v);
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetInt(SgSummary s, const char key[], PetscInt v)
{
  char buf[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof(buf), "%" PetscInt_FMT, v));
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetBool(SgSummary s, const char key[], PetscBool v)
{
  PetscFunctionBeginUser;
  PetscCall(SgSummarySetRaw(s, key, v ? "true" : "false"));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetString(SgSummary s, const char key[], const char v[])
{
  char   buf[1024];
  size_t k = 0;

  PetscFunctionBeginUser;
  buf[k++] = '"';
  for (const char *c = v; *c && k < sizeof(buf) - 3; c++) {
    if (*c == '"' || *c == '\\') buf[k++] = '\\';
    buf[k++] = (*c == '\n' || *c == '\t') ? ' ' : *c;
  }
  buf[k++] = '"';
  buf[k]   = 0;
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetRealArray(SgSummary s, const char key[], PetscInt n, const PetscReal v[])
{
  char  *buf;
  size_t len = 32 * (size_t)n + 4, k = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(len, &buf));
  buf[k++] = '[';
  for (PetscInt i = 0; i < n; i++) {
    JSONReal(buf + k, len - k, v[i]);
    k += strlen(buf + k);
    if (i < n - 1) buf[k++] = ',';
  }
  buf[k++] = ']';
  buf[k]   = 0;
  PetscCall(SgSummarySetRaw(s, key, buf));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummarySetIntArray(SgSummary s, const char key[], PetscInt n, const PetscInt v[])
{
  PetscReal *r;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, &r));
  for (PetscInt i = 0; i < n; i++) r[i] = (PetscReal)v[i];
  PetscCall(SgSummarySetRealArray(s, key, n, r));
  PetscCall(PetscFree(r));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSummaryWrite(MPI_Comm comm, SgSummary s, const char option[], const char name[])
{
  FILE *fp;

  PetscFunctionBeginUser;
  if (!name[0]) PetscFunctionReturn(0);
  PetscCall(SgFileOpen(comm, option, name, &fp));
  if (fp) {
    fprintf(fp, "{\n");
    for (PetscInt i = 0; i < s->n; i++) fprintf(fp, "  \"%s\": %s%s\n", s->key[i], s->val[i], i < s->n - 1 ? "," : "");
    fprintf(fp, "}\n");
  }
  PetscCall(SgFileClose(comm, name, &fp));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- HDF5 + XDMF */
/* PETSc stores a field of vector "v" whose section field is "f" as <group>/v_f */
static PetscErrorCode DatasetName(Vec v, const char suffix[], char name[], size_t len)
{
  const char  *vname, *fname;
  DM           dm;
  PetscSection s;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetName((PetscObject)v, &vname));
  PetscCall(VecGetDM(v, &dm));
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(PetscSectionGetFieldName(s, 0, &fname));
  PetscCall(PetscSNPrintf(name, len, "%s%s_%s", vname, suffix, fname));
  PetscFunctionReturn(0);
}

/* s with the XML special characters & < > " ' as entities (out: len bytes; a name too long for it is an error) */
static PetscErrorCode XmlEscape(const char s[], char out[], size_t len)
{
  size_t n = 0;

  PetscFunctionBeginUser;
  for (const char *c = s; *c; c++) {
    const char *e = *c == '&' ? "&amp;" : *c == '<' ? "&lt;" : *c == '>' ? "&gt;" : *c == '"' ? "&quot;" : *c == '\'' ? "&apos;" : NULL;
    size_t      l = e ? strlen(e) : 1;
    PetscCheck(n + l < len, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-output_file: the name '%s' is too long for the XDMF file", s);
    if (e) memcpy(out + n, e, l);
    else out[n] = *c;
    n += l;
  }
  out[n] = 0;
  PetscFunctionReturn(0);
}

/* One <Grid> of the XDMF file: the mesh and the fields; step >= 0: the datasets of that load step (their names end in
   _step<step>) at the time value time, inside a temporal collection. */
static PetscErrorCode WriteXDMFGrid(FILE *fp, const char h5base[], PetscInt dim, PetscInt nvert, PetscInt ncell, PetscInt step, PetscReal time, PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  const char *ctype = dim == 2 ? "Triangle" : "Tetrahedron", *ind = step >= 0 ? "  " : "";
  char        suffix[32] = "";

  PetscFunctionBeginUser;
  if (step >= 0) {
    PetscCall(PetscSNPrintf(suffix, sizeof(suffix), "_step%" PetscInt_FMT, step));
    fprintf(fp, "   <Grid Name=\"step%" PetscInt_FMT "\" GridType=\"Uniform\">\n", step);
    fprintf(fp, "     <Time Value=\"%.17g\"/>\n", (double)time);
  } else fprintf(fp, "  <Grid Name=\"body\" GridType=\"Uniform\">\n");
  fprintf(fp, "%s   <Information Name=\"magnification\" Value=\"%g\"/>\n", ind, (double)magnification);
  fprintf(fp, "%s   <Topology TopologyType=\"%s\" NumberOfElements=\"%" PetscInt_FMT "\">\n", ind, ctype, ncell);
  fprintf(fp, "%s    <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Int\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n%s   </Topology>\n", ind, ncell, dim + 1, h5base, ind);
  fprintf(fp, "%s   <Geometry GeometryType=\"%s\">\n", ind, dim == 2 ? "XY" : "XYZ");
  fprintf(fp, "%s    <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n%s   </Geometry>\n", ind, nvert, dim, h5base, ind);
  for (PetscInt i = 0; i < nv; i++) {
    const char *name;
    char        dset[256];
    PetscInt    bs;
    char        xn[512], xd[768];
    PetscCall(PetscObjectGetName((PetscObject)vf[i], &name));
    PetscCall(DatasetName(vf[i], suffix, dset, sizeof(dset)));
    PetscCall(XmlEscape(name, xn, sizeof(xn)));
    PetscCall(XmlEscape(dset, xd, sizeof(xd)));
    name = xn;
    PetscCall(VecGetBlockSize(vf[i], &bs));
    fprintf(fp, "%s   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", ind, name, bs > 1 ? "Vector" : "Scalar");
    if (bs == 2) { /* ParaView wants 3-component vectors: pad the 2D displacement with a zero */
      fprintf(fp, "%s    <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, 0*$0)\" Dimensions=\"%" PetscInt_FMT " 3\">\n", ind, nvert);
      for (PetscInt d = 0; d < 2; d++)
        fprintf(fp, "%s     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%" PetscInt_FMT " 1\"><DataItem Dimensions=\"3 2\" Format=\"XML\">0 %" PetscInt_FMT " 1 1 %" PetscInt_FMT " 1</DataItem><DataItem Dimensions=\"%" PetscInt_FMT " 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/%s</DataItem></DataItem>\n", ind, nvert, d, nvert, nvert, h5base, xd);
      fprintf(fp, "%s    </DataItem>\n", ind);
    } else fprintf(fp, "%s    <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/%s</DataItem>\n", ind, nvert, bs, h5base, xd);
    fprintf(fp, "%s   </Attribute>\n", ind);
  }
  for (PetscInt i = 0; i < nc; i++) {
    const char *name;
    char        dset[256];
    char        xn[512], xd[768];
    PetscCall(PetscObjectGetName((PetscObject)cf[i], &name));
    PetscCall(DatasetName(cf[i], suffix, dset, sizeof(dset)));
    PetscCall(XmlEscape(name, xn, sizeof(xn)));
    PetscCall(XmlEscape(dset, xd, sizeof(xd)));
    name = xn;
    fprintf(fp, "%s   <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Cell\">\n", ind, name);
    fprintf(fp, "%s    <DataItem Dimensions=\"%" PetscInt_FMT " 1\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/cell_fields/%s</DataItem>\n%s   </Attribute>\n", ind, ncell, h5base, xd, ind);
  }
  fprintf(fp, "%s  </Grid>\n", ind);
  PetscFunctionReturn(0);
}

/* The XDMF file of the HDF5 file h5name: one grid, or (nsteps > 0) a temporal collection of the steps[] at times[]
   that ParaView plays as an animation. */
static PetscErrorCode WriteXDMF(SgElasticity p, const char h5name[], const char xname[], PetscInt nsteps, const PetscInt steps[], const PetscReal times[], PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  FILE       *fp;
  const char *h5base;
  char        xbase[PETSC_MAX_PATH_LEN * 6];
  PetscInt    nvert, ncell, dim;
  MPI_Comm    comm;
  DM          dmVert;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(p, &comm));
  PetscCall(SgElasticityGetDimension(p, &dim));
  PetscCall(SgElasticityGetDMs(p, NULL, &dmVert, NULL, NULL));
  /* the XDMF file sits beside the HDF5 file and names it relative to itself */
  h5base = strrchr(h5name, '/') ? strrchr(h5name, '/') + 1 : h5name;
  PetscCall(XmlEscape(h5base, xbase, sizeof(xbase))); /* a file name with & or < must not break the XML */
  h5base = xbase;
  PetscCall(VecGetSize(cf[0], &ncell));
  {
    Vec g;
    PetscCall(DMGetGlobalVector(dmVert, &g));
    PetscCall(VecGetSize(g, &nvert));
    PetscCall(DMRestoreGlobalVector(dmVert, &g));
  }
  PetscCall(SgFileOpen(comm, "-output_file", xname, &fp));
  if (fp) {
    fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
    if (nsteps > 0) {
      fprintf(fp, "  <Grid Name=\"body\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
      for (PetscInt k = 0; k < nsteps; k++) PetscCall(WriteXDMFGrid(fp, h5base, dim, nvert, ncell, steps[k], times[k], nv, vf, nc, cf, magnification));
      fprintf(fp, "  </Grid>\n");
    } else PetscCall(WriteXDMFGrid(fp, h5base, dim, nvert, ncell, -1, 0, nv, vf, nc, cf, magnification));
    fprintf(fp, " </Domain>\n</Xdmf>\n");
  }
  PetscCall(FileFinish(comm, xname, &fp, FILE_KEEP)); /* committed with the .h5 file */
  PetscFunctionReturn(0);
}

typedef struct {
  DM            dm;
  PetscInt      nv, nc;
  Vec          *vf, *cf;
  PetscReal     magnification;
  PetscInt      nsteps; /* 0: one set of fields; else the load steps steps[] filled by fill */
  const PetscInt *steps;
  SgOutputFill  fill;
  void         *fctx;
} FieldsCtx;

/* VecView of v under the name <its name>_step<step> (the name restored after) */
static PetscErrorCode ViewStep(Vec v, PetscInt step, PetscViewer viewer)
{
  const char *name;
  char        base[256], sname[300];

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetName((PetscObject)v, &name));
  PetscCall(PetscStrncpy(base, name, sizeof(base)));
  PetscCall(PetscSNPrintf(sname, sizeof(sname), "%s_step%" PetscInt_FMT, base, step));
  PetscCall(PetscObjectSetName((PetscObject)v, sname));
  PetscCall(VecView(v, viewer));
  PetscCall(PetscObjectSetName((PetscObject)v, base));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteFieldsH5(PetscViewer viewer, void *ctx)
{
  FieldsCtx *f = (FieldsCtx *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(f->dm, viewer));
  if (!f->nsteps) {
    for (PetscInt i = 0; i < f->nv; i++) PetscCall(VecView(f->vf[i], viewer));
    for (PetscInt i = 0; i < f->nc; i++) PetscCall(VecView(f->cf[i], viewer));
  }
  for (PetscInt k = 0; k < f->nsteps; k++) {
    PetscCall(f->fill(f->fctx, k, f->nv, f->vf, f->nc, f->cf));
    for (PetscInt i = 0; i < f->nv; i++) PetscCall(ViewStep(f->vf[i], f->steps[k], viewer));
    for (PetscInt i = 0; i < f->nc; i++) PetscCall(ViewStep(f->cf[i], f->steps[k], viewer));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "magnification", PETSC_REAL, &f->magnification));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputWrite(SgElasticity p, const char h5name[], FieldsCtx *ctx, const PetscReal times[])
{
  char           xname[PETSC_MAX_PATH_LEN + 8], msg[PETSC_MAX_PATH_LEN + 256];
  PetscBool      ok;
  PetscErrorCode ierr;
  MPI_Comm       comm;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(p, &comm));
  PetscCall(SgElasticityGetDMs(p, &ctx->dm, NULL, NULL, NULL));
  PetscCall(PetscLogEventBegin(SG_Output, 0, 0, 0, 0));
  PetscCall(SgFileWriteHDF5(comm, "-output_file", h5name, WriteFieldsH5, ctx, PETSC_FALSE, &ok, msg, sizeof(msg)));
  PetscCheck(ok, comm, PETSC_ERR_FILE_WRITE, "%s", msg);
  PetscCall(SgOutputXdmfName(h5name, xname, sizeof(xname)));
  ierr = WriteXDMF(p, h5name, xname, ctx->nsteps, ctx->steps, times, ctx->nv, ctx->vf, ctx->nc, ctx->cf, ctx->magnification);
  if (ierr) PetscCall(SgFileAbandon(comm, h5name)); /* the .xmf.part is gone already */
  PetscCall(ierr);
  PetscCall(SgFileCommit(comm, h5name));
  PetscCall(SgFileCommit(comm, xname));
  PetscCall(PetscLogEventEnd(SG_Output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Write mesh, vertex fields (first: displacement, on the full mesh with Dirichlet values) and cell fields to
   <name>.h5 and the matching <name>.xmf. Both are written as ".part" first and renamed together, so that a failure of
   either leaves neither new file (and the previous pair intact). */
PetscErrorCode SgOutputWrite(SgElasticity p, const char h5name[], PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  FieldsCtx ctx = {NULL, nv, nc, vf, cf, magnification, 0, NULL, NULL, NULL};

  PetscFunctionBeginUser;
  PetscCall(OutputWrite(p, h5name, &ctx, NULL));
  PetscFunctionReturn(0);
}

/* The same for load steps: fill(fctx, k, ...) puts the fields of the k-th of the nsteps steps into vf and cf, stored
   as <name>_step<steps[k]>; the .xmf is a temporal collection with the time values times[k] (the load factors). */
PetscErrorCode SgOutputWriteSteps(SgElasticity p, const char h5name[], PetscInt nsteps, const PetscInt steps[], const PetscReal times[], SgOutputFill fill, void *fctx, PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  FieldsCtx ctx = {NULL, nv, nc, vf, cf, magnification, nsteps, steps, fill, fctx};

  PetscFunctionBeginUser;
  PetscCall(OutputWrite(p, h5name, &ctx, times));
  PetscFunctionReturn(0);
}
