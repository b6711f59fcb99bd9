// Indenter profiles (src/core/model/profile.*, src/core/metrics/profile_stationary.*):
// the MDR image and the Hertz-type scales of each profile, the stationary
// states of the cone, the power law and the sphere against an independent computation
// (the branch ODEs integrated along the contact by adaptive Dormand-Prince,
// the trailing edge the zero of that pressure), the power law with n = 2
// against the parabola on the history and load case sets, the cone's limits,
// and the refusals (docs/design.md, "Indenter profiles").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>

#include "cases/case_set.hpp"
#include "cases/load_case_set.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/metrics/profile_stationary.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/load.hpp"

namespace {

using mdrmap::Branch;
using mdrmap::Case;
using mdrmap::Profile;
using mdrmap::State;

const double kPi = boost::math::constants::pi<double>();

Case cone_case(double beta, double d, double tau, double v, std::vector<Branch> b = {}) {
  Case c = mdrmap::step_case(d, 1.0, tau, v, v, 1.0, 1.0, 11);
  c.indenter.as<mdrmap::Parabola>().R = 0.0;
  c.indenter.profile = Profile::of<mdrmap::Cone>();
  c.indenter.as<mdrmap::Cone>().beta = beta;
  c.rheology.branches = std::move(b);
  return c;
}

Case power_case(double n, double A, double d, double tau, double v, std::vector<Branch> b = {}) {
  Case c = cone_case(10.0, d, tau, v, std::move(b));
  c.indenter.profile = Profile::of<mdrmap::Power>();
  c.indenter.as<mdrmap::Cone>().beta = 0.0;
  c.indenter.as<mdrmap::Power>().n = n;
  c.indenter.as<mdrmap::Power>().A = A;
  return c;
}

Case sphere_case(double R, double d, double tau, double v, std::vector<Branch> b = {}) {
  Case c = cone_case(10.0, d, tau, v, std::move(b));
  c.indenter = mdrmap::Sphere{R};
  return c;
}

Case under_load(Case c, double F0) {
  c.loading.d = 0.0;
  c.loading.F0 = F0;
  return c;
}

double rel(double a, double b) {
  return a == b ? 0.0 : std::fabs(a - b) / std::fmax(std::fabs(a), std::fabs(b));
}

TEST(ProfileModel, ImageOfEachProfile) {
  EXPECT_NEAR(mdrmap::mdr_kappa(2.0), 2.0, 4e-16);
  EXPECT_NEAR(mdrmap::mdr_kappa(1.0), kPi / 2.0, 4e-16);
  // kappa_3 = sqrt(pi) Gamma(5/2) / Gamma(2) = 3 pi / 4
  EXPECT_NEAR(mdrmap::mdr_kappa(3.0), 0.75 * kPi, 1e-15);
  const Case cone = cone_case(20.0, 0.1, 1.0, 1.0);
  const double c = kPi / 2.0 * std::tan(20.0 * kPi / 180.0);
  EXPECT_NEAR(cone.indenter.g(-0.3), c * 0.3, 1e-16);
  EXPECT_NEAR(cone.indenter.slope(0.3), c, 1e-16);
  EXPECT_NEAR(cone.indenter.slope(-0.3), -c, 1e-16);
  const Case p = power_case(1.5, 0.7, 0.1, 1.0, 1.0);
  const double a = p.a1();
  EXPECT_NEAR(p.indenter.g(a), 0.1, 1e-16);
  // the parabola's arithmetic is the seed's, bit for bit
  Case par = mdrmap::step_case(0.01, 3.0, 1.0, 1.0, 1.0);
  for (double x : {-0.7, 0.1, 1.3e-9, 4.0}) {
    EXPECT_EQ(par.indenter.g(x), x * x / 3.0);
    EXPECT_EQ(par.indenter.slope(x), 2.0 * x / 3.0);
  }
  EXPECT_EQ(par.a1(), std::sqrt(3.0) * std::sqrt(0.01));
}

// a0 of a load: F0 = 4 G int over [-a0, a0] of (g(a0) - g), by Gauss-Legendre
TEST(ProfileModel, HertzRadiusOfEachProfile) {
  std::vector<Case> cases = {cone_case(10.0, 0.1, 1.0, 1.0), cone_case(60.0, 0.1, 1.0, 1.0),
                             power_case(1.5, 0.7, 0.1, 1.0, 1.0),
                             power_case(3.0, 2.0, 0.1, 1.0, 1.0),
                             mdrmap::step_case(0.1, 2.0, 1.0, 1.0, 1.0)};
  for (Case c : cases) {
    c.rheology.G = 2.5;
    for (double F0 : {1e-6, 0.3, 40.0}) {
      c = under_load(c, F0);
      const double a0 = c.a0(), d0 = c.indenter.g(a0);
      // one half, in x = t^2 (|x|^n is then smooth for 2n integer)
      const double half = boost::math::quadrature::gauss<double, 30>::integrate(
          [&](double t) { return (d0 - c.indenter.g(t * t)) * 2.0 * t; }, 0.0, std::sqrt(a0));
      EXPECT_LT(rel(4.0 * c.rheology.G * 2.0 * half, F0), 1e-13)
          << mdrmap::profile_name(c.indenter.profile) << " F0 = " << F0;
    }
  }
}

// --- The independent stationary state: the branch ODEs along the contact ----

struct Reference {
  const Case& c;
  double w, a1, L;
  Reference(const Case& cc, double ww) : c(cc), w(ww), a1(0.0), L(ww * cc.rheology.tau) {}
  // -g'(x) on the side `behind` (x >= 0) or ahead of the tip (the indenter's g')
  double minus_slope(double x, bool behind) const {
    const double y = std::fabs(x);
    const double m = y > 0.0 ? c.indenter.slope(y) : c.indenter.slope(1e-300 * a1);
    return behind ? -m : m;
  }
  double h(double x) const { return c.indenter.g(a1) - c.indenter.g(std::fabs(x)); }
  // y = (q_1 .. q_N, int p/4, int p/4 (-g')); x in [-a1, end]
  std::vector<double> integrate_to(double end) const {
    namespace ode = boost::numeric::odeint;
    const std::size_t N = c.rheology.branches.size();
    std::vector<double> y(N + 2, 0.0);
    auto rhs = [&](bool behind) {
      return [this, N, behind](const std::vector<double>& s, std::vector<double>& ds, double x) {
        const double hx = h(x), mg = minus_slope(x, behind);
        double P = c.rheology.G * (hx + L * mg);
        for (std::size_t i = 0; i < N; ++i) {
          const double lam = w * c.rheology.branches[i].tau;
          ds[i] = (hx - s[i]) / lam;
          P += c.rheology.branches[i].G * (hx - s[i]);
        }
        ds[N] = P;
        ds[N + 1] = P * mg;
      };
    };
    auto stepper =
        ode::make_controlled(1e-15, 1e-14, ode::runge_kutta_dopri5<std::vector<double>>());
    ode::integrate_adaptive(stepper, rhs(false), y, -a1, std::fmin(end, 0.0), 1e-6 * a1);
    if (end > 0.0) ode::integrate_adaptive(stepper, rhs(true), y, 0.0, end, 1e-6 * a1);
    return y;
  }
  double pressure(double x) const { // p/4 at x >= 0, behind the tip
    const std::vector<double> y = integrate_to(x);
    const double hx = h(x);
    double P = c.rheology.G * (hx + L * minus_slope(x, true));
    for (std::size_t i = 0; i < c.rheology.branches.size(); ++i)
      P += c.rheology.branches[i].G * (hx - y[i]);
    return P;
  }
  State at_depth(double d) {
    a1 = c.indenter.contact_radius(d);
    double a2 = a1;
    if (pressure(0.0) <= 0.0)
      a2 = 0.0;
    else if (pressure(a1) < 0.0) {
      std::uintmax_t it = 100;
      const auto r =
          boost::math::tools::toms748_solve([&](double x) { return pressure(x); }, 0.0, a1,
                                            boost::math::tools::eps_tolerance<double>(50), it);
      a2 = 0.5 * (r.first + r.second);
    }
    const std::vector<double> y = integrate_to(a2);
    const std::size_t N = c.rheology.branches.size();
    State st;
    st.a1 = a1;
    st.a2 = a2;
    st.d = d;
    st.FN = 4.0 * y[N];
    st.Fx = 4.0 * y[N + 1];
    st.mu = st.Fx / st.FN;
    return st;
  }
};

void expect_close(const State& got, const State& ref, double tol, const std::string& what) {
  EXPECT_LT(rel(got.FN, ref.FN), tol) << what << " FN " << got.FN << " vs " << ref.FN;
  EXPECT_LT(rel(got.Fx, ref.Fx), tol) << what << " Fx " << got.Fx << " vs " << ref.Fx;
  EXPECT_LT(std::fabs(got.a2 - ref.a2), tol * ref.a1)
      << what << " a2 " << got.a2 << " vs " << ref.a2;
}

std::vector<std::vector<Branch>> rheologies() {
  return {{}, {{2.0, 0.3}}, {{1.5, 0.05}, {4.0, 2.0}, {0.5, 20.0}}};
}

std::vector<Case> profiles(double d, double tau, double v, const std::vector<Branch>& b) {
  return {cone_case(10.0, d, tau, v, b), cone_case(45.0, d, tau, v, b),
          power_case(1.5, 0.8, d, tau, v, b), power_case(3.0, 2.0, d, tau, v, b),
          sphere_case(2.0 * d, d, tau, v, b)}; // (a1/R = 0.64 at depth d)
}

std::string label(const Case& c, double w) {
  return std::string(mdrmap::profile_name(c.indenter.profile)) + " a1=" + std::to_string(c.a1()) +
         " branches=" + std::to_string(c.rheology.branches.size()) + " w=" + std::to_string(w);
}

TEST(ProfileStationary, AgainstTheBranchOdesAtFixedDepth) {
  double worst = 0.0;
  for (const auto& b : rheologies())
    for (double tau : {1.0, 0.0}) {
      if (tau == 0.0 && b.empty()) continue;
      for (double v : {0.02, 0.3, 3.0})
        for (const Case& c : profiles(0.05, tau, v, b)) {
          const State got = mdrmap::stationary_state(c, v);
          const State ref = Reference(c, v).at_depth(c.loading.d);
          expect_close(got, ref, 1e-10, label(c, v));
          worst = std::fmax(worst, std::fmax(rel(got.FN, ref.FN), rel(got.Fx, ref.Fx)));
        }
    }
  std::printf("profile stationary vs ODE, fixed depth: worst relative %.3g\n", worst);
}

TEST(ProfileStationary, UnderLoadMeetsTheLoadAndTheDepthState) {
  for (const auto& b : rheologies())
    for (double v : {0.02, 3.0})
      for (const Case& c : profiles(0.05, 1.0, v, b)) {
        const Case l = under_load(c, 0.02);
        const State st = mdrmap::stationary_state(l, v);
        EXPECT_LT(rel(st.FN, 0.02), 1e-12) << label(c, v);
        // the state at the depth it found is the fixed-depth state there
        Case at = c;
        at.loading.d = st.d;
        const State ref = Reference(at, v).at_depth(st.d);
        expect_close(st, ref, 1e-10, label(c, v) + " under load");
      }
}

// --- Power law with n = 2, A = 1/(2R) is the parabola ----------------------------

Case as_power(const Case& c) {
  Case p = c;
  p.indenter.profile = Profile::of<mdrmap::Power>();
  p.indenter.as<mdrmap::Power>().n = 2.0;
  p.indenter.as<mdrmap::Power>().A = 1.0 / (2.0 * c.indenter.as<mdrmap::Parabola>().R);
  p.indenter.as<mdrmap::Parabola>().R = 0.0;
  return p;
}

void expect_same(const State& a, const State& b, double tol, const std::string& what) {
  EXPECT_LT(rel(a.FN, b.FN), tol) << what;
  EXPECT_LT(rel(a.Fx, b.Fx), tol) << what;
  EXPECT_LT(rel(a.mu, b.mu), tol) << what;
  EXPECT_LT(rel(a.a2, b.a2), tol) << what;
  EXPECT_LT(rel(a.d, b.d), tol) << what;
}

TEST(ProfileStationary, PowerTwoIsTheParabolaOnTheCaseSets) {
  std::vector<mdrmap::NamedCase> set = mdrmap::history_case_set();
  for (auto& nc : mdrmap::load_case_set())
    set.push_back(nc);
  int compared = 0;
  for (const auto& nc : set)
    for (int spectrum = 0; spectrum < 2; ++spectrum) {
      Case c = nc.c;
      if (spectrum) {
        const double t = c.rheology.tau > 0.0 ? c.rheology.tau : 1.0;
        c.rheology.branches = {{2.0 * c.rheology.G, 0.1 * t}, {0.5 * c.rheology.G, 10.0 * t}};
      }
      mdrmap::validate(c);
      const Case p = as_power(c);
      mdrmap::validate(p);
      for (std::size_t k = 0; k <= c.history.size(); ++k) {
        const double w = c.history.before(k);
        expect_same(mdrmap::stationary_state(p, w), mdrmap::stationary_state(c, w), 1e-14,
                    nc.name + (spectrum ? " spectrum" : "") + " w=" + std::to_string(w));
        ++compared;
      }
    }
  EXPECT_GT(compared, 100);
}

// the general path (root of the edge, Kelvin brackets in n, branches by
// quadrature) taken at n = 2 gives the parabola's closed forms
TEST(ProfileStationary, GeneralPathAtNTwoIsTheParabola) {
  double worst = 0.0;
  for (const auto& b : rheologies())
    for (double v : {1e-3, 0.02, 0.3, 3.0, 300.0}) {
      Case c = mdrmap::step_case(0.05, 2.0, 1.0, v, v);
      c.rheology.branches = b;
      const State par = mdrmap::stationary_state(c, v);
      const State gen = mdrmap::profile_detail::general_stationary(as_power(c), v);
      EXPECT_LT(rel(gen.FN, par.FN), 1e-12) << v;
      EXPECT_LT(rel(gen.Fx, par.Fx), 1e-12) << v;
      EXPECT_LT(std::fabs(gen.a2 - par.a2), 1e-12 * par.a1) << v;
      worst = std::fmax(worst, std::fmax(rel(gen.FN, par.FN), rel(gen.Fx, par.Fx)));
    }
  std::printf("general path at n = 2 vs parabola: worst relative %.3g\n", worst);
}

// --- The cone on the Kelvin foundation -------------------------------------------

TEST(ProfileStationary, ConeOnKelvinClosedFormAndLimits) {
  const double beta = 15.0, d = 0.04;
  const double c = kPi / 2.0 * std::tan(beta * kPi / 180.0), a1 = d / c;
  for (double L : {1e-3 * a1, 0.3 * a1, 0.9 * a1}) {
    const State st = mdrmap::stationary_state(cone_case(beta, d, 1.0, L), L);
    // mu = c L (2 a1 - L/2) / (a1^2 + L^2/2), a2 = a1 - L (docs/design.md)
    EXPECT_LT(rel(st.mu, c * L * (2.0 * a1 - 0.5 * L) / (a1 * a1 + 0.5 * L * L)), 1e-13) << L;
    EXPECT_LT(rel(st.a2, a1 - L), 1e-13) << L;
  }
  // v tau >= a1: the rear face has let go, mu = (pi/2) tan(beta) exactly
  for (double L : {a1, 2.0 * a1, 1e6 * a1}) {
    const State st = mdrmap::stationary_state(cone_case(beta, d, 1.0, L), L);
    EXPECT_LT(rel(st.mu, c), 1e-14) << L;
    EXPECT_EQ(st.a2, 0.0) << L;
  }
  // v -> 0: mu ~ 2 c v tau / a1 -> 0
  const double L = 1e-9 * a1;
  const State slow = mdrmap::stationary_state(cone_case(beta, d, 1.0, L), L);
  EXPECT_LT(rel(slow.mu, 2.0 * c * L / a1), 1e-8);
  // under load: the closed-form leading edge carries F0 on both branches of it
  for (double L2 : {0.01, 0.5, 5.0}) {
    const Case l = under_load(cone_case(beta, d, 1.0, L2), 0.01);
    EXPECT_LT(rel(mdrmap::stationary_state(l, L2).FN, 0.01), 1e-14) << L2;
  }
}

TEST(ProfileStationary, ConeWithASpectrumTendsToTheGlassyCone) {
  // every branch glassy (lambda_k >> a1) and tau = 0: the elastic cone with G0,
  // mu -> 0; fast with a dashpot: mu -> (pi/2) tan beta
  const Case glassy = cone_case(20.0, 0.05, 0.0, 1e7, {{3.0, 1.0}});
  const State g = mdrmap::stationary_state(glassy, 1e7);
  const double c = kPi / 2.0 * std::tan(20.0 * kPi / 180.0), a1 = 0.05 / c;
  EXPECT_LT(rel(g.FN, 4.0 * 4.0 * c * a1 * a1), 1e-6); // 8 G0 c n/(n+1) a1^2
  EXPECT_LT(g.mu, 1e-6);
  const State f = mdrmap::stationary_state(cone_case(20.0, 0.05, 1.0, 1e3, {{3.0, 0.01}}), 1e3);
  EXPECT_LT(rel(f.mu, c), 1e-2);
}

// --- Refusals -------------------------------------------------------------------

std::string refused(const Case& c) {
  try {
    mdrmap::validate(c);
  } catch (const mdrmap::InvalidInput& e) {
    return e.option();
  }
  return "";
}

TEST(ProfileModel, BadInputIsRefusedNamingTheOption) {
  Case c = cone_case(10.0, 0.1, 1.0, 1.0);
  EXPECT_EQ(refused(c), "");
  c.indenter.as<mdrmap::Parabola>().R = 2.0;
  EXPECT_EQ(refused(c), "R");
  for (double beta : {0.0, 90.0, -5.0, 120.0}) {
    c = cone_case(beta, 0.1, 1.0, 1.0);
    EXPECT_EQ(refused(c), "beta") << beta;
  }
  Case p = power_case(0.999, 1.0, 0.1, 1.0, 1.0);
  EXPECT_EQ(refused(p), "n");
  p = power_case(1.0, 0.0, 0.1, 1.0, 1.0);
  EXPECT_EQ(refused(p), "A");
  p = power_case(2.0, 1.0, 0.1, 1.0, 1.0);
  p.indenter.as<mdrmap::Cone>().beta = 10.0;
  EXPECT_EQ(refused(p), "beta");
  Case par = mdrmap::step_case(0.1, 2.0, 1.0, 1.0, 1.0);
  par.indenter.as<mdrmap::Power>().n = 2.0;
  EXPECT_EQ(refused(par), "n");
}

TEST(ProfileModel, OnlyTheRowsTakeOtherProfiles) {
  const Case c = cone_case(10.0, 0.1, 1.0, 1.0);
  for (const mdrmap::SolverKind k : mdrmap::kSolverKinds) {
    const bool takes = k != mdrmap::SolverKind::Exact; // auto, row, baseline
    EXPECT_EQ(mdrmap::solver_handles(k, mdrmap::model_needs(c)), takes) << mdrmap::solver_name(k);
    if (takes) continue;
    try {
      mdrmap::run_case(mdrmap::CheckedCase(c), k, 1e-3);
      ADD_FAILURE() << "not refused: " << mdrmap::solver_name(k);
    } catch (const mdrmap::InvalidInput& e) {
      EXPECT_EQ(e.option(), "profile");
      EXPECT_NE(std::string(e.what()).find("auto, row or baseline"), std::string::npos);
    }
  }
  // the guards at the solvers' own entries
  EXPECT_THROW(mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-3), mdrmap::InvalidInput);
  EXPECT_TRUE(mdrmap::solver_handles(mdrmap::SolverKind::Exact,
                                     mdrmap::model_needs(mdrmap::step_case(0.1, 1, 1, 1, 1))));
}

// The reduction of the transients: the power law n = 2, A = 1/(2R) through
// the spectrum solver's profile path (tip cut, forces split at the tip) is
// the parabola. On the Kelvin history set at fixed depth against the
// continuum solution of the parabola (exact), and on three load-set cases
// against the Kelvin load solver: within rtol 1e-3, the estimate at least a
// third of the error.
TEST(ProfileTransient, PowerTwoIsTheParabola) {
  std::vector<mdrmap::NamedCase> set = mdrmap::history_case_set(21);
  const std::vector<mdrmap::NamedCase> load = mdrmap::load_case_set(21);
  set.insert(set.end(), load.begin(), load.begin() + 3);
  for (const auto& nc : set) {
    const Case p = as_power(nc.c);
    mdrmap::RunResult ref;
    if (nc.c.loading.by_force()) {
      mdrmap::LoadOptions lo;
      lo.rtol = 1e-7;
      ref = mdrmap::run_load(mdrmap::CheckedCase(nc.c), lo);
    } else {
      ref = mdrmap::run_exact(mdrmap::CheckedCase(nc.c), 1e-12);
    }
    const mdrmap::RunResult r =
        mdrmap::run_case(mdrmap::CheckedCase(p), mdrmap::SolverKind::Auto, 1e-3);
    ASSERT_EQ(r.info.solver, "row");
    const double err = mdrmap::case_error(r.series, ref.series, nc.c).max();
    EXPECT_LE(err, 1e-3) << nc.name;
    EXPECT_GE(r.info.error_estimate, err / 3.0) << nc.name;
  }
}

// The sliver behind the tip. After a drop from 1e8 v0 the rear face of the
// power law n = 2 lets go 3.2e-4 a1 behind the tip, inside the tip's cell
// until a1/dx ~ 200. The sliver's forces were a trapezoid of p g' taken at
// e/2 and e (50% over on F_x for a constant p): mu erred 1.4e-5 at every rtol
// from 1e-3 to 1e-4 (estimate 4.1e-7 at 1e-4). A exactly and B linear there:
// 1.5e-8 at rtol 1e-4.
TEST(ProfileTransient, TheSliverBehindTheTipIsIntegratedExactly) {
  const std::vector<mdrmap::NamedCase> set = mdrmap::history_case_set(21);
  const Case& c = mdrmap::named_case(set, "ratio 1e8 then 1e-8").c;
  const mdrmap::RunResult ref = mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-12);
  const mdrmap::RunResult r =
      mdrmap::run_case(mdrmap::CheckedCase(as_power(c)), mdrmap::SolverKind::Auto, 1e-4);
  const double err = mdrmap::case_error(r.series, ref.series, c).max();
  EXPECT_LE(err, 1e-5);
  EXPECT_GE(r.info.error_estimate, err / 3.0);
}

// The error metric with a floor (the estimate's: two runs compared) measures
// a cone's and a power law's F_x and mu on their Scales::friction. With the
// parabola's sqrt(d/R) at R = 0 the floor was infinite and every F_x and mu
// difference read 0: the estimates of these profiles saw F_N and a2 only.
TEST(ProfileModel, TheEstimatesMetricSeesFrictionOfEveryProfile) {
  for (const Case& c : {cone_case(10.0, 0.01, 1.0, 0.01), power_case(3.0, 1.0, 0.01, 1.0, 0.01),
                        under_load(cone_case(10.0, 0.01, 1.0, 0.01), 1e-3)}) {
    const mdrmap::RunResult r =
        mdrmap::run_case(mdrmap::CheckedCase(c), mdrmap::SolverKind::Auto, 1e-3);
    mdrmap::Series other = r.series;
    for (std::size_t k = 0; k < other.size(); ++k) {
      other.Fx[k] *= 1.0 + 1e-3;
      other.mu[k] *= 1.0 + 1e-3;
    }
    const mdrmap::CaseError e = mdrmap::case_error(other, r.series, c, 1e-12);
    EXPECT_NEAR(e.Fx, 1e-3, 1e-9) << mdrmap::profile_name(c.indenter.profile);
    EXPECT_NEAR(e.mu, 1e-3, 1e-9) << mdrmap::profile_name(c.indenter.profile);
  }
}

// A transient in closed form: on the Kelvin foundation at fixed depth a rise
// from v tau < a1 to v tau > a1 lets the cone's rear face go at once (the
// pressure behind the tip, 4 G (h - L c), is negative everywhere), and no
// released material touches again (its gap grows as s c (L - a1) after s tau;
// docs/design.md, "Indenter profiles"). So from t = 0+ the state is the
// stationary one of the new velocity: mu = (pi/2) tan beta, a2 = 0,
// F_N = 4 G c (a1^2/2 + L a1). The spectrum solver at rtol 1e-3 and 1e-4,
// every sample of the rise and of the segment after it, to 1e-13.
TEST(ProfileTransient, ConeRiseAcrossTheTipIsStationaryAtOnce) {
  for (const double beta : {10.0, 45.0})
    for (const double rtol : {1e-3, 1e-4}) {
      Case c = cone_case(beta, 0.01, 1.0, 1.0);
      const double cc = 0.5 * kPi * std::tan(beta * kPi / 180.0), a1 = 0.01 / cc;
      c.history.v0 = 0.3 * a1; // v tau = 0.3 a1: the rear face in contact
      c.history.segments = {mdrmap::Segment{3.0 * a1, 2.0}, mdrmap::Segment{30.0 * a1, 1.0}};
      const mdrmap::RunResult r =
          mdrmap::run_case(mdrmap::CheckedCase(c), mdrmap::SolverKind::Auto, rtol);
      ASSERT_EQ(r.info.solver, "row");
      EXPECT_GT(r.series.pre.a2, 0.5 * a1); // in contact behind the tip before the rise
      for (std::size_t k = 0; k < r.series.size(); ++k) {
        const double L = c.history.segments[static_cast<std::size_t>(r.series.segment[k])].w;
        EXPECT_NEAR(r.series.mu[k], cc, 1e-13 * cc) << "beta " << beta << " sample " << k;
        EXPECT_NEAR(r.series.FN[k], 4.0 * cc * (0.5 * a1 * a1 + L * a1), 1e-13 * r.series.FN[k]);
        EXPECT_LE(std::fabs(r.series.a2[k]), 1e-13 * a1);
      }
    }
}

} // namespace
