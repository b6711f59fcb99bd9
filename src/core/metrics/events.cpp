#include "core/metrics/events.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/metrics/stationary.hpp"

namespace mdrmap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A deviation at or below this fraction of the segment's largest |mu| is
/// rounding whatever the error estimate (the exact solver's is ~1e-15).
constexpr double kRoundingDeviation = 1e-12;

/// ln(w1/w0), or NaN where it is undefined or zero.
double log_ratio(double w0, double w1) {
  if (!(w0 > 0.0) || !(w1 > 0.0) || w0 == w1) return kNaN;
  return std::log(w1 / w0);
}

/// The transient of a segment read off its samples i0 .. i0 + n - 1.
Transient from_samples(const Series& s, std::size_t i0, long n, double mu_ss,
                       TransientTracker::Reference ref, double direction) {
  TransientTracker tr(mu_ss, s.mu[i0], ref, direction);
  for (long j = 1; j < n; ++j) {
    const std::size_t i = i0 + static_cast<std::size_t>(j);
    tr.add(s.t[i] - s.t[i0], s.mu[i]);
  }
  return tr.result();
}

/// The transient of a segment from its probes.
Transient from_probes(const Probes& p, double mu_ss, TransientTracker::Reference ref,
                      double direction) {
  TransientTracker tr(mu_ss, p.mu.front(), ref, direction);
  for (std::size_t i = 1; i < p.t.size(); ++i)
    tr.add(p.t[i], p.mu[i]);
  return tr.result();
}

/// D_c from a transient at velocity w, or why it is undefined
/// (docs/design.md, "Event metrics").
const char* decay_slip(const Transient& tr, double w, double* d_c) {
  *d_c = kNaN;
  if (!(w > 0.0)) return "hold";
  if (tr.ref_at_end) return "peak_at_end";
  if (!(tr.overshoot <= 1.0 / std::exp(1.0))) return "overshoot";
  if (std::isnan(tr.t_decay)) return "no_decay";
  *d_c = w * (tr.t_decay - tr.t_ref);
  return nullptr;
}

/// -0 as +0 (a value is never printed or stored as -0).
void positive_zeros(EventMetrics& e) {
  for (double* x :
       {&e.mu_max, &e.t_max, &e.slip_max, &e.mu_min, &e.t_min, &e.slip_min, &e.mu_peak, &e.t_peak,
        &e.slip_peak, &e.d_c, &e.overshoot, &e.a, &e.a_minus_b, &e.b, &e.healing})
    *x += 0.0;
}

/// The extrema, the peak and the decay of segment k's transient tr; false
/// where the segment shows none (no change, or its noise).
bool read_transient(EventMetrics& e, const Transient& tr, double noise) {
  e.mu_max = tr.mu_max;
  e.t_max = tr.t_max;
  e.slip_max = e.w_after * tr.t_max;
  e.mu_min = tr.mu_min;
  e.t_min = tr.t_min;
  e.slip_min = e.w_after * tr.t_min;
  const double direction = e.w_after > e.w_before ? 1.0 : -1.0;
  e.mu_peak = direction > 0.0 ? tr.mu_max : tr.mu_min;
  e.t_peak = direction > 0.0 ? tr.t_max : tr.t_min;
  const double scale = std::max({std::abs(tr.mu_max), std::abs(tr.mu_min), std::abs(e.mu_after)});
  if (e.w_before == e.w_after) {
    e.d_c_undefined = "no_change";
  } else if (!(tr.dev_ref > std::max(noise, kRoundingDeviation) * scale)) {
    e.d_c_undefined = "no_transient";
  } else {
    e.d_c_undefined = decay_slip(tr, e.w_after, &e.d_c);
    e.overshoot = tr.overshoot;
    return true;
  }
  // no transient: what the solver shows is its noise
  e.mu_peak = e.mu_after;
  e.t_peak = 0.0;
  e.d_c = kNaN;
  e.overshoot = 0.0;
  return false;
}

} // namespace

TransientTracker::Reference transient_reference(const Case& c) {
  return c.rheology.tau > 0.0 ? TransientTracker::Reference::Change
                              : TransientTracker::Reference::Peak;
}

std::vector<EventMetrics> event_metrics(const Case& c, const Series& series,
                                        const std::vector<Transient>& transients,
                                        double error_estimate, const std::vector<Probes>& probes) {
  if (series.size() != c.total_samples())
    throw std::invalid_argument("event_metrics: the series does not match the case's samples");
  if (!transients.empty() && transients.size() != c.history.size())
    throw std::invalid_argument("event_metrics: one transient per segment expected");
  if (!probes.empty() && probes.size() != c.history.size())
    throw std::invalid_argument("event_metrics: one probe series per segment expected");
  const TransientTracker::Reference ref = transient_reference(c);
  std::vector<EventMetrics> out(c.history.size());
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    EventMetrics& e = out[k];
    const long N = c.sampling.count(k);
    const std::size_t i0 = c.first_sample(k), i_end = i0 + static_cast<std::size_t>(N) - 1;
    e.t = series.t[i0];
    e.w_before = c.history.before(k);
    e.w_after = c.history.segments[k].w;
    e.ss_before = stationary_state(c, e.w_before);
    e.ss_after = stationary_state(c, e.w_after);
    e.mu_before = k == 0 ? series.pre.mu : series.mu[i0 - 1];
    e.after = series.at(i0);
    e.mu_after = e.after.mu;
    const double direction = e.w_after > e.w_before ? 1.0 : -1.0;
    const Transient tr = !transients.empty() ? transients[k]
                         : !probes.empty() && !probes[k].t.empty()
                             ? from_probes(probes[k], e.ss_after.mu, ref, direction)
                             : from_samples(series, i0, N, e.ss_after.mu, ref, direction);
    const bool transient = read_transient(e, tr, error_estimate);
    e.slip_peak = e.w_after * e.t_peak;
    e.end = series.at(i_end);
    const double lr = log_ratio(e.w_before, e.w_after);
    const bool jump = ref == TransientTracker::Reference::Change;
    e.a_minus_b = (e.ss_after.mu - e.ss_before.mu) / lr;
    if (!transient) {
      e.a = e.a_minus_b; // the whole change is direct
      e.b = std::isnan(lr) ? kNaN : 0.0;
    } else if (!jump && tr.ref_at_end) {
      e.a = e.b = kNaN; // no peak within the segment: no direct effect to read
    } else {
      e.a = ((jump ? e.mu_after : e.mu_peak) - e.mu_before) / lr;
      e.b = e.a - e.a_minus_b;
    }
    e.healing = kNaN;
    if (k >= 1 && e.w_before == 0.0 && e.w_after > 0.0)
      e.healing = e.mu_max - stationary_state(c, c.history.before(k - 1)).mu;
    positive_zeros(e);
  }
  return out;
}

} // namespace mdrmap
