#pragma once
// Private to the study config: grid axes (parse_axis in study/config.hpp
// reads one), the shape and size of a grid, and walking its combinations.
#include <string>
#include <vector>

#include "study/config.hpp"

namespace mdrmap::study::detail {

/// The names an axis may have: d, R, tau, v, v1, v1_over_v (the [grid] keys).
const std::vector<std::string>& axis_names();

/// Grid axes in study order; the fifth is v1 or v1_over_v.
inline constexpr const char* kAxisOrder[4] = {"d", "R", "tau", "v"};

/// Checks that c.axes is d, R, tau, v, v1|v1_over_v, each non-empty.
/// Throws ConfigError without location.
void check_axes_shape(const StudyConfig& c);

/// The number of cases of a grid, as a double (no overflow).
double grid_size(const StudyConfig& c);

/// Refuses grids over 1e9 cases. Throws ConfigError("config") without location.
void check_grid_size(const StudyConfig& c);

/// The smallest, largest and smallest positive value (the cases where the
/// core's checks, each monotone in each parameter, can fail first).
std::vector<double> extremes(const std::vector<double>& v);

/// Calls f(row) for every combination of the five axis value lists, in C
/// order (last axis fastest); v1 is v1_over_v * v when `ratio`.
template <class F>
void for_each_combination(const std::vector<double>& D, const std::vector<double>& R,
                          const std::vector<double>& T, const std::vector<double>& V,
                          const std::vector<double>& V1, bool ratio, double G, F f) {
  for (const double d : D)
    for (const double r : R)
      for (const double tau : T)
        for (const double v : V)
          for (const double x : V1) {
            StepRow s;
            s.d = d;
            s.R = r;
            s.tau = tau;
            s.v = v;
            s.v1 = ratio ? x * v : x;
            s.G = G;
            f(s);
          }
}

} // namespace mdrmap::study::detail
