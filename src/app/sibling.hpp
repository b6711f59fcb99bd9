#pragma once
// The subcommands that need MPI, parallel HDF5 or Ceres (study, fit) are
// programs of their own beside mdrmap (mdrmap-study, mdrmap-fit): mdrmap
// replaces itself by one of them (execv: the same process id, so each rank
// that mpirun or srun starts as mdrmap becomes the sibling before MPI_Init),
// and simulate, stationary and help start without loading those libraries.

#include <string>
#include <vector>

namespace mdrmap::app {

/// Runs the program `name` from the directory of this executable with this
/// process's arguments (argv[0] becomes its path). Returns only when it
/// cannot be run: prints one line naming it and returns kExitRuntime.
int run_sibling(const char* name, char** argv);

/// The entry of a sibling: its subcommand's main with the arguments after
/// `subcommand` (the one that mdrmap passed on, or none when run directly);
/// one line and kExitRuntime for an exception that escapes it.
int sibling_main(const char* subcommand, int argc, char** argv,
                 int (*command)(const std::vector<std::string>&, int, char**));

} // namespace mdrmap::app
