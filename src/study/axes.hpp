#pragma once
// Private to the study config: grid axes (parse_axis in study/config.hpp
// reads one), the size of a grid.
#include <string>
#include <vector>

#include "study/config.hpp"

namespace mdrmap::study::detail {

/// The number of cases of a grid, as a double (no overflow).
double grid_size(const StudyConfig& c);

/// Refuses grids over 1e9 cases. Throws ConfigError("config") without location.
void check_grid_size(const StudyConfig& c);

/// The smallest, largest and smallest positive value (the cases where the
/// core's checks, each monotone in each parameter, can fail first).
std::vector<double> extremes(const std::vector<double>& v);

} // namespace mdrmap::study::detail
