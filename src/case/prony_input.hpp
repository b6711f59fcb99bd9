#pragma once
// The relaxation spectrum of `mdrmap simulate` (and the Python module) from
// its text --prony G1:TAU1,G2:TAU2,... (a file: material/prony_file.hpp), the Maxwell branches of
// the rheology (core/model/rheology.hpp) in the user's units. Every term is checked against the
// table's branch specs (branch_modulus_spec, branch_time_spec); a message names the term as a key
// (G3, tau3) and, for a file, its line.
#include <string>
#include <utility>
#include <vector>

#include "core/model/rheology.hpp"

namespace mdrmap::cases {

/// "G1:TAU1,G2:TAU2,...": 1 to kMaxBranches terms, each a modulus and a time,
/// both finite and > 0. Throws InvalidInput("prony").
std::vector<Branch> parse_prony(const std::string& text);

/// The terms given as (G, TAU) pairs, checked as parse_prony checks the
/// terms of a text (a message shows term k as 'G:TAU'). Throws InvalidInput("prony").
std::vector<Branch> prony_of_pairs(const std::vector<std::pair<double, double>>& pairs);

/// "G1:TAU1,G2:TAU2,..." with 17 significant digits (what the `# case`
/// line prints; parse_prony reads it back to the same branches).
std::string format_prony(const std::vector<Branch>& branches);

} // namespace mdrmap::cases
