// Maxima and half-maximum widths of friction-velocity curves (peak.hpp).
#include "peak.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "common.hpp"

namespace mdrmap::physics {

std::pair<double, double> refine_max(const std::function<double(double)>& f,
                                     const std::vector<double>& v, std::size_t i) {
  double lo = std::log10(v[i == 0 ? 0 : i - 1]), hi = std::log10(v[std::min(i + 1, v.size() - 1)]);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(std::pow(10.0, x1)), f2 = f(std::pow(10.0, x2));
  while (hi - lo > 1e-7) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(std::pow(10.0, x1));
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(std::pow(10.0, x2));
    }
  }
  const double x = 0.5 * (lo + hi);
  return {std::pow(10.0, x), f(std::pow(10.0, x))};
}

double crossing(const std::function<double(double)>& f, double a, double b, double level) {
  double la = std::log10(a), lb = std::log10(b);
  const bool rising = f(a) < level;
  for (int it = 0; it < 60; ++it) {
    const double m = 0.5 * (la + lb);
    if ((f(std::pow(10.0, m)) < level) == rising)
      la = m;
    else
      lb = m;
  }
  return std::pow(10.0, 0.5 * (la + lb));
}

Peak peak_of(const std::function<double(double)>& f, const std::vector<double>& v,
             const std::vector<double>& mu) {
  const std::size_t i =
      static_cast<std::size_t>(std::max_element(mu.begin(), mu.end()) - mu.begin());
  Peak p;
  std::tie(p.v, p.mu) = refine_max(f, v, i);
  p.v_lo = p.v_hi = NAN;
  for (std::size_t j = i; j-- > 0;)
    if (mu[j] < 0.5 * p.mu) {
      p.v_lo = crossing(f, v[j], v[j + 1], 0.5 * p.mu);
      break;
    }
  for (std::size_t j = i + 1; j < v.size(); ++j)
    if (mu[j] < 0.5 * p.mu) {
      p.v_hi = crossing(f, v[j - 1], v[j], 0.5 * p.mu);
      break;
    }
  return p;
}

Peak scan(const Case& c, const std::vector<double>& v, std::ostream& csv,
          const std::string& label) {
  const auto f = [&c](double w) { return mu_stationary(c, w); };
  std::vector<double> mu;
  for (double w : v) {
    mu.push_back(f(w));
    csv << label << "," << w << "," << mu.back() << "\n";
  }
  return peak_of(f, v, mu);
}

} // namespace mdrmap::physics
