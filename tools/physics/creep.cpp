// Study 5: Lee-Radok creep from rest under a step load, creep_depth (the
// retardation spectrum) against two independent computations: the Talbot
// inversion of J_bar(s) and the hereditary integral by product integration.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <ostream>
#include <vector>

#include "core/metrics/creep.hpp"
#include "studies.hpp"

namespace mdrmap::physics {
namespace {

/// J(t) by the fixed Talbot inversion (Abate and Valko 2004) of
/// J_bar(s) = 1 / (s^2 G_bar(s)), G_bar(s) = G / s + sum G_k tau_k / (1 + s tau_k).
double talbot_J(const Rheology& r, double t) {
  using cd = std::complex<double>;
  const auto Jbar = [&r](cd s) {
    cd gbar = r.G / s;
    for (const Branch& b : r.branches)
      gbar += b.G * b.tau / (1.0 + s * b.tau);
    return 1.0 / (s * s * gbar);
  };
  const int M = 24;
  const double rr = 2.0 * M / (5.0 * t);
  double sum = 0.5 * std::exp(rr * t) * Jbar(cd(rr, 0.0)).real();
  for (int k = 1; k < M; ++k) {
    const double th = k * M_PI / M, cot = 1.0 / std::tan(th);
    const cd s = rr * th * cd(cot, 1.0);
    const cd sigma(1.0, th + (th * cot - 1.0) * cot);
    sum += (std::exp(t * s) * Jbar(s) * sigma).real();
  }
  return rr / M * sum;
}

/// d^(3/2)(t) = X(t) from the Lee-Radok integral C = int_0^t G(t - t') dX(t'),
/// C = 3 F0 / (16 sqrt R), X(0+) = C / G0, X piecewise linear on the grid
/// (product integration, the exponentials integrated exactly; second order).
std::vector<double> hereditary_X(const Rheology& r, double C, const std::vector<double>& t) {
  const double g0 = r.G0();
  std::vector<double> I(r.branches.size(), 0.0), X;
  double x = C / g0, prev = 0.0;
  for (double tn : t) {
    const double dt = tn - prev;
    double lhs = r.G * dt, rhs = C - r.G * x;
    for (std::size_t k = 0; k < r.branches.size(); ++k) {
      const Branch& b = r.branches[k];
      const double e = std::exp(-dt / b.tau);
      lhs += b.G * b.tau * (-std::expm1(-dt / b.tau));
      rhs -= b.G * (C / g0 * std::exp(-tn / b.tau) + e * I[k]);
      I[k] *= e;
    }
    const double slope = rhs / lhs;
    for (std::size_t k = 0; k < r.branches.size(); ++k)
      I[k] += slope * r.branches[k].tau * (-std::expm1(-dt / r.branches[k].tau));
    x += slope * dt;
    X.push_back(x);
    prev = tn;
  }
  return X;
}

/// Largest |d_hereditary / d_creep - 1| with `per` grid points per decade.
double hereditary_error(const Case& c, double C, double lo, double hi, int per) {
  const std::vector<double> t = logspace(lo, hi, per);
  const std::vector<double> X = hereditary_X(c.rheology, C, t);
  double e = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i)
    e = std::max(e, std::abs(std::cbrt(X[i] * X[i]) / creep_depth(c, t[i]) - 1.0));
  return e;
}

void creep_row(const char* name, const Rheology& r, std::ostream& csv) {
  const Case c = make_case(r, true);
  const double C = 3.0 * c.loading.F0 / (16.0 * std::sqrt(c.indenter.as<mdrmap::Parabola>().R));
  const double lo = 1e-4 * r.branches.front().tau, hi = 1e4 * r.branches.back().tau;
  const std::vector<double> t = logspace(lo, hi, 400);
  const std::vector<double> X = hereditary_X(r, C, t);
  double e_talbot = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double d = creep_depth(c, t[i]);
    const double d_t = std::cbrt(std::pow(C * talbot_J(r, t[i]), 2.0));
    e_talbot = std::max(e_talbot, std::abs(d_t / d - 1.0));
    if (i % 10 == 0)
      csv << name << "," << t[i] << "," << d << "," << d_t << "," << std::cbrt(X[i] * X[i]) << "\n";
  }
  std::printf("  %-14s d(0+) %.6g  d(inf) %.6g  max |d/d_creep - 1| over %zu times %g..%g: Talbot "
              "%.1e; hereditary, 100/200/400/800 per decade: %.1e %.1e %.1e %.1e\n",
              name, creep_depth(c, lo), creep_depth(c, 1e3 * hi), t.size(), lo, hi, e_talbot,
              hereditary_error(c, C, lo, hi, 100), hereditary_error(c, C, lo, hi, 200),
              hereditary_error(c, C, lo, hi, 400), hereditary_error(c, C, lo, hi, 800));
}

} // namespace

void study_creep(const Options& o) {
  auto csv = open_csv(o, "spectrum_creep.csv", "spectrum,t,d_creep,d_talbot,d_hereditary");
  std::printf("\n# 5. Lee-Radok creep under a step load F0 = 16/3 (a0 = d0 = 1 with G = 1): "
              "creep_depth against two independent computations\n");
  creep_row("SLS G0/G=10", decade_spectrum(1, 10.0), csv);
  creep_row("6x G0/G=100", decade_spectrum(6, 100.0), csv);
  creep_row("6x G0/G=1e4", decade_spectrum(6, 1e4), csv);
}

} // namespace mdrmap::physics
