// Tests of the seed paper's estimates (src/core/analytic.*) against physics
// computed independently here: Gauss-Legendre quadrature of the paper's
// integrands in long double, closed-form limits derived by hand (series
// expansions are quoted in the comments), and long double evaluations of the
// contact edges by Newton's method on the defining quadratic.
//
// Units: a1 = sqrt(R d), L = w tau (w the velocity the contact elements follow),
// zeta = L / a1. With x in the moving frame, the force per unit length of the
// contact is 4 G p(x) with p(x) = d - x^2/R - 2 L x/R (eq. 6 with eq. 8), and
//   F_N = 4G int p dx,  F_x = 4G int p (-2x/R) dx   over [-a1, a2].
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/metrics/analytic.hpp"
#include "core/model/case.hpp"
#include "test_case.hpp"

namespace {

using mdrmap::Case;
using mdrmap::State;
namespace analytic = mdrmap::analytic;
using ld = long double;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr ld kEpsLd = std::numeric_limits<ld>::epsilon();
constexpr ld kPiLd = 3.141592653589793238462643383279502884L;

// ---------------------------------------------------------------------------
// Quadrature: n-point Gauss-Legendre rule on [-1, 1], nodes by Newton's method
// on the Legendre polynomial P_n (three-term recurrence), all in long double.
struct GaussRule {
  std::vector<ld> x, w;
};

GaussRule gauss_legendre(int n) {
  GaussRule g;
  const auto un = static_cast<std::size_t>(n);
  g.x.resize(un);
  g.w.resize(un);
  const ld nl = static_cast<ld>(n);
  for (std::size_t i = 0; i < un; ++i) {
    ld z = std::cos(kPiLd * (static_cast<ld>(i) + 0.75L) / (nl + 0.5L));
    ld dp = 1.0L;
    for (int it = 0; it < 100; ++it) {
      ld p0 = 1.0L, p1 = z; // P_0, P_1
      for (int k = 2; k <= n; ++k) {
        const ld kl = static_cast<ld>(k);
        const ld p2 = ((2.0L * kl - 1.0L) * z * p1 - (kl - 1.0L) * p0) / kl;
        p0 = p1;
        p1 = p2;
      }
      dp = nl * (z * p1 - p0) / (z * z - 1.0L); // P_n'(z)
      const ld dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) <= 2.0L * kEpsLd) break;
    }
    g.x[i] = z;
    g.w[i] = 2.0L / ((1.0L - z * z) * dp * dp);
  }
  return g;
}

const GaussRule& rule8() {
  static const GaussRule g = gauss_legendre(8);
  return g;
}

struct Quad {
  ld value = 0; ///< integral of f
  ld abs = 0;   ///< integral of |f| (for the rounding bound of the sum)
};

// Composite 8-point Gauss-Legendre on `panels` equal panels of [a, b]. The
// paper's integrands are polynomials of degree <= 3, which an 8-point rule
// integrates exactly; what is left is rounding, bounded by ~eps_ld * int|f|.
template <class F> Quad integrate(const F& f, ld a, ld b, int panels = 16) {
  const GaussRule& g = rule8();
  Quad q;
  const ld h = (b - a) / static_cast<ld>(panels);
  for (int k = 0; k < panels; ++k) {
    const ld lo = a + h * static_cast<ld>(k);
    const ld mid = lo + 0.5L * h;
    for (std::size_t i = 0; i < g.x.size(); ++i) {
      const ld fx = f(mid + 0.5L * h * g.x[i]);
      q.value += g.w[i] * fx;
      q.abs += g.w[i] * std::fabs(fx);
    }
  }
  q.value *= 0.5L * h;
  q.abs *= 0.5L * h;
  return q;
}

// Forces of the contact set [-a1, a2] whose elements follow the indenter at
// velocity w, by quadrature of the paper's integrands (eqs. 9 and 10, with
// F_x = int p (-g') dx). kappa = int|f| / |int f| is the condition number of
// the sum: the quadrature's own rounding error is below ~ 64 kappa eps_ld.
struct QuadForces {
  ld FN = 0, Fx = 0, kappaN = 1, kappaX = 1;
};

QuadForces quad_forces(const Case& c, double a2, double w) {
  // The limits are the contact set that contact_forces is given: the code's a1
  // (a rounded double) and the double a2, both exact in long double.
  const ld a1 = static_cast<ld>(analytic::a1(c));
  const ld d = c.loading.d, R = c.indenter.as<mdrmap::Parabola>().R, G = c.rheology.G;
  const ld L = static_cast<ld>(w) * static_cast<ld>(c.rheology.tau);
  auto p = [&](ld x) { return d - x * x / R - 2.0L * L * x / R; };
  auto px = [&](ld x) { return p(x) * (-2.0L * x / R); };
  const Quad qn = integrate(p, -a1, static_cast<ld>(a2));
  const Quad qx = integrate(px, -a1, static_cast<ld>(a2));
  QuadForces r;
  r.FN = 4.0L * G * qn.value;
  r.Fx = 4.0L * G * qx.value;
  r.kappaN = qn.value != 0 ? qn.abs / std::fabs(qn.value) : 1.0L;
  r.kappaX = qx.value != 0 ? qx.abs / std::fabs(qx.value) : 1.0L;
  return r;
}

double rel(double got, ld want) {
  return static_cast<double>(std::fabs((static_cast<ld>(got) - want) / want));
}

// Long double reference of the stationary trailing edge: Newton on the
// force-zero condition q(x) = x^2 + 2 L x - a1^2 = 0 (eq. 6 at x = a2), started
// at x = a1 where q >= 0; q is convex and increasing on [0, a1], so the
// iteration decreases monotonically to the root. The sum x^2 + 2Lx - a1^2 has
// terms of size a1^2 and slope 2(x + L), so the root is accurate to ~eps_ld x.
ld a2_newton(ld a1, ld L) {
  ld x = a1;
  for (int it = 0; it < 500; ++it) {
    const ld q = x * x + 2.0L * L * x - a1 * a1;
    const ld nx = x - q / (2.0L * (x + L));
    if (!(nx < x)) break; // monotone decrease has stopped: converged
    x = nx;
  }
  return x;
}

// Long double reference of a1 - a2: Newton on the equation for delta = a1 - a2,
// delta^2 - 2 (a1 + L) delta + 2 L a1 = 0 (its smaller root), started at 0;
// the function is convex and decreasing there, so the iterates increase
// monotonically. The terms 2(a1+L) delta and 2 L a1 have equal size at the
// root, slope ~2(a1+L): accurate to ~eps_ld delta, also when L << a1.
ld a1_minus_a2_newton(ld a1, ld L) {
  ld x = 0.0L;
  for (int it = 0; it < 500; ++it) {
    const ld f = x * x - 2.0L * (a1 + L) * x + 2.0L * L * a1;
    const ld nx = x - f / (2.0L * x - 2.0L * (a1 + L));
    if (!(nx > x)) break;
    x = nx;
  }
  return x;
}

using mdrmap::testing::make_case;
using mdrmap::testing::v1_of;

// Velocity giving v tau / a1 = zeta.
double vel(const Case& c, double zeta) {
  return zeta * analytic::a1(c) / c.rheology.tau;
}

// Hertz force of the MDR parabola: (16/3) G sqrt(R) d^{3/2}, in long double.
ld hertz(const Case& c) {
  return 16.0L / 3.0L * static_cast<ld>(c.rheology.G) *
         std::sqrt(static_cast<ld>(c.indenter.as<mdrmap::Parabola>().R)) *
         std::pow(static_cast<ld>(c.loading.d), 1.5L);
}

} // namespace

// ---------------------------------------------------------------------------
// The quadrature tool itself: P_n nodes and weights integrate x^k exactly for
// k <= 2n - 1. Tolerance: a few eps_ld (sums of 8 terms of size <= 2).
TEST(AnalyticQuadrature, GaussRuleIsExactForPolynomials) {
  const GaussRule& g = rule8();
  for (int k = 0; k <= 15; ++k) {
    ld sum = 0;
    for (std::size_t i = 0; i < g.x.size(); ++i)
      sum += g.w[i] * std::pow(g.x[i], static_cast<ld>(k));
    const ld want = (k % 2 == 0) ? 2.0L / static_cast<ld>(k + 1) : 0.0L;
    EXPECT_LE(std::fabs(sum - want), 32.0L * kEpsLd) << "k=" << k;
  }
}

// ---------------------------------------------------------------------------
// Corrected eqs. (9), (10) against quadrature over many contact sets.
// Tolerance: the closed form adds non-negative terms (a few eps_double after
// rounding of a1, a2); the quadrature's rounding is <= 64 kappa eps_ld. 1e-13 is
// ~500 eps_double, far below any wrong coefficient or sign (>= 1e-3 effects
// for every case with a2 > 0 or L > 0).
TEST(AnalyticForces, MatchQuadratureOfPaperIntegrands) {
  const double d_over_R[] = {1e-12, 1e-6, 1e-2, 0.3};
  const double Rs[] = {1e-3, 1.0, 7.5e2};
  const double taus[] = {0.0, 1e-3, 2.5};
  const double zetas[] = {1e-4, 0.1, 1.0, 10.0, 1e4, 1e8};
  const double fracs[] = {0.0, 0.01, 0.3, 0.5, 0.9, 0.999, 1.0};
  int n = 0;
  double worst = 0.0, worst_ratio = 0.0;
  for (double dr : d_over_R)
    for (double R : Rs)
      for (double tau : taus)
        for (double zeta : zetas) {
          Case c = make_case(dr * R, R, tau, 1.0, 0.0, 3.0e6);
          const double A = analytic::a1(c);
          const double w = tau > 0.0 ? zeta * A / tau : 1.0;
          std::vector<double> a2s;
          for (double f : fracs)
            a2s.push_back(f == 1.0 ? A : f * A);
          a2s.push_back(analytic::a2_stationary(c, w));
          for (double a2 : a2s) {
            const auto a1m = static_cast<double>(static_cast<ld>(A) - static_cast<ld>(a2));
            const State st = analytic::contact_forces(c, a2, a1m, w);
            const QuadForces q = quad_forces(c, a2, w);
            const double tolN = 1e-13 + static_cast<double>(64.0L * q.kappaN * kEpsLd);
            const double tolX = 1e-13 + static_cast<double>(64.0L * q.kappaX * kEpsLd);
            ASSERT_TRUE(std::isfinite(st.FN) && std::isfinite(st.Fx));
            EXPECT_LE(rel(st.FN, q.FN), tolN) << "d/R=" << dr << " R=" << R << " tau=" << tau
                                              << " zeta=" << zeta << " a2/a1=" << a2 / A;
            if (q.Fx != 0.0L) {
              EXPECT_LE(rel(st.Fx, q.Fx), tolX) << "d/R=" << dr << " R=" << R << " tau=" << tau
                                                << " zeta=" << zeta << " a2/a1=" << a2 / A;
              if (q.kappaX < 10) worst = std::max(worst, rel(st.Fx, q.Fx));
              worst_ratio = std::max(worst_ratio, rel(st.Fx, q.Fx) / tolX);
            } else {
              EXPECT_EQ(st.Fx, 0.0);
            }
            EXPECT_NEAR(st.mu, st.Fx / st.FN, 4 * kEps * st.mu);
            EXPECT_EQ(st.a2, a2);
            if (q.kappaN < 10) worst = std::max(worst, rel(st.FN, q.FN));
            worst_ratio = std::max(worst_ratio, rel(st.FN, q.FN) / tolN);
            ++n;
          }
        }
  std::cout << "[ info ] " << n << " contact sets; worst relative difference to quadrature "
            << worst << " (kappa < 10); worst difference / tolerance " << worst_ratio << "\n";
}

// ---------------------------------------------------------------------------
// Errata. The printed eq. (9) has -(a1^3 - a2^3)/(3R), eq. (10) (and 16) have
// -(a1^4 - a2^4)/2. For a generic contact set they miss the quadrature by far
// more than 1%, while the corrected forms agree to rounding.
namespace {
ld paper_eq9(const Case& c, ld a2, ld w) {
  const ld a1 = static_cast<ld>(analytic::a1(c)), d = c.loading.d,
           R = c.indenter.as<mdrmap::Parabola>().R, G = c.rheology.G, tau = c.rheology.tau;
  return 4.0L * G *
         (d * (a1 + a2) - (a1 * a1 * a1 - a2 * a2 * a2) / (3.0L * R) +
          tau * w / R * (a1 * a1 - a2 * a2));
}
ld paper_eq10(const Case& c, ld a2, ld w) {
  const ld a1 = static_cast<ld>(analytic::a1(c)), d = c.loading.d,
           R = c.indenter.as<mdrmap::Parabola>().R, G = c.rheology.G, tau = c.rheology.tau;
  return 8.0L * G / (R * R) *
         (R * d / 2.0L * (a1 * a1 - a2 * a2) - (std::pow(a1, 4.0L) - std::pow(a2, 4.0L)) / 2.0L +
          2.0L * tau * w / 3.0L * (a1 * a1 * a1 + a2 * a2 * a2));
}
} // namespace

TEST(AnalyticErrata, PrintedEq9And10DisagreeWithQuadratureCorrectedAgree) {
  Case c = make_case(1e-2, 1.0, 1.0, 1.0, 0.0, 1.0);
  const double A = analytic::a1(c);
  const double w = vel(c, 1.0);
  for (double a2 : {analytic::a2_stationary(c, w), 0.5 * A, 0.8 * A}) {
    const QuadForces q = quad_forces(c, a2, w);
    const State st = analytic::contact_forces(c, a2, A - a2, w);
    EXPECT_GT(std::fabs(paper_eq9(c, a2, w) / q.FN - 1.0L), 0.01L) << "a2/a1=" << a2 / A;
    EXPECT_GT(std::fabs(paper_eq10(c, a2, w) / q.Fx - 1.0L), 0.01L) << "a2/a1=" << a2 / A;
    EXPECT_LT(rel(st.FN, q.FN), 1e-14); // kappa = 1 here (p >= 0 or small cancellation)
    EXPECT_LT(rel(st.Fx, q.Fx), 1e-13);
  }
}

// Eq. (16) repeats the /2 of eq. (10): with the old contact set [-a1, a2(v)]
// and velocity v1 it misses the quadrature too.
TEST(AnalyticErrata, PrintedEq16DisagreesWithQuadrature) {
  Case c = make_case(1e-2, 1.0, 1.0, 1.0, 0.0, 1.0);
  const double v = vel(c, 2.0), v1 = 0.1 * v;
  const double a2v = analytic::a2_stationary(c, v);
  const QuadForces q = quad_forces(c, a2v, v1);
  EXPECT_GT(std::fabs(paper_eq10(c, a2v, v1) / q.Fx - 1.0L), 0.01L);
  EXPECT_LT(rel(analytic::jump(c, v, v1).Fx, q.Fx), 1e-13);
}

// Eqs. (12), (13) are the a2 -> 0 limits: quadrature over [-a1, 0] with the
// same velocity reproduces them exactly (up to rounding). This is the check
// that eq. (13) agrees with the corrected /4 and not with the printed /2 of (10).
TEST(AnalyticErrata, Eq12And13AreTheQuadratureOverMinusA1ToZero) {
  for (double zeta : {1e-3, 1.0, 1e3}) {
    Case c = make_case(4e-3, 2.0, 0.5, 1.0, 0.0, 2.0);
    const double v = vel(c, zeta);
    const QuadForces q = quad_forces(c, 0.0, v);
    EXPECT_LT(rel(analytic::FN_inf(c, v), q.FN), 1e-14) << zeta;
    EXPECT_LT(rel(analytic::Fx_inf(c, v), q.Fx), 1e-14) << zeta;
    // The printed /2 removes the a1^4/4 term; it shows unless the tau v term
    // dominates (zeta >> 1).
    if (zeta <= 1.0) {
      EXPECT_GT(std::fabs(paper_eq10(c, 0.0L, v) / q.Fx - 1.0L), 0.01L) << zeta;
    }
  }
}

// ---------------------------------------------------------------------------
// Stationary trailing edge (eq. 7).

// Force-zero condition d - a2^2/R - 2 tau v a2/R = 0, residual in long double.
// The residual relative to d equals (2(a2+L) a2/a1^2) * (relative error of a2),
// and 2(a2+L)a2/a1^2 is between 1 and 2, so the check bounds the relative
// error of a2 itself. The code's a2 carries ~6 roundings (sqrt(R)sqrt(d),
// hypot, +, /, *): 1e-14 is ~45 eps.
TEST(AnalyticStationary, A2SatisfiesForceZeroCondition) {
  for (double dr : {1e-12, 1e-6, 0.3})
    for (double lz = -8.0; lz <= 8.0; lz += 0.5) {
      Case c = make_case(dr * 0.02, 0.02, 1e-3, 1.0);
      const double w = vel(c, std::pow(10.0, lz));
      const ld a2 = analytic::a2_stationary(c, w);
      const ld d = c.loading.d, R = c.indenter.as<mdrmap::Parabola>().R,
               L = static_cast<ld>(w) * static_cast<ld>(c.rheology.tau);
      const ld residual = d - a2 * a2 / R - 2.0L * L * a2 / R;
      EXPECT_LE(std::fabs(residual / d), 1e-14L) << "d/R=" << dr << " zeta=1e" << lz;
      EXPECT_GT(a2, 0.0L);
      EXPECT_LE(a2, static_cast<ld>(analytic::a1(c)));
    }
}

// Where eq. (7) is well conditioned (zeta <= 1: sqrt(L^2 + Rd) / a2 <= 3.5),
// the naive form loses at most ~2 bits: agreement to 1e-14 relative.
TEST(AnalyticStationary, EqualsNaiveEq7WhereWellConditioned) {
  for (double zeta : {0.0, 1e-6, 1e-3, 0.1, 0.5, 1.0}) {
    Case c = make_case(3e-5, 0.1, 2.0, 1.0);
    const double w = vel(c, zeta);
    const double naive = std::sqrt(w * w * c.rheology.tau * c.rheology.tau +
                                   c.indenter.as<mdrmap::Parabola>().R * c.loading.d) -
                         w * c.rheology.tau;
    EXPECT_NEAR(analytic::a2_stationary(c, w), naive, 1e-14 * naive) << zeta;
  }
}

// At v tau / a1 = 1e8 the naive eq. (7) in double has sqrt(L^2 + a1^2) = L to
// the last bit: all digits are lost. The code's form agrees with the long
// double Newton root to 1e-14 (~45 eps, as above).
TEST(AnalyticStationary, AccurateAtHighSpeedWhereNaiveEq7Fails) {
  for (double zeta : {1e4, 1e6, 1e8}) {
    Case c = make_case(1e-6, 1e-3, 1e-3, 1.0);
    const double w = vel(c, zeta);
    const ld a1 = std::sqrt(static_cast<ld>(c.indenter.as<mdrmap::Parabola>().R) *
                            static_cast<ld>(c.loading.d));
    const ld L = static_cast<ld>(w) * static_cast<ld>(c.rheology.tau);
    const ld ref = a2_newton(a1, L);
    EXPECT_LT(rel(analytic::a2_stationary(c, w), ref), 1e-14) << zeta;
    // Sanity of the reference: the leading term a1^2/(2L) of the expansion
    // a2 = a1^2/(2L) (1 - a1^2/(4L^2) + ...).
    EXPECT_NEAR(static_cast<double>(ref / (a1 * a1 / (2.0L * L))), 1.0, 0.3 / (zeta * zeta));
    if (zeta == 1e8) {
      const double naive = std::sqrt(w * w * c.rheology.tau * c.rheology.tau +
                                     c.indenter.as<mdrmap::Parabola>().R * c.loading.d) -
                           w * c.rheology.tau;
      EXPECT_GT(rel(naive, ref), 0.5) << "naive eq. (7) unexpectedly accurate: " << naive;
    }
  }
}

// a1 - a2 against the long double Newton root of its own quadratic, for L from
// 1e-8 a1 (where a1 - a2 ~ L cancels in a1 - a2) to 1e8 a1. Tolerance as above.
TEST(AnalyticStationary, A1MinusA2AccurateEverywhere) {
  for (double lz = -8.0; lz <= 8.0; lz += 0.25) {
    Case c = make_case(2e-4, 5e-2, 3.0, 1.0);
    const double w = vel(c, std::pow(10.0, lz));
    const ld a1 = std::sqrt(static_cast<ld>(c.indenter.as<mdrmap::Parabola>().R) *
                            static_cast<ld>(c.loading.d));
    const ld L = static_cast<ld>(w) * static_cast<ld>(c.rheology.tau);
    const ld ref = a1_minus_a2_newton(a1, L);
    EXPECT_LT(rel(analytic::a1_minus_a2_stationary(c, w), ref), 1e-14) << "zeta=1e" << lz;
    // Cross-check of the two references where a1 - a2 does not cancel.
    if (lz >= 0.0) {
      EXPECT_LT(std::fabs((a1 - a2_newton(a1, L)) / ref - 1.0L), 1e-17L);
    }
  }
  Case c0 = make_case(2e-4, 5e-2, 0.0, 1.0);
  EXPECT_EQ(analytic::a1_minus_a2_stationary(c0, 1.0), 0.0);
  EXPECT_EQ(analytic::a2_stationary(c0, 1.0), analytic::a1(c0));
}

// ---------------------------------------------------------------------------
// Limits.

// tau = 0: elastic Hertz contact, F_N = (16/3) G sqrt(R) d^{3/2}, symmetric
// contact [-a1, a1], no friction. Tolerance: a few roundings (1e-14).
TEST(AnalyticLimits, HertzAtTauZero) {
  for (double dr : {1e-12, 1e-4, 0.3}) {
    Case c = make_case(dr * 3.0, 3.0, 0.0, 5.0, 0.0, 7.0);
    const State st = analytic::stationary(c, c.history.v0);
    EXPECT_LT(rel(st.FN, hertz(c)), 1e-14);
    EXPECT_EQ(st.Fx, 0.0);
    EXPECT_EQ(st.mu, 0.0);
    EXPECT_EQ(st.a2, analytic::a1(c));
  }
}

// tau -> 0 with everything else fixed. Expansions in zeta (derived from eq. 7
// and the corrected eqs. 9, 10; a2/a1 = 1 - zeta + zeta^2/2 + ...):
//   F_N / F_Hertz = 1 + (3/4) zeta^2 - (1/2) zeta^3 + ...
//   mu / sqrt(d/R) = 2 zeta - (3/2) zeta^2 + O(zeta^4)
// So F_N converges with order 2, mu with order 1 (observed orders asserted to
// +-0.05), and the leading coefficients hold to within the next term
// (|ratio - 1| <= zeta, the next coefficients being 2/3 and 3/4).
TEST(AnalyticLimits, ConvergesToHertzAsTauToZero) {
  Case c = make_case(1e-3, 0.4, 1.0, 1.0, 0.0, 2.0);
  const double sdr = std::sqrt(c.loading.d / c.indenter.as<mdrmap::Parabola>().R);
  auto eN = [&](double zeta) {
    c.rheology.tau = zeta; // v = a1 below, so zeta = tau * a1 / a1
    return rel(analytic::stationary(c, analytic::a1(c)).FN, hertz(c));
  };
  auto mu = [&](double zeta) {
    c.rheology.tau = zeta;
    return analytic::stationary(c, analytic::a1(c)).mu / sdr;
  };
  for (double zeta : {1e-1, 1e-2, 1e-3}) {
    EXPECT_NEAR(eN(zeta) / (0.75 * zeta * zeta), 1.0, zeta) << zeta;
    EXPECT_NEAR(std::log10(eN(zeta) / eN(zeta / 10)), 2.0, 0.05) << zeta;
  }
  for (double zeta : {1e-1, 1e-2, 1e-4, 1e-6, 1e-8}) {
    EXPECT_NEAR(mu(zeta) / (2.0 * zeta), 1.0, zeta) << zeta;
    EXPECT_NEAR(std::log10(mu(zeta) / mu(zeta / 10)), 1.0, 0.05) << zeta;
  }
}

// v -> infinity. With w = 1/zeta (expansions as above, a2/a1 = w/2 - w^3/8 ...):
//   F_N / F_N^inf = 1 + w^2/4 - w^3/6 + ...
//   F_x / F_x^inf = 1 - w^3/16 + ...
//   mu / mu_inf  = 1 - 7w/24 - w^2/18 + ...
// Eqs. (12)/(13) carry the growing tau v term, so the forces approach them
// faster (orders 2 and 3) than the friction coefficient approaches eq. (14)
// (order 1). Coefficients checked to within the next term, orders to +-0.05.
// Rounding: at the largest zeta used the deviation is still >= 1e4 eps.
TEST(AnalyticLimits, HighSpeedLimitsEq12To14) {
  Case c = make_case(2e-5, 0.03, 0.7, 1.0, 0.0, 1.5e6);
  auto state = [&](double zeta) { return analytic::stationary(c, vel(c, zeta)); };
  auto eN = [&](double zeta) { return state(zeta).FN / analytic::FN_inf(c, vel(c, zeta)) - 1.0; };
  auto eX = [&](double zeta) { return 1.0 - state(zeta).Fx / analytic::Fx_inf(c, vel(c, zeta)); };
  auto eM = [&](double zeta) { return 1.0 - state(zeta).mu / analytic::mu_inf(c); };
  for (double zeta : {10.0, 100.0, 1e3}) {
    const double w = 1.0 / zeta;
    EXPECT_NEAR(eN(zeta) / (w * w / 4), 1.0, w) << zeta;
    EXPECT_NEAR(std::log10(eN(zeta) / eN(zeta * 10)), 2.0, 0.05) << zeta;
    EXPECT_NEAR(eX(zeta) / (w * w * w / 16), 1.0, w) << zeta;
    if (zeta < 1e3) {
      EXPECT_NEAR(std::log10(eX(zeta) / eX(zeta * 10)), 3.0, 0.05) << zeta;
    }
  }
  for (double zeta : {10.0, 1e2, 1e4, 1e6, 1e8}) {
    const double w = 1.0 / zeta;
    const double roundoff = 16 * kEps / (7 * w / 24);
    EXPECT_NEAR(eM(zeta) / (7 * w / 24), 1.0, w + roundoff) << zeta;
    if (zeta <= 1e6) {
      EXPECT_NEAR(std::log10(eM(zeta) / eM(zeta * 10)), 1.0, 0.05) << zeta;
    }
  }
  EXPECT_NEAR(state(1e8).mu / analytic::mu_inf(c), 1.0, 1e-8);
  EXPECT_DOUBLE_EQ(analytic::mu_inf(c),
                   4.0 / 3.0 * std::sqrt(c.loading.d / c.indenter.as<mdrmap::Parabola>().R));
  // The friction coefficient rises monotonically from 0 to mu_inf with speed.
  double prev = 0.0;
  for (double lz = -6.0; lz <= 8.0; lz += 0.1) {
    const double m = state(std::pow(10.0, lz)).mu;
    EXPECT_GT(m, prev) << lz;
    EXPECT_LT(m, analytic::mu_inf(c)) << lz;
    prev = m;
  }
}

// ---------------------------------------------------------------------------
// The step.

// After a drop v -> v1 (zeta = k^-1, zeta1 = k):
//   mu(0+) / mu_post = 1 + 5k/12 - 23k^2/16 + ...,  mu_post = (3/4) sqrt(d/R).
// Coefficient checked to within the next term (|ratio - 1| <= 4k), order 1.
TEST(AnalyticJump, PostDropLimit) {
  Case c = make_case(1e-4, 0.05, 2e-3, 1.0, 0.0, 1e6);
  auto e = [&](double k) {
    return analytic::jump(c, vel(c, 1.0 / k), vel(c, k)).mu / analytic::mu_post_drop_limit(c) - 1.0;
  };
  for (double k : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    EXPECT_NEAR(e(k) / (5.0 * k / 12.0), 1.0, 4.0 * k) << k;
    EXPECT_NEAR(std::log10(e(k) / e(k / 10)), 1.0, 0.05) << k;
  }
  EXPECT_DOUBLE_EQ(analytic::mu_post_drop_limit(c),
                   0.75 * std::sqrt(c.loading.d / c.indenter.as<mdrmap::Parabola>().R));
}

// Increase v -> v1 > v: the elements in (a2(v1), a2(v)] would have negative
// force p(x) < 0 with velocity v1, so they detach at once; the contact is
// [-a1, a2(v1)] with velocity v1, the stationary state at v1. Checked against
// quadrature over that set (kappa-aware tolerance as in MatchQuadrature...).
TEST(AnalyticJump, IncreaseEqualsStationaryAtNewVelocity) {
  for (double zeta : {1e-3, 0.3, 1.0, 30.0})
    for (double ratio : {1.0, 1.001, 2.0, 1e3}) {
      Case c = make_case(1e-3, 0.2, 0.1, 1.0, 0.0, 1.0);
      const double v = vel(c, zeta), v1 = ratio * v;
      const State j = analytic::jump(c, v, v1);
      const double a2v1 = analytic::a2_stationary(c, v1);
      const QuadForces q = quad_forces(c, a2v1, v1);
      EXPECT_EQ(j.a2, a2v1);
      EXPECT_LT(rel(j.FN, q.FN), 1e-13);
      EXPECT_LT(rel(j.Fx, q.Fx), 1e-13 + static_cast<double>(64.0L * q.kappaX * kEpsLd));
      const State st1 = analytic::stationary(c, v1);
      EXPECT_EQ(j.FN, st1.FN);
      EXPECT_EQ(j.Fx, st1.Fx);
      // Physical reason: force density at velocity v1 is negative beyond a2(v1).
      if (ratio > 1.0) {
        const ld x = 0.5L * (static_cast<ld>(a2v1) + analytic::a2_stationary(c, v));
        const ld L1 = static_cast<ld>(v1) * static_cast<ld>(c.rheology.tau);
        EXPECT_LT(static_cast<ld>(c.loading.d) - x * x / c.indenter.as<mdrmap::Parabola>().R -
                      2.0L * L1 * x / c.indenter.as<mdrmap::Parabola>().R,
                  0.0L);
      }
    }
}

// Decrease v -> v1 < v: the old contact set [-a1, a2(v)] keeps touching (its
// force density with v1 is >= that with v, which is >= 0), moving at v1:
// corrected eqs. (15), (16), checked by quadrature. F_N drops at the step,
// below both stationary values: the paper's "maximal" is a minimum.
TEST(AnalyticJump, DecreaseUsesOldContactSetWithNewVelocity) {
  for (double zeta : {1e-3, 0.3, 1.0, 30.0, 1e6})
    for (double ratio : {0.0, 1e-4, 0.1, 0.5, 0.999}) {
      Case c = make_case(1e-3, 0.2, 0.1, 1.0, 0.0, 1.0);
      const double v = vel(c, zeta), v1 = ratio * v;
      const State j = analytic::jump(c, v, v1);
      const double a2v = analytic::a2_stationary(c, v);
      const QuadForces q = quad_forces(c, a2v, v1);
      EXPECT_EQ(j.a2, a2v);
      EXPECT_LT(rel(j.FN, q.FN), 1e-13) << zeta << " " << ratio;
      EXPECT_LT(rel(j.Fx, q.Fx), 1e-13 + static_cast<double>(64.0L * q.kappaX * kEpsLd))
          << zeta << " " << ratio;
      // Every element of [-a1, a2(v)] keeps a non-negative force at v1.
      const ld L1 = static_cast<ld>(v1) * static_cast<ld>(c.rheology.tau);
      const ld x = a2v;
      EXPECT_GE(static_cast<ld>(c.loading.d) - x * x / c.indenter.as<mdrmap::Parabola>().R -
                    2.0L * L1 * x / c.indenter.as<mdrmap::Parabola>().R,
                -1e-15L * c.loading.d);
      const State pre = analytic::stationary(c, v);
      const State post = analytic::stationary(c, v1);
      EXPECT_LT(j.FN, pre.FN) << zeta << " " << ratio;
      // Below post by the integral over [a2(v), a2(v1)], which is second order in
      // a2(v1) - a2(v) and can fall below rounding (zeta = 1e6, ratio 0.999).
      EXPECT_LE(j.FN, post.FN * (1 + 4 * kEps)) << zeta << " " << ratio;
      EXPECT_LT(j.Fx, pre.Fx) << zeta << " " << ratio;
    }
}

// ---------------------------------------------------------------------------
// Start-stop limit: with a2(v) -> 0 the free tail is d exp(-t/tau) (flat, over
// lengths ~v tau >> a1) and v1 -> 0, so the edge solves d - x^2/R = d e^{-t/tau},
// x = a1 sqrt(1 - e^{-t/tau}). Reference in long double with expm1l; the
// code's value carries ~4 roundings: 2e-15 relative. tau = 0: instant recovery.
TEST(AnalyticStartStop, A2Formula) {
  Case c = make_case(3e-6, 1e-3, 1e-3, 1.0);
  const ld a1 = std::sqrt(static_cast<ld>(c.indenter.as<mdrmap::Parabola>().R) *
                          static_cast<ld>(c.loading.d));
  for (double t_over_tau : {1e-20, 1e-8, 1e-3, 0.1, 1.0, 3.0, 10.0, 50.0}) {
    const double t = t_over_tau * c.rheology.tau;
    const ld want = a1 * std::sqrt(-std::expm1(-static_cast<ld>(t) / c.rheology.tau));
    const double got = analytic::a2_start_stop(c, t);
    EXPECT_LT(rel(got, want), 2e-15) << t_over_tau;
    const ld x = got;
    const ld resid = (c.loading.d - x * x / c.indenter.as<mdrmap::Parabola>().R) -
                     c.loading.d * std::exp(-static_cast<ld>(t) / c.rheology.tau);
    EXPECT_LT(std::fabs(resid / c.loading.d), 1e-15L) << t_over_tau;
  }
  EXPECT_EQ(analytic::a2_start_stop(c, 0.0), 0.0);
  c.rheology.tau = 0.0;
  EXPECT_EQ(analytic::a2_start_stop(c, 1e-9), analytic::a1(c));
}

// ---------------------------------------------------------------------------
// Hard ranges: finite, positive, physically ordered results for d/R from 1e-12
// to 0.3, v tau / a1 from 1e-4 to 1e8 and tau = 0, in SI units (G = 1 MPa,
// tau = 1 ms, R from 1 um to 1 m, d = (d/R) R), and for drops and
// rises at the step.
TEST(AnalyticHardRanges, FiniteAndPhysical) {
  auto check = [](const State& st, const Case& c, const char* what) {
    const double A = analytic::a1(c);
    const double mu_max =
        4.0 / 3.0 * std::sqrt(c.loading.d / c.indenter.as<mdrmap::Parabola>().R) * (1 + 1e-12);
    EXPECT_TRUE(std::isfinite(st.FN) && std::isfinite(st.Fx) && std::isfinite(st.mu) &&
                std::isfinite(st.a2))
        << what;
    EXPECT_GT(st.FN, 0.0) << what;
    EXPECT_GE(st.Fx, 0.0) << what;
    EXPECT_GE(st.mu, 0.0) << what;
    EXPECT_LE(st.mu, mu_max) << what << " d=" << c.loading.d
                             << " R=" << c.indenter.as<mdrmap::Parabola>().R;
    EXPECT_GE(st.a2, 0.0) << what;
    EXPECT_LE(st.a2, A) << what;
    // Bounds from p >= 0 on the contact: F_N between the Hertz-like integrals.
    // p <= d + 2 L a1 / R on a contact of length <= 2 a1.
    EXPECT_LE(st.FN,
              4.0 * c.rheology.G *
                  (2 * A * c.loading.d + 4 * A * A * std::max(c.history.v0, v1_of(c)) *
                                             c.rheology.tau / c.indenter.as<mdrmap::Parabola>().R) *
                  (1 + 1e-12))
        << what;
  };
  int n = 0;
  for (double R : {1e-6, 1e-3, 1.0})
    for (double dr : {1e-12, 1e-8, 1e-4, 1e-2, 0.3}) {
      const double d = dr * R;
      for (double tau : {0.0, 1e-3})
        for (double lz = -4.0; lz <= 8.0; lz += 1.0) {
          const double A = std::sqrt(R) * std::sqrt(d);
          const double v = std::pow(10.0, lz) * A / 1e-3; // zeta for tau = 1 ms
          for (double ratio : {0.0, 1e-4, 0.5, 2.0, 1e4}) {
            const Case c = make_case(d, R, tau, v, ratio * v, 1e6);
            ASSERT_EQ(analytic::a1(c), A);
            ASSERT_NO_THROW(mdrmap::validate(c));
            check(analytic::stationary(c, v), c, "stationary");
            check(analytic::jump(c, v, ratio * v), c, "jump");
            if (tau > 0) {
              const double a2 = analytic::a2_start_stop(c, 0.37 * tau);
              EXPECT_TRUE(std::isfinite(a2) && a2 > 0.0 && a2 < A);
            }
            EXPECT_TRUE(std::isfinite(analytic::FN_inf(c, v)) && analytic::FN_inf(c, v) > 0);
            EXPECT_TRUE(std::isfinite(analytic::Fx_inf(c, v)) && analytic::Fx_inf(c, v) > 0);
            ++n;
          }
        }
    }
  EXPECT_GT(n, 500);
}
