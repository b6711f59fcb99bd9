#pragma once
// Private to the study config: CSV case lists ([cases] file = ...;
// read_cases_csv in study/config.hpp reads one).
#include <string>

#include "study/config.hpp"

namespace mdrmap::study::detail {

/// Resolves a [cases] file against the INI's directory ("" for none) and
/// checks it can be read. Throws ConfigError("cases.file") without location.
std::string resolve_cases_file(const std::string& file, const std::string& base_dir);

} // namespace mdrmap::study::detail
