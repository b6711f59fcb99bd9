#include "core/metrics/profile_stationary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <variant>
#include <vector>

#include "core/metrics/analytic.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/metrics/profile_branches.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/numerics/root.hpp"

// Derivation: docs/design.md, "Indenter profiles". The branches' integrals
// (split into glassy part and remainder where that keeps the digits, each
// piece between kinks and layers): profile_branches.hpp.

namespace mdrmap {
namespace {

struct Term {
  double G;   // branch modulus
  double lam; // w tau_k
};

// The contact of the image g at leading edge a1 (depth g(a1)), velocity w.
struct Contact {
  double a1 = 0.0, L = 0.0, G = 0.0;
  bool linear = false; // g = c |x| (the cone): the Kelvin edge in closed form
  std::vector<Term> terms;
  profile::BranchContact shape; // g, a1 and the evaluation budget of the branches
};

struct Edge {
  double a2, delta; // trailing edge and a1 - a2, each without cancellation
};

Contact make_contact(const Case& c, double a1, double w, profile::Budget& budget) {
  Contact k;
  k.a1 = a1;
  k.L = w * c.rheology.tau;
  k.G = c.rheology.G;
  k.linear = c.indenter.visit([](const auto& s) { return s.linear(); });
  for (const Branch& b : c.rheology.branches)
    if (w * b.tau > 0.0) k.terms.push_back({b.G, w * b.tau});
  k.shape.img = c.indenter.image();
  k.shape.a1 = a1;
  k.shape.budget = &budget;
  return k;
}

template <class F> double root(F f, double lo, double hi) {
  return numerics::toms748(f, lo, hi, numerics::bits_tolerance(52), {"profile_stationary"}).mid();
}

/// |g'| at distance y >= 0 from the tip.
double slope_mag(const Contact& k, double y) {
  return k.shape.slope_mag(y);
}

/// g at distance y >= 0 from the tip.
double g_at(const Contact& k, double y) {
  return std::visit([y](const auto& i) { return i.g(y); }, k.shape.img);
}

/// The signed antiderivatives int_0^t g and int_0^t g'^2.
double int_g(const Contact& k, double t) {
  return std::visit([t](const auto& i) { return i.integral_g(t); }, k.shape.img);
}
double int_slope_squared(const Contact& k, double t) {
  return std::visit([t](const auto& i) { return i.integral_slope_squared(t); }, k.shape.img);
}

/// The Kelvin trailing edge: the root of g(a1) - g(a2) = L g'(a2) (the
/// cone: a2 = a1 - L, the contact ends at the tip once L >= a1).
Edge kelvin_edge(const Contact& k) {
  const double a1 = k.a1, L = k.L, half = 0.5 * a1;
  if (L == 0.0) return {a1, 0.0};
  if (k.linear) return L >= a1 ? Edge{0.0, a1} : Edge{a1 - L, L};
  auto in_delta = [&](double dl) { return k.shape.depth_left(dl) - L * slope_mag(k, a1 - dl); };
  if (in_delta(half) >= 0.0) {
    const double dl = root(in_delta, 0.0, half);
    return {a1 - dl, dl};
  }
  const double d = g_at(k, a1);
  auto in_a2 = [&](double x) { return g_at(k, x) + L * slope_mag(k, x) - d; };
  const double a2 = root(in_a2, 0.0, half);
  return {a2, a1 - a2};
}

/// The Kelvin brackets F_N / (4 G) = int (h - L g') and
/// F_x / (4 G) = int (h - L g') (-g') over the contact [-a1, a2], h = d - g:
/// d (a1 + a2) - int g + L D and D^2 / 2 + L int g'^2, D = g(a1) - g(a2).
void kelvin_brackets(const Contact& k, const Edge& e, double& N, double& X) {
  const double a1 = k.a1, a2 = e.a2, d = g_at(k, a1);
  const double D = k.shape.depth_left(e.delta);
  N = (d * a1 - int_g(k, a1)) + (d * a2 - int_g(k, a2)) + k.L * D;
  X = 0.5 * D * D + k.L * (int_slope_squared(k, a1) + int_slope_squared(k, a2));
}

/// p / 4 at x >= 0 of the contact (behind the tip: g' > 0), x = a1 - delta.
double pressure_behind(const Contact& k, double x, double delta) {
  const double h = k.shape.depth_left(delta); // d - g(x)
  double p = k.G * (h - k.L * slope_mag(k, x));
  for (const Term& t : k.terms)
    p += t.G * profile::branch_stress(k.shape, t.lam, x, delta);
  return p;
}

Edge spectrum_edge(const Contact& k) {
  const double a1 = k.a1, half = 0.5 * a1;
  if (k.L == 0.0 && k.terms.empty()) return {a1, 0.0};      // at rest: elastic, symmetric
  if (pressure_behind(k, 0.0, a1) <= 0.0) return {0.0, a1}; // lets go at the tip
  if (pressure_behind(k, half, half) > 0.0) {
    auto f = [&](double dl) { return pressure_behind(k, a1 - dl, dl); };
    if (f(0.0) >= 0.0) return {a1, 0.0};
    const double dl = root(f, 0.0, half);
    return {a1 - dl, dl};
  }
  const double x = root([&](double t) { return pressure_behind(k, t, a1 - t); }, 0.0, half);
  return {x, a1 - x};
}

/// sum_k G_k int r_k over the contact.
double branch_normal(const Contact& k, const Edge& e) {
  double s = 0.0;
  for (const Term& t : k.terms)
    s += t.G * profile::branch_normal(k.shape, t.lam, e.a2);
  return s;
}

/// sum_k G_k int r_k (-g') over the contact.
double branch_friction(const Contact& k, const Edge& e) {
  double s = 0.0;
  for (const Term& t : k.terms)
    s += t.G * profile::branch_friction(k.shape, t.lam, e.a2, e.delta);
  return s;
}

/// The forces of the contact; F_x (and mu) only where `friction` is asked.
State forces(const Contact& k, const Edge& e, bool friction = true) {
  double N = 0.0, X = 0.0;
  kelvin_brackets(k, e, N, X);
  const bool any = !k.terms.empty();
  State st;
  st.a2 = e.a2;
  st.a1 = k.a1;
  st.FN = 4.0 * (k.G * N + (any ? branch_normal(k, e) : 0.0));
  if (!friction) return st;
  st.Fx = 4.0 * (k.G * X + (any ? branch_friction(k, e) : 0.0));
  st.mu = st.Fx / st.FN;
  return st;
}

/// The general path at leading edge a1 (depth g(a1)).
State at_edge(const Case& c, double a1, double w, profile::Budget& budget, bool friction = true) {
  const Contact k = make_contact(c, a1, w, budget);
  State st = forces(k, k.terms.empty() ? kelvin_edge(k) : spectrum_edge(k), friction);
  st.d = g_at(k, a1);
  return st;
}

/// Power law with n = 2 and the parabola: g = c x^2, the parabola of R = 1/c.
bool quadratic(const Indenter& i) {
  return i.visit([](const auto& s) { return s.quadratic(); });
}

Case as_parabola(const Case& c) {
  Case p = c;
  p.indenter = Parabola{c.indenter.parabolic() ? c.indenter.as<Parabola>().R
                                               : 1.0 / c.indenter.coefficient()};
  return p;
}

State parabola_stationary(const Case& p, double w) {
  const bool load = p.loading.by_force();
  if (!p.rheology.kelvin())
    return load ? spectrum_stationary_load(p, w) : spectrum_stationary(p, w);
  return load ? stationary_under_load(p, w) : analytic::stationary(p, w);
}

/// The cone on the Kelvin foundation under load, in closed form: with
/// q = F0 / (4 G c) = a0^2, a1 = sqrt(q - L^2/2) while a1 > L, else the
/// root of a1^2/2 + L a1 = q.
double cone_kelvin_edge(const Case& c, double w) {
  const double L = w * c.rheology.tau;
  const double q = c.loading.F0 / (4.0 * c.rheology.G * c.indenter.coefficient());
  if (q > 1.5 * L * L) return std::sqrt(q - 0.5 * L * L);
  return 2.0 * q / (std::sqrt(L * L + 2.0 * q) + L);
}

/// The leading edge of stationary sliding under load: F_N grows with a1.
double load_edge(const Case& c, double w, profile::Budget& budget) {
  const bool linear = c.indenter.visit([](const auto& s) { return s.linear(); });
  if (linear && c.rheology.kelvin()) return cone_kelvin_edge(c, w);
  const double F0 = c.loading.F0;
  auto f = [&](double a1) { return at_edge(c, a1, w, budget, false).FN / F0 - 1.0; };
  // (the edges stay below the profile's largest radius)
  return numerics::scaled_root(f, c.a0(), 4000, numerics::bits_tolerance(52),
                               {"profile_stationary: load"}, c.indenter.max_radius());
}

void check_velocity(double w) {
  if (!(w >= 0.0) || !std::isfinite(w))
    throw std::invalid_argument("profile_stationary: w must be finite and >= 0");
}

} // namespace

double profile_stationary_depth(const Case& c, double w) {
  check_velocity(w);
  if (!c.loading.by_force())
    throw std::invalid_argument("profile_stationary_depth: the case needs a load F0 > 0");
  if (quadratic(c.indenter)) return parabola_stationary(as_parabola(c), w).d;
  profile::Budget budget;
  return c.indenter.g(load_edge(c, w, budget));
}

State profile_stationary(const Case& c, double w) {
  check_velocity(w);
  if (quadratic(c.indenter)) return parabola_stationary(as_parabola(c), w);
  profile::Budget budget; // the whole state's: under load every trial edge charges it
  const double a1 = c.loading.by_force() ? load_edge(c, w, budget) : c.a1();
  State st = at_edge(c, a1, w, budget);
  if (!c.loading.by_force()) st.d = c.loading.d;
  return st;
}

namespace profile_detail {
State general_stationary(const Case& c, double w) {
  check_velocity(w);
  profile::Budget budget;
  State st = at_edge(c, c.a1(), w, budget);
  st.d = c.loading.d;
  return st;
}
} // namespace profile_detail

} // namespace mdrmap
