/* custom_law.c: a friction law of a program's own, registered with SgContactLawRegister and chosen by -friction_type
   like the library's: "tresca_x", a Tresca bound that varies along the contact boundary,
       |lam_T| <= s(x) = s0 + s1 x_1      (-friction_tresca_x_s0, -friction_tresca_x_s1; s(x) > 0 on Gamma_c),
   the law's one file: its options and checks, its bound at a contact vertex (from the vertex's coordinates, which the
   contact object hands every law), its derivative in lam_N (0: the bound does not depend on the contact pressure, the
   Jacobians stay symmetric), its view and the names of its parameters in the summary and the checkpoint.

   The program solves the problem of the options (the driver's options: -box_*, -dirichlet_*, -contact_ids, -cont_type,
   ...) once and writes the JSON summary (-summary_file) and the fields (-output_file). The law's part of the KKT
   measures, its fields and summary keys (law_measures.c) and its part of PDAS, the state update and the rows of the
   linear system (law_pdas.c), come from the ops every law with a bound gets unless the type sets its own. With s1 = 0 the law is -friction_type tresca with
   -friction_bound s0, bit for bit; when every contact vertex slips the friction force is the integral of s over
   Gamma_c (tests/law.ini). Built from the source tree against lib/libsignorini.a:
       make bin/custom_law && bin/custom_law -options_file options/sliding_block.opts -friction_type tresca_x \
           -friction_tresca_x_s0 0.02 -friction_tresca_x_s1 0.04 -summary_file law.json */
#include <signorini.h>
#include "contact/contactimpl.h" /* struct _n_SgContactLaw: the ops a law type fills */

static const char help[] = "Registers a friction law of its own (tresca_x: a Tresca bound s0 + s1 x_1) and solves the problem of the options with it.\n\n";

typedef struct {
  PetscReal s[2]; /* s0, s1 */
  PetscBool set;
} TrescaX;

static const char *const TrescaXNames[] = {"friction_tresca_x_s0", "friction_tresca_x_s1"};

/* the bound at owned contact vertex i: the coordinates of the contact vertices are law->x (dim per vertex) */
static void Bound_TrescaX(SgContactLaw law, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg)
{
  const TrescaX *tx = (TrescaX *)law->data;

  (void)lamN;
  *g = tx->s[0] + tx->s[1] * law->x[i * law->dim];
  if (dg) *dg = 0;
}

static PetscErrorCode SetFromOptions_TrescaX(SgContactLaw law, PetscOptionItems *PetscOptionsObject)
{
  TrescaX  *tx = (TrescaX *)law->data;
  PetscBool set1;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-friction_tresca_x_s0", "tresca_x: the bound s0 + s1 x_1, its value at x_1 = 0", &tx->s[0], &tx->set));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-friction_tresca_x_s1", "tresca_x: the bound s0 + s1 x_1, its slope along x_1", &tx->s[1], &set1));
  PetscCheck(PetscIsNormalReal(tx->s[0]) || tx->s[0] == 0, law->comm, PETSC_ERR_USER_INPUT, "-friction_tresca_x_s0: must be finite, got %g", (double)tx->s[0]);
  PetscCheck(PetscIsNormalReal(tx->s[1]) || tx->s[1] == 0, law->comm, PETSC_ERR_USER_INPUT, "-friction_tresca_x_s1: must be finite, got %g", (double)tx->s[1]);
  PetscFunctionReturn(0);
}

/* after the options: s0 given; s > 0 is checked at the vertices (SetUp of the contact knows them only later: here the
   bound at the ends of the interval the program is made for, x_1 in [0, 1]) */
static PetscErrorCode SetUp_TrescaX(SgContactLaw law)
{
  TrescaX *tx = (TrescaX *)law->data;

  PetscFunctionBeginUser;
  PetscCheck(tx->set, law->comm, PETSC_ERR_USER_INPUT, "-friction_type tresca_x needs the bound: give -friction_tresca_x_s0 (and -friction_tresca_x_s1)");
  PetscCheck(tx->s[0] > 0 && tx->s[0] + tx->s[1] > 0, law->comm, PETSC_ERR_USER_INPUT, "-friction_tresca_x_s0 %g, -friction_tresca_x_s1 %g: the bound s0 + s1 x_1 must be positive for x_1 in [0, 1]", (double)tx->s[0], (double)tx->s[1]);
  PetscCall(PetscSNPrintf(law->desc, sizeof(law->desc), "Tresca s = %g + %g x_1", (double)tx->s[0], (double)tx->s[1]));
  PetscFunctionReturn(0);
}

static PetscErrorCode GetParameters_TrescaX(SgContactLaw law, PetscInt *n, const char *const **names, const PetscReal **values)
{
  PetscFunctionBeginUser;
  *n      = 2;
  *names  = TrescaXNames;
  *values = ((TrescaX *)law->data)->s;
  PetscFunctionReturn(0);
}

static PetscErrorCode View_TrescaX(SgContactLaw law, PetscViewer v)
{
  TrescaX *tx = (TrescaX *)law->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "Tresca friction with |lam_T| <= %g + %g x_1, gamma_T = %g gamma\n", (double)tx->s[0], (double)tx->s[1], (double)law->gfac));
  PetscFunctionReturn(0);
}

static PetscErrorCode LawCreate_TrescaX(SgContactLaw law)
{
  TrescaX *tx;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&tx));
  law->data               = tx; /* SgContactLawDestroy frees it */
  law->friction           = PETSC_TRUE;
  law->coupled            = PETSC_FALSE;
  law->ops.bound          = Bound_TrescaX;
  law->ops.setfromoptions = SetFromOptions_TrescaX;
  law->ops.setup          = SetUp_TrescaX;
  law->ops.getparameters  = GetParameters_TrescaX;
  law->ops.view           = View_TrescaX;
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MPI_Comm    comm;
  SgProblem   prob;
  SgCont      cont;
  PetscBool   converged;
  const char *reason;
  char        sumfile[PETSC_MAX_PATH_LEN] = "", outfile[PETSC_MAX_PATH_LEN] = "";

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscCall(SgContactLawRegister("tresca_x", LawCreate_TrescaX)); /* before any problem reads -friction_type */
  PetscOptionsBegin(comm, NULL, "custom_law: a friction law of one's own", NULL);
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-summary_file", "JSON summary of the run", sumfile, sizeof(sumfile), NULL));
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-output_file", "HDF5 fields of the result (the law's too: traction, slip, state)", outfile, sizeof(outfile), NULL));
  PetscOptionsEnd();
  PetscCall(SgProblemCreate(comm, &prob));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgProblemSetUp(prob));
  PetscCall(SgContCreate(prob, &cont));
  PetscCall(SgProblemDestroy(&prob)); /* the controller holds it */
  PetscCall(SgContSetFromOptions(cont));
  PetscCall(SgContSetUp(cont));
  PetscCall(SgContSolve(cont));
  PetscCall(SgContGetConvergedReason(cont, &converged, &reason));
  PetscCall(PetscPrintf(comm, "custom law: %s (%s)\n", converged ? "converged" : "FAILED", reason));
  PetscCall(SgContWriteSummary(cont, sumfile));
  PetscCall(SgContWriteFields(cont, outfile, 1));
  PetscCall(SgContDestroy(&cont));
  PetscCall(PetscFinalize());
  return converged ? 0 : 1;
}
