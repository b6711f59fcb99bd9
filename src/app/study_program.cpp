// mdrmap-study: `mdrmap study` (MPI and parallel HDF5), which mdrmap runs in
// its place (app/sibling.hpp).
#include "app/sibling.hpp"
#include "app/study_cmd.hpp"

int main(int argc, char** argv) {
  return mdrmap::app::sibling_main("study", argc, argv, mdrmap::app::study_main);
}
