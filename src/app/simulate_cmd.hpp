#pragma once
// `mdrmap simulate`: one case (a velocity step or history), printed as CSV.
#include <string>
#include <vector>

namespace mdrmap::app {

/// Exit codes of every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;  ///< the solver or the output failed
inline constexpr int kExitBadInput = 2; ///< bad command line; one line on stderr names the option
inline constexpr int kExitInterrupted = 3; ///< study stopped by a signal; resumable

/// The text of `mdrmap simulate --help`.
std::string simulate_help();

/// Runs `mdrmap simulate` with `args` (the arguments after the subcommand
/// name). Writes the result to stdout or --output, diagnostics to stderr, and
/// returns the exit code.
int simulate_main(const std::vector<std::string>& args);

} // namespace mdrmap::app
