#pragma once
// The fixed, documented set of hard scenes used by the tests and the
// benchmark: zeta = v tau / a1 from 1e-4 to 1e8, v1/v from 0 to 1e2, d/R from
// 1e-12 to 0.3, tau = 0, v1 = v, SI scales, and scenes where mu falls to
// below 1e-6 of its value before the step.
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace mdrmap {

struct NamedScene {
  std::string name;
  Scene scene;
};

std::vector<NamedScene> hard_case_set();

} // namespace mdrmap
