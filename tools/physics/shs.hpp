#pragma once
// One slide-hold-slide run of the spectrum solver, at fixed depth or under
// load: stationary sliding at v0, a hold, the reslide at v0; the friction peak
// of the reslide and the state at the end of the hold.
#include "core/model/case.hpp"

namespace mdrmap::physics {

struct Healing {
  double mu_pre = 0, mu_peak = 0, t_peak = 0, Fx_peak = 0, FN_peak = 0, FN_hold = 0, err = 0;
  double d_hold = 0, a1_hold = 0; ///< depth and contact half-width at the end of the hold
  double mu_peak_events = 0;      ///< the reslide's mu_peak from the event metrics (a check)
  double healing() const { return mu_peak - mu_pre; }
};

/// Stationary sliding at v0, a hold of t_hold at the base case's loading (its
/// depth or its load F0), reslide at v0 for 20 a1/v0 (a1 = 1); samples
/// log-spaced (100 per decade over 8 decades of each segment). The peak is
/// the largest reslide sample, refined by a parabola in log t through it and
/// its neighbours. Throws CaseAbandoned as run_spectrum does.
Healing shs(const Case& base, double v0, double t_hold, double rtol);

} // namespace mdrmap::physics
