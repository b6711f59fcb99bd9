// mdrmap-fit: `mdrmap fit` (Ceres Solver and MPI), which mdrmap runs in its
// place (app/sibling.hpp).
#include "app/fit_cmd.hpp"
#include "app/sibling.hpp"

int main(int argc, char** argv) {
  return mdrmap::app::sibling_main("fit", argc, argv, mdrmap::app::fit_main);
}
