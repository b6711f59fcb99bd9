#pragma once
// The maximum of a stationary friction-velocity curve and its width at half
// maximum, from a scan in log v refined by golden section and bisection.
#include <cmath>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/model/case.hpp"

namespace mdrmap::physics {

struct Peak {
  double v = 0, mu = 0, v_lo = 0, v_hi = 0; // position, height, half-maximum crossings
  double width() const { return std::log10(v_hi / v_lo); }
};

/// Maximum of f(log10 v) near the sample index i of a scan: golden section
/// on the bracket of its neighbours. Returns {v*, f(v*)}.
std::pair<double, double> refine_max(const std::function<double(double)>& f,
                                     const std::vector<double>& v, std::size_t i);

/// Crossing of f = level between scan samples a and b (bisection in log v).
double crossing(const std::function<double(double)>& f, double a, double b, double level);

/// The global maximum of a scan, refined, and the half-maximum crossings
/// nearest to it on either side (NaN where the scan does not reach below).
Peak peak_of(const std::function<double(double)>& f, const std::vector<double>& v,
             const std::vector<double>& mu);

/// Scans mu(v) of the case over v, writes rows "label,v,mu" and returns the peak.
Peak scan(const Case& c, const std::vector<double>& v, std::ostream& csv, const std::string& label);

} // namespace mdrmap::physics
