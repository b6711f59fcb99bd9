// Slide-hold-slide runs of the spectrum solver (shs.hpp).
#include "shs.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/metrics/events.hpp"
#include "core/solvers/spectrum.hpp"

namespace mdrmap::physics {
namespace {

/// Vertex of the parabola through three points (x, y): the interpolated maximum.
std::pair<double, double> vertex(const double (&x)[3], const double (&y)[3]) {
  const double h0 = x[0] - x[1], h2 = x[2] - x[1];
  const double C = ((y[2] - y[1]) / h2 - (y[0] - y[1]) / h0) / (h2 - h0);
  const double B = (y[2] - y[1]) / h2 - C * h2;
  if (!(C < 0.0)) return {x[1], y[1]};
  return {x[1] - B / (2.0 * C), y[1] - B * B / (4.0 * C)};
}

/// The largest reslide sample (indices n + 1 .. 2n - 1), refined by the parabola.
void reslide_peak(const Series& s, std::size_t n, double t_hold, Healing& h) {
  std::size_t i = n + 1;
  for (std::size_t k = n + 1; k < 2 * n; ++k)
    if (s.mu[k] > s.mu[i]) i = k;
  h.mu_peak = s.mu[i], h.t_peak = s.t[i] - t_hold, h.Fx_peak = s.Fx[i], h.FN_peak = s.FN[i];
  if (i > n + 1 && i + 1 < 2 * n) {
    double x[3], y[3];
    for (int j = 0; j < 3; ++j) {
      const std::size_t k = i - 1 + static_cast<std::size_t>(j);
      x[j] = std::log(s.t[k] - t_hold), y[j] = s.mu[k];
    }
    const auto [xv, yv] = vertex(x, y);
    h.mu_peak = std::max(yv, s.mu[i]), h.t_peak = std::exp(xv);
  }
}

} // namespace

Healing shs(const Case& base, double v0, double t_hold, double rtol) {
  Case c = base;
  c.history.v0 = v0;
  c.history.segments = {Segment{0.0, t_hold}, Segment{v0, 20.0 / v0}};
  c.sampling.samples = 801;
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 8.0;
  SpectrumOptions so;
  so.rtol = rtol;
  const RunResult res = run_spectrum(CheckedCase(c), so);
  const Series& s = res.series;
  const std::size_t n = static_cast<std::size_t>(c.sampling.samples);
  Healing h;
  h.mu_pre = s.pre.mu;
  h.FN_hold = s.FN[n - 1];
  h.d_hold = s.d[n - 1], h.a1_hold = s.a1[n - 1];
  h.err = res.info.error_estimate;
  reslide_peak(s, n, t_hold, h);
  h.mu_peak_events = event_metrics(c, s, res.transients, h.err, res.probes).at(1).mu_peak;
  return h;
}

} // namespace mdrmap::physics
