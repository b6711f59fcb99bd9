#pragma once
// The relaxation spectrum of `mdrmap simulate` (and the Python module) from
// its texts: --prony G1:TAU1,G2:TAU2,... or --prony-file FILE (CSV with the
// header G,tau), the Maxwell branches of the rheology (core/model/rheology.hpp)
// in the user's units. Every term is checked against the table's branch specs
// (branch_modulus_spec, branch_time_spec); a message names the term as a key
// (G3, tau3) and, for a file, its line.
#include <string>
#include <vector>

#include "core/model/rheology.hpp"

namespace mdrmap::app {

/// "G1:TAU1,G2:TAU2,...": 1 to kMaxBranches terms, each a modulus and a time,
/// both finite and > 0. Throws InvalidInput("prony").
std::vector<Branch> parse_prony(const std::string& text);

/// A CSV file of terms: the first line that is not blank or a comment is the
/// header `G,tau`, then one term `G,tau` per line (1 to kMaxBranches).
/// Blank lines and lines whose first non-blank character is '#' are skipped;
/// spaces around a value and a final CR are allowed. Throws
/// InvalidInput("prony-file") with "FILE:LINE: " where a line is at fault.
std::vector<Branch> read_prony_file(const std::string& path);

/// "G1:TAU1,G2:TAU2,..." with 17 significant digits (what the `# case`
/// line prints; parse_prony reads it back to the same branches).
std::string format_prony(const std::vector<Branch>& branches);

} // namespace mdrmap::app
