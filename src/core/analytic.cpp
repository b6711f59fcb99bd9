#include "core/analytic.hpp"

#include <cmath>

namespace mdrmap::analytic {

double a1(const Scene& s) {
  return contact_radius(s);
}

double a2_stationary(const Scene& s, double w) {
  const double L = w * s.tau;
  const double A = a1(s);
  // R d / (sqrt(L^2 + R d) + L), with R d = a1^2 and hypot against overflow.
  return A * (A / (std::hypot(L, A) + L));
}

double a1_minus_a2_stationary(const Scene& s, double w) {
  const double L = w * s.tau;
  const double A = a1(s);
  if (L == 0.0) return 0.0;
  // a1 + L - sqrt(L^2 + a1^2) = 2 a1 L / (a1 + L + sqrt(L^2 + a1^2))
  return 2.0 * A * (L / (A + L + std::hypot(L, A)));
}

State contact_forces(const Scene& s, double a2, double a1_minus_a2, double w) {
  const double A = a1(s);
  const double L = w * s.tau;
  const double diff2 = a1_minus_a2 * (A + a2); // a1^2 - a2^2
  State st;
  st.a2 = a2;
  // corrected eq. (9): 4G [ d (a1 + a2) - (a1^3 + a2^3)/(3R) + w tau (a1^2 - a2^2)/R ]
  st.FN = 4.0 * s.G / s.R * ((2.0 / 3.0) * A * A * A + A * A * a2 - a2 * a2 * a2 / 3.0 + L * diff2);
  // corrected eq. (10): 8G/R^2 [ R d/2 (a1^2 - a2^2) - (a1^4 - a2^4)/4 + 2 w tau/3 (a1^3 + a2^3) ]
  st.Fx = 8.0 * s.G / (s.R * s.R) *
          (0.25 * diff2 * diff2 + (2.0 / 3.0) * L * (A * A * A + a2 * a2 * a2));
  st.mu = st.Fx / st.FN;
  return st;
}

State stationary(const Scene& s, double w) {
  return contact_forces(s, a2_stationary(s, w), a1_minus_a2_stationary(s, w), w);
}

double FN_inf(const Scene& s) {
  return 4.0 * s.G * ((2.0 / 3.0) * std::sqrt(s.R) * std::pow(s.d, 1.5) + s.tau * s.v * s.d);
}

double Fx_inf(const Scene& s) {
  return 4.0 * s.G * (0.5 * s.d * s.d + (4.0 / 3.0) * s.tau * s.v * s.d * std::sqrt(s.d / s.R));
}

double mu_inf(const Scene& s) {
  return (4.0 / 3.0) * std::sqrt(s.d / s.R);
}

double mu_post_drop_limit(const Scene& s) {
  return 0.75 * std::sqrt(s.d / s.R);
}

State jump(const Scene& s) {
  if (s.v1 >= s.v) return stationary(s, s.v1);
  // corrected eqs. (15), (16): contact set of velocity v, elements moving at v1
  return contact_forces(s, a2_stationary(s, s.v), a1_minus_a2_stationary(s, s.v), s.v1);
}

double a2_start_stop(const Scene& s, double t) {
  if (s.tau == 0.0) return a1(s);
  return a1(s) * std::sqrt(-std::expm1(-t / s.tau));
}

} // namespace mdrmap::analytic
