#pragma once
// The exit codes of every subcommand of mdrmap.

namespace mdrmap::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;  ///< the solver or the output failed
inline constexpr int kExitBadInput = 2; ///< bad command line; one line on stderr names the option
inline constexpr int kExitInterrupted = 3; ///< study stopped by a signal; resumable

} // namespace mdrmap::app
