// Tests of the continuum solution after the velocity step (src/core/exact.*)
// against the definition of the model (docs/design.md, "The model"),
// evaluated here independently in long double:
//
// - In the moving frame x, the free tail left by stationary sliding at v is
//   h(a2v) exp(-(x - a2v)/(v tau)); after the step every free element relaxes
//   with exp(-t/tau) while the frame moves on at v1, so at time t the free
//   depression at x is T(x, t) = c(t) h(a2v) exp(-(x - a2v)/(v tau)) with
//   c(t) = exp(-(1 - v1/v) t / tau).
// - Free material touches the indenter again where T(x, t) <= h(x) = d - x^2/R.
//   Material in contact (at the step or re-touched) stays in contact while its
//   force, h(x) - 2 v1 tau x / R, is >= 0, i.e. while x <= a2(v1).
// - So a2(t) = min(x*(t), a2(v1)), x* the right end of {x : T(x, t) <= h(x)},
//   and the forces are those of the contact set [-a1, a2(t)] moving at v1.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/model/case.hpp"
#include "core/solvers/exact.hpp"
#include "test_case.hpp"

namespace {

using mdrmap::Case;
using mdrmap::ExactSolution;
using mdrmap::State;
namespace analytic = mdrmap::analytic;
using ld = long double;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr ld kEpsLd = std::numeric_limits<ld>::epsilon();

using mdrmap::testing::make_case;
using mdrmap::testing::t_end_of;
using mdrmap::testing::v1_of;

// One-step case with zeta = v tau / a1 and v1 = ratio * v, observed over the
// default window 6 tau with `samples` linear samples.
Case scene_z(double zeta, double ratio, double d_over_R = 1e-3, double R = 0.05, double tau = 2e-3,
             double G = 1e6, long samples = 201) {
  const double d = d_over_R * R;
  const double v = zeta * std::sqrt(R * d) / tau;
  return make_case(d, R, tau, v, ratio * v, G, 0.0, samples);
}

// ---------------------------------------------------------------------------
// Long double reimplementation of the definition: bisection for the edge on
// [a2v, min(a2v1, a1)], forces by corrected eqs. (9), (10) with velocity v1.
struct Ref {
  ld d, R, G, tau, v, v1, a1, L, L1, a2v, a2v1, ha2v;

  explicit Ref(const Case& c)
      : d(c.loading.d), R(c.indenter.as<mdrmap::Parabola>().R), G(c.rheology.G),
        tau(c.rheology.tau), v(c.history.v0), v1(v1_of(c)), a1(std::sqrt(R * d)), L(v * tau),
        L1(v1 * tau), a2v(a2_of(L)), a2v1(a2_of(L1)), ha2v(d - a2v * a2v / R) {}

  // Eq. (7) rationalised (the naive difference loses all digits for L >> a1,
  // also in long double).
  ld a2_of(ld l) const { return a1 * a1 / (std::sqrt(l * l + a1 * a1) + l); }
  ld h(ld x) const { return d - x * x / R; }
  ld c(ld t) const { return std::exp(-(1.0L - v1 / v) * t / tau); }
  ld tail(ld x, ld t) const { return c(t) * ha2v * std::exp(-(x - a2v) / L); }
  /// h(x) - T(x, t): >= 0 where the free surface has come up to the indenter.
  ld margin(ld x, ld t) const { return h(x) - tail(x, t); }

  ld edge(ld t, bool* capped = nullptr) const {
    const ld hi0 = std::min(a2v1, a1);
    if (margin(hi0, t) >= 0) {
      if (capped) *capped = true;
      return hi0;
    }
    if (capped) *capped = false;
    ld lo = a2v, hi = hi0; // margin(lo) = h(a2v) (1 - c) > 0 > margin(hi)
    for (int it = 0; it < 400; ++it) {
      const ld mid = 0.5L * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (margin(mid, t) >= 0 ? lo : hi) = mid;
    }
    return 0.5L * (lo + hi);
  }

  struct St {
    ld FN, Fx, mu, a2;
  };
  St forces(ld a2) const {
    const ld diff2 = (a1 - a2) * (a1 + a2); // a1^2 - a2^2
    const ld cubes = a1 * a1 * a1 + a2 * a2 * a2;
    St st;
    st.a2 = a2;
    st.FN = 4.0L * G * (d * (a1 + a2) - cubes / (3.0L * R) + L1 * diff2 / R);
    st.Fx = 8.0L * G / (R * R) *
            (R * d / 2.0L * diff2 - diff2 * (a1 * a1 + a2 * a2) / 4.0L + 2.0L * L1 / 3.0L * cubes);
    st.mu = st.Fx / st.FN;
    return st;
  }
  St at(ld t) const { return forces(t > 0 ? edge(t) : a2v); }
};

// ---------------------------------------------------------------------------
// Composite 8-point Gauss-Legendre quadrature in long double (exact for the
// cubic integrands up to rounding ~ eps_ld * int|f|).
struct Quad {
  ld value = 0, abs = 0;
};

template <class F> Quad integrate(const F& f, ld a, ld b, int panels = 8) {
  // Nodes and weights of the 8-point rule (Newton on P_8, computed once).
  static const std::vector<std::pair<ld, ld>> rule = [] {
    std::vector<std::pair<ld, ld>> r;
    const int n = 8;
    for (int i = 0; i < n; ++i) {
      ld z = std::cos(3.141592653589793238462643383279502884L * (i + 0.75L) / (n + 0.5L));
      ld dp = 1;
      for (int it = 0; it < 100; ++it) {
        ld p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const ld p2 = ((2.0L * k - 1.0L) * z * p1 - (k - 1.0L) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1.0L);
        const ld dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) <= 2 * kEpsLd) break;
      }
      r.emplace_back(z, 2.0L / ((1.0L - z * z) * dp * dp));
    }
    return r;
  }();
  Quad q;
  const ld h = (b - a) / panels;
  for (int k = 0; k < panels; ++k) {
    const ld mid = a + h * (k + 0.5L);
    for (const auto& [x, w] : rule) {
      const ld fx = f(mid + 0.5L * h * x);
      q.value += w * fx;
      q.abs += w * std::fabs(fx);
    }
  }
  q.value *= 0.5L * h;
  q.abs *= 0.5L * h;
  return q;
}

double rel(double got, ld want) {
  return static_cast<double>(std::fabs((static_cast<ld>(got) - want) / want));
}

} // namespace

// ---------------------------------------------------------------------------
// t = 0+, before the step, and the end of the transient.
TEST(ExactBasics, JumpPreAndLateTime) {
  for (double zeta : {1e-3, 0.5, 2.0, 1e4})
    for (double ratio : {0.0, 0.2, 0.9, 1.0, 3.0}) {
      const Case c = scene_z(zeta, ratio);
      const ExactSolution ex(c);
      const State j = analytic::jump(c, c.history.v0, v1_of(c)), a = ex.at(0.0);
      EXPECT_NEAR(a.FN, j.FN, 1e-15 * j.FN);
      EXPECT_NEAR(a.Fx, j.Fx, 1e-15 * j.Fx);
      EXPECT_NEAR(a.a2, j.a2, 1e-15 * j.a2);
      const State p = ex.pre(), st = analytic::stationary(c, c.history.v0);
      EXPECT_EQ(p.FN, st.FN);
      EXPECT_EQ(p.Fx, st.Fx);
      EXPECT_EQ(p.a2, st.a2);
      // After 60 tau the free tail is down by e^{-60} ~ 1e-26: stationary at v1
      // (for v1 = 0 the edge approaches a1 only asymptotically; the remaining
      // F_x ~ (a1^2 - a2^2)^2 is compared on the scale of the jump).
      const State late = ex.at(60.0 * c.rheology.tau), post = analytic::stationary(c, v1_of(c));
      EXPECT_NEAR(late.FN, post.FN, 1e-14 * post.FN) << zeta << " " << ratio;
      EXPECT_NEAR(late.Fx, post.Fx, 1e-14 * std::max(j.Fx, post.Fx)) << zeta << " " << ratio;
      EXPECT_NEAR(late.mu, post.mu, 1e-14 * std::max(j.mu, post.mu)) << zeta << " " << ratio;
      EXPECT_NEAR(late.a2, post.a2, 1e-15 * analytic::a1(c)) << zeta << " " << ratio;
    }
}

// Continuity at 0+: the root satisfies y^2 <= R h(a2v) (1 - c) <= a1^2 (1 - c)
// and y^2 <= 2 L^2 (1 - c) (from e^{-z}/phi2(z) <= 2), with 1 - c <= t/tau, so
// |a2(t) - a2v| / a1 <= sqrt(t/tau) min(1, sqrt(2) zeta).
TEST(ExactBasics, ContinuousAtZeroPlus) {
  for (double zeta : {1e-3, 0.5, 2.0, 1e4})
    for (double ratio : {0.0, 0.5}) {
      const Case c = scene_z(zeta, ratio);
      const ExactSolution ex(c, 52);
      const double a1 = analytic::a1(c), a2v = analytic::a2_stationary(c, c.history.v0);
      for (double tt : {1e-14, 1e-10, 1e-6, 1e-3}) {
        const State st = ex.at(tt * c.rheology.tau);
        const double bound = std::sqrt(tt) * std::min(1.0, std::sqrt(2.0) * zeta);
        EXPECT_LE(std::fabs(st.a2 - a2v) / a1, bound * (1 + 1e-9) + 4 * kEps) << zeta << " " << tt;
        EXPECT_GE(st.a2, a2v);
      }
    }
}

// ---------------------------------------------------------------------------
// Start-stop limit, zeta = 1e8, v1 = 0. Expanding the defining equation in
// 1/zeta at fixed c = e^{-t/tau} (units a1 = 1):
//   a2 = sqrt(1 - c) + c / (2 zeta) - 3 c sqrt(1 - c) / (8 zeta^2) + ...
// so |a2 - a2_start_stop| / a1 <= 1/(2 zeta) (asserted with bound 1/zeta), and
// the deviation times zeta tends to c/2 (asserted to 1/zeta + rounding at
// zeta = 1e4, 1e6 where the deviation is well above rounding).
// Forces: with w = 0, F_N and F_x change by <= 1.6 (delta a2 / a1) relative to
// F_N and to the start-stop maximum 2 G a1^4/R^2: tolerance 2/zeta + 1e-14.
TEST(ExactStartStop, MatchesA1SqrtOneMinusExp) {
  const double zeta = 1e8;
  const Case cs = scene_z(zeta, 0.0);
  const ExactSolution ex(cs);
  const double a1 = analytic::a1(cs);
  const double Fx_scale =
      2.0 * cs.rheology.G * std::pow(a1, 4) /
      (cs.indenter.as<mdrmap::Parabola>().R * cs.indenter.as<mdrmap::Parabola>().R);
  for (double tt : {0.01, 0.1, 0.5, 1.0, 2.0, 4.0, 6.0, 12.0}) {
    const double t = tt * cs.rheology.tau;
    const State st = ex.at(t);
    const double a2ss = analytic::a2_start_stop(cs, t);
    EXPECT_LE(std::fabs(st.a2 - a2ss) / a1, 1.0 / zeta + 4 * kEps) << tt;
    // a1 - a2ss = a1 c / (1 + sqrt(1 - c)), free of cancellation.
    const double c = std::exp(-tt);
    const State want = analytic::contact_forces(cs, a2ss, a1 * c / (1 + std::sqrt(1 - c)), 0.0);
    EXPECT_NEAR(st.FN, want.FN, (2.0 / zeta + 1e-14) * want.FN) << tt;
    EXPECT_NEAR(st.Fx, want.Fx, (2.0 / zeta + 1e-14) * Fx_scale) << tt;
  }
  for (double z : {1e4, 1e6}) {
    const Case cz = scene_z(z, 0.0);
    const ExactSolution exz(cz, 52);
    for (double tt : {0.1, 1.0, 3.0}) {
      const double t = tt * cz.rheology.tau;
      const double dev = (exz.at(t).a2 - analytic::a2_start_stop(cz, t)) / analytic::a1(cz);
      const double c = std::exp(-tt);
      EXPECT_NEAR(dev * z / (c / 2), 1.0, 1.0 / z + 8 * kEps / dev) << z << " " << tt;
    }
  }
}

// ---------------------------------------------------------------------------
// The transient against its definition, evaluated directly in long double.
// Sign checks use delta = 1e-13 a1: at t >= 0.01 tau the margin h - T has
// slope >= ~0.1 d/a1 at the edge, so |margin(x* +- delta)| >= 1e-14 d, five
// orders above its long double rounding (~eps_ld d); the code's edge is good
// to ~1e-15 a1.
TEST(ExactTransient, EdgeSatisfiesTheDefinition) {
  const double tts[] = {0.01, 0.05, 0.2, 0.5, 1.0, 2.0, 4.0, 8.0};
  int capped_seen = 0, root_seen = 0;
  for (double zeta : {0.1, 1.0, 10.0, 1e3})
    for (double ratio : {0.0, 1e-3, 0.1, 0.5}) {
      const Case c = scene_z(zeta, ratio);
      const ExactSolution ex(c);
      const Ref ref(c);
      const ld a1 = ref.a1, delta = 1e-13L * a1;
      for (double tt : tts) {
        const double t = tt * c.rheology.tau;
        const ld tl = t;
        const ld x = ex.at(t).a2;
        // (b) never beyond the stationary edge at v1
        EXPECT_LE(x, ref.a2v1 * (1 + 4 * kEpsLd) + 4 * kEps * a1) << zeta << " " << ratio;
        // (c) material in contact at the step, now at a2v + v1 t, is still in
        // contact as long as it has not passed a2(v1)
        EXPECT_GE(x, std::min(ref.a2v + ref.v1 * tl, ref.a2v1) - 4 * kEps * a1);
        // (a) free surface at or below the indenter just left of the edge ...
        EXPECT_GE(ref.margin(x - delta, tl), 0.0L) << zeta << " " << ratio << " " << tt;
        // ... and on the whole re-touched interval [a2v, x*)
        for (int k = 0; k <= 16; ++k) {
          const ld xk = ref.a2v + (x - delta - ref.a2v) * k / 16.0L;
          EXPECT_GE(ref.margin(xk, tl), 0.0L) << zeta << " " << ratio << " " << tt << " " << k;
        }
        const bool capped = std::fabs(x - ref.a2v1) <= 8 * kEps * a1;
        if (capped) {
          ++capped_seen;
          continue;
        }
        ++root_seen;
        // ... a gap just right of it, and on to a1 (beyond a1, h < 0 < T).
        EXPECT_LT(ref.margin(x + delta, tl), 0.0L) << zeta << " " << ratio << " " << tt;
        for (int k = 0; k <= 16; ++k) {
          const ld xk = x + delta + (a1 - x - delta) * k / 16.0L;
          EXPECT_LT(ref.margin(xk, tl), 0.0L) << zeta << " " << ratio << " " << tt << " " << k;
        }
      }
    }
  // Both branches (root and cap) must have been exercised.
  EXPECT_GT(capped_seen, 10);
  EXPECT_GT(root_seen, 30);
}

// Monotone transient after a drop: the contact grows (a2 up), so F_N (its
// integrand with v1 is >= 0 up to a2(v1)) rises and F_x (d F_x/d a2 =
// -8 G a2 p(a2) / R <= 0) and mu fall, ending at the stationary values at v1.
// Tolerances: a few roundings of each quantity.
TEST(ExactTransient, MonotoneAndReachesStationary) {
  for (double zeta : {0.1, 1.0, 10.0, 1e3})
    for (double ratio : {0.0, 1e-3, 0.1, 0.5}) {
      const Case c = scene_z(zeta, ratio);
      const ExactSolution ex(c);
      State prev = ex.at(0.0);
      const State j = prev;
      for (int k = 1; k <= 400; ++k) {
        const State st = ex.at(8.0 * c.rheology.tau * k / 400.0);
        EXPECT_GE(st.a2, prev.a2 - 4 * kEps * prev.a2) << zeta << " " << ratio << " " << k;
        EXPECT_GE(st.FN, prev.FN * (1 - 8 * kEps)) << zeta << " " << ratio << " " << k;
        EXPECT_LE(st.Fx, prev.Fx + 8 * kEps * j.Fx) << zeta << " " << ratio << " " << k;
        EXPECT_LE(st.mu, prev.mu + 8 * kEps * j.mu) << zeta << " " << ratio << " " << k;
        prev = st;
      }
      const State post = analytic::stationary(c, v1_of(c)), late = ex.at(60.0 * c.rheology.tau);
      EXPECT_NEAR(late.mu, post.mu, 1e-14 * j.mu) << zeta << " " << ratio;
      EXPECT_LT(post.mu, j.mu);
    }
}

// Forces at time t are the quadrature of the paper's integrand with velocity
// v1 over [-a1, a2(t)]. F_N: integrand >= 0 on the contact (kappa = 1), the
// code's closed form is a sum of non-negative terms: 1e-13 relative. F_x: its
// integrand changes sign at x = 0; error measured on the scale of the jump
// value (the largest F_x of the transient, docs/design.md, "Error metric")
// plus the quadrature's rounding bound 64 eps_ld int|f|.
TEST(ExactTransient, ForcesEqualQuadratureOverContactSet) {
  for (double zeta : {0.1, 1.0, 10.0, 1e3})
    for (double ratio : {0.0, 1e-3, 0.1, 0.5}) {
      const Case c = scene_z(zeta, ratio);
      const ExactSolution ex(c);
      const ld a1 = analytic::a1(c), d = c.loading.d, R = c.indenter.as<mdrmap::Parabola>().R,
               G = c.rheology.G;
      const ld L1 = static_cast<ld>(v1_of(c)) * static_cast<ld>(c.rheology.tau);
      auto p = [&](ld x) { return d - x * x / R - 2.0L * L1 * x / R; };
      auto px = [&](ld x) { return p(x) * (-2.0L * x / R); };
      const double Fx_scale = ex.at(0.0).Fx;
      for (double tt : {0.0, 0.01, 0.3, 1.0, 3.0, 8.0}) {
        const State st = ex.at(tt * c.rheology.tau);
        const Quad qn = integrate(p, -a1, static_cast<ld>(st.a2));
        const Quad qx = integrate(px, -a1, static_cast<ld>(st.a2));
        EXPECT_LT(rel(st.FN, 4 * G * qn.value), 1e-13) << zeta << " " << ratio << " " << tt;
        const ld errx = std::fabs(static_cast<ld>(st.Fx) - 4 * G * qx.value);
        EXPECT_LE(errx, 1e-13L * Fx_scale + 64 * kEpsLd * 4 * G * qx.abs)
            << zeta << " " << ratio << " " << tt;
        EXPECT_GE(p(static_cast<ld>(st.a2)), -1e-15L * d); // no tensile element
      }
    }
}

// ---------------------------------------------------------------------------
// Similarity (docs/design.md, "Similarity"): mu/sqrt(d/R), F_N/(G a1 d),
// F_x/(G d^2), a2/a1 are functions of (zeta, zeta1, t/tau) only. Random
// scalings of d/R (1e-12..0.3), R, G, tau, at fixed zeta, zeta1, must give the
// same curves to 1e-12 on the contract's scale (max over the series; a2 on
// a1): the only differences are roundings and root brackets, both ~1e-15.
TEST(ExactSimilarity, DimensionlessCurvesCollapse) {
  struct Base {
    double zeta, zeta1;
  };
  const Base bases[] = {{0.3, 0.0}, {1.0, 0.2}, {50.0, 0.01}, {1e-2, 5e-3}, {1e5, 0.0}};
  std::mt19937_64 rng(20240611);
  auto logu = [&](double lo, double hi) {
    return std::pow(10.0, std::uniform_real_distribution<double>(lo, hi)(rng));
  };
  for (const Base& b : bases) {
    auto dimless = [&](const Case& c) {
      const auto r = mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-12);
      const double a1 = analytic::a1(c),
                   sdr = std::sqrt(c.loading.d / c.indenter.as<mdrmap::Parabola>().R);
      std::vector<std::vector<double>> out(4);
      for (std::size_t k = 0; k < r.series.size(); ++k) {
        out[0].push_back(r.series.mu[k] / sdr);
        out[1].push_back(r.series.FN[k] / (c.rheology.G * a1 * c.loading.d));
        out[2].push_back(r.series.Fx[k] / (c.rheology.G * c.loading.d * c.loading.d));
        out[3].push_back(r.series.a2[k] / a1);
      }
      out[0].push_back(r.series.pre.mu / sdr);
      out[1].push_back(r.series.pre.FN / (c.rheology.G * a1 * c.loading.d));
      out[2].push_back(r.series.pre.Fx / (c.rheology.G * c.loading.d * c.loading.d));
      out[3].push_back(r.series.pre.a2 / a1);
      return out;
    };
    // 61 samples over 6 tau: the same instants in units of tau for every scaling
    auto scene = [&](double dr, double R, double tau, double G) {
      const double d = dr * R, a1 = std::sqrt(R * d);
      return make_case(d, R, tau, b.zeta * a1 / tau, b.zeta1 * a1 / tau, G, 6.0 * tau, 61);
    };
    const auto ref = dimless(scene(1e-3, 1.0, 1.0, 1.0));
    for (int trial = 0; trial < 6; ++trial) {
      const double dr = trial == 0 ? 1e-12 : (trial == 1 ? 0.3 : logu(-12.0, -0.5));
      const Case c = scene(dr, logu(-6, 3), logu(-6, 3), logu(-3, 9));
      const auto got = dimless(c);
      for (std::size_t q = 0; q < 4; ++q) {
        double scale = 0.0;
        for (double x : ref[q])
          scale = std::max(scale, std::fabs(x));
        if (q == 3) scale = 1.0; // a2 / a1 is already on the a1 scale
        for (std::size_t k = 0; k < ref[q].size(); ++k)
          EXPECT_NEAR(got[q][k], ref[q][k], 1e-12 * scale)
              << "zeta=" << b.zeta << " zeta1=" << b.zeta1 << " d/R=" << dr << " q=" << q
              << " k=" << k;
      }
    }
  }
}

// ---------------------------------------------------------------------------
// No transient: a rise (elements beyond a2(v1) detach at once), tau = 0
// (nothing remembers), v1 = v. The state is the stationary state at v1 for
// every t >= 0.
TEST(ExactConstant, RiseElasticAndNoChange) {
  std::vector<Case> scenes;
  for (double zeta : {1e-3, 1.0, 1e3}) {
    scenes.push_back(scene_z(zeta, 2.0));
    scenes.push_back(scene_z(zeta, 1.0));
    scenes.push_back(scene_z(zeta, 1e6));
  }
  for (double ratio : {0.0, 0.3, 1.0, 5.0}) {
    scenes.push_back(make_case(1e-4, 0.02, 0.0, 3.0, 3.0 * ratio, 1e6));
  }
  for (const Case& c : scenes) {
    const ExactSolution ex(c);
    const State post = analytic::stationary(c, v1_of(c));
    const double T = c.rheology.tau > 0 ? c.rheology.tau : analytic::a1(c) / c.history.v0;
    for (double tt : {0.0, 1e-9, 1e-3, 0.5, 1.0, 10.0, 100.0}) {
      const State st = ex.at(tt * T);
      EXPECT_EQ(st.FN, post.FN) << c.rheology.tau << " " << v1_of(c) / c.history.v0 << " " << tt;
      EXPECT_EQ(st.Fx, post.Fx);
      EXPECT_EQ(st.mu, post.mu);
      EXPECT_EQ(st.a2, post.a2);
    }
  }
}

// ---------------------------------------------------------------------------
// Precision: ExactSolution(bits = 52) against the long double bisection across
// hard regimes, at t >= 0.01 tau (closer to t = 0 the direct margin h - T is a
// difference of nearly equal terms; see ExactTransient). Tolerance 1e-12: F_N
// pointwise relative; F_x and mu on the contract's scale (their largest value,
// at t = 0+); a2 on a1. The long double reference itself is good to ~1e-16
// (bisection to eps_ld, eq. 7 rationalised).
TEST(ExactPrecision, AgreesWithLongDoubleBisection) {
  const double tts[] = {0.01, 0.1, 0.5, 1.0, 3.0, 10.0};
  double worst[4] = {0, 0, 0, 0};
  for (double zeta : {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e8})
    for (double ratio : {0.0, 0.01, 0.5, 0.99})
      for (double dr : {1e-12, 1e-4, 0.3}) {
        const Case c = scene_z(zeta, ratio, dr, 0.7, 3e-3, 2e6);
        const ExactSolution ex(c, 52);
        const Ref ref(c);
        const auto r0 = ref.forces(ref.a2v);
        for (double tt : tts) {
          const double t = tt * c.rheology.tau;
          const State st = ex.at(t);
          const auto r = ref.at(t);
          const double e[4] = {rel(st.FN, r.FN),
                               static_cast<double>(std::fabs(st.Fx - r.Fx) / r0.Fx),
                               static_cast<double>(std::fabs(st.mu - r.mu) / r0.mu),
                               static_cast<double>(std::fabs(st.a2 - r.a2) / ref.a1)};
          for (int q = 0; q < 4; ++q) {
            EXPECT_LE(e[q], 1e-12) << "q=" << q << " zeta=" << zeta << " v1/v=" << ratio
                                   << " d/R=" << dr << " t/tau=" << tt;
            worst[q] = std::max(worst[q], e[q]);
          }
        }
      }
  std::cout << "[ info ] worst difference to long double: FN " << worst[0] << ", Fx " << worst[1]
            << ", mu " << worst[2] << ", a2 " << worst[3] << "\n";
}

// ---------------------------------------------------------------------------
// run_exact: error estimate and tolerance control, against the long double
// reference sampled at the same instants (t = 0 and t >= 0.03 tau here, where
// the reference is good to ~1e-16 on the contract's scale, see ExactPrecision).
namespace {
struct Regime {
  double zeta, ratio;
};
const Regime kRegimes[] = {{1e-4, 0.0}, {1e-3, 0.9}, {1e-2, 0.0}, {1e-2, 0.5}, {0.1, 0.0},
                           {1.0, 0.0},  {1.0, 0.3},  {1e2, 0.0},  {1e8, 0.0},  {10.0, 0.99}};

// The long double reference at the case's sample instants (one segment).
mdrmap::Series reference_series(const Case& c) {
  const Ref ref(c);
  mdrmap::Series out;
  out.resize(c.total_samples());
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double t = c.sampling.offset(static_cast<long>(k), t_end_of(c));
    const auto r = ref.at(t);
    out.set(k, t, 0,
            State{static_cast<double>(r.FN), static_cast<double>(r.Fx), static_cast<double>(r.mu),
                  static_cast<double>(r.a2)});
  }
  return out;
}
} // namespace

// rtol = 1e-12: estimate < 1e-10 and true error (vs long double) < 1e-12;
// rtol = 1e-3: within 1e-3 of the tight run (and of the reference).
TEST(ExactRunExact, ErrorEstimateAndLooseTolerance) {
  for (const Regime& g : kRegimes) {
    const Case c = scene_z(g.zeta, g.ratio); // 201 samples over 6 tau
    const auto tight = mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-12);
    EXPECT_LT(tight.info.error_estimate, 1e-10) << g.zeta << " " << g.ratio;
    EXPECT_EQ(tight.info.solver, "exact");
    ASSERT_EQ(tight.series.size(), 201u);
    for (std::size_t k = 0; k < tight.series.size(); ++k) {
      EXPECT_EQ(tight.series.t[k], c.sampling.offset(static_cast<long>(k), t_end_of(c)));
      EXPECT_EQ(tight.series.segment[k], 0);
    }
    EXPECT_EQ(tight.series.t.back(), 6.0 * c.rheology.tau);
    const double a1 = analytic::a1(c);
    const auto ref = reference_series(c);
    EXPECT_LT(mdrmap::case_error(tight.series, ref, a1).max(), 1e-12) << g.zeta << " " << g.ratio;
    const auto loose = mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-3);
    EXPECT_LT(mdrmap::case_error(loose.series, tight.series, a1).max(), 1e-3)
        << g.zeta << " " << g.ratio;
    EXPECT_LT(mdrmap::case_error(loose.series, ref, a1).max(), 1e-3) << g.zeta << " " << g.ratio;
  }
}

// exact.hpp: "info.error_estimate bounds the case error". The true case error
// (vs the long double reference, itself good to ~1e-16, allowed 1e-14) must
// not exceed it. F_x and mu on the contract's scale (their values at t = 0+)
// respond to a2 with sensitivity up to 4 a1^2 / (a1^2 - a2(v)^2) ~ 2/zeta, so
// small zeta is the test.
TEST(ExactRunExact, ErrorEstimateBoundsActualError) {
  for (const Regime& g : kRegimes)
    for (double rtol : {1e-3, 1e-6, 1e-9}) {
      const Case c = scene_z(g.zeta, g.ratio); // 201 samples over 6 tau
      const auto run = mdrmap::run_exact(mdrmap::CheckedCase(c), rtol);
      const auto err = mdrmap::case_error(run.series, reference_series(c), analytic::a1(c));
      EXPECT_LE(err.max(), run.info.error_estimate + 1e-14)
          << "zeta=" << g.zeta << " v1/v=" << g.ratio << " rtol=" << rtol << ": FN " << err.FN
          << " Fx " << err.Fx << " mu " << err.mu << " a2 " << err.a2 << " estimate "
          << run.info.error_estimate;
    }
}

// Informative: cost per sample (no assertion on time).
TEST(ExactRunExact, TimePerSample) {
  for (const Regime& g : kRegimes) {
    const Case c = scene_z(g.zeta, g.ratio, 1e-3, 0.05, 2e-3, 1e6, 20001);
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-12);
    const auto t1 = std::chrono::steady_clock::now();
    const double us = std::chrono::duration<double, std::micro>(t1 - t0).count();
    std::cout << "[ info ] run_exact zeta=" << g.zeta << " v1/v=" << g.ratio << ": "
              << us / static_cast<double>(c.sampling.samples) << " us/sample, "
              << r.info.root_solves << " root solves\n";
    EXPECT_EQ(r.series.size(), static_cast<std::size_t>(c.sampling.samples));
  }
}
