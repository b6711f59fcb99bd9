#pragma once
// Private to the study config: what its readers (the INI schema, grid axes,
// case lists) share beyond strings and locations (study/ini.hpp): strict
// number parsing, the range of each case field, and the checks of a whole
// study.
#include <cstdint>
#include <functional>
#include <string>

#include "study/config.hpp"
#include "study/ini.hpp"

namespace mdrmap::study::detail {

// --- Numbers ------------------------------------------------------------------

enum class NumError { None, Empty, NotNumber, NotFinite, TooLarge };

struct Num {
  double x = 0.0;
  NumError err = NumError::None;
};

/// Strict: the whole text is one decimal (or hex) floating-point number.
Num to_number(const std::string& s);

/// "'abc' is not a number" and the like.
std::string number_problem(const std::string& text, NumError e);

/// Strict integer: optional sign and decimal digits; huge values clamp near 1e18.
bool to_integer(const std::string& s, long long& out);

// --- The whole study ----------------------------------------------------------

/// Where the setting behind an option ("section.key" or "config") was made.
using WhereFn = std::function<Where(const std::string& option)>;

/// Every check that involves more than one setting (grids: shape, size, the
/// time series' memory and every case; case lists are checked when read).
/// Throws ConfigError located by where(option). Defined in study/config.cpp.
void check_study(const StudyConfig& c, const WhereFn& where);

/// Checks grid case i (0-based) as expand_cases does: the row, the window
/// and the samples. Throws ConfigError naming the axis and "case i+1".
void check_grid_case(const StudyConfig& c, std::size_t i, const Row& r);

/// Checks the window and samples of a case list's case i (0-based; its row
/// was checked when read), as expand_cases does. Throws ConfigError naming
/// the file and "case i+1".
void check_listed_case(const StudyConfig& c, std::size_t i, const Row& r);

/// Refuses a case list of n cases whose time series would not fit in 64 GiB.
void check_case_list_size(const StudyConfig& c, std::size_t n);

/// A case list's row in canonical text (its listed columns' values, comma
/// separated, numbers normalized, a newline).
std::string canonical_row(const StudyConfig& c, const Row& r);

/// canonical() of a case list of `count` cases whose canonical rows hash to `sha256`.
std::string canonical_case_list(const StudyConfig& c, std::uint64_t count,
                                const std::string& sha256);

} // namespace mdrmap::study::detail
