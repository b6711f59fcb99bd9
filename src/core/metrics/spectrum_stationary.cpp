#include "core/metrics/spectrum_stationary.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/metrics/load_stationary.hpp"
#include "core/numerics/phi.hpp"
#include "core/numerics/root.hpp"

// Derivation (docs/design.md, "Materials with a relaxation spectrum"). With
// s = x + a1, h = s (2 a1 - s) / R and the branch's equation
// lambda dq/ds = h - q, q(0) = 0, the branch stress r = h - q solves
// lambda r' + r = lambda h', r(0) = 0:
//   r = (2 lambda / R) [ (a1 + lambda)(1 - e^(-s/lambda)) - s ].
// P = p R / 8 is then, with E = (a1^2 - x^2) / 2 and L = w tau,
//   P = G E - G L x + sum_k G_k Q_k,   Q_k = R r_k / 2, written two exact ways:
//   Q = lambda (lambda - x) - lambda (a1 + lambda) e^(-s/lambda)      ("relaxed" form)
//     = E - D,  D = (s^2 / lambda) (a1 phi_2(-z) - s phi_3(-z)), z = s / lambda ("glassy").
// Each branch uses the form without cancellation: glassy for lambda >= a1 / 2
// (z <= 4 on the contact), relaxed below. Q is concave (Q'' = -(a1 + lambda)
// e^(-z) / lambda), so P is; P(-a1) = G L a1 >= 0 (and P'(-a1) = G0 a1 - G L
// > 0 when L = 0), Q(0) >= 0 (e^t >= 1 + t), Q(a1) < 0 for lambda > 0: one zero
// a2 in (0, a1], found in x when it lies below a1/2 and in delta = a1 - x
// above, so that a2 and a1 - a2 both keep their digits.
//
// No second contact behind a2. Compare the free material behind a2 with the
// same material held on the indenter (u = h). Both start from the state at a2;
// the held one would carry p_c(x) < 0 for x > a2 (P concave, decreasing through
// its zero), the free one p = 0. The difference is the element's response to
// the load history -p_c >= 0, non-decreasing from 0: by superposition
// u_free - h = integral of J(t - t') d(-p_c)(t') > 0 (J > 0 for t > 0, the
// creep compliance of creep.hpp). So the free surface lies strictly below the
// indenter everywhere behind a2 (also past x = a1, where h < 0): the contact is
// the single interval [-a1, a2].

namespace mdrmap {
namespace {

struct Term {
  double G;   // branch modulus
  double lam; // w tau_k (shifted)
};

// The contact at leading edge a1 and velocity w: moduli and lengths of P.
struct Contact {
  double a1 = 0.0, L = 0.0, G = 0.0, Ge = 0.0;
  std::vector<Term> glassy, relaxed;
};

Contact make_contact(const Rheology& shifted, double a1, double w) {
  Contact k;
  k.a1 = a1;
  k.L = w * shifted.tau;
  k.G = shifted.G;
  k.Ge = shifted.G;
  for (const Branch& b : shifted.branches) {
    const double lam = w * b.tau;
    if (lam >= 0.5 * a1) {
      k.glassy.push_back({b.G, lam});
      k.Ge += b.G;
    } else {
      k.relaxed.push_back({b.G, lam});
    }
  }
  return k;
}

// A point of the contact given by x, s = a1 + x and delta = a1 - x, each
// computed by the caller without cancellation.
struct Point {
  double x, s, delta;
};

double glassy_D(double a1, double s, double lam) {
  double phi[6];
  numerics::phi_all(s / lam, phi);
  return s * (s / lam) * (a1 * phi[2] - s * phi[3]);
}

double relaxed_Q(double a1, const Point& p, double lam) {
  if (lam == 0.0) return 0.0; // at rest: relaxed at once
  return lam * ((lam - p.x) - (a1 + lam) * std::exp(-p.s / lam));
}

// P = p R / 8 at a point of the contact.
double pressure(const Contact& k, const Point& p) {
  double P = k.Ge * (0.5 * p.delta * p.s) - k.G * k.L * p.x;
  for (const Term& t : k.glassy)
    P -= t.G * glassy_D(k.a1, p.s, t.lam);
  for (const Term& t : k.relaxed)
    P += t.G * relaxed_Q(k.a1, p, t.lam);
  return P;
}

struct Edge {
  double a2, delta; // trailing edge and a1 - a2
};

template <class F> double root(F f, double lo, double hi) {
  return numerics::toms748(f, lo, hi, numerics::bits_tolerance(50), {"spectrum_stationary"}).mid();
}

Edge trailing_edge(const Contact& k) {
  const double a1 = k.a1, half = 0.5 * a1;
  const double Pm = pressure(k, {half, a1 + half, half});
  if (Pm > 0.0) { // the zero lies in (a1/2, a1]: solve in delta
    auto f = [&](double dl) { return pressure(k, {a1 - dl, 2.0 * a1 - dl, dl}); };
    if (f(0.0) >= 0.0) return {a1, 0.0}; // w = 0: elastic, symmetric
    const double dl = root(f, 0.0, half);
    return {a1 - dl, dl};
  }
  if (Pm == 0.0) return {half, half};
  auto f = [&](double x) { return pressure(k, {x, a1 + x, a1 - x}); };
  const double x = root(f, 0.0, half);
  return {x, a1 - x};
}

// Forces of the contact [-a1, a2]: integrals of P and of P (-x) over it.
State forces(const Contact& k, const Edge& e, double R) {
  const double A = k.a1, a2 = e.a2, S = A + a2, dS = e.delta * S; // dS = a1^2 - a2^2
  const double cubes = A * A * A + a2 * a2 * a2;
  // 2 int E, 2 int E (-x): the Kelvin brackets of analytic.cpp
  double N = k.Ge * ((2.0 / 3.0) * A * A * A + A * A * a2 - a2 * a2 * a2 / 3.0) + k.G * k.L * dS;
  double X = k.Ge * 0.25 * dS * dS + k.G * (2.0 / 3.0) * k.L * cubes;
  for (const Term& t : k.glassy) {
    double phi[6];
    numerics::phi_all(S / t.lam, phi);
    const double c = S * S * (S / t.lam);
    N -= 2.0 * t.G * c * (A * phi[3] - S * phi[4]);
    X -= 2.0 * t.G * c * (S * S * (phi[4] - phi[5]) - A * a2 * phi[3]);
  }
  for (const Term& t : k.relaxed) {
    const double l = t.lam;
    if (l == 0.0) continue;
    const double ez = std::exp(-S / l);
    N += 2.0 * t.G * l * (0.5 * dS + l * (a2 - l) + l * (A + l) * ez);
    X += 2.0 * t.G * l *
         (0.5 * l * dS + cubes / 3.0 - l * (A - l) * (A + l) - l * (A + l) * (l + a2) * ez);
  }
  State st;
  st.a2 = a2;
  st.a1 = A;
  st.FN = 4.0 / R * N;
  st.Fx = 8.0 / (R * R) * X;
  st.mu = st.Fx / st.FN;
  return st;
}

State solve(const Rheology& shifted, double R, double a1, double w) {
  const Contact k = make_contact(shifted, a1, w);
  return forces(k, trailing_edge(k), R);
}

void check_velocity(double w) {
  if (!(w >= 0.0) || !std::isfinite(w))
    throw std::invalid_argument("spectrum_stationary: w must be finite and >= 0");
}

} // namespace

State spectrum_stationary(const Case& c, double w) {
  check_velocity(w);
  State st = solve(c.rheology.shifted(), c.indenter.as<Parabola>().R, c.a1(), w);
  st.d = c.loading.d;
  return st;
}

double spectrum_stationary_depth(const Case& c, double w) {
  check_velocity(w);
  const double F0 = c.loading.F0, R = c.indenter.as<Parabola>().R;
  if (!(F0 > 0.0) || !std::isfinite(F0))
    throw std::invalid_argument("spectrum_stationary_depth: the case needs a load F0 > 0");
  const Rheology r = c.rheology.shifted();
  // FN grows strictly with a1 (in s = x + a1, dP/da1 > 0 at every s): one root
  auto f = [&](double a1) { return solve(r, R, a1, w).FN / F0 - 1.0; };
  const double a1 = numerics::scaled_root(f, c.a0(), 4000, numerics::bits_tolerance(50),
                                          {"spectrum_stationary: load"});
  return a1 * (a1 / R);
}

State spectrum_stationary_load(const Case& c, double w) {
  return spectrum_stationary(at_depth(c, spectrum_stationary_depth(c, w)), w);
}

} // namespace mdrmap
