#pragma once
// Small text helpers of the case readers: those of the input readers
// (material/text.hpp).
#include "material/text.hpp"

namespace mdrmap::cases {

using material::trimmed;

} // namespace mdrmap::cases
