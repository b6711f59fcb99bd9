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
  State after;            ///< the state at t_k+ (the segment's first sample; after.mu = mu_after)
  /// The largest and the smallest mu within the segment, their times since
  /// the change and their slips w_k t (from the solution, not the samples).
  double mu_max = 0.0, t_max = 0.0, slip_max = 0.0;
  double mu_min = 0.0, t_min = 0.0, slip_min = 0.0;
  /// The extremum on the side of the change: mu_max after a rise, mu_min
  /// after a drop or into a hold; mu_after where the segment shows no
  /// transient (no change, or a deviation within the solver's error).
  double mu_peak = 0.0;
  double t_peak = 0.0;    ///< its time since the change
  double slip_peak = 0.0; ///< its slip since the change, w_k t_peak
  State end;              ///< the state at the segment's end (its last sample)
  State ss_before;        ///< stationary state at w_(k-1)
  State ss_after;         ///< stationary state at w_k
  /// Slip over which |mu - mu_ss(w_k)| first falls to 1/e of its value at the
  /// reference point: the change (t_k+) for a material with a parallel
  /// dashpot, the peak (mu_peak) for one without, the slip counted from
  /// there. NaN where d_c_undefined says why.
  double d_c = 0.0;
  /// Why d_c is NaN (nullptr where it is defined): "no_change", "hold",
  /// "no_transient", "peak_at_end", "overshoot", "no_decay".
  const char* d_c_undefined = nullptr;
  /// Largest excursion of mu beyond mu_ss(w_k), after the reference point, on
  /// the side opposite to it, relative to its deviation; 0 for a one-sided
  /// transient.
  double overshoot = 0.0;
  /// Direct effect (mu_direct - mu(t_k-)) / ln(w_k / w_(k-1)), mu_direct =
  /// mu(t_k+) with a parallel dashpot, mu_peak without one; NaN if a
  /// velocity is 0 or they are equal, or without a dashpot if the peak is
  /// the segment's end (peak_at_end). Where the segment shows no transient
  /// the whole change is direct: a = a - b, b = 0.
  double a = 0.0;
  /// (mu_ss(w_k) - mu_ss(w_(k-1))) / ln(w_k / w_(k-1)); NaN likewise.
  double a_minus_b = 0.0;
  double b = 0.0; ///< a - (a - b); NaN likewise
  /// Static healing of a reslide after a hold (w_(k-1) = 0 < w_k, k >= 1):
  /// mu_max - mu_ss(w_(k-2)), the stationary mu of the slide before the hold;
  /// NaN for any other segment.
  double healing = 0.0;
};

/// One record per segment of the history. `series` holds the case's samples
/// (segment after segment, sampling.count(k) each); `transients` (RunResult::
/// transients) one Transient per segment from the solver's solution, or none:
/// then the extrema and the decay are read off the samples (as the parabola
/// through consecutive samples), and depend on where they fall.
/// `probes` (RunResult::probes), where given in place of transients: the
/// solution at instants fixed by each segment, read as the samples would be.
/// `error_estimate` (RunInfo::error_estimate): a deviation from mu_ss at the
/// reference point within it times the segment's largest |mu| is no
/// transient (the solver's noise).
std::vector<EventMetrics> event_metrics(const Case& c, const Series& series,
                                        const std::vector<Transient>& transients = {},
                                        double error_estimate = 0.0,
                                        const std::vector<Probes>& probes = {});

/// How a material's transient is read (docs/design.md, "Event metrics"):
/// from the change where a parallel dashpot makes the friction jump there,
/// else from the peak after it.
TransientTracker::Reference transient_reference(const Case& c);

} // namespace mdrmap
