// The shared error control (core/solvers/refine.hpp) on synthetic runs whose
// error is known: C / cells^p in F_N at every sample.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/numerics/run_control.hpp"
#include "core/solvers/refine.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

Case synthetic_case() {
  return testing::history_case(1.0, {{1.0, 1.0}}, 5);
}

/// A run whose F_N errs by C / cells^p (F_x, mu, a2 exact); `cells` below
/// `fail_below` is abandoned. Records the resolutions asked for.
struct Synthetic {
  Synthetic(double c, double order, double fail = 0.0) : C(c), p(order), fail_below(fail) {}
  double C, p, fail_below;
  std::vector<double> asked;
  ResolutionRun operator()(const Case& c, double cells) {
    asked.push_back(cells);
    if (cells < fail_below) throw CaseAbandoned("too coarse");
    ResolutionRun run;
    run.series.resize(static_cast<std::size_t>(c.total_samples()));
    for (std::size_t k = 0; k < run.series.size(); ++k) {
      State st;
      st.FN = 1.0 + C / std::pow(cells, p);
      st.Fx = 0.1;
      st.mu = 0.1;
      st.a2 = -0.5;
      run.series.set(k, static_cast<double>(k), 0, st);
    }
    run.steps = 1;
    return run;
  }
};

Refinement rule(double rtol, bool observed) {
  Refinement r;
  r.solver = "synthetic";
  r.cells = 32.0;
  r.max_cells = 1e4;
  r.rtol = rtol;
  r.observed_order = observed;
  return r;
}

RunResult run(Synthetic& s, const Refinement& r) {
  const Case c = synthetic_case();
  return refine(c, r, [&](double cells, double, double) { return s(c, cells); });
}

// Second order: the companion's difference C (1/16^2 - 1/32^2) is 3 times the
// fine run's error; set to 1.5 rtol. The third run (a/dx 8) shows r = 4, so
// the difference is halved: 0.75 rtol, accepted at a/dx 32, and still 1.5
// times the true error. Without the credit the case refines.
TEST(RefineObservedOrder, SecondOrderIsCreditedWhereItDecides) {
  const double C = 1.024, rtol = 2e-3; // F_N errs by 1e-3 at a/dx 32
  Synthetic s(C, 2.0);
  const RunResult r = run(s, rule(rtol, true));
  const double d0 = C * (1.0 / 256.0 - 1.0 / 1024.0) / (1.0 + C / 1024.0); // relative to the fine
  EXPECT_EQ(s.asked, (std::vector<double>{32.0, 16.0, 8.0}));
  EXPECT_EQ(r.info.cells_per_a1, 32.0);
  EXPECT_EQ(r.info.steps, 3);
  EXPECT_NEAR(r.info.error_estimate, 0.5 * d0, 1e-3 * d0);
  EXPECT_GE(r.info.error_estimate, C / 1024.0); // the true error (F_N is 1)

  Synthetic plain(C, 2.0);
  const RunResult q = run(plain, rule(rtol, false));
  EXPECT_GT(q.info.cells_per_a1, 32.0);
}

// First order: r = 2, no credit (the difference is the fine run's error);
// the case refines as without the option.
TEST(RefineObservedOrder, FirstOrderIsNotCredited) {
  const double C = 0.048, rtol = 1e-3; // d0 = C / 32 = 1.5 rtol, d1 = C / 16
  Synthetic s(C, 1.0);
  const RunResult r = run(s, rule(rtol, true));
  ASSERT_GE(s.asked.size(), 3u);
  EXPECT_EQ(s.asked[2], 8.0);
  EXPECT_GT(r.info.cells_per_a1, 32.0);
  EXPECT_LE(r.info.error_estimate, rtol);
}

// Outside (rtol, 2 rtol] no third run is made; a third run that is abandoned
// leaves the difference as it is.
TEST(RefineObservedOrder, NoThirdRunWhereItCannotDecideOrIsAbandoned) {
  const double C = 1.024;
  Synthetic far(C, 2.0);
  run(far, rule(1e-3, true)); // d0 = 3 rtol: refined without a third run
  EXPECT_GT(far.asked[2], 32.0);

  Synthetic failing(C, 2.0, 10.0);
  const RunResult r = run(failing, rule(2e-3, true)); // d0 = 1.5 rtol
  EXPECT_EQ(failing.asked[2], 8.0);
  EXPECT_GT(r.info.cells_per_a1, 32.0); // refined on the uncredited difference
}

} // namespace
} // namespace mdrmap
