#pragma once
// Every key a study config may hold, section by section, with its value,
// unit, allowed values, default and meaning: the [grid] and [history] keys
// from the core's parameter table and the study's column specs, the [cases]
// and [run] keys declared here (the INI schema, study/study_schema.cpp, takes
// their names from this table). `mdrmap help config` and the reference page
// docs/reference/config.md are generated from it.
#include <string>
#include <vector>

namespace mdrmap::study {

/// The largest [run] samples (per segment).
inline constexpr long kMaxRunSamples = 1'000'000;

struct ConfigKey {
  std::string section; ///< "grid", "history", "cases" or "run"
  std::string key;     ///< as written, or a pattern: "Gk", "wK_over_v"
  std::string value;   ///< its form: "SPEC", "N", "linear | log", ...
  std::string unit;    ///< a dimension (core/model/params.hpp's dim_name), or "" for none
  std::string allowed; ///< what a value may be
  std::string given;   ///< "required", "default 201", "optional", ...
  std::string meaning; ///< one line, lower case, no final period
};

/// Every key, in section order ([grid], [history], [cases], [run]).
const std::vector<ConfigKey>& config_keys();

/// The names of the [run] keys the reader takes.
std::vector<std::string> run_key_names();

} // namespace mdrmap::study
