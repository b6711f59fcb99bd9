// Study 6: slide-hold-slide healing under load against the same at fixed
// depth, for a standard linear solid and two six-term spectra: holds of
// 1e-3..1e4 of the longest relaxation time, beta per decade, and the contact's
// creep during the hold under load against Lee-Radok (core/metrics/creep.hpp).
//
// Both loadings start from the same stationary state: the load F0 is the
// normal force of stationary sliding at v0 at the depth d = 1 (so a1 = 1 and
// mu is in a1/R in both), v0 tau_max/a1 = 1e6 (every term glassy while the
// indenter slides, as in study 3).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "core/metrics/creep.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/numerics/run_control.hpp"
#include "shs.hpp"
#include "studies.hpp"

namespace mdrmap::physics {
namespace {

constexpr double kZeta = 1e6; // v0 tau_max / a1
constexpr int kPer = 2;       // holds per decade
constexpr int kLo = -3, kHi = 4;

/// One run: its result, or why it was left out; its wall time.
struct Outcome {
  Healing h;
  bool ok = false;
  std::string why;
  double seconds = 0.0;
};

Outcome timed_shs(const Case& base, double t_hold, double rtol) {
  Outcome r;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    r.h = shs(base, kZeta, t_hold, rtol);
    r.ok = true;
  } catch (const CaseAbandoned& e) {
    r.why = e.what();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

struct Hold {
  double t = 0.0, a1_creep = 0.0; ///< hold time; Lee-Radok contact half-width at its end
  Outcome depth, load;
};

void csv_row(std::ostream& csv, const std::string& label, const char* loading, const Hold& p,
             const Outcome& r) {
  const Healing& h = r.h;
  csv << label << "," << loading << "," << p.t << "," << h.mu_pre << "," << h.mu_peak << ","
      << h.healing() << "," << h.mu_peak_events << "," << h.t_peak << "," << h.FN_hold << ","
      << h.d_hold << "," << h.a1_hold << "," << p.a1_creep << "," << h.err << "," << r.seconds
      << "," << (r.ok ? "done" : "left out") << std::endl; // a row per run: progress shows
}

/// beta over [t, 10 t] for every hold t whose decade above was run ("-" if not).
void print_beta(const char* loading, const std::vector<Hold>& holds, bool load) {
  std::printf("    beta per decade, %-11s", loading);
  for (std::size_t i = 0; i + kPer < holds.size(); i += kPer) {
    const Outcome& a = load ? holds[i].load : holds[i].depth;
    const Outcome& b = load ? holds[i + kPer].load : holds[i + kPer].depth;
    if (a.ok && b.ok)
      std::printf(" [%g,%g] %.4f", holds[i].t, holds[i + kPer].t, b.h.healing() - a.h.healing());
    else
      std::printf(" [%g,%g] -", holds[i].t, holds[i + kPer].t);
  }
  std::printf("\n");
}

void print_hold(const Hold& p) {
  const auto cell = [](const Outcome& r) {
    if (r.ok)
      std::printf("  %9.5f %7.1e %6.2f", r.h.healing(), r.h.err, r.seconds);
    else
      std::printf("  %9s %7s %6.2f", "left out", "-", r.seconds);
  };
  std::printf("  %9.3g", p.t);
  cell(p.depth);
  cell(p.load);
  if (p.load.ok)
    std::printf("  %8.4f %8.4f %+9.2e\n", p.load.h.a1_hold, p.a1_creep,
                p.load.h.a1_hold / p.a1_creep - 1.0);
  else
    std::printf("\n");
}

void material(const char* name, const std::string& label, const Rheology& r, double rtol,
              std::ostream& csv) {
  const Case depth = make_case(r, false);
  Case load = make_case(r, true);
  load.loading.F0 = spectrum_stationary(depth, kZeta).FN;
  const double d_ss = spectrum_stationary_depth(load, kZeta);
  std::printf("\n  %s: F0 = %.6g (stationary at d = 1), stationary depth under F0 %.12g, "
              "Lee-Radok d(0+) %.6g, d(inf) %.6g, longest retardation time %.4g\n",
              name, load.loading.F0, d_ss, creep_depth(load, 0.0), creep_depth(load, 1e12),
              creep_spectrum(r).rho.back());
  std::printf("  %9s  %9s %7s %6s  %9s %7s %6s  %8s %8s %9s\n", "t_h/tmax", "depth:heal", "err",
              "s", "load:heal", "err", "s", "a1_hold", "a1_LR", "a1/a1_LR-1");
  std::vector<Hold> holds;
  double seconds = 0.0;
  for (int i = kLo * kPer; i <= kHi * kPer; ++i) {
    Hold p;
    p.t = std::pow(10.0, static_cast<double>(i) / kPer);
    p.a1_creep = std::sqrt(load.indenter.as<mdrmap::Parabola>().R * creep_depth(load, p.t));
    p.depth = timed_shs(depth, p.t, rtol);
    p.load = timed_shs(load, p.t, rtol);
    csv_row(csv, label, "depth", p, p.depth);
    csv_row(csv, label, "load", p, p.load);
    print_hold(p);
    for (const Outcome* o : {&p.depth, &p.load})
      if (!o->ok)
        std::printf("    left out (%s): %s\n", o == &p.depth ? "depth" : "load", o->why.c_str());
    seconds += p.depth.seconds + p.load.seconds;
    holds.push_back(p);
  }
  print_beta("fixed depth", holds, false);
  print_beta("under load", holds, true);
  std::printf("    (%.1f s for %zu runs)\n", seconds, 2 * holds.size());
}

} // namespace

void study_healing_load(const Options& o) {
  auto csv = open_csv(o, "spectrum_healing_load.csv",
                      "spectrum,G0_over_G,loading,t_hold,mu_pre,mu_peak,healing,mu_peak_events,"
                      "t_peak,FN_hold,d_hold,a1_hold,a1_creep,error_estimate,seconds,status");
  std::printf("\n# 6. Slide-hold-slide healing under load against fixed depth (run_spectrum, rtol "
              "%g): the same stationary state before the hold (d = 1, a1 = 1, v0 tau_max/a1 = "
              "%g); healing = mu_peak - mu_ss [a1/R], beta per decade of hold; a1 at the end of "
              "the hold under load against Lee-Radok creep from rest (a1_LR = sqrt(R d(t)))\n",
              o.rtol, kZeta);
  struct Material {
    const char* name;
    const char* label;
    Rheology r;
  };
  const Material materials[] = {
      {"SLS G0/G=100 (tau1 = 1)", "SLS,100", decade_spectrum(1, 100.0)},
      {"6x equal weights G0/G=100", "6x-equal,100", decade_spectrum(6, 100.0)},
      {"6x sqrt-linear G0/G=100", "6x-sqrt,100", sqrt_linear_spectrum(6, 100.0)}};
  for (int k = 1; k <= 3; ++k)
    if (o.load_material == 0 || o.load_material == k)
      material(materials[k - 1].name, materials[k - 1].label, materials[k - 1].r, o.rtol, csv);
}

} // namespace mdrmap::physics
