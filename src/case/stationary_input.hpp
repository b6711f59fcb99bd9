#pragma once
// The input of `mdrmap stationary` (and of mdrmap.stationary in Python): the
// case as simulate reads it (case/case_input.hpp) without its history and
// sampling, and its velocities from --v, --v-list or --v-range, with the
// command line's checks and messages; and the states at those velocities
// (core/metrics/stationary.hpp).
#include <string>
#include <vector>

#include "case/case_input.hpp"
#include "core/model/state.hpp"
#include "core/numerics/run_control.hpp"

namespace mdrmap::cases {

/// Velocities of one run at most: every state is computed before any is written.
inline constexpr long kMaxVelocities = 1'000'000;

/// "at most N velocities" (the limit, as the messages and the help say it).
std::string velocity_count_text();

/// The stationary problem: the case and its velocities.
struct StationaryInput {
  CaseInput in;                   ///< the case, with a history of one segment
  std::string velocity_option;    ///< v, v-list or v-range: named for a velocity's problem
  std::vector<double> velocities; ///< the states' velocities, in order
};

/// Reads the case from its option texts as simulate does (without history
/// and sampling) and its velocities from exactly one of v, v-list
/// ("V1,V2,...") and v-range ("LO:HI:N"). Throws InvalidInput.
StationaryInput read_stationary_input(const OptionTexts& texts);

/// read_stationary_input of typed values (read_case_input's): v a number,
/// v-list a list of numbers.
StationaryInput read_stationary_input(OptionValues values);

/// The stationary states at a.velocities, in order; charges one unit to
/// `control` per velocity (a stop request ends it: Interrupted) and reports
/// the fraction done.
std::vector<State> stationary_states(const StationaryInput& a,
                                     const RunControl& control = RunControl{});

} // namespace mdrmap::cases
