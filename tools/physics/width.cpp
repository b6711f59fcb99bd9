// Study 2: the width (decades of v at half maximum) of the stationary
// friction-velocity curve, at fixed depth and under load, for spectra of
// 1..6 terms, power-law weights and the polyisobutylene series.
#include <cstdio>
#include <sstream>
#include <string>

#include "peak.hpp"
#include "studies.hpp"

namespace mdrmap::physics {
namespace {

void width_row(const char* name, const Case& fixed, const Case& load, const std::vector<double>& v,
               std::ostream& csv, const std::string& label) {
  const Peak a = scan(fixed, v, csv, label + ",depth");
  const Peak b = scan(load, v, csv, label + ",load");
  std::printf("  %-22s %11.4g %9.4g %8.3f   %11.4g %9.4g %8.3f\n", name, a.v, a.mu, a.width(), b.v,
              b.mu, b.width());
}

/// One row of a decade spectrum (N terms, G0/G, weights ~ tau_k^p).
void decade_row(const char* name, const std::string& label, int n, double ratio, double p,
                std::ostream& csv) {
  const Rheology r = decade_spectrum(n, ratio, p);
  width_row(name, make_case(r, false), make_case(r, true), logspace(1e-11, 1e5, 20), csv, label);
}

} // namespace

void study_width(const Options& o) {
  auto csv = open_csv(o, "spectrum_width.csv", "spectrum,G0_over_G,loading,v_over_a,mu_over_aR");
  std::printf("\n# 2. Width of the stationary friction-velocity curve, decades of v at half maximum"
              "\n# equal terms a decade apart, longest tau = 1, sum G_k = G0 - G; PIB: G = 1e5 Pa, "
              "times in s\n#   %-22s %11s %9s %8s   %11s %9s %8s\n",
              "spectrum", "depth: v*", "mu*", "width", "load: v*", "mu*", "width");
  char name[64];
  for (double ratio : {100.0, 1e3})
    for (int n : {1, 2, 4, 6}) {
      std::snprintf(name, sizeof name, "%d x 1/decade G0/G=%g", n, ratio);
      std::ostringstream label;
      label << "N" << n << "," << ratio;
      decade_row(name, label.str(), n, ratio, 0.0, csv);
    }
  for (int n : {1, 2, 4, 6}) { // each term G_k = 10 G: G0/G grows with N
    std::snprintf(name, sizeof name, "%d x G_k=10G", n);
    std::ostringstream label;
    label << "N" << n << "g10," << 1.0 + 10.0 * n;
    decade_row(name, label.str(), n, 1.0 + 10.0 * n, 0.0, csv);
  }
  for (double pw : {-0.25, -0.5}) {
    std::snprintf(name, sizeof name, "6 x G_k~tau_k^%g G0/G=1000", pw);
    std::ostringstream label;
    label << "N6p" << pw << "," << 1e3;
    decade_row(name, label.str(), 6, 1e3, pw, csv);
  }
  const Rheology pib = read_pib(o.pib, 1e5);
  const double g0 = pib.G0();
  std::printf("  (PIB: G0/G = %.4g)\n", g0 / pib.G);
  width_row("PIB (30 terms)", make_case(pib, false), make_case(pib, true),
            logspace(1e-10, 1e15, 10), csv, "PIB," + std::to_string(g0 / pib.G));
}

} // namespace mdrmap::physics
