/* libFuzzer target: the options as the Python module passes an option dict (one PetscOptionsSetValue
   a name and its whole value, python/fecontact/scene.py), into the scene: fuzz_options.c with
   FUZZ_OPTION_PAIRS (its input one "name<TAB>value" line an option; its deny list and bounds alike). */
#define FUZZ_OPTION_PAIRS 1
#include "fuzz_options.c"
