/* xdmf.c: the XDMF file beside an HDF5 result, which ParaView opens: its name, the mesh and the fields' datasets, one
   grid or a temporal collection of load steps. */
#include "io/ioimpl.h"

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
    const char *e = *c == '&' ? "&amp;" : *c == '<' ? "&lt;"
                                      : *c == '>'   ? "&gt;"
                                      : *c == '"'   ? "&quot;"
                                      : *c == '\''  ? "&apos;"
                                                    : NULL;
    size_t      l = e ? strlen(e) : 1;
    PetscCheck(n + l < len, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-output_file: the name '%s' is too long for the XDMF file", s);
    if (e) memcpy(out + n, e, l);
    else out[n] = *c;
    n += l;
  }
  out[n] = 0;
  PetscFunctionReturn(0);
}

/* The name of field v and of its dataset (with suffix), both XML-escaped: xn[512], xd[768] */
static PetscErrorCode AttributeNames(Vec v, const char suffix[], char xn[], char xd[])
{
  const char *name;
  char        dset[256];

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetName((PetscObject)v, &name));
  PetscCall(DatasetName(v, suffix, dset, sizeof(dset)));
  PetscCall(XmlEscape(name, xn, 512));
  PetscCall(XmlEscape(dset, xd, 768));
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
    PetscInt    bs;
    char        xn[512], xd[768];
    PetscCall(AttributeNames(vf[i], suffix, xn, xd));
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
    char        xn[512], xd[768];
    PetscCall(AttributeNames(cf[i], suffix, xn, xd));
    name = xn;
    fprintf(fp, "%s   <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Cell\">\n", ind, name);
    fprintf(fp, "%s    <DataItem Dimensions=\"%" PetscInt_FMT " 1\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/cell_fields/%s</DataItem>\n%s   </Attribute>\n", ind, ncell, h5base, xd, ind);
  }
  fprintf(fp, "%s  </Grid>\n", ind);
  PetscFunctionReturn(0);
}

/* The XDMF file of the HDF5 file h5name: one grid, or (nsteps > 0) a temporal collection of the steps[] at times[]
   that ParaView plays as an animation. */
PetscErrorCode SgOutputWriteXDMF(SgElasticity p, const char h5name[], const char xname[], PetscInt nsteps, const PetscInt steps[], const PetscReal times[], PetscInt nv, Vec vf[], PetscInt nc, Vec cf[], PetscReal magnification)
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
  PetscCall(SgFileFinish(comm, xname, &fp, SG_FILE_KEEP)); /* committed with the .h5 file */
  PetscFunctionReturn(0);
}
