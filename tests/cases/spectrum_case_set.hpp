#pragma once
// The spectrum histories the spectrum solver is tested on (issue 19, "Done
// when" 2; docs/design.md, "Materials with a relaxation spectrum"): standard
// linear solids (G0/G = 2, 100, 1e4), six equal-weight terms a decade apart,
// the 30-term polyisobutylene series (jobs/examples/pib_prony.csv, times
// scaled to a longest term of 1, G = 1e5 Pa added), 13 terms over 12
// decades, 32 terms, a parallel dashpot with two terms, a branch 1e-9 of the
// longest time (far faster than any step), the Kelvin limit (N = 0) and
// shifts aT of 1e-12 to 1e3; tenfold steps up and down, a velocity ratio of
// 1e-6, slide-hold-slide with holds of 1e-3 to 1e6 of the longest time; at
// fixed depth and under load.
#include <utility>
#include <vector>

#include "cases/case_set.hpp"

namespace mdrmap {

/// The element of the tests' spectra: long-term modulus G, dashpot time tau
/// (0: none) and Maxwell terms (G_k, tau_k).
Rheology material(double G, double tau, const std::vector<std::pair<double, double>>& terms);

/// A history on the material r: R = 2, d/R = 1e-3 or F0 = 1e-3 G R^2 (load),
/// v0 = zeta0 a / t_ref (t_ref the longest unshifted time), segments
/// (w / v0, T / t_ref), `samples` per segment.
Case spectrum_history(const Rheology& r, bool load, double zeta0,
                      const std::vector<std::pair<double, double>>& segs, long samples);

/// Lengths: R = 2; at fixed depth d/R = 1e-3, under load F0 = 1e-3 G R^2.
/// Velocities from zeta0 = v0 t_ref / a (a = a1 at fixed depth, a0 under
/// load), t_ref the longest unshifted time of the element (aT = 1); durations
/// in t_ref. Names start with "depth " or "load ". `samples` per segment.
std::vector<NamedCase> spectrum_case_set(long samples = 21);

} // namespace mdrmap
