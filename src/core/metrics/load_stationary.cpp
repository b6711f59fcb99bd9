#include "core/metrics/load_stationary.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/metrics/analytic.hpp"
#include "core/numerics/root.hpp"

namespace mdrmap {
namespace {

// Left side minus 4/3 of the equation for alpha (see the header), written as
// sums of non-negative terms: alpha - beta = 2 alpha z / (alpha + z + hypot).
// Where z >= alpha the same divided through by z (hypot + z overflows near
// the largest double).
double residual(double alpha, double z) {
  double beta = 0.0, diff = 0.0;
  if (z >= alpha) {
    const double r = alpha / z, s = 1.0 + std::hypot(1.0, r);
    beta = alpha * (r / s);
    diff = 2.0 * alpha / (r + s);
  } else {
    const double hyp = std::hypot(z, alpha);
    beta = alpha * (alpha / (hyp + z));
    diff = 2.0 * alpha * (z / (alpha + z + hyp));
  }
  const double sum = alpha + beta;
  return sum * sum * (2.0 * alpha - beta) / 3.0 + z * diff * sum - 4.0 / 3.0;
}

} // namespace

double stationary_alpha(double zeta0) {
  if (!(zeta0 >= 0.0) || !std::isfinite(zeta0))
    throw std::invalid_argument("stationary_alpha: zeta0 must be finite and >= 0");
  if (zeta0 == 0.0) return 1.0;
  // bracket around the better of the two limits (4/3 / zeta0, not 4 / (3
  // zeta0): 3 zeta0 overflows above 6e307, and a zero start never grows)
  auto f = [&](double a) { return residual(a, zeta0); };
  // residual(0) = -4/3 and residual(1) > 0: each loop ends within the
  // exponent range (2100 halvings or doublings; the bound guards NaN only)
  const numerics::ScaledBracket e =
      numerics::scaled_bracket(f, std::min(1.0, std::sqrt(4.0 / 3.0 / zeta0)), 2100);
  if (!(e.flo <= 0.0) || !(e.fhi >= 0.0))
    throw std::domain_error("stationary_alpha: no bracket at zeta0 = " + std::to_string(zeta0));
  if (e.lo == e.hi) return e.lo;
  return numerics::toms748(f, e.lo, e.hi, e.flo, e.fhi, numerics::bits_tolerance(52),
                           {"stationary_alpha"})
      .mid();
}

double stationary_depth(const Case& c, double w) {
  const double a0 = c.a0();
  const double alpha = stationary_alpha(w * c.rheology.tau / a0);
  const double a1 = alpha * a0;
  return a1 * (a1 / c.indenter.as<Parabola>().R);
}

Case at_depth(const Case& c, double d) {
  Case cc = c;
  cc.loading.d = d;
  cc.loading.F0 = 0.0;
  return cc;
}

State stationary_under_load(const Case& c, double w) {
  return analytic::stationary(at_depth(c, stationary_depth(c, w)), w);
}

} // namespace mdrmap
