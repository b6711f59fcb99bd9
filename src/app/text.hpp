#pragma once
// Small text helpers of the command-line readers: those of the input readers
// (material/text.hpp).
#include "material/text.hpp"

namespace mdrmap::app {

using material::trimmed;

} // namespace mdrmap::app
