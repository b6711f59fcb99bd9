#pragma once
// `mdrmap fit`: fits case parameters to lab records (case/fit_problem.hpp,
// fit/least_squares.hpp); over MPI the ranks share the model evaluations.
#include <string>
#include <vector>

namespace mdrmap::app {

/// The text of `mdrmap fit --help`.
std::string fit_help();

/// The text of `mdrmap fit --help-all` (and `mdrmap help fit`).
std::string fit_help_all();

/// Runs `mdrmap fit` with `args` (after the subcommand name); argc/argv for
/// MPI_Init. Returns the exit code.
int fit_main(const std::vector<std::string>& args, int argc, char** argv);

} // namespace mdrmap::app
