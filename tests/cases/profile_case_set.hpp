#pragma once
// The indenter-profile histories the spectrum solver is tested on (issue 21,
// "Done when" 2; docs/design.md, "Indenter profiles"): the cone (10 and 45
// degrees), the power laws n = 1.5 and 3 and the exact sphere (a/R = 0.5) on
// the Kelvin foundation, a standard linear solid and a dashpot with two
// terms; tenfold steps down and up, drop-hold-reslide, slide-hold-slide, and
// for the cone the steps across v tau = a (where its rear face lets go at
// the tip); at fixed depth and under load.
#include <vector>

#include "cases/case_set.hpp"

namespace mdrmap {

/// Lengths: the contact a = 1e-2 (a1 at fixed depth, a0 under load: the depth
/// or load of the profile that gives it); velocities from zeta0 = v0 t_ref / a,
/// t_ref the longest time of the element; durations in t_ref. Names start
/// with "depth " or "load ", then the profile. `samples` per segment.
std::vector<NamedCase> profile_case_set(long samples = 21);

} // namespace mdrmap
