#pragma once
// The number range of the element-row solver (core/solvers/spectrum*.hpp):
// the solver of every relaxation spectrum and every profile other than the
// parabola. Inside these limits its arithmetic stays in normal doubles; a case
// outside is refused at validation, naming its option (issue 32: beyond them
// a velocity's square overflowed to rows of NaN with exit 0, and the modes of
// a spectrum lost their decay to rounding).
//
//   velocity    every w > 0 of the history (v0, each segment's W): w^2 and
//               c w^2 (c the profile's coefficient, the forcing of a sub-step)
//               within [1e-280, 1e300]
//   times       every shifted relaxation time aT tau_k, and aT tau of the
//               dashpot, within [1e-150, 1e150]
//   moduli      without a dashpot (tau = 0), every G_k >= 1e-12 G0 (the modes
//               of the branches are eigenvalues of a matrix of G_k G_l / G0)
//   profile     a cone's or power law's coefficient c = kappa_n A within
//               [1e-100, 1e100] (and n <= 100, in the parameter table)
#include "core/model/case.hpp"

namespace mdrmap {

/// Whether the element row solves the case: a spectrum or a profile other
/// than the parabola (the Kelvin parabola has its own solvers).
bool uses_element_row(const Case& c);

/// The spectrum's limits of the row (times, moduli); throws InvalidInput
/// naming "prony", "aT" or "tau". validate(Rheology) calls it for a spectrum.
void check_spectrum_limits(const Rheology& r);

/// The profile's coefficient of a cone or power law within [1e-100, 1e100];
/// throws InvalidInput naming "beta" or "A". (The parabola: nothing.)
void check_profile_limits(const Indenter& i);

/// Every limit of the row for the case (check_spectrum_limits, the dashpot's
/// shifted time, the velocities); throws InvalidInput naming "v", "history",
/// "prony", "aT" or "tau". validate(Case) calls it where uses_element_row;
/// the dispatch where the spectrum solver is asked for explicitly.
void check_element_row(const Case& c);

} // namespace mdrmap
