#pragma once
// The straightforward fixed-step element row under load control, kept as an
// independent brute-force check of the load-control solver (docs/design.md,
// "Load control", the independent check). Deliberately plain:
// elements over the whole travel path, one fixed time step, contact decided at
// step ends, raw element sums. The depth follows from the force balance each
// step: over the contact set C, F0 = 4 G dx sum_C (D - g - tau w g') with
// D = d + tau d', so D is explicit, and d relaxes towards D exactly over the
// step, d <- D + (d - D) exp(-dt/tau) (stable for dt >> tau and tau = 0).
// First order in dx and in dt. Shares no code with the load-control solver.
#include "core/metrics/analytic.hpp"
#include "core/model/case.hpp"
#include "core/solvers/result.hpp"
#include "core/solvers/run_control.hpp"

namespace mdrmap {

/// Where the run starts at t = 0.
enum class LoadBaselineStart {
  Stationary, ///< stationary sliding at v0 under F0 (depth from load_check::stationary_depth)
  Undeformed, ///< foundation undeformed, indenter at rest on it, F0 applied at t = 0
};

struct LoadBaselineOptions {
  double cells_per_a0 = 100;   ///< a0/dx, a0 the Hertz radius of F0
  double steps_per_cell = 1.0; ///< dt = dx / (steps_per_cell * largest velocity)...
  double dt = 0.0;             ///< ...unless dt > 0 is given (holds, creep)
  double phase = 0.0;          ///< element offset at t = 0, in cells (0: one at xi = 0)
  double depth_limit = 2.25;   ///< window: contact allowed up to a1 = sqrt(limit) a0
  LoadBaselineStart start = LoadBaselineStart::Stationary;
  bool graded_start = true;       ///< undeformed start: steps t dt / tau until t = tau
  long max_elements = 20'000'000; ///< refuse cases that would need more
  bool estimate_error = true;     ///< half-resolution companion for error_estimate
  /// Work budget and stop flag (nullptr: the default budget, no stop flag):
  /// every step, balance and touch charges the elements it visits.
  const RunControl* control = nullptr;
};

/// Runs a load-controlled case (c.loading.by_force()); throws InvalidInput for
/// a depth-controlled case or bad options, std::runtime_error when the depth
/// leaves the window or the case is too expensive. F_N equals F0 at every
/// sample by construction (the depth is chosen so); d, a1 are in the series.
RunResult run_load_baseline(const Case& c, const LoadBaselineOptions& opt);

namespace load_check {

/// Normal force of stationary sliding at velocity w at fixed depth d:
/// analytic::stationary on a copy of the case held at depth d.
double stationary_force(const Case& c, double d, double w);

/// The depth of stationary sliding at w under c.loading.F0: the root of
/// stationary_force(c, d, w) = F0 (bracketed from d0 = a0^2/R downwards, TOMS 748
/// to the last bit). tau = 0 or w = 0: d0.
double stationary_depth(const Case& c, double w);

/// The stationary state at w under load: the fixed-depth stationary state at
/// stationary_depth(c, w).
State stationary_state(const Case& c, double w);

} // namespace load_check

} // namespace mdrmap
