/* checkpoint.c: the checkpoint file (-checkpoint_file, -restart_file): the problem's fingerprint, atomic writing, and a
   writer and a reader through which each owner of a state saves and loads its own (src/cont/state.c). Vertex data are
   stored with the vertex coordinates and matched by them on reading, so a restart may use another number of ranks
   (another partition) than the run that wrote the file. The writer is in checkpoint_write.c, the reader in
   checkpoint_read.c, the problem's fingerprint in fingerprint.c, a history row's numbers in history.c; here the file's
   layout and the vertices a rank owns (both sides count them). */
#include "io/ioimpl.h"

/* ------------------------------------------------------------------ the file
   The group /checkpoint holds the vertex coordinates (by which a reader matches the vertices of any partition), the
   mesh size and the problem's fingerprint, written and checked by the writer and the reader; beside them, whatever each owner of a state puts
   in through a writer and takes out through a reader (the controller, its type, the friction state, the load steps:
   src/cont/state.c). The file is written whole or not at all (SgFileWriteHDF5: a .part renamed). */

/* the number of vertices this rank owns (the vertices whose data it writes) */
PetscErrorCode SgCheckpointOwnedVertices(SgElasticity el, PetscInt *nown)
{
  const SgMesh *m;
  DM            dmVert;
  PetscSection  gs;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  *nown = 0;
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) (*nown)++;
  }
  PetscFunctionReturn(0);
}
