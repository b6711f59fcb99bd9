#pragma once
// References for the element-row case sets (tests/test_spectrum_case_set.cpp,
// tests/test_profile_case_set.cpp): the spectrum solver at fixed resolutions,
// refined by doubling until the bound of its own error is below a goal, and
// the adaptive run at rtol measured against one.
#include <limits>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// CPU time of this process, in ms.
double cpu_ms();

/// The spectrum solver at `cells` per a (no estimate; edge to 1e-9 a, load
/// balance to 1e-11 F0).
RunResult fixed_resolution(const Case& c, double cells);

/// Difference of two runs by the error metric (the finer one as reference).
double run_difference(const Series& coarse, const Series& fine, const Case& c);

/// Differences below this are not the resolution's: the runs locate the
/// trailing edge to 1e-9 a and balance the load to 1e-11 F0, and round at
/// ~1e-12 (the Kelvin case converges to 1e-9 of the continuum solution at
/// a/dx = 2048, its differences then no longer falling).
constexpr double kReferenceNoise = 1e-8;

/// A reference refined by doubling the resolution from n0: after three runs
/// N/4, N/2, N the differences D1 (N/4 to N/2) and D2 (N/2 to N) give the
/// ratio r = D1 / D2 (4 at second order) and the bound of the finest run's
/// error D2 / (min(r, 4) - 1) (the sum of the differences still to come, each
/// r times smaller). Doubles until the bound is below `goal`, N passes n_max
/// (fixed depth 8192, under load 256) or a run passes the work budget; the
/// ratio must show convergence (r > 1.5), otherwise the bound is infinite; a
/// difference D2 below kReferenceNoise bounds the error by it.
struct Reference {
  Series series;
  double cells = 0.0, ratio = 0.0, bound = std::numeric_limits<double>::infinity(), ms = 0.0;
};
Reference refine(const Case& c, double goal);

/// One adaptive run of the spectrum solver at rtol against a reference.
struct CheckedRun {
  bool abandoned = false; ///< past the work budget (what: the reason)
  std::string what;
  double error = 0.0, estimate = 0.0, ms = 0.0, cells = 0.0;
};
CheckedRun adaptive_run(const Case& c, double rtol, const Series& reference);

/// The case errors of the fixed-step brute-force solver (spectrum_baseline)
/// at each resolution a1/dx of `cells`, against a reference.
std::vector<double> brute_force_errors(const Case& c, const Series& reference,
                                       const std::vector<double>& cells);

} // namespace mdrmap
