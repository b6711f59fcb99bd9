#pragma once
// The checks the element-row case sets share (tests/test_spectrum_case_set.cpp,
// tests/test_profile_case_set.cpp): runs known to fail (not run; reported with
// figures in the lists), and the adaptive run at rtol against a reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "cases/refined_reference.hpp"

namespace mdrmap {

/// A run of today's solver that fails its check or cannot be afforded here.
struct KnownFailure {
  const char* name;
  double rtol;
};

template <std::size_t N>
bool known_failure(const KnownFailure (&list)[N], const std::string& name, double rtol) {
  return std::any_of(std::begin(list), std::end(list),
                     [&](const KnownFailure& k) { return name == k.name && rtol == k.rtol; });
}

/// The adaptive run at rtol: within rtol of the reference, its estimate at
/// least a third of the true error and at most rtol. Prints its row (case,
/// rtol, error, estimate, CPU ms, a/dx).
inline void check_run(const NamedCase& nc, double rtol, const Series& reference) {
  const CheckedRun r = adaptive_run(nc.c, rtol, reference);
  if (r.abandoned) {
    ADD_FAILURE() << nc.name << " at rtol " << rtol << ": " << r.what << " after " << r.ms << " ms";
    return;
  }
  std::printf("| %s | %g | %.2e | %.2e | %.0f | a/dx %g |\n", nc.name.c_str(), rtol, r.error,
              r.estimate, r.ms, r.cells);
  EXPECT_LE(r.error, rtol) << nc.name << " at rtol " << rtol;
  EXPECT_GE(r.estimate, r.error / 3.0) << nc.name << " at rtol " << rtol;
  EXPECT_LE(r.estimate, rtol) << nc.name << " at rtol " << rtol;
}

/// A test's name for case i of a set: its index and name, alphanumeric.
inline std::string case_test_name(const std::vector<NamedCase>& set, std::size_t i) {
  std::string s;
  for (char ch : set[i].name)
    s += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return std::to_string(i) + "_" + s;
}

} // namespace mdrmap
