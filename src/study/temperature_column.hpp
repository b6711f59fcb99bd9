#pragma once
// A study's temperature column with a unit (issue 33): `temperature = 25C,
// 40C` or `linspace:20C:60C:5` in [grid] (or an override), as `--T` takes
// it. The values of one column share one unit (C, K or none); a bare column
// is in TREF's unit as before. Once the WLF constants are known the values
// are converted to TREF's unit where both have one (T[K] = T[C] + 273.15),
// so /cases/temperature is in TREF's unit. A case list's cells take a unit
// each where TREF has one (converted as they are read).
#include <string>

#include "study/config.hpp"

namespace mdrmap::study::detail {

/// `spec` without its temperatures' unit letters, the unit in `unit`. Each
/// temperature with a unit is checked (finite, not below absolute zero).
/// Throws ConfigError(option) for mixed units or a bad temperature.
std::string without_temperature_units(const std::string& option, const std::string& spec,
                                      TempUnit& unit);

/// A case list's temperature cell with a unit ("35C", "308.15K"): the unit,
/// removed from `cell`, which must then be a temperature; None for a bare
/// cell (TREF's unit). A unit needs TREF's (its values are converted to it):
/// refused otherwise. Throws ConfigError(option) with `here` ("FILE:LINE:COL: ") first.
TempUnit listed_temperature_unit(const StudyConfig& c, const std::string& option,
                                 const std::string& here, std::string& cell);

/// A listed temperature `x` in `unit` converted to TREF's unit.
double listed_in_wlf_unit(const StudyConfig& c, double x, TempUnit unit);

/// Converts a temperature column with a unit to TREF's unit where TREF has
/// another one (idempotent: the column then has TREF's unit).
void temperatures_in_wlf_unit(StudyConfig& c);

} // namespace mdrmap::study::detail
