/* io/ioimpl.h: the summary and the history; included by the files of src/io only */
#pragma once

#include "sg.h"


struct _n_SgSummary {
  PetscInt n, cap;
  char   **key, **val; /* values JSON-encoded */
};


struct _n_SgHistory {
  PetscInt      n, cap;
  SgHistoryRow *rows;
};