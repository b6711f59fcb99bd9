#pragma once
// Event metrics of a velocity history, in the usual rate-and-state sense
// (Dieterich; Ruina; Marone 1998), one record per velocity change k (the
// change at the start of segment k, from w_(k-1) to w_k; w_(-1) = v0).
// The extremum and the decay come from the solver's solution where the solver
// gives it (core/metrics/transient.hpp), else from the run's samples
// (docs/design.md, "Event metrics").
#include <vector>

#include "core/metrics/transient.hpp"
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

struct EventMetrics {
  double t = 0.0;         ///< time of the change t_k
  double w_before = 0.0;  ///< w_(k-1)
  double w_after = 0.0;   ///< w_k
  double mu_before = 0.0; ///< mu(t_k-): the last sample of the previous segment (pre for k = 0)
  double mu_after = 0.0;  ///< mu(t_k+): the first sample of the segment
  double mu_peak = 0.0;   ///< extremum of mu in the segment: the value farthest from mu_ss(w_k)
  double t_peak = 0.0;    ///< its time since the change
  double slip_peak = 0.0; ///< its slip since the change, w_k t_peak
  State end;              ///< the state at the segment's end (its last sample)
  State ss_before;        ///< stationary state at w_(k-1)
  State ss_after;         ///< stationary state at w_k
  /// Slip since the change over which |mu - mu_ss(w_k)| first falls to 1/e of
  /// its value at t_k+; NaN if it does not within the segment, if mu(t_k+) =
  /// mu_ss(w_k), during a hold, or if the transient overshoots by more than
  /// 1/e (overshoot > 1/e: not a decay).
  double d_c = 0.0;
  /// Largest excursion of mu beyond mu_ss(w_k) on the side opposite to
  /// mu(t_k+), relative to |mu(t_k+) - mu_ss(w_k)|; 0 for a one-sided transient.
  double overshoot = 0.0;
  /// Direct effect (mu(t_k+) - mu(t_k-)) / ln(w_k / w_(k-1)); NaN if a
  /// velocity is 0 or they are equal.
  double a = 0.0;
  /// (mu_ss(w_k) - mu_ss(w_(k-1))) / ln(w_k / w_(k-1)); NaN likewise.
  double a_minus_b = 0.0;
  double b = 0.0; ///< a - (a - b); NaN likewise
};

/// One record per segment of the history. `series` holds the case's samples
/// (segment after segment, samples.samples each); `transients` (RunResult::
/// transients) one Transient per segment from the solver's solution, or none:
/// then the extremum and the decay are read off the samples (as the parabola
/// through consecutive samples), and depend on where they fall.
std::vector<EventMetrics> event_metrics(const Case& c, const Series& series,
                                        const std::vector<Transient>& transients = {});

} // namespace mdrmap
