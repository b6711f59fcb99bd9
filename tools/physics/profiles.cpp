// Study 7: indenter profiles on the Kelvin foundation, from the stationary
// states of profile_stationary (docs/design.md, "Indenter profiles"):
//   7a  the cone at fixed depth and under load: where the rear face lets go,
//       how mu reaches (pi/2) tan beta, against the parabola and the power law
//   7b  the friction maximum against the exponent n of f = A r^n
//   7c  the cone's stationary state against its closed form
// Units: G = 1, tau = 1, d = 1 at fixed depth, F0 = 1 under load, A = 1;
// x = v tau / a (a = a1 at fixed depth, a0 under load), mu / g'(a): mu is the
// pressure-weighted mean of the slope -g' over the contact, so 0 <= mu <= g'(a1)
// (the cone: mu / c, c = (pi/2) tan beta).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/metrics/profile_stationary.hpp"
#include "core/solvers/checked_case.hpp"
#include "peak.hpp"
#include "studies.hpp"

namespace mdrmap::physics {
namespace {

const double kBetas[] = {5.0, 10.0, 30.0};

Indenter cone(double beta) {
  return mdrmap::Cone{beta};
}

Indenter power(double n) {
  return mdrmap::Power{n, 1.0};
}

Indenter parabola() {
  return mdrmap::Parabola{1.0};
}

/// The Kelvin foundation G = tau = 1 at depth d = 1 or under F0 = 1.
Case kelvin_case(const Indenter& ind, bool load) {
  Case c;
  c.indenter = ind;
  c.rheology.G = 1.0;
  c.rheology.tau = 1.0;
  if (load)
    c.loading.F0 = 1.0;
  else
    c.loading.d = 1.0;
  c.history.v0 = 1.0;
  c.history.segments = {Segment{1.0, 1.0}};
  validate(c);
  return c;
}

/// The stationary state at x = v tau / a, in units of a (edges) and g'(a) (mu).
struct Point {
  double mu, a2, a1;
};

Point at(const Case& c, double x) {
  const double a = c.edge_scale();
  const State st = profile_stationary(c, x * a / c.rheology.tau);
  return {st.mu / c.indenter.slope(a), st.a2 / a, st.a1 / a};
}

const char* loading_name(bool load) {
  return load ? "load" : "depth";
}

/// The curve over x = 1e-3 .. 1e3 (40 per decade), written as CSV rows.
std::vector<double> curve(const Case& c, const std::vector<double>& x, std::ostream& csv,
                          const std::string& label) {
  std::vector<double> mu;
  for (double xi : x) {
    const Point p = at(c, xi);
    mu.push_back(p.mu);
    csv << label << "," << loading_name(c.loading.by_force()) << "," << xi << "," << p.mu << ","
        << p.a2 << "," << p.a1 << "\n";
  }
  return mu;
}

/// The x in [lo, hi] where `above(x)` turns true (bisection in log x).
template <class F> double threshold(F above, double lo, double hi) {
  double l = std::log10(lo), h = std::log10(hi);
  for (int it = 0; it < 80; ++it) {
    const double m = 0.5 * (l + h);
    (above(std::pow(10.0, m)) ? h : l) = m;
  }
  return std::pow(10.0, 0.5 * (l + h));
}

/// One row of 7a: the cone at one beta and loading.
void cone_row(double beta, bool load, const std::vector<double>& x, std::ostream& csv,
              std::vector<double>& first) {
  const Case c = kelvin_case(cone(beta), load);
  std::ostringstream label;
  label << "cone," << beta;
  const std::vector<double> mu = curve(c, x, csv, label.str());
  double spread = 0.0, fall = 0.0;
  if (first.empty()) first = mu;
  for (std::size_t i = 0; i < mu.size(); ++i) {
    spread = std::max(spread, std::fabs(mu[i] - first[i]));
    if (i > 0) fall = std::max(fall, mu[i - 1] - mu[i]);
  }
  const double loss = threshold([&](double xi) { return at(c, xi).a2 <= 0.0; }, 1e-3, 1e3);
  const double p99 = threshold([&](double xi) { return at(c, xi).mu >= 0.99; }, 1e-3, 1e3);
  const double p999 = threshold([&](double xi) { return at(c, xi).mu >= 0.999; }, 1e-3, 1e3);
  const double over = *std::max_element(mu.begin(), mu.end()) - 1.0;
  std::printf("  %4.0f %-5s %9.5f %11.7f %10.6f %10.6f %10.2e %10.2e %9.5f %9.2e\n", beta,
              loading_name(load), c.edge_scale(), loss, p99, p999, over, fall,
              at(c, 1e-3).mu / 1e-3, spread);
}

/// The maximum of a curve, or NaN where it has none inside the scan (it
/// still rises at its end, or reaches a plateau there: the cone).
std::pair<double, double> maximum(const Case& c, const std::vector<double>& x,
                                  const std::vector<double>& mu) {
  const std::size_t i =
      static_cast<std::size_t>(std::max_element(mu.begin(), mu.end()) - mu.begin());
  if (mu.back() >= mu[i] - 1e-12) return {NAN, NAN};
  return refine_max([&c](double xi) { return at(c, xi).mu; }, x, i);
}

void study_cone(const std::vector<double>& x, std::ostream& csv) {
  std::printf("\n# 7a. The cone on the Kelvin foundation (G = tau = 1, d = 1 or F0 = 1): mu/c, "
              "c = (pi/2) tan beta,\n#     against x = v tau/a (a = a1 at fixed depth, a0 under "
              "load); 'fall': largest decrease between\n#     neighbouring scan points (0: "
              "monotone); 'spread': largest |mu/c - that of beta = 5| on the scan\n"
              "# %4s %-5s %9s %11s %10s %10s %10s %10s %9s %9s\n",
              "beta", "load", "a", "a2=0 at x", "mu/c=.99", "mu/c=.999", "max-1", "fall",
              "mu/c/x@0", "spread");
  for (bool load : {false, true}) {
    std::vector<double> first;
    for (double beta : kBetas)
      cone_row(beta, load, x, csv, first);
  }
  std::printf("  closed forms: a2 = 0 at x = 1 (depth), sqrt(2/3) = %.7f (load); small x: mu/c = "
              "2x\n",
              std::sqrt(2.0 / 3.0));
}

/// One row of 7b: the maxima of power law n at fixed depth and under load.
void power_row(const Indenter& ind, double n, const std::vector<double>& x, std::ostream& csv,
               std::ostream& peaks) {
  std::printf("  %5.2f", n);
  for (bool load : {false, true}) {
    const Case c = kelvin_case(ind, load);
    std::ostringstream label;
    label << (ind.is<mdrmap::Parabola>() ? "parabola," : "power,") << n;
    const std::vector<double> mu = curve(c, x, csv, label.str());
    const auto [xs, ms] = maximum(c, x, mu);
    const Point p = std::isnan(xs) ? Point{NAN, NAN, NAN} : at(c, xs);
    std::printf("   %9.4g %9.4g %9.4g %8.4g", xs, ms, load ? p.a1 : mu.back(), p.a2);
    peaks << n << "," << loading_name(load) << "," << xs << "," << ms << "," << p.a1 << "," << p.a2
          << "," << mu.back() << "\n";
  }
  std::printf("   %9.4g\n", n / (2.0 * n - 1.0));
}

void study_power(const Options& o, const std::vector<double>& x, std::ostream& csv) {
  auto peaks =
      open_csv(o, "profile_peaks.csv",
               "n,loading,x_peak,mu_peak_over_slope,a1_over_a,a2_over_a,mu_end_over_slope");
  std::printf("\n# 7b. Power law f = r^n (A = 1) on the Kelvin foundation: the maximum of mu/g'(a) "
              "against\n#     x = v tau/a (golden section in log x; NaN: no maximum inside "
              "1e-3..1e3); n = 2 is the parabola\n"
              "# %5s   %9s %9s %9s %8s   %9s %9s %9s %8s   %9s\n",
              "n", "depth: x*", "mu*/g'", "mu(1e3)", "a2*/a1", "load: x*", "mu*/g'", "a1*/a0",
              "a2*/a0", "n/(2n-1)");
  for (double n : {1.0, 1.01, 1.05, 1.1, 1.25, 1.5, 2.0, 3.0, 4.0})
    power_row(power(n), n, x, csv, peaks);
  std::printf("  parabola (R = 1), its own closed form:\n");
  power_row(parabola(), 2.0, x, csv, peaks);
}

/// The cone on the Kelvin foundation (own derivation, docs/design.md): with
/// L = v tau, p = 4 G c (a1 + x + L) ahead of the tip and 4 G c (a1 - L - x)
/// behind it, so a2 = max(a1 - L, 0) and, with a1 - a2 = min(L, a1),
///   F_N = 4 G c [a1^2/2 + L a1 + a2^2/2]
///   F_x = 4 G c^2 [(a1 - a2)(a1 + a2)/2 + L a1]
/// Under load F_N = F0 = 4 G c q: a1 = sqrt(q - L^2/2) while q > 3 L^2/2,
/// else a1^2/2 + L a1 = q, a1 = 2 q / (L + sqrt(L^2 + 2 q)).
State cone_closed_form(double G, double c, double a1, double L) {
  State st;
  st.a1 = a1;
  st.a2 = std::max(a1 - L, 0.0);
  st.FN = 4.0 * G * c * (0.5 * a1 * a1 + L * a1 + 0.5 * st.a2 * st.a2);
  st.Fx = 4.0 * G * c * c * (0.5 * std::min(L, a1) * (a1 + st.a2) + L * a1);
  st.mu = st.Fx / st.FN;
  return st;
}

double cone_load_edge(double G, double c, double F0, double L) {
  const double q = F0 / (4.0 * G * c);
  return q > 1.5 * L * L ? std::sqrt(q - 0.5 * L * L) : 2.0 * q / (L + std::sqrt(L * L + 2.0 * q));
}

double rel(double a, double b) {
  return a == b ? 0.0 : std::fabs(a - b) / std::fabs(b);
}

/// The largest relative difference of FN, Fx, mu and a1 and of a2/a1 over
/// the betas and x = 1e-3 .. 1e3 (10 per decade, and the points x = 1, sqrt(2/3)).
double cone_check(bool load) {
  double worst = 0.0;
  std::vector<double> xs = logspace(1e-3, 1e3, 10);
  xs.push_back(std::sqrt(2.0 / 3.0));
  for (double beta : kBetas)
    for (double xi : xs) {
      const Case c = kelvin_case(cone(beta), load);
      const double L = xi * c.edge_scale(), cc = c.indenter.coefficient();
      const State s = profile_stationary(c, L);
      const double a1 = load ? cone_load_edge(1.0, cc, c.loading.F0, L) : c.a1();
      const State f = cone_closed_form(1.0, cc, a1, L);
      worst = std::max({worst, rel(s.FN, f.FN), rel(s.Fx, f.Fx), rel(s.mu, f.mu), rel(s.a1, f.a1),
                        std::fabs(s.a2 - f.a2) / f.a1});
    }
  return worst;
}

void study_check() {
  std::printf(
      "\n# 7c. The cone against its closed form (own derivation: a2 = max(a1 - v tau, 0), "
      "F_N = 4Gc [a1^2/2 + L a1 + a2^2/2],\n#     F_x = 4Gc^2 [(a1 - a2)(a1 + a2)/2 + L a1]; "
      "Popov & Hess's printed formulas were not available to compare),\n#     beta = 5, 10, "
      "30, x = 1e-3..1e3: largest relative difference of F_N, F_x, mu, a1 and a2/a1\n");
  for (bool load : {false, true}) {
    const double worst = cone_check(load);
    std::printf("  %-5s %.3g\n", loading_name(load), worst);
    if (!(worst <= 1e-12))
      throw std::runtime_error("part 7c: the cone's stationary state is off its closed form");
  }
}

} // namespace

void study_profiles(const Options& o) {
  auto csv = open_csv(o, "profile_friction.csv",
                      "profile,param,loading,x,mu_over_slope,a2_over_a,a1_over_a");
  const std::vector<double> x = logspace(1e-3, 1e3, 40);
  study_cone(x, csv);
  study_power(o, x, csv);
  study_check();
}

} // namespace mdrmap::physics
