/* fecontact: run a scene described by PETSc options.
     mpirun -n N fecontact -options_file input/<scene>.opts [overrides]
   The whole of it is in the library (FCMain, src/scene/driver.c). */
#include <fecontact.h>

int main(int argc, char **argv)
{
  return FCMain(argc, argv);
}
