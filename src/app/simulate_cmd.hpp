#pragma once
// `mdrmap simulate`: one case (a velocity step or history), printed as CSV.
#include <string>
#include <vector>

#include "app/exit_codes.hpp"

namespace mdrmap::app {

/// The text of `mdrmap simulate --help`: the usage and the options in groups.
std::string simulate_help();

/// The text of `mdrmap simulate --help-all` (and `mdrmap help simulate`):
/// every option, the output and the exit codes.
std::string simulate_help_all();

/// The full entries of one group of simulate's options (its key in the
/// summary: "geometry", "material", "history", "output", "solver"); "" for
/// an unknown key.
std::string simulate_section_help(const std::string& key);

/// Runs `mdrmap simulate` with `args` (the arguments after the subcommand
/// name). Writes the result to stdout or --output, diagnostics to stderr, and
/// returns the exit code.
int simulate_main(const std::vector<std::string>& args);

} // namespace mdrmap::app
