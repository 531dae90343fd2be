/* registry.c: the files of a run, registered before any work: the file written for each name (the target of a link,
   a device written directly), names too long for HDF5, the .xmf beside an .h5, and two options naming one file. */
#include "io/ioimpl.h"
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

/* The result and input files of a run are registered here before any work (SgFileCheckWritable, SgFileCheckInput):
   that refuses names too long for the libraries, files that are not regular files where a rename would replace
   them, and two options naming the same file. A registered name may differ from the file written:
   - a symbolic link to a regular file is written through: "<target>.part" (HDF5: "<target>.<tag>.part"), renamed onto
     the target (the link stays);
   - a character device or FIFO (text results only) is written directly, without a ".part" and a rename. */
typedef struct {
  char      option[64];
  char      name[PETSC_MAX_PATH_LEN];     /* as given */
  char      path[PETSC_MAX_PATH_LEN];     /* the file written: name, or the target of a symbolic link */
  char      key[PATH_MAX + NAME_MAX + 2]; /* realpath of the directory + "/" + base name of path */
  PetscBool direct, input, exists;
  dev_t     dev;
  ino_t     ino;
} SgFileEntry;

#define SG_FILE_MAX 48
static SgFileEntry FileTable[SG_FILE_MAX];
static int         FileCount = 0;

static SgFileEntry *FileFind(const char name[])
{
  for (int i = 0; i < FileCount; i++)
    if (!strcmp(FileTable[i].name, name) && !FileTable[i].input) return &FileTable[i];
  return NULL;
}

/* The file written for a result name (the target of a symbolic link), and whether it is written directly. */
void SgFileResolve(const char name[], const char **path, PetscBool *direct)
{
  const SgFileEntry *e = FileFind(name);
  *path                = e ? e->path : name;
  *direct              = e ? e->direct : PETSC_FALSE;
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

/* The XDMF file written beside an HDF5 result: F.h5 -> F.xmf, else F + ".xmf". The .xmf names its datasets FILE:/path
   with FILE the .h5 file's base name, and ParaView's XDMF reader cuts that reference at the first ':': a base name
   with ':' would give a result ParaView reads without fields, so it is refused (a directory with ':' is fine). */
PetscErrorCode SgOutputXdmfName(const char h5name[], char xname[], size_t len)
{
  size_t      n;
  const char *base = strrchr(h5name, '/') ? strrchr(h5name, '/') + 1 : h5name;

  PetscFunctionBeginUser;
  PetscCheck(!strchr(base, ':'), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
             "-output_file '%s': the file name has a ':', and the .xmf file beside it references its datasets as FILE:/dataset, which ParaView's XDMF reader cuts at the first ':' (no fields would be read); choose a file name without ':' (a directory with ':' is fine)", h5name);
  PetscCall(PetscStrncpy(xname, h5name, len));
  PetscCall(PetscStrlen(xname, &n));
  if (n > 3 && !strcmp(xname + n - 3, ".h5")) xname[n - 3] = 0;
  PetscCall(PetscStrlcat(xname, ".xmf", len));
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
    const size_t sl = e->input ? 0 : strlen(SG_HDF5_PART_SUFFIX), hl = strlen(e->path) + sl;
    if (hl > h5max) {
      char with[96] = "";
      if (sl) snprintf(with, sizeof(with), " (%zu with the temporary file's suffix \"%s\")", h5max, SG_HDF5_PART_SUFFIX);
      snprintf(msg, len, "%s: the file name '%s' is %zu characters long; HDF5 through OpenMPI's MPI-IO accepts at most %zu here%s: use a shorter path (e.g. a relative one or a symbolic link to the directory)", e->option, e->name, n, h5max - sl, with);
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
PetscErrorCode SgFileRegister(MPI_Comm comm, const char option[], const char name[], PetscBool input, PetscBool hdf5)
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
