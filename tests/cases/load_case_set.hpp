#pragma once
// The load-controlled histories the load solver is tested and benchmarked on
// (docs/design.md, "Load control"): steps up and down by 10x at
// zeta0 = v0 tau / a0 = 0.1, 1, 10; slide-hold-slide with holds from 0.1 to
// 1000 tau; a hold of 1e4 tau (the depth creeps); velocity ratios 1e-6 and 1e6;
// zeta0 from 1e-4 to 1e6; tau = 0; twenty segments; loads F0 from 1e-12 to
// 1e3 G R^2; six drop-hold-rise histories (a re-touch front from a tangency)
// and four reslides of 5e-4 .. 3e-5 a0 travel after a long hold (pieces of
// free material narrower than a cell at rtol's resolution).
#include <vector>

#include "cases/case_set.hpp"

namespace mdrmap {

/// At least 20 histories; `samples` per segment. Names starting with "3seg"
/// are the three-segment histories of the benchmark.
std::vector<NamedCase> load_case_set(long samples = 61);

} // namespace mdrmap
