#pragma once
// `mdrmap simulate`: one case (a velocity step or history), printed as CSV.
#include <string>
#include <vector>

#include "app/exit_codes.hpp"

namespace mdrmap::app {

/// The text of `mdrmap simulate --help`.
std::string simulate_help();

/// Runs `mdrmap simulate` with `args` (the arguments after the subcommand
/// name). Writes the result to stdout or --output, diagnostics to stderr, and
/// returns the exit code.
int simulate_main(const std::vector<std::string>& args);

} // namespace mdrmap::app
