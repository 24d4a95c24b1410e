/* Type registries (compliance builders, constraint schemes): a PetscFunctionList and the names
   registered so far, which the unknown-type error of -xxx_type lists. */
#include "../fcimpl.h"

PetscErrorCode FCRegistryAdd(PetscFunctionList *list, char known[], size_t len, const char name[], void (*create)(void))
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(list, name, create));
  if (known[0]) PetscCall(PetscStrlcat(known, ", ", len));
  PetscCall(PetscStrlcat(known, name, len));
  PetscFunctionReturn(0);
}
