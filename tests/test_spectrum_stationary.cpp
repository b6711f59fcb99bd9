// Stationary sliding of a material with a relaxation spectrum and its
// indentation creep (src/core/metrics/spectrum_stationary.*, creep.*), checked
// against computations independent of their closed forms: the branch ODE
// integrated by Duhamel's integral with composite Gauss-Legendre quadrature in
// long double, the contact forces by quadrature of that pressure, the trailing
// edge as the zero of it, the free surface behind the contact by RK4, the creep
// compliance by the convolution identity int G(t - s) J(s) ds = t.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include "core/metrics/analytic.hpp"
#include "core/metrics/creep.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/model/case.hpp"
#include "core/numerics/phi.hpp"

namespace {

using mdrmap::Branch;
using mdrmap::Case;
using mdrmap::Rheology;
using mdrmap::State;
using ld = long double;

Rheology rheology(double G, double tau, std::vector<Branch> b) {
  Rheology r;
  r.G = G;
  r.tau = tau;
  r.branches = std::move(b);
  return r;
}

Case depth_case(const Rheology& r, double d = 0.02, double R = 3.0) {
  Case c;
  c.indenter.as<mdrmap::Parabola>().R = R;
  c.rheology = r;
  c.loading.d = d;
  return c;
}

Case load_case(const Rheology& r, double F0 = 0.7, double R = 3.0) {
  Case c;
  c.indenter.as<mdrmap::Parabola>().R = R;
  c.rheology = r;
  c.loading.F0 = F0;
  return c;
}

double rel(double got, double want) {
  return std::fabs(got - want) / std::fabs(want);
}

// Integral of e^-y P(y) (P a polynomial of degree <= 2) over [0, top]: 20-point
// Gauss on panels that double in width, exact to long double rounding.
template <class F> ld duhamel(F f, ld top) {
  ld sum = 0, lo = 0;
  for (ld hi : {0.5L, 1.0L, 2.0L, 4.0L, 8.0L, 16.0L, 32.0L, 48.0L, 64.0L, 80.0L}) {
    hi = std::min(hi, top);
    if (hi > lo) sum += boost::math::quadrature::gauss<ld, 20>::integrate(f, lo, hi);
    lo = hi;
  }
  return sum;
}

// Integral over [a, b]: 20-point Gauss on the panels between the given
// interior points, the widest of them cut into equal panels of at most (b - a)/48.
template <class F> ld panels(F f, ld a, ld b, std::vector<ld> cuts) {
  cuts.push_back(a);
  cuts.push_back(b);
  std::sort(cuts.begin(), cuts.end());
  ld sum = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const ld lo = std::max(a, cuts[i]), hi = std::min(b, cuts[i + 1]);
    if (!(hi > lo)) continue;
    const int n = static_cast<int>(std::ceil(48 * (hi - lo) / (b - a)));
    for (int k = 0; k < n; ++k)
      sum += boost::math::quadrature::gauss<ld, 20>::integrate(f, lo + (hi - lo) * k / n,
                                                               lo + (hi - lo) * (k + 1) / n);
  }
  return sum;
}

// ---------------------------------------------------------------------------
// Reference pressure by quadrature. Along the contact the material point at
// s = x + a1 has met h(s') = s'(2 a1 - s')/R since it entered, and a branch of
// lambda = w tau_k holds (Duhamel) q(s) = int_0^(s/lambda) e^-y h(s - lambda y) dy.
// A branch with lambda < a1 is summed as its stress r = h - q =
// int e^-y [h(s) - h(s - lambda y)] dy + h(s) e^(-s/lambda); one with lambda >= a1
// as -q, its spring's G_k h joining G h. The polynomial parts are integrated
// exactly below, the branch parts by quadrature.
struct Reference {
  ld a1, R, G, L, Ge;
  std::vector<ld> Gk, lam;
  std::vector<bool> slow; // lambda < a1: summed as r

  Reference(const Case& c, double w) {
    const Rheology r = c.rheology.shifted();
    a1 = static_cast<ld>(c.a1());
    R = c.indenter.as<mdrmap::Parabola>().R;
    G = r.G;
    L = static_cast<ld>(w) * static_cast<ld>(r.tau);
    Ge = G;
    for (const Branch& b : r.branches) {
      Gk.push_back(b.G);
      lam.push_back(static_cast<ld>(w) * static_cast<ld>(b.tau));
      slow.push_back(lam.back() < a1);
      if (!slow.back()) Ge += b.G;
    }
  }
  // branch part of p R/8... of p/4: sum over branches at the point s
  ld branches(ld s) const {
    ld sum = 0;
    for (std::size_t k = 0; k < Gk.size(); ++k) {
      const ld l = lam[k];
      if (l == 0) continue;
      const ld z = s / l, top = std::min(z, 80.0L);
      if (slow[k]) {
        auto f = [&](ld y) {
          const ld D = l * y; // h(s) - h(s - D) = D (2 a1 - 2 s + D) / R
          return std::exp(-y) * D * (2 * a1 - 2 * s + D) / R;
        };
        sum += Gk[k] * (duhamel(f, top) + s * (2 * a1 - s) / R * std::exp(-z));
      } else {
        auto f = [&](ld y) {
          const ld sp = s - l * y;
          return std::exp(-y) * sp * (2 * a1 - sp) / R;
        };
        sum -= Gk[k] * duhamel(f, top);
      }
    }
    return sum;
  }
  // p/4 at x (s = a1 + x, dl = a1 - x given without cancellation)
  ld p4(ld x, ld s, ld dl) const { return Ge * dl * s / R - 2 * G * L * x / R + branches(s); }
  std::vector<ld> cuts(ld a2) const {
    std::vector<ld> c;
    for (std::size_t k = 0; k < lam.size(); ++k)
      for (ld m : {0.25L, 1.0L, 4.0L, 16.0L, 64.0L})
        if (slow[k] && m * lam[k] < a1 + a2) c.push_back(-a1 + m * lam[k]);
    return c;
  }
  // F_N and F_x of [-a1, a2]: polynomial parts exactly, branches by quadrature
  std::pair<ld, ld> forces(ld a2) const {
    const ld dS = (a1 - a2) * (a1 + a2), c3 = a1 * a1 * a1 + a2 * a2 * a2;
    ld FN = Ge * ((a1 + a2) * a1 * a1 - c3 / 3) / R + G * L * dS / R;
    ld Fx = Ge * dS * dS / (2 * R * R) + 4 * G * L * c3 / (3 * R * R);
    auto bn = [&](ld x) { return branches(a1 + x); };
    auto bx = [&](ld x) { return branches(a1 + x) * (-2 * x / R); };
    FN += panels(bn, -a1, a2, cuts(a2));
    Fx += panels(bx, -a1, a2, cuts(a2));
    return {4 * FN, 4 * Fx};
  }
};

std::vector<Rheology> spectra() {
  return {
      rheology(1.0, 0.0, {{9.0, 1.0}}),                               // SLS, G0/G = 10
      rheology(0.5, 0.0, {{3.0, 0.01}, {20.0, 1.0}, {400.0, 100.0}}), // Prony, 4 decades
      rheology(2.0, 0.3, {{5.0, 0.05}, {50.0, 3.0}}),                 // with a dashpot
      rheology(1.0, 0.0, {{1e4, 1e-3}, {1e-3, 10.0}}),                // extreme ratios
  };
}

// ---------------------------------------------------------------------------

TEST(SpectrumStationary, PhiFunctionsMatchTheirDefinition) {
  for (double z : {0.0, 1e-12, 1e-5, 0.1, 0.9, 1.999, 2.0, 2.001, 3.0, 4.0, 7.5, 30.0, 1e3}) {
    double phi[6];
    mdrmap::numerics::phi_all(z, phi);
    const ld Z = z;
    for (int n = 1; n <= 5; ++n) {
      ld want = 0;
      if (z <= 4.0) { // the series, long double
        ld term = 1;
        for (int j = 1; j <= n; ++j)
          term /= j;
        for (int j = 0; j < 200; ++j) {
          want += term;
          term *= -Z / (j + n + 1);
        }
      } else { // (-1)^n (e^-z - sum_(j<n) (-z)^j / j!) / z^n
        ld s = std::exp(-Z), t = 1;
        for (int j = 0; j < n; ++j) {
          s -= t;
          t *= -Z / (j + 1);
        }
        want = (n % 2 ? -s : s) / std::pow(Z, static_cast<ld>(n));
      }
      EXPECT_LT(rel(phi[n], static_cast<double>(want)), 8e-16) << "z = " << z << ", n = " << n;
    }
  }
}

// N = 0 is the Kelvin foundation: analytic::stationary over 16 decades of zeta.
TEST(SpectrumStationary, KelvinEqualsAnalytic) {
  for (double tau : {0.0, 1.0})
    for (int e = -80; e <= 80; e += 5) {
      const Case c = depth_case(rheology(1.7, tau, {}));
      const double w = e == -80 ? 0.0 : std::pow(10.0, e / 10.0) * c.a1();
      const State got = mdrmap::spectrum_stationary(c, w),
                  want = mdrmap::analytic::stationary(c, w);
      for (auto f : {&State::FN, &State::a2, &State::d, &State::a1})
        EXPECT_LT(rel(got.*f, want.*f), 1e-13) << "zeta = " << w * tau / c.a1();
      if (want.Fx == 0.0) {
        EXPECT_EQ(got.Fx, 0.0);
      } else {
        EXPECT_LT(rel(got.Fx, want.Fx), 1e-13) << "zeta = " << w * tau / c.a1();
        EXPECT_LT(rel(got.mu, want.mu), 1e-13) << "zeta = " << w * tau / c.a1();
      }
    }
}

// The closed forms (edge and forces) against quadrature of the ODE's solution,
// w tau_1 / a1 from 1e-8 to 1e8 for four spectra.
TEST(SpectrumStationary, ClosedFormMatchesQuadrature) {
  for (const Rheology& r : spectra())
    for (int e = -8; e <= 8; ++e) {
      const Case c = depth_case(r);
      const double w = std::pow(10.0, e) * c.a1() / r.branches[0].tau;
      const State st = mdrmap::spectrum_stationary(c, w);
      const Reference ref(c, w);
      const auto [FN, Fx] = ref.forces(st.a2);
      SCOPED_TRACE("w tau1 / a1 = 1e" + std::to_string(e) +
                   ", N = " + std::to_string(r.branches.size()));
      EXPECT_LT(rel(st.FN, static_cast<double>(FN)), 1e-12);
      EXPECT_LT(rel(st.Fx, static_cast<double>(Fx)), 1e-12);
      // the trailing edge: the zero of the reference pressure, in x and in a1 - x
      const ld a1 = ref.a1;
      auto px = [&](ld x) { return ref.p4(x, a1 + x, a1 - x); };
      auto pd = [&](ld dl) { return ref.p4(a1 - dl, 2 * a1 - dl, dl); };
      const ld a2 = st.a2, dl = static_cast<ld>(c.a1()) - a2;
      const ld up = a2 * (1 + 1e-9L), down = a2 * (1 - 1e-9L);
      EXPECT_GT(px(down), 0) << "p must be positive before a2";
      EXPECT_LT(px(up), 0) << "p must be negative after a2";
      std::uintmax_t it = 100;
      const auto tol = boost::math::tools::eps_tolerance<ld>(60);
      const auto rx = boost::math::tools::toms748_solve(px, down, up, tol, it);
      EXPECT_LT(std::fabs(0.5L * (rx.first + rx.second) / a2 - 1), 1e-13L);
      // near a1 the double a2 is what limits a1 - a2: it must be a2 rounded
      // (within 2 ulps), the reference zero found in delta = a1 - x
      if (dl > 0 && dl < 1e-3L * a1) {
        const ld lo = dl * (1 - 1e-5L), hi = dl * (1 + 1e-5L);
        ASSERT_TRUE(pd(lo) < 0 && pd(hi) > 0) << "a1 - a2 off by more than 1e-5";
        it = 100;
        const auto rd = boost::math::tools::toms748_solve(pd, lo, hi, tol, it);
        const ld want = a1 - 0.5L * (rd.first + rd.second);
        const double ulp = std::nextafter(st.a2, 1e300) - st.a2;
        EXPECT_LE(std::fabs(a2 - want), 2.0L * ulp) << "a1 - a2 = " << static_cast<double>(dl);
      }
    }
}

TEST(SpectrumStationary, ElasticLimits) {
  for (const Rheology& r : spectra()) {
    const Case c = depth_case(r);
    const double a1 = c.a1(), R = c.indenter.as<mdrmap::Parabola>().R, d = c.loading.d;
    const double hertz = 16.0 / 3.0 * std::sqrt(R) * std::pow(d, 1.5);
    // at rest the branches have relaxed: elastic with G
    const State rest = mdrmap::spectrum_stationary(c, 0.0);
    EXPECT_LT(rel(rest.FN, r.G * hertz), 1e-14);
    EXPECT_EQ(rest.Fx, 0.0);
    EXPECT_EQ(rest.a2, a1);
    // fast: glassy branches (G0); without a dashpot the symmetric Hertz contact
    // of G0, with one analytic::FN_inf with G0 in the spring (a2 -> 0)
    double shortest = 1e300;
    for (const Branch& b : r.branches)
      shortest = std::min(shortest, b.tau);
    const double w = 1e9 * a1 / shortest;
    const State fast = mdrmap::spectrum_stationary(c, w);
    if (r.tau == 0.0) {
      EXPECT_LT(rel(fast.FN, r.G0() * hertz), 1e-7);
      EXPECT_LT(fast.a2 / a1, 1.0);
      EXPECT_GT(fast.a2 / a1, 1.0 - 1e-7);
    } else {
      const double FNinf =
          4.0 * (r.G0() * (2.0 / 3.0) * std::sqrt(R) * std::pow(d, 1.5) + r.G * r.tau * w * d);
      EXPECT_LT(rel(fast.FN, FNinf), 1e-7);
      EXPECT_LT(fast.a2 / a1, 1e-7);
    }
  }
}

// Behind a2 the free element (p = 0) is integrated by RK4 from the contact's
// state there (branches from the reference quadrature): its depression stays
// strictly below the indenter (u > h) over two contact widths.
TEST(SpectrumStationary, NoSecondContactBehindTheTrailingEdge) {
  for (const Rheology& r : spectra())
    for (double zeta : {0.03, 0.3, 3.0}) {
      const Case c = depth_case(r);
      const double a1 = c.a1(), R = c.indenter.as<mdrmap::Parabola>().R;
      const double w = zeta * a1 / r.branches[0].tau;
      const State st = mdrmap::spectrum_stationary(c, w);
      const std::size_t N = r.branches.size();
      // state y = (u, q_1..q_N) at x = a2; q by Duhamel quadrature of h
      std::vector<double> y(N + 1);
      const double s2 = a1 + st.a2;
      y[0] = s2 * (2 * a1 - s2) / R;
      for (std::size_t k = 0; k < N; ++k) {
        const ld l = w * r.branches[k].tau;
        auto f = [&](ld t) { return std::exp(-t) * (s2 - l * t) * (2 * a1 - (s2 - l * t)) / R; };
        y[k + 1] = static_cast<double>(duhamel(f, std::min<ld>(s2 / l, 80)));
      }
      const double G0 = r.G0();
      // dy/dx: w tau_k q_k' = u - q_k; u algebraic (tau = 0) or G w tau u' = -(G0 u - sum G_k q_k)
      auto rhs = [&](const std::vector<double>& v) {
        std::vector<double> dv(N + 1, 0.0);
        double u = v[0], sum = 0.0;
        for (std::size_t k = 0; k < N; ++k)
          sum += r.branches[k].G * v[k + 1];
        if (r.tau == 0.0)
          u = sum / G0;
        else
          dv[0] = -(G0 * u - sum) / (r.G * r.tau * w);
        for (std::size_t k = 0; k < N; ++k)
          dv[k + 1] = (u - v[k + 1]) / (w * r.branches[k].tau);
        return dv;
      };
      double shortest = r.tau > 0.0 ? r.tau : 1e300;
      for (const Branch& b : r.branches)
        shortest = std::min(shortest, b.tau);
      const double span = 4.0 * a1, h = std::min(span / 4000.0, 0.05 * w * shortest);
      double x = st.a2, worst = 1e300;
      for (long i = 0; x < st.a2 + span; ++i) {
        auto add = [&](const std::vector<double>& a, const std::vector<double>& b, double f) {
          std::vector<double> o(a);
          for (std::size_t j = 0; j < o.size(); ++j)
            o[j] += f * b[j];
          return o;
        };
        const auto k1 = rhs(y), k2 = rhs(add(y, k1, h / 2)), k3 = rhs(add(y, k2, h / 2)),
                   k4 = rhs(add(y, k3, h));
        for (std::size_t j = 0; j <= N; ++j)
          y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
        x += h;
        double u = y[0];
        if (r.tau == 0.0) {
          u = 0.0;
          for (std::size_t k = 0; k < N; ++k)
            u += r.branches[k].G * y[k + 1] / G0;
        }
        const double gap = u - (a1 - x) * (a1 + x) / R; // > 0: no contact
        if (x > st.a2 + 0.01 * a1) worst = std::min(worst, gap / (a1 * a1 / R));
      }
      EXPECT_GT(worst, 0.0) << "zeta = " << zeta << ", N = " << N;
    }
}

// Under load: N = 0 is load_stationary; a spectrum meets F0 to rounding.
TEST(SpectrumStationary, UnderLoad) {
  for (double tau : {0.0, 0.5})
    for (int e = -8; e <= 8; ++e) {
      const Case c = load_case(rheology(1.3, tau, {}));
      const double w = std::pow(10.0, e) * c.a0() / std::max(tau, 1.0);
      const State got = mdrmap::spectrum_stationary_load(c, w);
      const State want = mdrmap::stationary_under_load(c, w);
      for (auto f : {&State::FN, &State::a2, &State::d, &State::a1})
        EXPECT_LT(rel(got.*f, want.*f), 1e-12) << "zeta0 = 1e" << e;
      if (tau > 0.0) {
        EXPECT_LT(rel(got.mu, want.mu), 1e-12) << "zeta0 = 1e" << e;
      }
    }
  for (const Rheology& r : spectra())
    for (int e = -8; e <= 8; e += 2) {
      const Case c = load_case(r);
      const double w = std::pow(10.0, e) * c.a0() / r.branches[0].tau;
      const State st = mdrmap::spectrum_stationary_load(c, w);
      EXPECT_LT(rel(st.FN, c.loading.F0), 4e-15) << "e = " << e;
      EXPECT_LT(rel(st.a1, std::sqrt(c.indenter.as<mdrmap::Parabola>().R * st.d)), 1e-15);
    }
}

// Time-temperature superposition: mu(v, aT) = mu(aT v, 1).
TEST(SpectrumStationary, ShiftFactorIsAVelocityScale) {
  for (Rheology r : spectra())
    for (double aT : {1e-6, 0.03, 7.0, 1e5})
      for (double v : {1e-4, 0.1, 30.0}) {
        Rheology s = r;
        s.aT = aT;
        const State a = mdrmap::spectrum_stationary(depth_case(s), v);
        const State b = mdrmap::spectrum_stationary(depth_case(r), aT * v);
        EXPECT_LT(rel(a.FN, b.FN), 1e-12);
        EXPECT_LT(rel(a.Fx, b.Fx), 1e-12);
        EXPECT_LT(rel(a.mu, b.mu), 1e-12);
        EXPECT_LT(rel(a.a2, b.a2), 1e-12);
        const State la = mdrmap::spectrum_stationary_load(load_case(s), v);
        const State lb = mdrmap::spectrum_stationary_load(load_case(r), aT * v);
        EXPECT_LT(rel(la.mu, lb.mu), 1e-12);
        EXPECT_LT(rel(la.d, lb.d), 1e-12);
      }
}

// ---------------------------------------------------------------------------
// Creep.

TEST(Creep, StandardLinearSolidIsTheTextbookFormula) {
  const double G = 2.0, G1 = 30.0, tau1 = 0.4;
  const Rheology r = rheology(G, 0.0, {{G1, tau1}});
  const double G0 = G + G1, rho = tau1 * G0 / G; // retardation time
  for (double t : {0.0, 1e-9, 0.01, 1.0, 7.0, 100.0, 1e4}) {
    const double want = 1.0 / G0 + (1.0 / G - 1.0 / G0) * -std::expm1(-t / rho);
    EXPECT_LT(rel(mdrmap::creep_compliance(r, t), want), 2e-15) << "t = " << t;
  }
}

TEST(Creep, KelvinDepthIsTheSeedFormula) {
  Case c = load_case(rheology(1.3, 0.7, {}));
  const double d0 = c.a0() * c.a0() / c.indenter.as<mdrmap::Parabola>().R;
  for (double t : {1e-8, 0.1, 0.7, 5.0, 50.0}) {
    const double want = d0 * std::cbrt(std::pow(-std::expm1(-t / 0.7), 2.0));
    EXPECT_LT(rel(mdrmap::creep_depth(c, t), want), 4e-15) << "t = " << t;
  }
  c.rheology.tau = 0.0; // elastic: Hertz at once
  EXPECT_LT(rel(mdrmap::creep_depth(c, 1.0), d0), 4e-15);
}

// int_0^t G(t - s) J(s) ds = t (G_bar J_bar = 1/s^2), the dashpot's delta
// giving G tau J(t); and the residues' sum J(0) + sum c = 1/G.
TEST(Creep, ConvolutionWithTheRelaxationModulusIsTime) {
  std::vector<Rheology> all = spectra();
  Rheology wide = rheology(1.0, 0.0, {}); // 17 equal terms 1e-8 .. 1e8, and a dashpot
  for (int e = -8; e <= 8; ++e)
    wide.branches.push_back({0.5, std::pow(10.0, e)});
  all.push_back(wide);
  wide.tau = 1e-9;
  all.push_back(wide);
  for (Rheology r : all) {
    r.aT = 0.3;
    const mdrmap::CreepSpectrum cs = mdrmap::creep_spectrum(r);
    const Rheology s = r.shifted();
    const std::size_t nr = s.branches.size() + (s.tau > 0.0 ? 1 : 0);
    ASSERT_EQ(cs.rho.size(), nr);
    double sum = cs.J0;
    for (std::size_t j = 0; j < nr; ++j) {
      EXPECT_GT(cs.c[j], 0.0);
      sum += cs.c[j];
      // interlacing: one retardation time above each relaxation time (the
      // branches are listed ascending), below the next; with a dashpot one more first
      const std::size_t k = s.tau > 0.0 ? j : j + 1; // branches below rho_j
      if (k > 0) {
        EXPECT_GT(cs.rho[j], s.branches[k - 1].tau);
      }
      if (k < s.branches.size()) {
        EXPECT_LT(cs.rho[j], s.branches[k].tau);
      }
    }
    EXPECT_LT(rel(sum, 1.0 / r.G), 1e-13);
    for (double t : {1e-9, 1e-5, 3e-3, 0.2, 4.0, 90.0, 3e3, 1e9}) {
      auto f = [&](ld u) { // G_reg(u) J(t - u)
        return static_cast<ld>(s.relaxation_modulus(static_cast<double>(u))) *
               mdrmap::creep_compliance(cs, t - static_cast<double>(u));
      };
      std::vector<ld> cuts{0, static_cast<ld>(t)};
      for (int k = 1; k < 80; ++k) {
        cuts.push_back(t * std::pow(10.0L, -k / 2.0L));
        cuts.push_back(t - t * std::pow(10.0L, -k / 2.0L));
      }
      ld conv = s.G * s.tau * mdrmap::creep_compliance(cs, t);
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) // graded panels, 30-point Gauss each
        conv += boost::math::quadrature::gauss<ld, 30>::integrate(f, cuts[i], cuts[i + 1]);
      EXPECT_LT(std::fabs(conv / t - 1), 1e-8L) << "t = " << t;
    }
  }
}

// ---------------------------------------------------------------------------
// The friction maximum of the standard linear solid under load (docs/physics.md
// numbers): mu / (a0/R) against v tau1 / a0, a0 from the long-term G. Its peak
// moves to lower v tau1 / a0 as G0/G grows and tends to the Kelvin bell's
// (tau_K = tau1 G1 / G) as G1 -> infinity.
struct Peak {
  double zeta, mu; // v tau / a0 at the maximum and mu / (a0/R) there
};

Peak friction_peak(const Rheology& r, double tau_ref) {
  const Case c = load_case(r);
  const double a0 = c.a0(), scale = a0 / c.indenter.as<mdrmap::Parabola>().R;
  auto neg_mu = [&](double lg) {
    const double w = std::pow(10.0, lg) * a0 / tau_ref;
    const double mu = r.kelvin() ? mdrmap::stationary_under_load(c, w).mu
                                 : mdrmap::spectrum_stationary_load(c, w).mu;
    return -mu / scale;
  };
  double best = -8.0, bv = 0.0; // coarse scan, then Brent around the best
  for (double lg = -8.0; lg <= 8.0; lg += 0.05)
    if (neg_mu(lg) < bv) bv = neg_mu(lg), best = lg;
  std::uintmax_t it = 200;
  const auto m = boost::math::tools::brent_find_minima(neg_mu, best - 0.05, best + 0.05, 40, it);
  return {std::pow(10.0, m.first), -m.second};
}

TEST(SpectrumStationary, FrictionPeakOfTheStandardLinearSolid) {
  const Peak kelvin = friction_peak(rheology(1.0, 1.0, {}), 1.0);
  std::printf("Kelvin: zeta0* = %.4f  mu* = %.4f a0/R\n", kelvin.zeta, kelvin.mu);
  EXPECT_NEAR(kelvin.zeta, 1.398, 1e-3);
  EXPECT_NEAR(kelvin.mu, 0.886, 1e-3);
  double last = 1e300;
  for (double ratio : {2.0, 10.0, 100.0, 1e3, 1e4, 1e6}) {
    const double G1 = ratio - 1.0, tau1 = 1.0;
    const Peak p = friction_peak(rheology(1.0, 0.0, {{G1, tau1}}), tau1);
    std::printf("G0/G = %g: v tau1/a0 = %.6g  (v tau_K/a0 = %.4f)  mu* = %.4f a0/R\n", ratio,
                p.zeta, p.zeta * G1, p.mu);
    EXPECT_LT(p.zeta, last);
    last = p.zeta;
    if (ratio == 1e6) {
      EXPECT_NEAR(p.zeta * G1 / kelvin.zeta, 1.0, 1e-2);
      EXPECT_NEAR(p.mu / kelvin.mu, 1.0, 1e-2);
    }
  }
}

} // namespace
