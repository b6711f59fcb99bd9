// Study 3: slide-hold-slide healing at fixed depth over holds of 1e-6..1e4 of
// the longest relaxation time, beta per decade, for nine six-term spectra.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "shs.hpp"
#include "studies.hpp"

namespace mdrmap::physics {
namespace {

/// Healing over holds 10^lo .. 10^hi (in the longest tau_k = 1), `per` per
/// decade, rows into csv; prints beta per decade (healing(10 t) - healing(t)).
void healing_series(const char* name, const Rheology& r, double v0, double rtol, int lo, int hi,
                    std::ostream& csv, const std::string& label) {
  const int per = 4;
  const Case base = make_case(r, false);
  std::vector<double> th, heal;
  double err = 0.0;
  for (int i = lo * per; i <= hi * per; ++i) {
    th.push_back(std::pow(10.0, static_cast<double>(i) / per));
    const Healing h = shs(base, v0, th.back(), rtol);
    heal.push_back(h.healing());
    err = std::max(err, h.err);
    csv << label << "," << th.back() << "," << h.mu_pre << "," << h.mu_peak << "," << h.healing()
        << "," << h.t_peak << "," << h.Fx_peak << "," << h.FN_peak << "," << h.FN_hold << ","
        << h.err << std::endl; // a row per run: progress shows in the file
  }
  std::printf("  %-26s err<=%.1e  beta per decade [hold range]:", name, err);
  std::printf("\n    ");
  for (std::size_t i = 0; i + per < th.size(); i += per)
    std::printf(" [%g,%g] %.4f", th[i], th[i + per], heal[i + per] - heal[i]);
  std::printf("\n");
}

struct Run {
  double p, ratio, zeta; // p = NaN: sqrt_linear_spectrum
};

/// The run's name for the table and its label columns for the CSV.
void run_names(const Run& run, char (&name)[96], std::string& label) {
  if (std::isnan(run.p))
    std::snprintf(name, sizeof name, "sqrt-linear G0/G=%g v0tau6/a1=%g", run.ratio, run.zeta);
  else
    std::snprintf(name, sizeof name, "p=%g G0/G=%g v0tau6/a1=%g", run.p, run.ratio, run.zeta);
  std::ostringstream l;
  l << "6x,";
  if (std::isnan(run.p))
    l << "sqrt";
  else
    l << run.p;
  l << "," << run.ratio << "," << run.zeta;
  label = l.str();
}

} // namespace

void study_healing(const Options& o) {
  auto csv = open_csv(o, "spectrum_healing.csv",
                      "spectrum,p,G0_over_G,v0_taumax_over_a1,t_hold,mu_pre,mu_peak,healing,"
                      "t_peak,Fx_peak,FN_peak,FN_hold,error_estimate");
  std::printf("\n# 3. Slide-hold-slide healing at fixed depth (run_spectrum, rtol %g): 6 terms a "
              "decade apart, tau_k = 1e-5..1, G_k ~ tau_k^p, sum G_k = G0 - G; beta = healing "
              "per decade of hold [mu in a1/R]\n",
              o.rtol);
  const Run runs[] = {{0.0, 100.0, 1e6},  {0.0, 100.0, 1e3},   {0.0, 10.0, 1e6},
                      {-0.1, 100.0, 1e6}, {-0.15, 100.0, 1e6}, {-0.25, 100.0, 1e6},
                      {-0.5, 100.0, 1e6}, {0.25, 100.0, 1e6},  {NAN, 100.0, 1e6}};
  for (int i = 1; i <= 9; ++i) {
    if (o.healing_run != 0 && o.healing_run != i) continue;
    const Run& run = runs[i - 1];
    char name[96];
    std::string label;
    run_names(run, name, label);
    const Rheology r = std::isnan(run.p) ? sqrt_linear_spectrum(6, run.ratio)
                                         : decade_spectrum(6, run.ratio, run.p);
    healing_series(name, r, run.zeta, o.rtol, -6, 4, csv, label);
  }
}

} // namespace mdrmap::physics
