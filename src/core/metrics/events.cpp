#include "core/metrics/events.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/metrics/stationary.hpp"

namespace mdrmap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// ln(w1/w0), or NaN where it is undefined or zero.
double log_ratio(double w0, double w1) {
  if (!(w0 > 0.0) || !(w1 > 0.0) || w0 == w1) return kNaN;
  return std::log(w1 / w0);
}

/// The transient of a segment read off its samples i0 .. i0 + n - 1.
Transient from_samples(const Series& s, std::size_t i0, long n, double mu_ss) {
  TransientTracker tr(mu_ss, s.mu[i0]);
  for (long j = 1; j < n; ++j) {
    const std::size_t i = i0 + static_cast<std::size_t>(j);
    tr.add(s.t[i] - s.t[i0], s.mu[i]);
  }
  return tr.result();
}

/// D_c from a transient at velocity w (docs/design.md, "Event metrics").
double decay_slip(const Transient& tr, double w) {
  if (!(w > 0.0) || !(tr.overshoot <= 1.0 / std::exp(1.0))) return kNaN;
  return w * tr.t_decay; // (NaN if it does not decay to 1/e)
}

} // namespace

std::vector<EventMetrics> event_metrics(const Case& c, const Series& series,
                                        const std::vector<Transient>& transients) {
  const auto N = c.sampling.samples;
  if (series.size() != c.total_samples())
    throw std::invalid_argument("event_metrics: the series does not match the case's samples");
  if (!transients.empty() && transients.size() != c.history.size())
    throw std::invalid_argument("event_metrics: one transient per segment expected");
  std::vector<EventMetrics> out(c.history.size());
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    EventMetrics& e = out[k];
    const std::size_t i0 = k * static_cast<std::size_t>(N),
                      i_end = i0 + static_cast<std::size_t>(N) - 1;
    e.t = series.t[i0];
    e.w_before = c.history.before(k);
    e.w_after = c.history.segments[k].w;
    e.ss_before = stationary_state(c, e.w_before);
    e.ss_after = stationary_state(c, e.w_after);
    e.mu_before = k == 0 ? series.pre.mu : series.mu[i0 - 1];
    e.mu_after = series.mu[i0];
    Transient tr; // no change: no transient (what a solver shows there is its noise)
    tr.mu_peak = e.mu_after;
    if (e.w_before != e.w_after)
      tr = transients.empty() ? from_samples(series, i0, N, e.ss_after.mu) : transients[k];
    e.mu_peak = tr.mu_peak;
    e.t_peak = tr.t_peak;
    e.slip_peak = e.w_after * e.t_peak;
    e.end = series.at(i_end);
    e.d_c = decay_slip(tr, e.w_after);
    e.overshoot = tr.overshoot;
    const double lr = log_ratio(e.w_before, e.w_after);
    e.a = (e.mu_after - e.mu_before) / lr;
    e.a_minus_b = (e.ss_after.mu - e.ss_before.mu) / lr;
    e.b = e.a - e.a_minus_b;
  }
  return out;
}

} // namespace mdrmap
