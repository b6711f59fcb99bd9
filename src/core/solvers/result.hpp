#pragma once
// What a solver returns: the case's samples, the transients of its segments
// from the solution itself, and what the run cost; the tolerance every solver
// takes.
#include <string>
#include <vector>

#include "core/metrics/transient.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

/// What a run cost and how accurate it believes it is.
struct RunInfo {
  std::string solver;          ///< which solver ran: "exact", "row", "baseline" or "kelvin_load"
  double rtol = 0.0;           ///< requested tolerance
  double error_estimate = 0.0; ///< estimated case error (docs/design.md, "Error metric")
  double cells_per_a1 = 0.0;   ///< resolution a1/dx of the final run (0 for exact)
  long elements = 0;           ///< elements held in memory at once (peak, final run)
  long steps = 0;              ///< time steps taken, all runs included
  long element_updates = 0;    ///< element state updates, all runs included
  long root_solves = 0;        ///< scalar root solves (exact solver)
  int refinements = 0;         ///< resolutions tried by the error control
};

struct RunResult {
  Series series;
  /// One per segment, from the continuous solution (independent of the
  /// output instants: core/metrics/transient.hpp); empty where the solver
  /// gives only its samples (the event metrics then read those).
  std::vector<Transient> transients;
  /// Or one per segment, the solution at instants fixed by the segment (a
  /// stepping solver's: core/solvers/refine.hpp, ProbeRule), which the event
  /// metrics read in place of the samples; empty where the solver has none.
  std::vector<Probes> probes;
  RunInfo info;
};

/// Throws InvalidInput("rtol") unless 0 < rtol <= 0.1.
/// The range of rtol, as messages and help texts say it.
inline constexpr const char* kRtolAllowed = "a number in (0, 0.1]";
void validate_rtol(double rtol);

} // namespace mdrmap
