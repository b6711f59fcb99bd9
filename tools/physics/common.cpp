// The shared spectra, cases and CSV files of mdrmap_spectrum_physics (common.hpp).
#include "common.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/metrics/spectrum_stationary.hpp"

namespace mdrmap::physics {

Rheology decade_spectrum(int n, double glassy_ratio, double p) {
  Rheology r;
  r.G = 1.0;
  r.tau = 0.0;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double tk = std::pow(10.0, -(n - 1 - k));
    r.branches.push_back(Branch{std::pow(tk, p), tk});
    sum += r.branches.back().G;
  }
  for (Branch& b : r.branches)
    b.G *= (glassy_ratio - 1.0) / sum;
  return r;
}

Rheology sqrt_linear_spectrum(int n, double glassy_ratio) {
  Rheology r = decade_spectrum(n, glassy_ratio);
  const double s = (1.0 - std::sqrt(1.0 / glassy_ratio)) / n;
  for (int k = 0; k < n; ++k) {
    const double before = 1.0 - s * k, after = 1.0 - s * (k + 1);
    r.branches[static_cast<std::size_t>(k)].G = glassy_ratio * (before * before - after * after);
  }
  return r;
}

Rheology read_pib(const std::string& path, double G) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  Rheology r;
  r.G = G;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'G') continue;
    std::istringstream ls(line);
    Branch b;
    char comma = 0;
    if (ls >> b.G >> comma >> b.tau) r.branches.push_back(b);
  }
  return r;
}

Case make_case(const Rheology& r, bool load) {
  Case c;
  c.indenter.as<mdrmap::Parabola>().R = 1.0;
  c.rheology = r;
  if (load)
    c.loading.F0 = 16.0 / 3.0 * r.G;
  else
    c.loading.d = 1.0;
  c.history.v0 = 1.0;
  c.history.segments = {Segment{1.0, 1.0}};
  return c;
}

double mu_stationary(const Case& c, double v) {
  return c.loading.by_force() ? spectrum_stationary_load(c, v).mu : spectrum_stationary(c, v).mu;
}

std::vector<double> logspace(double lo, double hi, int per_decade) {
  std::vector<double> v;
  const int n = static_cast<int>(std::lround(std::log10(hi / lo) * per_decade));
  for (int i = 0; i <= n; ++i)
    v.push_back(lo * std::pow(10.0, static_cast<double>(i) / per_decade));
  return v;
}

std::ofstream open_csv(const Options& o, const std::string& name, const std::string& header) {
  std::ofstream f(o.out + "/" + name);
  if (!f) throw std::runtime_error("cannot write " + o.out + "/" + name);
  f.precision(10);
  f << header << "\n";
  return f;
}

} // namespace mdrmap::physics
