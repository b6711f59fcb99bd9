#pragma once
// kelvin_load, the load-control solver of the Kelvin parabola (docs/design.md,
// "Load control"): a prescribed normal force F0, the depth d(t) free. A row of
// Kelvin elements (a moving window, memory independent of travel) plus the
// depth, integrated with adaptive steps; see core/solvers/load_row.hpp for the
// construction. Auto runs it for the Kelvin parabola under load: the row
// (spectrum.hpp) solves those cases too, at several times its CPU time
// (tools/bench/kelvin_load.cpp).
#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/checked_case.hpp"
#include "core/solvers/load_row.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// Where a load-controlled run starts.
enum class LoadStart {
  Stationary, ///< stationary sliding at v0 under F0 (depth from stationary_depth)
  Rest,       ///< fully relaxed at rest under F0: the Hertz contact
  Undeformed  ///< at rest on undeformed material, F0 applied at t = 0 (creep);
              ///< the depth starts at 1e-12 d0, a time offset of 1e-18 tau
};

struct LoadOptions {
  double rtol = 1e-3;         ///< target case error; sets the resolution when cells == 0
  double cells = 0.0;         ///< fixed resolution a_ref/dx (0: chosen from rtol and refined)
  double time_tol = 0.0;      ///< local error per step, relative to d (0: from rtol)
  double dt_over_tau = 0.0;   ///< fixed time step h = dt_over_tau tau (0: adaptive steps)
  double phase = 0.5;         ///< element offset at t = 0, in cells
  bool estimate_error = true; ///< companion run (half resolution, shifted phase, looser steps)
  LoadStart start = LoadStart::Stationary;
  /// The window is sized for a contact radius of window_a0 a0 (0: the deepest
  /// stationary contact of the history); a run that goes deeper is rerun with
  /// the Hertz contact's window.
  double window_a0 = 0.0;
  /// A segment that has reached its stationary state under load keeps it, in
  /// a run whose resolution and steps are chosen from rtol (cells == 0,
  /// dt_over_tau == 0): no further steps (load_steps.hpp). false: steps on.
  bool keep_stationary = true;
  /// Work budget and stop flag (nullptr: the default budget, no stop flag).
  /// Every loop of the solver charges it (CaseAbandoned past the budget,
  /// Interrupted on a stop request).
  const RunControl* control = nullptr;
};

/// Runs a load-controlled case (c.loading.by_force()). The resolution is set
/// by a_ref = the stationary a1 at the largest velocity of the history (the
/// shallowest contact); the window is 1.6 times the deepest stationary contact
/// of the history wide on each side (a0 with a hold), widened to 1.6 a0 if the
/// edge leaves it.
/// `checks`, if given, receives what the run detected about the model's
/// structure (leading edge, one contact interval, deepest state).
/// With the resolution chosen from rtol (cells == 0), a piece of free
/// material narrower than two cells (a reslide's travel, a band let go at a
/// change) that matters at rtol is resolved first, and a case whose error
/// estimate stays above rtol after five resolutions throws CaseAbandoned
/// (stating the estimate and rtol) instead of returning a result. The case
/// was checked where it was made (CheckedCase); refused here is only what this
/// solver does not take (a fixed depth, Maxwell branches, another profile)
/// and rtol.
RunResult run_load(const CheckedCase& c, const LoadOptions& opt, LoadChecks* checks = nullptr);

} // namespace mdrmap
