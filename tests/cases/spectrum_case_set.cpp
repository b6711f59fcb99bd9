#include "cases/spectrum_case_set.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace mdrmap {

Rheology material(double G, double tau, const std::vector<std::pair<double, double>>& terms) {
  Rheology r;
  r.G = G;
  r.tau = tau;
  for (const auto& [Gk, tk] : terms)
    r.branches.push_back(Branch{Gk, tk});
  return r;
}

Case spectrum_history(const Rheology& r, bool load, double zeta0,
                      const std::vector<std::pair<double, double>>& segs, long samples) {
  Case c;
  c.indenter.as<Parabola>().R = 2.0;
  c.rheology = r;
  if (load)
    c.loading.F0 = 1e-3 * r.G * c.indenter.as<Parabola>().R * c.indenter.as<Parabola>().R;
  else
    c.loading.d = 1e-3 * c.indenter.as<Parabola>().R;
  const double t_ref = r.longest_time() / r.aT;
  c.history.v0 = zeta0 * c.edge_scale() / t_ref;
  for (const auto& [w, T] : segs)
    c.history.segments.push_back(Segment{w * c.history.v0, T * t_ref});
  c.sampling.samples = samples;
  return c;
}

namespace {

using Pairs = std::vector<std::pair<double, double>>;

/// r with the shift factor aT (the unshifted times kept).
Rheology with_shift(Rheology r, double aT) {
  r.aT = aT;
  return r;
}

/// `n` equal terms G_k a decade apart, the longest at 1.
Rheology decades(int n, double Gk) {
  Pairs t;
  for (int k = 0; k < n; ++k)
    t.emplace_back(Gk, std::pow(10.0, -k));
  return material(1.0, 0.0, t);
}

/// Polyisobutylene (jobs/examples/pib_prony.csv: shear moduli in Pa, times in
/// s), moduli in units of the added long-term G = 1e5 Pa, times in units of
/// the longest (7.757e6 s): 30 terms over 18.3 decades, G0/G = 9898.
Rheology polyisobutylene() {
  const Pairs si = {
      {619668.9808, 3.218704101e-12}, {18717667.17, 1.363659119e-11},
      {43166049.53, 5.653601803e-11}, {107135345.4, 2.339703538e-10},
      {137732072.8, 1.166073392e-09}, {274236904.2, 4.851911198e-09},
      {210486190.9, 2.249710623e-08}, {120230977.3, 9.652457391e-08},
      {51109802.47, 3.832185702e-07}, {15072941.22, 1.671136054e-06},
      {7433459.911, 7.195990894e-06}, {2033665.488, 2.888031619e-05},
      {868727.4659, 0.0001478848591}, {369293.2569, 0.0005871274223},
      {93877.17404, 0.002360627622},  {42948.47207, 0.009355184492},
      {21180.71986, 0.04028386693},   {2404.008581, 0.1798396994},
      {4454.84241, 0.8160072398},     {30918.69857, 3.292734344},
      {15223.29981, 13.02560141},     {43833.32776, 58.4660216},
      {27033.85014, 296.6923894},     {46322.08938, 1045.648011},
      {35611.58096, 5277.606868},     {42539.62713, 26350.31863},
      {20877.11428, 87973.43544},     {10312.61655, 412351.9504},
      {0.04613853728, 1830927.406},   {0.04407129232, 7757037.536},
  };
  Pairs t;
  for (const auto& [G, tau] : si)
    t.emplace_back(G / 1e5, tau / 7757037.536);
  return material(1.0, 0.0, t);
}

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

} // namespace

std::vector<NamedCase> spectrum_case_set(long samples) {
  const Rheology sls2 = material(1.0, 0.0, {{1.0, 1.0}});
  const Rheology sls100 = material(1.0, 0.0, {{99.0, 1.0}});
  const Rheology sls1e4 = material(1.0, 0.0, {{9999.0, 1.0}});
  const Rheology six = decades(6, 1.0);
  const Rheology wide = decades(13, 1.0); // 1e-12 .. 1
  Pairs terms;
  for (int k = 0; k < 32; ++k) // 1 .. 1.8e-8, the most terms a spectrum may have
    terms.emplace_back(0.5, std::pow(10.0, -0.25 * k));
  const Rheology thirty_two = material(1.0, 0.0, terms);
  const Rheology pib = polyisobutylene();
  const Rheology dash = material(1.0, 0.3, {{2.0, 1.0}, {2.0, 0.05}});
  const Rheology fast = material(1.0, 0.0, {{2.0, 1.0}, {10.0, 1e-9}});
  const Rheology kelvin = material(1.0, 1.0, {});
  const Pairs three = {{0.1, 1.0}, {0.0, 2.0}, {1.0, 1.0}}; // drop, hold, reslide
  const Pairs tenfold = {{10.0, 1.0}, {1.0, 1.0}, {0.1, 1.0}};
  std::vector<NamedCase> out;
  for (const bool load : {false, true}) {
    const std::string at = load ? "load " : "depth ";
    auto add = [&](const std::string& name, const Rheology& r, double zeta0, const Pairs& segs) {
      out.push_back({at + name, spectrum_history(r, load, zeta0, segs, samples)});
    };
    add("SLS G0/G=2 step down 10x", sls2, 1.0, {{0.1, 3.0}});
    add("SLS G0/G=100 step up 10x", sls100, 0.1, {{10.0, 2.0}});
    add("SLS G0/G=100 drop-hold-reslide", sls100, 1.0, three);
    add("six decades drop-hold-reslide", six, 1.0, three);
    add("six decades up 10x, back, down 10x", six, 0.3, tenfold);
    for (double th : {1e-3, 1.0, 1e4})
      add(fmt("six decades slide-hold-slide hold=%g", th), six, 1.0, {{0.0, th}, {1.0, 2.0}});
    // FAILS under load (tests/test_spectrum_case_set.cpp, kKnownFailures, with
    // the figures; also the 1e-4 runs of the dashpot, Kelvin, hold=1e4 and
    // aT=1e-2 cases under load): 118 s CPU at rtol 1e-3
    add("polyisobutylene drop-hold-reslide", pib, 1.0, three);
    add("dashpot and two terms drop-hold-reslide", dash, 1.0, three);
    // FAILS under load: the reference converges at first order (not rtol/10 of
    // 1e-3 at a/dx 256); rtol 1e-4: CaseAbandoned at the work budget (30 s)
    add("dashpot and two terms up 10x, back, down 10x", dash, 1.0, tenfold);
    add("branch at 1e-9 (<< dt) step down 10x", fast, 1.0, {{0.1, 2.0}});
    add("Kelvin (N=0) drop-hold-reslide", kelvin, 1.0, three);
    add("six decades aT=1e-2 up 10x, back, down 10x", with_shift(six, 1e-2), 1.0, tenfold);
    if (!load) {
      add("polyisobutylene slide-hold-slide hold=100", pib, 1.0, {{0.0, 100.0}, {1.0, 2.0}});
      // reslid at zeta0 = 1e6 for 3 a1: the terms down to 1e-6 t_ref matter
      add("12 decades slide-hold-slide hold=1e6, zeta0=1e6", wide, 1e6, {{0.0, 1e6}, {1.0, 3e-6}});
      add("SLS G0/G=1e4 drop-hold", sls1e4, 1.0, {{0.1, 1.0}, {0.0, 1.0}});
      add("32 terms (4 per decade) drop-hold-reslide", thirty_two, 1.0, three);
      add("six decades ratio 1e-6 then back", six, 1.0, {{1e-6, 1.0}, {1.0, 1.0}});
      // the twin of "SLS G0/G=100 step up 10x" (velocities times 1e12, durations 1e-12)
      add("SLS G0/G=100 aT=1e-12 step up 10x", with_shift(sls100, 1e-12), 1e11, {{10.0, 2e-12}});
      add("SLS G0/G=100 aT=1e3 step down 10x", with_shift(sls100, 1e3), 1.0, {{0.1, 2.0}});
    } else {
      add("12 decades slide-hold-slide hold=100, zeta0=1e6", wide, 1e6,
          {{0.0, 100.0}, {1.0, 3e-6}});
      add("six decades aT=1e2 step down 10x", with_shift(six, 1e2), 1.0, {{0.1, 2.0}});
    }
  }
  return out;
}

} // namespace mdrmap
