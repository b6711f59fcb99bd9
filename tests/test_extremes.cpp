// Inputs at the edges of the number range, and the work budget (issue 23,
// classes 3 and 7). A case is either refused at validation, naming the option
// whose value puts a derived quantity (contact radius, w tau, w tau / a, slip,
// sample time, forces) out of range, or computed finite and right; every
// solver charges its loops to the case's RunControl, so no case runs past its
// budget or on after a stop request.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <string>
#include <vector>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/solvers/dispatch.hpp"

namespace mdrmap {
namespace {

Case depth_case(std::vector<Segment> segments, double d = 1e-3, double R = 1.0, double tau = 1.0,
                double v = 1.0, long samples = 201) {
  Case c;
  c.loading.d = d;
  c.indenter.as<Parabola>().R = R;
  c.rheology.tau = tau;
  c.history.v0 = v;
  c.history.segments = std::move(segments);
  c.sampling.samples = samples;
  return c;
}

Case load_case(std::vector<Segment> segments, long samples = 11, double F0 = 16.0 / 3.0,
               double R = 1.0) {
  Case c = depth_case(std::move(segments), 1e-3, R, 1.0, 1.0, samples);
  c.loading.d = 0.0;
  c.loading.F0 = F0; // a0 = 1 by default
  return c;
}

/// The option validate() names, "" if it accepts the case.
std::string refused_option(const Case& c) {
  try {
    validate(c);
  } catch (const InvalidInput& e) {
    return e.option();
  }
  return "";
}

bool all_finite(const Series& s) {
  for (std::size_t k = 0; k < s.size(); ++k)
    for (double x : {s.t[k], s.FN[k], s.Fx[k], s.mu[k], s.a2[k], s.d[k], s.a1[k]})
      if (!std::isfinite(x)) return false;
  return true;
}

TEST(Extremes, OutOfRangeScalesAreRefusedNamingTheirOption) {
  struct Row {
    const char* label;
    Case c;
    const char* option;
  };
  const std::vector<Row> rows = {
      // w tau = 1e308 at a1 = 1: a2 and F_N lost the w tau terms (mu = 2e305 was stored)
      {"a segment's w tau overflows the forces", depth_case({{1e308, 1.0}}, 1.0), "history"},
      // was blamed on --tau
      {"a segment's w tau / a overflows at a tiny contact",
       depth_case({{1e300, 1.0}}, 1e-60, 1e-60), "history"},
      {"v0 tau / a overflows", depth_case({{1.0, 1.0}}, 1e-3, 1.0, 1e300, 1e300), "tau"},
      {"contact radius 3e-152 (F_x was nan)", depth_case({{1.0, 1.0}}, 1e-3, 1e-300), "d"},
      {"contact radius 1e150 (F_N was nan)", depth_case({{1.0, 1.0}}, 1.0, 1e300), "d"},
      {"a segment's slip W T overflows", depth_case({{1e300, 1e300}}), "history"},
      // under load the contact shrinks as 1/sqrt(zeta0): a1 = 1.6e-154 (never returned)
      {"under load a segment's W shrinks the contact to 1e-154", load_case({{5e307, 1.0}}),
       "history"},
      // a0 = 0.72: 3 zeta0 overflowed, the bracket started at 0 and never grew (a hang)
      {"under load W = 5e307 at a0 = 0.72", load_case({{5e307, 1.0}}, 11, 0.2, 10.0), "history"},
      {"under load W = 7e307 at a0 = 0.72", load_case({{7e307, 1.0}}, 11, 0.2, 10.0), "history"},
      // a hang too; with the bracket mended, zeta0 + hypot overflowed and the
      // root a1 = 1.3 a0 of the elastic terms alone was taken (accepted)
      {"under load W = 1e308 at a0 = 0.72", load_case({{1e308, 1.0}}, 11, 0.2, 10.0), "history"},
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(r.label);
    EXPECT_EQ(refused_option(r.c), r.option);
  }
}

/// The SLS of issue 32 (G = G1 = 1, tau1 = 1, no dashpot) at depth 0.1 on R = 10.
Case sls_case(std::vector<Segment> segments, double v = 1.0) {
  Case c = depth_case(std::move(segments), 0.1, 10.0, 0.0, v, 3);
  c.rheology.branches = {{1.0, 1.0}};
  return c;
}

Case with_profile(Case c, Profile p, double beta_or_A, double n = 0.0) {
  c.indenter = Indenter{};
  c.indenter.profile = p;
  (p == Profile::of<Cone>() ? c.indenter.as<Cone>().beta : c.indenter.as<Power>().A) = beta_or_A;
  c.indenter.as<Power>().n = n;
  c.loading.d = 0.01;
  return c;
}

// The element row's number range (issue 32): beyond it w^2 overflowed into
// rows of NaN with exit 0, a later segment ended in a root finder's "do not
// bracket", a shift of 1e300 in "a free mode does not decay", and a cone of
// 1e-300 degrees was blamed on R.
TEST(Extremes, ElementRowLimitsAreRefusedNamingTheirOption) {
  Case shifted = sls_case({{0.1, 1.0}});
  shifted.rheology.branches = {{1.0, 1.0}, {1.0, 1e-5}};
  shifted.rheology.aT = 1e300;
  Case tiny_branch = sls_case({{0.1, 1.0}});
  tiny_branch.rheology.branches = {{1.0, 1.0}, {1e-13, 1e-5}};
  Case long_branch = sls_case({{0.1, 1.0}});
  long_branch.rheology.branches = {{1.0, 1e200}};
  Case long_dashpot = with_profile(depth_case({{0.1, 1.0}}), Profile::of<Cone>(), 10.0);
  long_dashpot.rheology.tau = 1e200;
  const struct {
    const char* label;
    Case c;
    const char* option;
  } rows[] = {
      {"v0 = 1e155 (rows of NaN, exit 0)", sls_case({{0.1, 1.0}}, 1e155), "v"},
      {"v0 = 1e-145", sls_case({{0.1, 1.0}}, 1e-145), "v"},
      {"a segment at 1e155 (do not bracket)", sls_case({{0.0, 1.0}, {1e155, 1e-170}}), "history"},
      {"aT = 1e300 (a free mode does not decay)", shifted, "aT"},
      {"G2 = 1e-13 G0 without a dashpot", tiny_branch, "prony"},
      {"tau1 = 1e200", long_branch, "prony"},
      {"a cone's dashpot of 1e200", long_dashpot, "tau"},
      {"cone of 1e-300 degrees (was blamed on R)",
       with_profile(sls_case({{0.1, 1.0}}), Profile::of<Cone>(), 1e-300), "beta"},
      {"power law of A = 1e200",
       with_profile(sls_case({{0.1, 1.0}}), Profile::of<Power>(), 1e200, 1.5), "A"},
      {"power law of n = 200",
       with_profile(sls_case({{0.1, 1.0}}), Profile::of<Power>(), 1.0, 200.0), "n"},
  };
  for (const auto& r : rows) {
    SCOPED_TRACE(r.label);
    EXPECT_EQ(refused_option(r.c), r.option);
  }
  // the Kelvin parabola asked of the spectrum solver: the same limits
  EXPECT_THROW(run_case(CheckedCase(depth_case({{1e155, 1e-170}})), SolverKind::Row, 1e-3),
               InvalidInput);
}

// At the edges of that range the row runs, finite: the SLS sliding at
// v0 tau1 / a1 = 1e149 is the elastic contact of the glassy modulus G0 = 2,
// F_N = 16/3 G0 a1^3 / R (a1 = sqrt(R d) = 1), at 1e-139 that of G = 1.
TEST(Extremes, ElementRowRunsAtTheEdgesOfItsRange) {
  const Case fast = sls_case({{1e149, 1e-150}}, 1e149);
  ASSERT_EQ(refused_option(fast), "");
  const RunResult r = run_case(CheckedCase(fast), SolverKind::Auto, 1e-3);
  ASSERT_TRUE(all_finite(r.series));
  const double glassy = 16.0 / 3.0 * 2.0 / 10.0;
  EXPECT_NEAR(r.series.FN.back(), glassy, 1e-3 * glassy);
  const Case slow = sls_case({{1e-139, 1.0}}, 1e-139); // fully relaxed: G = 1
  ASSERT_EQ(refused_option(slow), "");
  const RunResult s = run_case(CheckedCase(slow), SolverKind::Auto, 1e-3);
  ASSERT_TRUE(all_finite(s.series));
  EXPECT_NEAR(s.series.FN.back(), glassy / 2.0, 1e-3 * glassy);
}

// Under load at zeta0 -> infinity the viscous term carries the load:
// alpha^2 zeta0 -> 4/3 (corrections ~ zeta0^-3/2), up to the largest double.
TEST(Extremes, LoadedContactAtTheLargestSpeedsKeepsItsLimit) {
  for (double z : {1e12, 6.93e307, 9.7e307, 1.38e308, 1.7976931348623157e308}) {
    const double alpha = stationary_alpha(z);
    EXPECT_NEAR(alpha * alpha * z, 4.0 / 3.0, 1e-13) << z;
  }
}

// Accepted cases at the edges: finite, and equal to what the physics says.
TEST(Extremes, HoldsNearTheLargestDoubleAreFiniteAndRight) {
  // 201 samples of a hold of 1e306: j T overflowed (rows of inf and nan)
  const Case c = depth_case({{0.0, 1e306}, {1.0, 1.0}});
  ASSERT_EQ(refused_option(c), "");
  const RunResult r = run_case(CheckedCase(c), SolverKind::Auto, 1e-6);
  ASSERT_TRUE(all_finite(r.series));
  for (std::size_t k = 1; k < r.series.size(); ++k)
    EXPECT_LE(r.series.t[k - 1], r.series.t[k]) << k;
  EXPECT_EQ(r.series.t[200], 1e306);
  // after a hold of 1000 tau (exp(-1000) = 0) the state no longer depends on
  // the hold's length: every later hold sample, and the reslide, are the same
  const Case ref_case = depth_case({{0.0, 1e3}, {1.0, 1.0}});
  const RunResult ref = run_case(CheckedCase(ref_case), SolverKind::Auto, 1e-6);
  for (long j = 1; j < 201; ++j) {
    const auto k = static_cast<std::size_t>(j);
    EXPECT_NEAR(r.series.FN[k], ref.series.FN[200], 1e-14 * ref.series.FN[200]) << j;
    EXPECT_EQ(r.series.a2[k], ref.series.a2[200]) << j;
  }
  for (std::size_t k = 201; k < 402; ++k) {
    EXPECT_NEAR(r.series.FN[k], ref.series.FN[k], 1e-14 * ref.series.FN[k]) << k;
    EXPECT_NEAR(r.series.mu[k], ref.series.mu[k], 1e-14 * ref.series.mu[k]) << k;
  }
}

TEST(Extremes, TheLargestRepresentableSpeedsGiveTheirLimits) {
  // zeta = w tau / a1 = 3e299: the limits of eqs. (12)-(14) to rounding
  const Case c = depth_case({{1e308, 1.0}}, 1e-3, 1.0, 1e-10);
  ASSERT_EQ(refused_option(c), "");
  const RunResult r = run_case(CheckedCase(c), SolverKind::Auto, 1e-6);
  ASSERT_TRUE(all_finite(r.series));
  const double w = 1e308;
  EXPECT_NEAR(r.series.FN.back(), analytic::FN_inf(c, w), 1e-12 * analytic::FN_inf(c, w));
  EXPECT_NEAR(r.series.Fx.back(), analytic::Fx_inf(c, w), 1e-12 * analytic::Fx_inf(c, w));
  EXPECT_NEAR(r.series.mu.back(), analytic::mu_inf(c), 1e-12 * analytic::mu_inf(c));
}

// A three-segment history each solver can run, and a budget far below it.
const Case& budget_case(bool load) {
  static const Case depth =
      depth_case({{0.1, 0.1}, {0.0, 0.1}, {1.0, 0.1}}, 1e-3, 1.0, 1.0, 1.0, 51);
  static const Case under_load = load_case({{0.1, 0.1}, {0.0, 0.1}, {1.0, 0.1}}, 51);
  return load ? under_load : depth;
}

struct SolverRow {
  SolverKind kind;
  bool load;
  const char* name; ///< as the budget message names the solver
  double rtol;      ///< one the solver meets on budget_case within the default budget
};

const std::vector<SolverRow>& solver_rows() {
  static const std::vector<SolverRow> rows = {{SolverKind::Exact, false, "exact", 1e-3},
                                              {SolverKind::Row, false, "row", 1e-3},
                                              {SolverKind::Row, true, "row", 1e-3},
                                              {SolverKind::Baseline, false, "baseline", 1e-2},
                                              {SolverKind::Auto, true, "kelvin_load", 1e-3}};
  return rows;
}

TEST(Extremes, EverySolverStopsAtItsWorkBudget) {
  for (const SolverRow& s : solver_rows()) {
    SCOPED_TRACE(s.name);
    RunControl small;
    small.max_work = 100;
    try {
      run_case(CheckedCase(budget_case(s.load)), s.kind, s.rtol, small);
      ADD_FAILURE() << "no CaseAbandoned";
    } catch (const CaseAbandoned& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(s.name, 0), 0U) << what;
      EXPECT_NE(what.find("budget"), std::string::npos) << what;
    }
    RunControl enough; // and the default budget runs it
    EXPECT_NO_THROW(run_case(CheckedCase(budget_case(s.load)), s.kind, s.rtol, enough));
    EXPECT_GT(enough.spent(), 100.0);
  }
}

TEST(Extremes, EverySolverStopsOnAStopRequest) {
  volatile std::sig_atomic_t stop = 1;
  for (const SolverRow& s : solver_rows()) {
    SCOPED_TRACE(s.name);
    RunControl control;
    control.stop = &stop;
    EXPECT_THROW(run_case(CheckedCase(budget_case(s.load)), s.kind, 1e-3, control), Interrupted);
  }
}

// The row's estimate cannot go below its rounding floor: at rtol 1e-15 the
// case fails with the estimate instead of being reported done.
TEST(Extremes, RowFailsACaseItCannotResolveToRtol) {
  const Case& c = budget_case(false);
  try {
    run_case(CheckedCase(c), SolverKind::Row, 1e-15);
    ADD_FAILURE() << "no CaseAbandoned";
  } catch (const CaseAbandoned& e) {
    EXPECT_NE(std::string(e.what()).find("stays above rtol 1.0000000000000001e-15"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LE(run_case(CheckedCase(c), SolverKind::Row, 1e-6).info.error_estimate, 1e-6);
}

// The fixed-step baseline reports its estimate like every solver and, like
// them, fails a case whose estimate is above rtol (issue 32: under load it
// was reported done with an estimate of 0.0178 at rtol 1e-3; its a1/dx 50 at
// rtol 0.1 gives 0.11 here); where it meets rtol it answers.
TEST(Extremes, BaselineFailsACaseWhoseEstimateIsAboveRtol) {
  Case under_load = depth_case({{0.1, 3.0}, {3.0, 3.0}}, 0.0, 10.0, 1.0, 1.0, 5);
  under_load.loading.F0 = 0.05;
  try {
    const RunResult r = run_case(CheckedCase(under_load), SolverKind::Baseline, 0.1);
    ADD_FAILURE() << "done with the estimate " << r.info.error_estimate << " at rtol 0.1";
  } catch (const CaseAbandoned& e) {
    EXPECT_NE(std::string(e.what()).find("is above rtol 0.1"), std::string::npos) << e.what();
  }
  // at depth its resolution follows rtol: a1/dx 70 at rtol 1e-2 gave 0.056
  const Case at_depth = depth_case({{0.1, 3.0}, {3.0, 3.0}}, 0.1, 10.0, 1.0, 1.0, 5);
  EXPECT_LE(run_case(CheckedCase(at_depth), SolverKind::Baseline, 1e-2).info.error_estimate, 1e-2);
}

// The friction integral's rounding (issue 32): a needle cone (beta
// 89.999999999 degrees, friction scale 4.5e10) at v tau_k/a1 up to 1e15 has
// mu ~ 6e-5, 1e-15 of its scale; the transient printed mu = -2.2e-7 and a
// pre-state 21% off with an estimate of 2.4e-4. Such a case is refused; one
// whose mu stands clear of the rounding, or is negligible, is within rtol of
// its stationary state.
TEST(Extremes, AFrictionWithinRoundingIsRefused) {
  Case needle = with_profile(depth_case({{1e5, 1e-12}}, 0.01, 1.0, 0.0, 1e4, 5),
                             Profile::of<Cone>(), 89.999999999);
  needle.rheology.branches = {{1.0, 1.0}, {10.0, 0.01}};
  try {
    const RunResult r = run_case(CheckedCase(needle), SolverKind::Auto, 1e-3);
    ADD_FAILURE() << "done with pre mu " << r.series.pre.mu << " (stationary "
                  << stationary_state(needle, 1e4).mu << ")";
  } catch (const CaseAbandoned& e) {
    EXPECT_NE(std::string(e.what()).find("rounding"), std::string::npos) << e.what();
  }
  // beta 10: mu 6e-12 and 6e-14 of its scale 0.088 at v tau/a1 3e12, 3e14;
  // the second is within rtol of a negligible friction
  for (const double v : {1e12, 1e14}) {
    Case cone =
        with_profile(depth_case({{v, 1e-12}}, 0.01, 1.0, 0.0, v, 3), Profile::of<Cone>(), 10.0);
    cone.rheology.branches = needle.rheology.branches;
    const double mu_ss = stationary_state(cone, v).mu;
    EXPECT_NEAR(run_case(CheckedCase(cone), SolverKind::Auto, 1e-3).series.pre.mu, mu_ss,
                1e-3 * std::max(mu_ss, kNegligibleFriction))
        << v;
  }
}

} // namespace
} // namespace mdrmap
