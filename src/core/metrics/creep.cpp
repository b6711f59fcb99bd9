#include "core/metrics/creep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/numerics/root.hpp"

namespace mdrmap {
namespace {

// The poles of f: times (ascending, distinct) and weights G_k tau_k (the
// dashpot as the pole at 0 of weight G tau).
struct Poles {
  double G = 0.0;
  std::vector<double> t, w;
};

Poles poles_of(const Rheology& r) {
  std::vector<std::pair<double, double>> p;
  if (r.tau > 0.0) p.emplace_back(0.0, r.G * r.tau);
  for (const Branch& b : r.branches)
    p.emplace_back(b.tau, b.G * b.tau);
  std::sort(p.begin(), p.end());
  Poles out;
  out.G = r.G;
  for (const auto& [t, w] : p) {
    if (!out.t.empty() && out.t.back() == t) {
      out.w.back() += w; // equal times: one branch
    } else {
      out.t.push_back(t);
      out.w.push_back(w);
    }
  }
  return out;
}

// rho = t_a + e (sign +1) or t_a - e (sign -1), e > 0: rho - t_j for every pole
// without cancellation at the anchor a.
double gap(const Poles& p, std::size_t a, int sign, double e, std::size_t j) {
  const double se = sign > 0 ? e : -e;
  return j == a ? se : (p.t[a] - p.t[j]) + se;
}

// e |f(rho)|-scaled: e f(rho), finite at e = 0 (-w_a sign there).
double scaled_f(const Poles& p, std::size_t a, int sign, double e) {
  double rest = p.G;
  for (std::size_t j = 0; j < p.t.size(); ++j)
    if (j != a) rest -= p.w[j] / gap(p, a, sign, e, j);
  return e * rest - (sign > 0 ? p.w[a] : -p.w[a]);
}

double f_prime_rho(const Poles& p, std::size_t a, int sign, double e, double rho) {
  double s = 0.0; // rho f'(rho) = rho sum w_j / (rho - t_j)^2
  for (std::size_t j = 0; j < p.t.size(); ++j) {
    const double g = gap(p, a, sign, e, j);
    s += p.w[j] * (rho / g) / g;
  }
  return s;
}

double solve_offset(const Poles& p, std::size_t a, int sign, double emax) {
  return numerics::toms748([&](double e) { return scaled_f(p, a, sign, e); }, 0.0, emax,
                           numerics::bits_tolerance(52), {"creep spectrum", 300})
      .mid();
}

// The root in (t_k, t_(k+1)) (k + 1 == size: in (t_k, inf)): the anchor is the
// pole on the side of the split point where f changes sign.
void add_root(const Poles& p, std::size_t k, CreepSpectrum& out) {
  std::size_t a = k;
  int sign = 1;
  double emax;
  if (k + 1 == p.t.size()) {
    // f > 0 once rho - t_k > sum w / G (every term then below G in sum)
    double W = 0.0;
    for (double w : p.w)
      W += w;
    emax = 2.0 * W / p.G;
    while (scaled_f(p, a, sign, emax) <= 0.0)
      emax *= 2.0;
  } else {
    const double lo = p.t[k], hi = p.t[k + 1];
    const double m = lo > 0.0 ? std::sqrt(lo) * std::sqrt(hi) : 0.5 * hi;
    const double fm = scaled_f(p, k, 1, m - lo); // sign of f(m)
    if (fm > 0.0) {
      emax = m - lo;
    } else {
      a = k + 1;
      sign = -1;
      emax = hi - m;
    }
  }
  const double e = solve_offset(p, a, sign, emax);
  const double rho = sign > 0 ? p.t[a] + e : p.t[a] - e;
  out.rho.push_back(rho);
  out.c.push_back(1.0 / f_prime_rho(p, a, sign, e, rho));
}

} // namespace

CreepSpectrum creep_spectrum(const Rheology& r) {
  const Rheology s = r.shifted();
  CreepSpectrum out;
  out.J0 = s.tau > 0.0 ? 0.0 : 1.0 / s.G0();
  const Poles p = poles_of(s);
  for (std::size_t k = 0; k < p.t.size(); ++k)
    add_root(p, k, out);
  return out;
}

double creep_compliance(const CreepSpectrum& s, double t) {
  double J = s.J0;
  for (std::size_t j = 0; j < s.rho.size(); ++j)
    J -= s.c[j] * std::expm1(-t / s.rho[j]);
  return J;
}

double creep_compliance(const Rheology& r, double t) {
  return creep_compliance(creep_spectrum(r), t);
}

double creep_depth(const Case& c, double t) {
  const double J = creep_compliance(c.rheology, t);
  const double x = 3.0 * c.loading.F0 * J / (16.0 * std::sqrt(c.indenter.as<Parabola>().R));
  return std::cbrt(x * x);
}

} // namespace mdrmap
