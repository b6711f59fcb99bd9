// Study 4: a velocity step v -> 10 v at fixed depth without a parallel dashpot
// (tau = 0): no instantaneous jump; how mu rises and where its first extremum lies.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "core/solvers/spectrum.hpp"
#include "studies.hpp"

namespace mdrmap::physics {
namespace {

/// Linear interpolation of mu in log t over the samples of segment 0 (t > 0).
double mu_at(const Series& s, std::size_t n, double t) {
  for (std::size_t k = 2; k < n; ++k)
    if (s.t[k] >= t) {
      const double f = std::log(t / s.t[k - 1]) / std::log(s.t[k] / s.t[k - 1]);
      return s.mu[k - 1] + f * (s.mu[k] - s.mu[k - 1]);
    }
  return s.mu[n - 1];
}

/// Prints the rise of mu after the step and the share of its extremum reached at fixed delays.
void print_rise(const char* name, const RunResult& res, double v1, double tmin) {
  const Series& s = res.series;
  const std::size_t n = s.size();
  const std::size_t imax =
      static_cast<std::size_t>(std::max_element(s.mu.begin(), s.mu.end()) - s.mu.begin());
  std::printf("  %-22s mu_pre %.6g  mu(0+)-mu_pre %.2e  peak %.6g at t/tau_min %.3g (travel "
              "%.3g a1)  final %.6g  err %.1e\n    mu(t)-mu_pre at t/tau_min:",
              name, s.pre.mu, s.mu[0] - s.pre.mu, s.mu[imax], s.t[imax] / tmin, v1 * s.t[imax],
              s.mu[n - 1], res.info.error_estimate);
  for (double f : {1e-4, 1e-3, 1e-2, 1e-1, 1.0, 3.0, 10.0})
    std::printf(" %g: %.4g", f, mu_at(s, n, f * tmin) - s.pre.mu);
  std::printf(
      "\n    jump share (mu(t)-mu_pre)/(peak-mu_pre) at t/tau_min 0.1, 1, 3: %.3f %.3f %.3f\n",
      (mu_at(s, n, 0.1 * tmin) - s.pre.mu) / (s.mu[imax] - s.pre.mu),
      (mu_at(s, n, tmin) - s.pre.mu) / (s.mu[imax] - s.pre.mu),
      (mu_at(s, n, 3.0 * tmin) - s.pre.mu) / (s.mu[imax] - s.pre.mu));
}

void direct_effect(const char* name, const Rheology& r, double v, double rtol, std::ostream& csv) {
  Case c = make_case(r, false);
  const double v1 = 10.0 * v, tmin = r.branches.front().tau;
  c.history.v0 = v;
  c.history.segments = {Segment{v1, std::max(40.0 / v1, 10.0 * r.branches.back().tau)}};
  c.sampling.samples = 1201;
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 12.0;
  SpectrumOptions so;
  so.rtol = rtol;
  const RunResult res = run_spectrum(CheckedCase(c), so);
  const Series& s = res.series;
  for (std::size_t k = 0; k < s.size(); ++k)
    csv << name << "," << s.t[k] / tmin << "," << s.mu[k] << "," << s.mu[k] - s.pre.mu << "\n";
  print_rise(name, res, v1, tmin);
}

} // namespace

void study_direct(const Options& o) {
  auto csv = open_csv(o, "spectrum_direct.csv", "spectrum,t_over_tau_min,mu_over_a1R,dmu");
  std::printf("\n# 4. Velocity step up v -> 10 v at fixed depth, tau = 0 (no parallel dashpot); "
              "z = v tau_min/a1 before the step\n");
  for (double z : {0.01, 0.1, 1.0, 10.0}) {
    char name[64];
    std::snprintf(name, sizeof name, "SLS G0/G=10 z=%g", z);
    direct_effect(name, decade_spectrum(1, 10.0), z, o.rtol, csv);
  }
  for (double z : {0.01, 0.1, 1.0}) {
    char name[64];
    std::snprintf(name, sizeof name, "6x G0/G=100 z=%g", z);
    direct_effect(name, decade_spectrum(6, 100.0), z / 1e-5, o.rtol, csv);
  }
}

} // namespace mdrmap::physics
