// The core's numerics floor (src/core/numerics): the bracketed root finder
// against roots known in closed form, its refusal of a non-bracket, its work
// charge against a count of the evaluations made; the phi functions against a
// long-double evaluation and their limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/numerics/phi.hpp"
#include "core/numerics/root.hpp"

namespace {

using mdrmap::RunControl;
using mdrmap::numerics::Bracket;
using mdrmap::numerics::NoBracket;
using mdrmap::numerics::RootSearch;

TEST(Root, CubeRootToTheRequestedBits) {
  auto f = [](double x) { return x * x * x - 2.0; };
  const double root = std::cbrt(2.0);
  for (int bits : {20, 40, 52}) {
    const Bracket r =
        mdrmap::numerics::toms748(f, 0.0, 2.0, mdrmap::numerics::bits_tolerance(bits), {"cube"});
    EXPECT_LE(r.lo, root);
    EXPECT_GE(r.hi, root);
    EXPECT_LE(std::abs(r.mid() - root), std::ldexp(root, 2 - bits)) << bits;
  }
}

TEST(Root, WidthToleranceBoundsTheBracket) {
  auto f = [](double x) { return std::exp(x) - 3.0; };
  const Bracket r = mdrmap::numerics::toms748(f, 0.0, 2.0, -2.0, std::exp(2.0) - 3.0,
                                              mdrmap::numerics::WidthTolerance{1e-9}, {"log 3"});
  EXPECT_LE(r.width(), 1e-9);
  EXPECT_LE(r.lo, std::log(3.0));
  EXPECT_GE(r.hi, std::log(3.0));
}

TEST(Root, ZeroEndIsTheRoot) {
  auto f = [](double x) { return x - 1.0; };
  const Bracket r =
      mdrmap::numerics::toms748(f, 1.0, 2.0, 0.0, 1.0, mdrmap::numerics::bits_tolerance(52), {"z"});
  EXPECT_EQ(r.lo, 1.0);
  EXPECT_EQ(r.hi, 1.0);
}

void expect_no_bracket(double fa, double fb) {
  auto f = [](double x) { return x; };
  try {
    mdrmap::numerics::toms748(f, 0.0, 1.0, fa, fb, mdrmap::numerics::bits_tolerance(52),
                              {"the named search"});
    ADD_FAILURE() << "no throw for f(a) = " << fa << ", f(b) = " << fb;
  } catch (const NoBracket& e) {
    EXPECT_NE(std::string(e.what()).find("the named search"), std::string::npos) << e.what();
  }
}

TEST(Root, RefusesValuesOfOneSignOrNotFinite) {
  expect_no_bracket(1.0, 2.0);
  expect_no_bracket(-1.0, -2.0);
  expect_no_bracket(std::numeric_limits<double>::quiet_NaN(), 1.0);
  expect_no_bracket(-1.0, std::numeric_limits<double>::infinity());
}

TEST(Root, ChargesEveryEvaluation) {
  for (const bool ends_given : {true, false}) {
    int calls = 0;
    auto f = [&](double x) {
      ++calls;
      return std::sin(x) - 0.5; // root pi/6 in [0, 1]
    };
    RunControl control;
    const RootSearch s{"sin", 200, &control, 3.0};
    const auto tol = mdrmap::numerics::bits_tolerance(52);
    const Bracket r =
        ends_given ? mdrmap::numerics::toms748(f, 0.0, 1.0, -0.5, std::sin(1.0) - 0.5, tol, s)
                   : mdrmap::numerics::toms748(f, 0.0, 1.0, tol, s);
    EXPECT_NEAR(r.mid(), std::acos(-1.0) / 6.0, 1e-15);
    EXPECT_EQ(r.evaluations, static_cast<std::uintmax_t>(calls)) << ends_given;
    EXPECT_EQ(control.spent(), 3.0 * calls) << ends_given;
  }
}

TEST(Root, BudgetEndsTheSearch) {
  RunControl control;
  control.max_work = 5.0;
  auto f = [](double x) { return std::tanh(x - 0.3); };
  EXPECT_THROW(mdrmap::numerics::toms748(f, 0.0, 1.0, mdrmap::numerics::bits_tolerance(52),
                                         {"tanh", 200, &control, 1.0}),
               mdrmap::CaseAbandoned);
}

TEST(Root, IncreasingRootWidensToTheBracket) {
  // a guess of the slope 1000 times too large: the secant step falls short,
  // widened by 4 until it brackets the root ln 5 (on either side of x0)
  for (const double x0 : {-3.0, 5.0}) {
    double k = 5000.0;
    auto f = [](double x) { return std::exp(x) - 5.0; };
    const double x = mdrmap::numerics::increasing_root(f, x0, k, 1e-12, -1e300, {"exp", 100});
    EXPECT_NEAR(x, std::log(5.0), 1e-12) << x0;
    EXPECT_GT(k, 0.0);
  }
}

TEST(Root, ScaledRootFromFarAboveAndBelow) {
  // cube roots from 1 of r = 1e-30 and 1e30: 33 halvings or doublings, each
  // bracket's ends the scaled start's, with their values
  for (const double r : {1e-30, 1.0, 1e30}) {
    auto f = [r](double x) { return std::cbrt(x) - std::cbrt(r); };
    const mdrmap::numerics::ScaledBracket e = mdrmap::numerics::scaled_bracket(f, 1.0, 4000);
    EXPECT_LE(e.flo, 0.0);
    EXPECT_GE(e.fhi, 0.0);
    EXPECT_EQ(e.flo, f(e.lo));
    EXPECT_EQ(e.fhi, f(e.hi));
    EXPECT_TRUE(e.lo == e.hi || e.hi == 1.0 || e.lo == 1.0) << r; // one side moves
    const double x =
        mdrmap::numerics::scaled_root(f, 1.0, 4000, mdrmap::numerics::bits_tolerance(52), {"cbrt"});
    EXPECT_NEAR(x, r, 1e-14 * r) << r;
  }
}

TEST(Root, IncreasingRootWithoutRootThrows) {
  double k = 1.0;
  auto f = [](double x) { return 2.0 + std::atan(x); }; // increasing, > 0.4
  EXPECT_THROW(mdrmap::numerics::increasing_root(f, 0.0, k, 1e-12, -1e300, {"atan", 100}),
               NoBracket);
}

} // namespace

// ---- phi functions ----------------------------------------------------------

namespace {

/// phi_n(z) in long double: the series (summed smallest first) for |z| <= 1,
/// else phi_1 from expm1l and the recurrence upward (|z| > 1: each step loses
/// at most a factor n + 1 of its 64 bits).
long double phi_reference(int n, long double z) {
  if (n == 0) return std::exp(-z);
  if (std::fabs(z) <= 1.0L) {
    long double terms[64], t = 1.0L;
    for (int k = 1; k <= n; ++k)
      t /= static_cast<long double>(k);
    for (int j = 0; j < 64; ++j) {
      terms[j] = t;
      t *= -z / static_cast<long double>(j + n + 1);
    }
    long double s = 0.0L;
    for (int j = 63; j >= 0; --j)
      s += terms[j];
    return s;
  }
  long double p = -std::expm1(-z) / z, f = 1.0L;
  for (int k = 1; k < n; ++k) {
    f /= static_cast<long double>(k);
    p = (f - p) / z;
  }
  return p;
}

} // namespace

// newton_in_bracket: the row's switch times and edge predictions.
TEST(Root, NewtonInBracketFindsTheRootToItsLastUlps) {
  // f = 1 - t - t^3 / 2 on (0, 2): one root, Newton converging from the secant
  auto f = [](double t, double& v, double& dv) {
    v = 1.0 - t - 0.5 * t * t * t;
    dv = -1.0 - 1.5 * t * t;
  };
  long double lo = 0.0L, hi = 2.0L; // (the root by bisection in long double)
  for (int i = 0; i < 200; ++i) {
    const long double m = 0.5L * (lo + hi);
    (1.0L - m - 0.5L * m * m * m > 0.0L ? lo : hi) = m;
  }
  const double h = 2.0, root = mdrmap::numerics::newton_in_bracket(f, 1.0, h);
  EXPECT_NEAR(root, static_cast<double>(lo), 8.0 * std::numeric_limits<double>::epsilon() * h);
}

TEST(Root, NewtonInBracketEndsAtItsEnds) {
  auto f = [](double t, double& v, double& dv) {
    v = 1.0 - t;
    dv = -1.0;
  };
  EXPECT_EQ(mdrmap::numerics::newton_in_bracket(f, 0.0, 0.5), 0.0); // (no root after a zero start)
  EXPECT_EQ(mdrmap::numerics::newton_in_bracket(f, 1.0, 0.5), 0.5); // (still positive at h)
  EXPECT_EQ(mdrmap::numerics::newton_in_bracket(f, 1.0, 1.0), 1.0); // (zero at h: not past it)
}

// With a noise, a point just past the root is accepted, and it is the last
// point evaluated (the caller's state there is formed); from a start far off,
// the steps that would leave the bracket bisect it.
TEST(Root, NewtonInBracketAcceptsThePointJustPastTheRoot) {
  double last = -1.0;
  int calls = 0;
  auto f = [&](double t, double& v, double& dv) {
    ++calls;
    last = t;
    v = std::cos(t) - 0.5; // root pi/3 on (0, 2)
    dv = -std::sin(t);
  };
  const double noise = 1e-9;
  for (const double start : {1.0, 1.99, 0.001}) {
    calls = 0;
    const double t = mdrmap::numerics::newton_in_bracket(
        f, 0.5, 2.0, [&](double, double) { return start; }, noise,
        mdrmap::numerics::NewtonEnd::Evaluated);
    EXPECT_EQ(t, last);
    EXPECT_LE(std::cos(t) - 0.5, 0.0);
    EXPECT_GE(std::cos(t) - 0.5, -noise);
    EXPECT_LT(calls, 12) << "start " << start;
  }
}

TEST(Phi, AgainstLongDoubleFromTinyToLarge) {
  // 10 points a decade over [1e-12, 1e3], and their negatives down to -30
  // (phi_n(-z) grows like e^z: no cancellation there, the same bound)
  double worst = 0.0;
  for (int i = 0; i <= 150; ++i) {
    const double x = std::pow(10.0, -12.0 + 0.1 * i);
    for (const double z : {x, -x}) {
      if (z < -30.0) continue;
      double all[6], four[4];
      mdrmap::numerics::phi_all(z, all);
      mdrmap::numerics::phi_all(z, four);
      for (int n = 0; n < 6; ++n) {
        const double ref = static_cast<double>(phi_reference(n, z));
        if (ref == 0.0) { // (phi_0 = e^-z underflows past z = 745)
          EXPECT_EQ(all[n], 0.0) << "n=" << n << " z=" << z;
          continue;
        }
        // phi(n, z) alone, and with the others: 6 of them, or 4
        for (const double got : {mdrmap::numerics::phi(n, z), all[n], n < 4 ? four[n] : all[n]}) {
          const double err = std::abs(got - ref) / std::abs(ref);
          worst = std::max(worst, err);
          // Horner's rule on the alternating series: its rounding grows with
          // sum |term| / |sum| = phi_n(-|z|) / phi_n(|z|) <= e^|z| (<= 7.4 for
          // |z| <= 2), the recurrences' with their error factors (< 2.5 a
          // step): 16 ulps bound either
          EXPECT_LE(err, 16.0 * std::numeric_limits<double>::epsilon()) << "n=" << n << " z=" << z;
        }
      }
    }
  }
  std::printf("phi: worst relative error %.3g eps over [1e-12, 1e3]\n",
              worst / std::numeric_limits<double>::epsilon());
}

TEST(Phi, ClosedFormsAndRecurrence) {
  // where the closed forms do not cancel (z >= 4): phi_1, phi_2 as written
  for (const double z : {4.0, 10.0, 100.0}) {
    EXPECT_NEAR(mdrmap::numerics::phi(1, z), (1.0 - std::exp(-z)) / z, 1e-15 / z);
    EXPECT_NEAR(mdrmap::numerics::phi(2, z), (std::exp(-z) - 1.0 + z) / (z * z), 1e-15 / z);
  }
  // z -> 0: phi_n -> 1/n!, with slope -1/(n+1)!
  const double z = 1e-9;
  double f = 1.0;
  for (int n = 0; n < 6; ++n) {
    if (n > 0) f /= n;
    EXPECT_NEAR(mdrmap::numerics::phi(n, z), f - z * f / (n + 1), 1e-18) << n;
  }
}
