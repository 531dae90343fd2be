/* output.c: result files written atomically: HDF5 fields + XDMF for ParaView, the JSON summary, CSV tables. */
#include "signorini.h"
#include <petscviewerhdf5.h>
#include <errno.h>
#include <sys/stat.h>

/* Every result file is written to "<name>.part" and renamed once complete: a failed or killed run leaves
   the previous result intact and never a half-written file under the final name. */
PetscErrorCode SgFileTmpName(const char name[], char tmp[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(tmp, len, "%s.part", name));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFileCommit(MPI_Comm comm, const char name[])
{
  PetscMPIInt rank;
  char        tmp[PETSC_MAX_PATH_LEN];
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Barrier(comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  if (rank == 0 && rename(tmp, name)) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s: %s", tmp, name, strerror(err));
  PetscFunctionReturn(0);
}

/* Remove a temporary file left by a failed write (rank 0). */
PetscErrorCode SgFileAbandon(MPI_Comm comm, const char name[])
{
  PetscMPIInt rank;
  char        tmp[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(SgFileTmpName(name, tmp, sizeof(tmp)));
  if (rank == 0) (void)remove(tmp);
  PetscFunctionReturn(0);
}

/* Open "<name>.part" for writing on rank 0 (NULL elsewhere); an error names the option that gave the file. */
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
    *fp = fopen(tmp, "w");
    if (!*fp) err = errno;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "%s: cannot write '%s': %s", option, name, strerror(err));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFileClose(MPI_Comm comm, const char name[], FILE **fp)
{
  int err = 0;

  PetscFunctionBeginUser;
  if (*fp) {
    if (fflush(*fp) || ferror(*fp)) err = EIO;
    if (fclose(*fp)) err = errno;
    *fp = NULL;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm));
  if (err) PetscCall(SgFileAbandon(comm, name));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "error writing '%s': %s", name, strerror(err));
  PetscCall(SgFileCommit(comm, name));
  PetscFunctionReturn(0);
}

/* Fail early (before any solve) if an output location cannot be written. */
PetscErrorCode SgFileCheckWritable(MPI_Comm comm, const char option[], const char name[])
{
  FILE *fp;

  PetscFunctionBeginUser;
  if (!name[0]) PetscFunctionReturn(0);
  {
    PetscMPIInt rank;
    int         isdir = 0;
    struct stat st;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank && !stat(name, &st) && S_ISDIR(st.st_mode)) isdir = 1;
    PetscCallMPI(MPI_Bcast(&isdir, 1, MPI_INT, 0, comm));
    PetscCheck(!isdir, comm, PETSC_ERR_FILE_OPEN, "%s: '%s' is a directory, not a file name", option, name);
  }
  PetscCall(SgFileOpen(comm, option, name, &fp));
  if (fp) fclose(fp);
  PetscCall(SgFileAbandon(comm, name));
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
static PetscErrorCode DatasetName(Vec v, char name[], size_t len)
{
  const char  *vname, *fname;
  DM           dm;
  PetscSection s;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetName((PetscObject)v, &vname));
  PetscCall(VecGetDM(v, &dm));
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(PetscSectionGetFieldName(s, 0, &fname));
  PetscCall(PetscSNPrintf(name, len, "%s_%s", vname, fname));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteXDMF(SgProblem p, const char h5name[], const char xname[], PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  FILE       *fp;
  const char *h5base, *ctype = p->dim == 2 ? "Triangle" : "Tetrahedron";
  PetscInt    nvert, ncell;

  PetscFunctionBeginUser;
  /* the XDMF file sits beside the HDF5 file and names it relative to itself */
  h5base = strrchr(h5name, '/') ? strrchr(h5name, '/') + 1 : h5name;
  PetscCall(VecGetSize(cf[0], &ncell));
  {
    Vec g;
    PetscCall(DMGetGlobalVector(p->dmVert, &g));
    PetscCall(VecGetSize(g, &nvert));
    PetscCall(DMRestoreGlobalVector(p->dmVert, &g));
  }
  PetscCall(SgFileOpen(p->comm, "-output_file", xname, &fp));
  if (fp) {
    fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n  <Grid Name=\"body\" GridType=\"Uniform\">\n");
    fprintf(fp, "   <Information Name=\"magnification\" Value=\"%g\"/>\n", (double)magnification);
    fprintf(fp, "   <Topology TopologyType=\"%s\" NumberOfElements=\"%" PetscInt_FMT "\">\n", ctype, ncell);
    fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Int\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n   </Topology>\n", ncell, p->dim + 1, h5base);
    fprintf(fp, "   <Geometry GeometryType=\"%s\">\n", p->dim == 2 ? "XY" : "XYZ");
    fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n   </Geometry>\n", nvert, p->dim, h5base);
    for (PetscInt i = 0; i < nv; i++) {
      const char *name;
      char        dset[256];
      PetscInt    bs;
      PetscCall(PetscObjectGetName((PetscObject)vf[i], &name));
      PetscCall(DatasetName(vf[i], dset, sizeof(dset)));
      PetscCall(VecGetBlockSize(vf[i], &bs));
      fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", name, bs > 1 ? "Vector" : "Scalar");
      if (bs == 2) { /* ParaView wants 3-component vectors: pad the 2D displacement with a zero */
        fprintf(fp, "    <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, 0*$0)\" Dimensions=\"%" PetscInt_FMT " 3\">\n", nvert);
        for (PetscInt d = 0; d < 2; d++)
          fprintf(fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%" PetscInt_FMT " 1\"><DataItem Dimensions=\"3 2\" Format=\"XML\">0 %" PetscInt_FMT " 1 1 %" PetscInt_FMT " 1</DataItem><DataItem Dimensions=\"%" PetscInt_FMT " 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/%s</DataItem></DataItem>\n", nvert, d, nvert, nvert, h5base, dset);
        fprintf(fp, "    </DataItem>\n");
      } else fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/%s</DataItem>\n", nvert, bs, h5base, dset);
      fprintf(fp, "   </Attribute>\n");
    }
    for (PetscInt i = 0; i < nc; i++) {
      const char *name;
      char        dset[256];
      PetscCall(PetscObjectGetName((PetscObject)cf[i], &name));
      PetscCall(DatasetName(cf[i], dset, sizeof(dset)));
      fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Cell\">\n", name);
      fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " 1\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/cell_fields/%s</DataItem>\n   </Attribute>\n", ncell, h5base, dset);
    }
    fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
  }
  PetscCall(SgFileClose(p->comm, xname, &fp));
  PetscFunctionReturn(0);
}

/* Write mesh, vertex fields (first: displacement, on the full mesh with Dirichlet values) and cell fields to
   <name>.h5 and the matching <name>.xmf. */
PetscErrorCode SgOutputWrite(SgProblem p, const char h5name[], PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
{
  PetscViewer viewer;
  char        tmp[PETSC_MAX_PATH_LEN], xname[PETSC_MAX_PATH_LEN];
  size_t      len;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Output, 0, 0, 0, 0));
  PetscCall(SgFileTmpName(h5name, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(p->comm, tmp, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(p->dm, viewer));
  for (PetscInt i = 0; i < nv; i++) PetscCall(VecView(vf[i], viewer));
  for (PetscInt i = 0; i < nc; i++) PetscCall(VecView(cf[i], viewer));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "magnification", PETSC_REAL, &magnification));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(SgFileCommit(p->comm, h5name));
  PetscCall(PetscStrncpy(xname, h5name, sizeof(xname)));
  PetscCall(PetscStrlen(xname, &len));
  if (len > 3 && !strcmp(xname + len - 3, ".h5")) xname[len - 3] = 0;
  PetscCall(PetscStrlcat(xname, ".xmf", sizeof(xname)));
  PetscCall(WriteXDMF(p, h5name, xname, nv, vf, nc, cf, magnification));
  PetscCall(PetscLogEventEnd(SG_Output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
