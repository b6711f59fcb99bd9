#pragma once
// The straightforward method of the paper, kept as a baseline and as an
// independent brute-force reference: elements laid over the whole travel
// path, one fixed time step dt = dx / (largest velocity of the history), starting from an
// undeformed foundation, contact decided at step ends, raw element sums for the forces.
#include "core/model/case.hpp"
#include "core/solvers/result.hpp"
#include "core/solvers/run_control.hpp"

namespace mdrmap {

struct BaselineOptions {
  double cells_per_a1 = 100;      ///< a1/dx
  double spinup_travel = 4.0;     ///< travel before the step, in units of a1 (>= 2)
  double steps_per_cell = 1.0;    ///< time step = dx / (steps_per_cell * largest velocity)
  long max_elements = 50'000'000; ///< refuse scenes that would need more
  bool estimate_error = true;     ///< run a half-resolution companion for error_estimate
  /// Work budget and stop flag (nullptr: the default budget, no stop flag).
  const RunControl* control = nullptr;
};

RunResult run_baseline(const Case& c, const BaselineOptions& opt);

} // namespace mdrmap
