#include "core/metrics/analytic.hpp"

#include <cmath>

namespace mdrmap::analytic {

double a2_stationary(const Case& c, double w) {
  const double L = w * c.rheology.tau;
  const double A = a1(c);
  // R d / (sqrt(L^2 + R d) + L), with R d = a1^2 and hypot against overflow.
  return A * (A / (std::hypot(L, A) + L));
}

double a1_minus_a2_stationary(const Case& c, double w) {
  const double L = w * c.rheology.tau;
  const double A = a1(c);
  if (L == 0.0) return 0.0;
  // a1 + L - sqrt(L^2 + a1^2) = 2 a1 L / (a1 + L + sqrt(L^2 + a1^2))
  return 2.0 * A * (L / (A + L + std::hypot(L, A)));
}

State contact_forces(const Case& c, double a2, double a1_minus_a2, double w) {
  const double A = a1(c);
  const double L = w * c.rheology.tau;
  const double diff2 = a1_minus_a2 * (A + a2); // a1^2 - a2^2
  State st;
  st.a2 = a2;
  // corrected eq. (9): 4G [ d (a1 + a2) - (a1^3 + a2^3)/(3R) + w tau (a1^2 - a2^2)/R ]
  st.FN = 4.0 * c.rheology.G / c.indenter.as<Parabola>().R *
          ((2.0 / 3.0) * A * A * A + A * A * a2 - a2 * a2 * a2 / 3.0 + L * diff2);
  // corrected eq. (10): 8G/R^2 [ R d/2 (a1^2 - a2^2) - (a1^4 - a2^4)/4 + 2 w tau/3 (a1^3 + a2^3) ]
  st.Fx = 8.0 * c.rheology.G / (c.indenter.as<Parabola>().R * c.indenter.as<Parabola>().R) *
          (0.25 * diff2 * diff2 + (2.0 / 3.0) * L * (A * A * A + a2 * a2 * a2));
  st.mu = st.Fx / st.FN;
  st.d = c.loading.d;
  st.a1 = A;
  return st;
}

State stationary(const Case& c, double w) {
  return contact_forces(c, a2_stationary(c, w), a1_minus_a2_stationary(c, w), w);
}

double FN_inf(const Case& c, double w) {
  const double d = c.loading.d, R = c.indenter.as<Parabola>().R, tau = c.rheology.tau;
  return 4.0 * c.rheology.G * ((2.0 / 3.0) * std::sqrt(R) * std::pow(d, 1.5) + tau * w * d);
}

double Fx_inf(const Case& c, double w) {
  const double d = c.loading.d, R = c.indenter.as<Parabola>().R, tau = c.rheology.tau;
  return 4.0 * c.rheology.G * (0.5 * d * d + (4.0 / 3.0) * tau * w * d * std::sqrt(d / R));
}

double mu_inf(const Case& c) {
  return (4.0 / 3.0) * std::sqrt(c.loading.d / c.indenter.as<Parabola>().R);
}

double mu_post_drop_limit(const Case& c) {
  return 0.75 * std::sqrt(c.loading.d / c.indenter.as<Parabola>().R);
}

State jump(const Case& c, double v, double w) {
  if (w >= v) return stationary(c, w);
  // corrected eqs. (15), (16): contact set of velocity v, elements moving at w
  return contact_forces(c, a2_stationary(c, v), a1_minus_a2_stationary(c, v), w);
}

double a2_start_stop(const Case& c, double t) {
  if (c.rheology.tau == 0.0) return a1(c);
  return a1(c) * std::sqrt(-std::expm1(-t / c.rheology.tau));
}

double depth_at(const Case& c, double x) {
  const double A = a1(c);
  return (A - x) * (A + x) / c.indenter.as<Parabola>().R;
}

} // namespace mdrmap::analytic
