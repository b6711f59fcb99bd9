#pragma once
// `mdrmap stationary`: the stationary sliding states of one case (any
// indenter profile, any rheology, at fixed depth or under load) at one or
// more velocities, printed as CSV. The case is read as `mdrmap simulate`
// reads it (case/case_input.hpp), without its history and sampling; the
// states are core/metrics/stationary.hpp's.
#include <string>
#include <vector>

namespace mdrmap::app {

/// The text of `mdrmap stationary --help`: the usage and the options in groups.
std::string stationary_help();

/// The text of `mdrmap stationary --help-all` (and `mdrmap help
/// stationary`): every option, the output and the exit codes.
std::string stationary_help_all();

/// Runs `mdrmap stationary` with `args` (the arguments after the subcommand
/// name). Writes the CSV to stdout or --output, diagnostics to stderr, and
/// returns the exit code (kExitOk, kExitRuntime, kExitBadInput).
int stationary_main(const std::vector<std::string>& args);

} // namespace mdrmap::app
