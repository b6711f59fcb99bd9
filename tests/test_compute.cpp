// One case of a study into its map row (src/study/compute.*), without MPI:
// the row's states against the closed forms where they are exact (stationary
// sliding before the step, a rise, the limits of fast sliding), its residuals
// against their definition, a failing case as a failed row, the time series.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/analytic.hpp"
#include "core/case.hpp"
#include "core/solver.hpp"
#include "io/case_row.hpp"
#include "study/compute.hpp"
#include "study/config.hpp"

namespace {

using mdrmap::Case;
using mdrmap::SolverKind;
using mdrmap::State;
using mdrmap::io::CaseRow;
using mdrmap::study::compute_case;
using mdrmap::study::StepRow;
using mdrmap::study::StudyConfig;
namespace analytic = mdrmap::analytic;
namespace io = mdrmap::io;

const char* const kWhen[3] = {"pre", "jump", "post"};
const char* const kQuantity[4] = {"FN", "Fx", "mu", "a2"};

StudyConfig config(double rtol, long samples = 21) {
  StudyConfig c;
  c.run.rtol = rtol;
  c.run.samples = samples;
  return c;
}

StepRow step(double d, double R, double tau, double v, double v1) {
  StepRow r;
  r.d = d, r.R = R, r.tau = tau, r.v = v, r.v1 = v1;
  return r;
}

double value(const CaseRow& row, const std::string& field) {
  return row.values.at(io::field_index(field));
}

State state(const CaseRow& row, const std::string& group, const std::string& when) {
  State s;
  s.FN = value(row, group + "/FN_" + when);
  s.Fx = value(row, group + "/Fx_" + when);
  s.mu = value(row, group + "/mu_" + when);
  s.a2 = value(row, group + "/a2_" + when);
  return s;
}

double rel(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

/// Every quantity of `got` within `tol` of `want` (relative), `what` naming the check.
void expect_state_near(const State& got, const State& want, double tol, const std::string& what) {
  EXPECT_LE(rel(got.FN, want.FN), tol) << what << ": FN " << got.FN << " vs " << want.FN;
  EXPECT_LE(rel(got.Fx, want.Fx), tol) << what << ": Fx " << got.Fx << " vs " << want.Fx;
  EXPECT_LE(rel(got.mu, want.mu), tol) << what << ": mu " << got.mu << " vs " << want.mu;
  EXPECT_LE(rel(got.a2, want.a2), tol) << what << ": a2 " << got.a2 << " vs " << want.a2;
}

void expect_state_eq(const State& got, const State& want, const std::string& what) {
  EXPECT_EQ(got.FN, want.FN) << what;
  EXPECT_EQ(got.Fx, want.Fx) << what;
  EXPECT_EQ(got.mu, want.mu) << what;
  EXPECT_EQ(got.a2, want.a2) << what;
}

/// A case computed with the default solver, and the Case its row ran.
struct Computed {
  CaseRow row;
  Case c;
};

Computed compute(const StudyConfig& cfg, const StepRow& s, bool timeseries = false) {
  return {compute_case(cfg, s, SolverKind::Auto, timeseries), mdrmap::study::case_for(cfg, s)};
}

// Before the step the foundation slides stationarily at v: the row's pre
// state is the closed form (eq. 7 with corrected 9, 10) at that case, for
// slow and fast sliding, and its residuals vanish.
TEST(ComputeCase, PreStateIsStationarySlidingAtV) {
  const StudyConfig cfg = config(1e-6);
  for (const double zeta : {1e-3, 0.3, 3.0, 1e3}) { // v tau / a1
    const double d = 1e-3, R = 2.0, tau = 0.5, a1 = std::sqrt(R * d);
    const StepRow s = step(d, R, tau, zeta * a1 / tau, 0.5 * zeta * a1 / tau);
    const auto [row, c] = compute(cfg, s);
    ASSERT_EQ(row.status, 1) << row.message;
    EXPECT_TRUE(row.message.empty());
    const State want = analytic::stationary(c, s.v);
    const std::string at = "zeta = " + std::to_string(zeta);
    expect_state_eq(state(row, "analytic", "pre"), want, at);
    expect_state_near(state(row, "results", "pre"), want, 1e-12, at);
    for (const char* q : kQuantity)
      EXPECT_LE(std::abs(value(row, std::string("residuals/") + q + "_pre")), 1e-12) << at << q;
    EXPECT_GT(value(row, "results/wall_seconds"), 0.0);
    EXPECT_GE(value(row, "results/error_estimate"), 0.0);
    EXPECT_LE(value(row, "results/error_estimate"), cfg.run.rtol);
  }
}

// Erratum: a rise out of stationary sliding at fixed depth detaches the
// elements between a2(v1) and a2(v) at once, so the state at t = 0+ and at
// the end of the window is the stationary state at v1. The analytic columns
// say so exactly; the solver agrees to its tolerance, and the contact has
// shrunk from a2(v).
TEST(ComputeCase, RiseIsStationaryAtV1AtOnce) {
  const StudyConfig cfg = config(1e-8);
  const StepRow s = step(1e-3, 1.0, 1.0, 0.01, 0.02);
  const auto [row, c] = compute(cfg, s);
  ASSERT_EQ(row.status, 1) << row.message;
  const State at_v1 = analytic::stationary(c, s.v1);
  expect_state_eq(state(row, "analytic", "jump"), at_v1, "analytic jump");
  expect_state_eq(state(row, "analytic", "post"), at_v1, "analytic post");
  expect_state_near(state(row, "results", "jump"), at_v1, 1e-12, "results jump");
  expect_state_near(state(row, "results", "post"), at_v1, 1e-12, "results post");
  for (const char* w : {"jump", "post"})
    for (const char* q : kQuantity)
      EXPECT_LE(std::abs(value(row, std::string("residuals/") + q + "_" + w)), 1e-12) << q << w;
  EXPECT_LT(value(row, "results/a2_jump"), analytic::a2_stationary(c, s.v) * (1.0 - 1e-3));
}

// A drop keeps the contact set of v at t = 0+ (its elements now move at v1:
// corrected eqs. 15, 16); the contact then grows and mu falls, monotonically,
// until the state is stationary sliding at v1, which here it reaches within
// the window of 6 tau: the post state is the closed form again.
TEST(ComputeCase, DropKeepsTheContactSetThenSlidesStationarilyAtV1) {
  const StudyConfig cfg = config(1e-8);
  const StepRow s = step(1e-3, 1.0, 1.0, 0.03, 0.003);
  const auto [row, c] = compute(cfg, s, true);
  ASSERT_EQ(row.status, 1) << row.message;
  const State jump = analytic::jump(c, s.v, s.v1), at_v1 = analytic::stationary(c, s.v1);
  expect_state_eq(state(row, "analytic", "jump"), jump, "analytic jump");
  expect_state_eq(state(row, "analytic", "post"), at_v1, "analytic post");
  expect_state_near(state(row, "results", "jump"), jump, 1e-12, "results jump");
  EXPECT_LE(rel(value(row, "results/a2_jump"), analytic::a2_stationary(c, s.v)), 1e-12);
  EXPECT_LT(jump.a2, at_v1.a2);
  EXPECT_GT(jump.mu, at_v1.mu);
  ASSERT_EQ(row.a2.size(), 21u);
  for (std::size_t k = 1; k < row.a2.size(); ++k) {
    EXPECT_GE(row.a2[k], row.a2[k - 1] * (1.0 - 1e-15)) << k;
    EXPECT_LE(row.mu[k], row.mu[k - 1] * (1.0 + 1e-15)) << k;
  }
  expect_state_near(state(row, "results", "post"), at_v1, 1e-12, "results post");
  for (const char* q : kQuantity)
    EXPECT_LE(std::abs(value(row, std::string("residuals/") + q + "_post")), 1e-12) << q;
}

// Every residual is (sim - analytic) / |analytic| of the row's own columns;
// the limit residuals compare the state before the step with the limits of
// fast sliding (eqs. 12-14) and mu just after it with 3/4 sqrt(d/R). A coarse
// fixed-step solver makes them all non-trivial.
TEST(ComputeCase, ResidualsAreRelativeDifferences) {
  StudyConfig cfg = config(0.05, 11);
  const StepRow s = step(1e-3, 1.0, 1.0, 0.03, 0.003);
  const CaseRow row = compute_case(cfg, s, SolverKind::Baseline, false);
  ASSERT_EQ(row.status, 1) << row.message;
  int nonzero = 0;
  auto check = [&](const std::string& res, double sim, double an) {
    EXPECT_DOUBLE_EQ(value(row, "residuals/" + res), (sim - an) / std::abs(an)) << res;
    nonzero += value(row, "residuals/" + res) != 0.0;
  };
  for (const char* w : kWhen)
    for (const char* q : kQuantity) {
      const std::string f = std::string(q) + "_" + w;
      check(f, value(row, "results/" + f), value(row, "analytic/" + f));
    }
  check("FN_inf", value(row, "results/FN_pre"), value(row, "analytic/FN_inf"));
  check("Fx_inf", value(row, "results/Fx_pre"), value(row, "analytic/Fx_inf"));
  check("mu_inf", value(row, "results/mu_pre"), value(row, "analytic/mu_inf"));
  check("mu_post_drop", value(row, "results/mu_jump"), value(row, "analytic/mu_post_drop"));
  EXPECT_GE(nonzero, 12); // the baseline's discretisation error shows
  EXPECT_GT(std::abs(value(row, "residuals/mu_post")), 1e-6);
}

// Elastic foundation (tau = 0): no friction, F_x = mu = 0 in both the closed
// form and the solver; the residual of two vanishing values is 0, not NaN.
TEST(ComputeCase, ResidualOfTwoZerosIsZero) {
  const StudyConfig cfg = config(1e-6);
  const CaseRow row = compute_case(cfg, step(1e-3, 1.0, 0.0, 0.02, 0.01), SolverKind::Auto, false);
  ASSERT_EQ(row.status, 1) << row.message;
  for (const char* w : kWhen)
    for (const char* q : {"Fx", "mu"}) {
      const std::string f = std::string(q) + "_" + w;
      EXPECT_EQ(value(row, "analytic/" + f), 0.0) << f;
      EXPECT_EQ(value(row, "results/" + f), 0.0) << f;
      EXPECT_EQ(value(row, "residuals/" + f), 0.0) << f;
    }
  // F_N of the elastic contact, 16/3 G a1^3 / R, is exact too
  const double a1 = std::sqrt(1e-3);
  EXPECT_LE(rel(value(row, "results/FN_post"), 16.0 / 3.0 * a1 * a1 * a1), 1e-12);
}

// The limit columns: mu -> 4/3 sqrt(d/R) for fast sliding, and 3/4 sqrt(d/R)
// right after a stop from it; the residuals measure the distance from them,
// O(a1 / (v tau)).
TEST(ComputeCase, LimitResidualsShrinkWithSlidingSpeed) {
  const StudyConfig cfg = config(1e-6);
  const double d = 1e-3, R = 1.0, tau = 1.0, a1 = std::sqrt(R * d);
  double previous = 0.0;
  for (const double zeta : {1.0, 1e2, 1e4}) {
    const CaseRow row =
        compute_case(cfg, step(d, R, tau, zeta * a1 / tau, 0.0), SolverKind::Auto, false);
    ASSERT_EQ(row.status, 1) << row.message;
    EXPECT_DOUBLE_EQ(value(row, "analytic/mu_inf"), 4.0 / 3.0 * std::sqrt(d / R));
    EXPECT_DOUBLE_EQ(value(row, "analytic/mu_post_drop"), 0.75 * std::sqrt(d / R));
    const double far = std::max(std::abs(value(row, "residuals/mu_inf")),
                                std::abs(value(row, "residuals/mu_post_drop")));
    EXPECT_LE(far, 1.0 / zeta) << "zeta = " << zeta;
    if (zeta > 1.0) {
      EXPECT_LT(far, 0.05 * previous) << "zeta = " << zeta;
    }
    previous = far;
  }
}

// A case that cannot run is a failed row with the reason, never an exception:
// every value zeroed but the wall time, no time series.
TEST(ComputeCase, FailingCaseIsAFailedRow) {
  const StepRow good = step(1e-3, 1.0, 1.0, 0.03, 0.003);
  StepRow bad_row = good;
  bad_row.v = 0.0;
  struct Failing {
    std::string what, message;
    StudyConfig cfg;
    StepRow row;
    SolverKind kind;
  };
  const std::vector<Failing> failing = {
      {"the solver refuses rtol", "must be a number in (0, 0.1]", config(0.5), good,
       SolverKind::Exact},
      {"a case the fixed-step solver cannot afford", "too expensive for the fixed-step method",
       config(0.05, 11), step(1e-3, 1.0, 1.0, 3e6, 3e5), SolverKind::Baseline},
      {"an invalid row (v = 0)", "must be a finite number > 0, got 0", config(1e-6), bad_row,
       SolverKind::Auto},
      {"too few samples", "must be an integer from 2 to", config(1e-6, 1), good, SolverKind::Auto},
  };
  for (const auto& f : failing) {
    CaseRow row;
    EXPECT_NO_THROW(row = compute_case(f.cfg, f.row, f.kind, true)) << f.what;
    EXPECT_EQ(row.status, -1) << f.what;
    EXPECT_NE(row.message.find(f.message), std::string::npos) << f.what << ": " << row.message;
    ASSERT_EQ(row.values.size(), io::row_fields().size());
    for (std::size_t i = 0; i < row.values.size(); ++i) {
      if (io::row_fields()[i] != "results/wall_seconds") {
        EXPECT_EQ(row.values[i], 0.0) << f.what << ": " << io::row_fields()[i];
      }
    }
    EXPECT_GE(value(row, "results/wall_seconds"), 0.0);
    EXPECT_TRUE(row.t.empty() && row.FN.empty() && row.Fx.empty() && row.mu.empty() &&
                row.a2.empty())
        << f.what;
  }
}

// The time series when asked: `samples` instants from t = 0+ to the end of
// the window, whose ends are the row's jump and post states; the row's values
// do not depend on it.
TEST(ComputeCase, TimeseriesWhenAsked) {
  const StudyConfig cfg = config(1e-6, 21);
  const StepRow s = step(1e-3, 1.0, 1.0, 0.03, 0.003);
  const CaseRow with = compute_case(cfg, s, SolverKind::Auto, true);
  const CaseRow without = compute_case(cfg, s, SolverKind::Auto, false);
  ASSERT_EQ(with.status, 1) << with.message;
  ASSERT_EQ(without.status, 1) << without.message;
  EXPECT_TRUE(without.t.empty() && without.FN.empty() && without.a2.empty());
  for (const auto* v : {&with.t, &with.FN, &with.Fx, &with.mu, &with.a2})
    EXPECT_EQ(v->size(), 21u);
  EXPECT_EQ(with.t.front(), 0.0);
  EXPECT_DOUBLE_EQ(with.t.back(), cfg.run.t_end_over_tau * s.tau);
  for (std::size_t k = 1; k < with.t.size(); ++k)
    EXPECT_GT(with.t[k], with.t[k - 1]);
  EXPECT_EQ(with.FN.front(), value(with, "results/FN_jump"));
  EXPECT_EQ(with.mu.front(), value(with, "results/mu_jump"));
  EXPECT_EQ(with.FN.back(), value(with, "results/FN_post"));
  EXPECT_EQ(with.a2.back(), value(with, "results/a2_post"));
  for (std::size_t i = 0; i < with.values.size(); ++i) {
    if (io::row_fields()[i] != "results/wall_seconds") {
      EXPECT_EQ(with.values[i], without.values[i]) << io::row_fields()[i];
    }
  }
}

} // namespace
