#pragma once
// The fixed, documented set of hard scenes used by the tests and the
// benchmark: zeta = v tau / a1 from 1e-4 to 1e8, v1/v from 0 to 1e2, d/R from
// 1e-12 to 0.3, tau = 0, v1 = v, SI scales, and scenes where mu falls to
// below 1e-6 of its value before the step.
#include <string>
#include <vector>

#include "core/model/case.hpp"

namespace mdrmap {

struct NamedCase {
  std::string name;
  Case c;
};

/// The seed's one-step experiment over the hard ranges (42 cases).
std::vector<NamedCase> hard_case_set();

/// Velocity histories over the hard ranges (docs/design.md, "Case sets"):
/// two and three drops, drop-rise-drop, holds from 1e-6 to 1e6 tau and
/// reslides, holds inside transients, 20 alternating segments, velocity
/// ratios 1e-8 to 1e8, tau = 0, d/R from 1e-12 to 0.3. `samples` per segment.
std::vector<NamedCase> history_case_set(long samples = 61);

/// The case of `set` called `name` (std::invalid_argument where there is none).
const NamedCase& named_case(const std::vector<NamedCase>& set, const std::string& name);

} // namespace mdrmap
