// Study 1: the standard linear solid under load, its friction maximum against
// velocity as G0/G grows towards the Kelvin limit.
#include <cstdio>
#include <sstream>

#include "peak.hpp"
#include "studies.hpp"

namespace mdrmap::physics {

void study_sls(const Options& o) {
  auto csv = open_csv(o, "spectrum_sls_load.csv", "model,G0_over_G,v_tau1_over_a0,mu_over_a0R");
  std::printf("\n# 1. Standard linear solid under load (tau = 0, G1 = G0 - G, tau1 = 1; Kelvin: "
              "tau_K = 1)\n# %-8s %14s %14s %16s\n",
              "G0/G", "v* tau1/a0", "mu*/(a0/R)", "v* tau_K/a0");
  const double ratios[] = {2.0, 10.0, 100.0, 1e3, 1e4};
  for (double ratio : ratios) {
    const Case c = make_case(decade_spectrum(1, ratio), true);
    std::ostringstream label;
    label << "sls," << ratio;
    const Peak p = scan(c, logspace(1e-8, 1e3, 40), csv, label.str());
    std::printf("  %-8.0f %14.5g %14.5g %16.5g\n", ratio, p.v, p.mu, p.v * (ratio - 1.0));
  }
  Rheology kelvin;
  kelvin.G = 1.0;
  kelvin.tau = 1.0;
  const Peak p = scan(make_case(kelvin, true), logspace(1e-4, 1e3, 40), csv, "kelvin,inf");
  std::printf("  %-8s %14s %14.5g %16.5g\n", "Kelvin", "-", p.mu, p.v);
}

} // namespace mdrmap::physics
