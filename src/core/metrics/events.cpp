#include "core/metrics/events.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/metrics/analytic.hpp"
#include "core/metrics/load_stationary.hpp"

namespace mdrmap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// ln(w1/w0), or NaN where it is undefined or zero.
double log_ratio(double w0, double w1) {
  if (!(w0 > 0.0) || !(w1 > 0.0) || w0 == w1) return kNaN;
  return std::log(w1 / w0);
}

/// Slip over which |mu - mu_ss| falls to 1/e of its first value, from the
/// samples i0 .. i0 + n - 1 of one segment at velocity w.
double one_over_e_slip(const Series& s, std::size_t i0, long n, double mu_ss, double w) {
  const double dev0 = std::abs(s.mu[i0] - mu_ss);
  if (!(w > 0.0) || !(dev0 > 0.0)) return kNaN;
  const double target = dev0 / std::exp(1.0);
  for (long j = 1; j < n; ++j) {
    const std::size_t i = i0 + static_cast<std::size_t>(j);
    const double dev = std::abs(s.mu[i] - mu_ss);
    if (dev <= target) {
      const double prev = std::abs(s.mu[i - 1] - mu_ss);
      const double f = (prev - target) / (prev - dev); // in (0, 1]
      const double t = s.t[i - 1] + f * (s.t[i] - s.t[i - 1]);
      return w * (t - s.t[i0]);
    }
  }
  return kNaN;
}

/// The stationary state at w: at the case's depth, or under its load F0.
State stationary_of(const Case& c, double w) {
  return c.loading.by_force() ? stationary_under_load(c, w) : analytic::stationary(c, w);
}

} // namespace

std::vector<EventMetrics> event_metrics(const Case& c, const Series& series) {
  const auto N = c.sampling.samples;
  if (series.size() != c.total_samples())
    throw std::invalid_argument("event_metrics: the series does not match the case's samples");
  std::vector<EventMetrics> out(c.history.size());
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    EventMetrics& e = out[k];
    const std::size_t i0 = k * static_cast<std::size_t>(N),
                      i_end = i0 + static_cast<std::size_t>(N) - 1;
    e.t = series.t[i0];
    e.w_before = c.history.before(k);
    e.w_after = c.history.segments[k].w;
    e.ss_before = stationary_of(c, e.w_before);
    e.ss_after = stationary_of(c, e.w_after);
    e.mu_before = k == 0 ? series.pre.mu : series.mu[i0 - 1];
    e.mu_after = series.mu[i0];
    std::size_t ip = i0;
    for (std::size_t i = i0; i <= i_end; ++i)
      if (std::abs(series.mu[i] - e.ss_after.mu) > std::abs(series.mu[ip] - e.ss_after.mu)) ip = i;
    e.mu_peak = series.mu[ip];
    e.t_peak = series.t[ip] - e.t;
    e.slip_peak = e.w_after * e.t_peak;
    e.end = series.at(i_end);
    e.d_c = one_over_e_slip(series, i0, N, e.ss_after.mu, e.w_after);
    const double lr = log_ratio(e.w_before, e.w_after);
    e.a = (e.mu_after - e.mu_before) / lr;
    e.a_minus_b = (e.ss_after.mu - e.ss_before.mu) / lr;
    e.b = e.a - e.a_minus_b;
  }
  return out;
}

} // namespace mdrmap
