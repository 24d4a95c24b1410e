/* The type registries (body, shape, material, compliance, scheme) are PetscFunctionLists; one helper finds a
   type and, on a miss, stops with an error that names the option and lists the registered types from the
   list itself, so that a type added by one registration line is listed with no other change. */
#include "../fcimpl.h"

PetscErrorCode FCRegistryFind(MPI_Comm comm, PetscFunctionList list, const char what[], const char option[],
                              const char type[], void (**create)(void))
{
  PetscFunctionBegin;
  *create = NULL;
  PetscCall(PetscFunctionListFind(list, type, create));
  if (!*create) {
    const char **names;
    int          n;
    char         known[1024] = "";
    PetscCall(PetscFunctionListGet(list, &names, &n));
    for (int i = 0; i < n; i++) {
      if (!names[i] || !names[i][0] || names[i][0] == ' ') continue; /* the array PetscFunctionListGet ends with */
      if (known[0]) PetscCall(PetscStrlcat(known, ", ", sizeof(known)));
      PetscCall(PetscStrlcat(known, names[i], sizeof(known)));
    }
    PetscCall(PetscFree(names));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "Unknown %s '%s' in %s (known: %s)", what, type, option, known);
  }
  PetscFunctionReturn(0);
}
