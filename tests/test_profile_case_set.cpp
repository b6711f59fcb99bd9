// The indenter-profile case set (tests/cases/profile_case_set.hpp; issue 21,
// "Done when" 2): transients of the cone and of the power laws n = 1.5 and 3
// at fixed depth and under load within rtol 1e-2, 1e-3 and 1e-4 of references
// refined here, the estimate at least a third of the true error; the
// brute-force solver converging to the references at first order.
//
// One test per case (ProfileCaseSet/ProfileCases.MeetsRtol/<name>), an
// executable of its own (ctest label profile-cases). Each prints its rows
// (case, rtol, error, estimate, CPU ms).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "case_checks.hpp"
#include "cases/profile_case_set.hpp"
#include "cases/refined_reference.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

const std::vector<NamedCase>& cases() {
  static const std::vector<NamedCase> set = profile_case_set(21);
  return set;
}

const NamedCase& by_name(const std::string& name) {
  return named_case(cases(), name);
}

constexpr double kRtols[] = {1e-2, 1e-3, 1e-4};

constexpr double kGoal = 1e-5; // the references' own error: rtol / 10 of the finest

class ProfileCases : public ::testing::TestWithParam<std::size_t> {};

// Within rtol of the reference at rtol 1e-2, 1e-3 and 1e-4, the estimate at least a
// third of the true error (and at most rtol).
TEST_P(ProfileCases, MeetsRtolWithAnHonestEstimate) {
  const NamedCase& nc = cases()[GetParam()];
  const Reference ref = refine(nc.c, kGoal);
  std::printf("| %s | reference | a/dx %g, ratio %.2f, own error <= %.2e | %.0f ms |\n",
              nc.name.c_str(), ref.cells, ref.ratio, ref.bound, ref.ms);
  EXPECT_LE(ref.bound, kGoal) << nc.name << ": the reference is not refined enough";
  for (const double rtol : kRtols)
    check_run(nc, rtol, ref.series);
}

std::string test_name(const ::testing::TestParamInfo<std::size_t>& info) {
  return case_test_name(cases(), info.param);
}

INSTANTIATE_TEST_SUITE_P(ProfileCaseSet, ProfileCases,
                         ::testing::Range<std::size_t>(0, cases().size()), test_name);

// The fixed-step brute-force method (every profile: h = d - g(x)) converges
// to the refined references at first order: an independent check of the
// references and of the tip handling. (The standard linear solid's reslides
// converge irregularly before a/dx 400: successive orders 0.6, 2.4, 1.0 for
// the cone and for n = 1.5 and 3; not used here.)
TEST(ProfileCaseSetBruteForce, ConvergesToTheReferenceAtFirstOrder) {
  for (const char* name :
       {"depth cone 10deg Kelvin step down 10x", "depth cone 10deg Kelvin drop-hold-reslide",
        "depth power n=1.5 Kelvin drop-hold-reslide", "depth power n=3 Kelvin drop-hold-reslide",
        "load cone 45deg Kelvin step down 10x"}) {
    const NamedCase& nc = by_name(name);
    const Reference ref = refine(nc.c, 1e-5);
    const std::vector<double> cells = {50, 100, 200, 400};
    const double t0 = cpu_ms();
    const std::vector<double> err = brute_force_errors(nc.c, ref.series, cells);
    const double order = testing::observed_order(cells, err);
    std::printf("%s: brute force errors %.2e %.2e %.2e %.2e at a/dx 50 .. 400: order %.2f (%.0f "
                "ms)\n",
                name, err[0], err[1], err[2], err[3], order, cpu_ms() - t0);
    EXPECT_GT(order, 0.8) << name;
    EXPECT_LT(order, 1.3) << name;
    EXPECT_LT(err[3], 3e-2) << name;
  }
}

} // namespace
} // namespace mdrmap
