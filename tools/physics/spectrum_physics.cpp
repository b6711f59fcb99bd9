// mdrmap_spectrum_physics: what a relaxation spectrum does to MDR friction,
// measured (issue 19 item 7; docs/design.md, "Materials with a relaxation
// spectrum"). Prints one table per part and writes its CSV files into --out
// DIR; tools/plot_spectrum_physics.py makes the README's figures from them.
//
//   mdrmap_spectrum_physics --out DIR [--pib FILE] [--part 1..5] [--rtol R] [--healing-run K]
//
// Units: R = 1, G = 1 (PIB: G = 1e5 Pa), d = 1 at fixed depth (a1 = 1) and
// F0 = 16/3 under load (a0 = 1): mu is in units of a/R, velocities in a per
// unit time. Not a test and not a benchmark: no timing, no pass/fail.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/metrics/creep.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/solvers/spectrum.hpp"

using namespace mdrmap;

namespace {

struct Options {
  std::string out;
  std::string pib = "jobs/examples/pib_prony.csv";
  int part = 0; // 0: all
  double rtol = 1e-3;
  int healing_run = 0; // part 3: only this run (1..9), 0: all
};

// ---------------------------------------------------------------- materials

/// tau = 0 and N terms a decade apart, the longest at tau_max = 1, moduli
/// G_k proportional to tau_k^p with sum G_k = G0/G - 1 (G = 1).
Rheology decade_spectrum(int n, double glassy_ratio, double p = 0.0) {
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

/// tau = 0 and N terms a decade apart (longest tau = 1) whose relaxation modulus
/// falls so that sqrt(G(t)/G0) drops by the same step at each term: G(tau_k^+) =
/// G0 (1 - k s)^2, s = (1 - sqrt(G/G0)) / N, the fastest term the heaviest.
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

/// Fixed depth d = 1 (a1 = 1) or load F0 = 16/3 G (a0 = 1); R = 1.
Case make_case(const Rheology& r, bool load) {
  Case c;
  c.indenter.R = 1.0;
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

// ------------------------------------------------------- curves and maxima

/// Maximum of f(log10 v) near the sample index i of a scan: golden section
/// on the bracket of its neighbours. Returns {v*, f(v*)}.
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

/// Crossing of f = level between scan samples a and b (bisection in log v).
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

struct Peak {
  double v = 0, mu = 0, v_lo = 0, v_hi = 0; // position, height, half-maximum crossings
  double width() const { return std::log10(v_hi / v_lo); }
};

/// The global maximum of a scan, refined, and the half-maximum crossings
/// nearest to it on either side (NaN where the scan does not reach below).
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

/// Scans mu(v) of the case over v, writes rows "label,v,mu" and returns the peak.
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

} // namespace

namespace {

// --------------------------------------------- 1. the SLS under load

void part_sls(const Options& o) {
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

// ------------------------------- 2. width of the friction-velocity curve

void width_row(const char* name, const Case& fixed, const Case& load, const std::vector<double>& v,
               std::ostream& csv, const std::string& label) {
  const Peak a = scan(fixed, v, csv, label + ",depth");
  const Peak b = scan(load, v, csv, label + ",load");
  std::printf("  %-22s %11.4g %9.4g %8.3f   %11.4g %9.4g %8.3f\n", name, a.v, a.mu, a.width(), b.v,
              b.mu, b.width());
}

void part_width(const Options& o) {
  auto csv = open_csv(o, "spectrum_width.csv", "spectrum,G0_over_G,loading,v_over_a,mu_over_aR");
  std::printf("\n# 2. Width of the stationary friction-velocity curve, decades of v at half maximum"
              "\n# equal terms a decade apart, longest tau = 1, sum G_k = G0 - G; PIB: G = 1e5 Pa, "
              "times in s\n#   %-22s %11s %9s %8s   %11s %9s %8s\n",
              "spectrum", "depth: v*", "mu*", "width", "load: v*", "mu*", "width");
  for (double ratio : {100.0, 1e3}) {
    for (int n : {1, 2, 4, 6}) {
      const Rheology r = decade_spectrum(n, ratio);
      char name[64];
      std::snprintf(name, sizeof name, "%d x 1/decade G0/G=%g", n, ratio);
      std::ostringstream label;
      label << "N" << n << "," << ratio;
      width_row(name, make_case(r, false), make_case(r, true), logspace(1e-11, 1e5, 20), csv,
                label.str());
    }
  }
  for (int n : {1, 2, 4, 6}) { // each term G_k = 10 G: G0/G grows with N
    const Rheology r = decade_spectrum(n, 1.0 + 10.0 * n);
    char name[64];
    std::snprintf(name, sizeof name, "%d x G_k=10G", n);
    std::ostringstream label;
    label << "N" << n << "g10," << 1.0 + 10.0 * n;
    width_row(name, make_case(r, false), make_case(r, true), logspace(1e-11, 1e5, 20), csv,
              label.str());
  }
  for (double pw : {-0.25, -0.5}) {
    const Rheology r = decade_spectrum(6, 1e3, pw);
    char name[64];
    std::snprintf(name, sizeof name, "6 x G_k~tau_k^%g G0/G=1000", pw);
    std::ostringstream label;
    label << "N6p" << pw << "," << 1e3;
    width_row(name, make_case(r, false), make_case(r, true), logspace(1e-11, 1e5, 20), csv,
              label.str());
  }
  const Rheology pib = read_pib(o.pib, 1e5);
  double g0 = pib.G;
  for (const Branch& b : pib.branches)
    g0 += b.G;
  std::printf("  (PIB: G0/G = %.4g)\n", g0 / pib.G);
  width_row("PIB (30 terms)", make_case(pib, false), make_case(pib, true),
            logspace(1e-10, 1e15, 10), csv, "PIB," + std::to_string(g0 / pib.G));
}

} // namespace

namespace {

// ------------------------------------- 3. slide-hold-slide healing, fixed depth

struct Healing {
  double mu_pre = 0, mu_peak = 0, t_peak = 0, Fx_peak = 0, FN_peak = 0, FN_hold = 0, err = 0;
  double healing() const { return mu_peak - mu_pre; }
};

/// Vertex of the parabola through three points (x, y): the interpolated maximum.
std::pair<double, double> vertex(const double (&x)[3], const double (&y)[3]) {
  const double h0 = x[0] - x[1], h2 = x[2] - x[1];
  const double C = ((y[2] - y[1]) / h2 - (y[0] - y[1]) / h0) / (h2 - h0);
  const double B = (y[2] - y[1]) / h2 - C * h2;
  if (!(C < 0.0)) return {x[1], y[1]};
  return {x[1] - B / (2.0 * C), y[1] - B * B / (4.0 * C)};
}

/// Stationary sliding at v0, a hold of t_hold at the fixed depth, reslide at v0
/// for 20 a1/v0; samples log-spaced (100 per decade over 8 decades of each
/// segment). The peak is the largest reslide sample, refined by a parabola in
/// log t through it and its neighbours.
Healing shs(const Rheology& r, double v0, double t_hold, double rtol) {
  Case c = make_case(r, false);
  c.history.v0 = v0;
  c.history.segments = {Segment{0.0, t_hold}, Segment{v0, 20.0 / v0}};
  c.sampling.samples = 801;
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 8.0;
  SpectrumOptions so;
  so.rtol = rtol;
  const RunResult res = run_spectrum(c, so);
  const Series& s = res.series;
  const std::size_t n = static_cast<std::size_t>(c.sampling.samples);
  Healing h;
  h.mu_pre = s.pre.mu;
  h.FN_hold = s.FN[n - 1];
  h.err = res.info.error_estimate;
  std::size_t i = n + 1;
  for (std::size_t k = n + 1; k < 2 * n; ++k)
    if (s.mu[k] > s.mu[i]) i = k;
  h.mu_peak = s.mu[i], h.t_peak = s.t[i] - t_hold, h.Fx_peak = s.Fx[i], h.FN_peak = s.FN[i];
  if (i > n + 1 && i + 1 < 2 * n) {
    double x[3], y[3];
    for (int j = 0; j < 3; ++j) {
      const std::size_t k = i - 1 + static_cast<std::size_t>(j);
      x[j] = std::log(s.t[k] - t_hold), y[j] = s.mu[k];
    }
    const auto [xv, yv] = vertex(x, y);
    h.mu_peak = std::max(yv, s.mu[i]), h.t_peak = std::exp(xv);
  }
  return h;
}

} // namespace

namespace {

/// Healing over holds 10^lo .. 10^hi (in the longest tau_k = 1), `per` per
/// decade, rows into csv; prints beta per decade (healing(10 t) - healing(t)).
void healing_series(const char* name, const Rheology& r, double v0, double rtol, int lo, int hi,
                    std::ostream& csv, const std::string& label) {
  const int per = 4;
  std::vector<double> th, heal;
  double err = 0.0;
  for (int i = lo * per; i <= hi * per; ++i) {
    th.push_back(std::pow(10.0, static_cast<double>(i) / per));
    const Healing h = shs(r, v0, th.back(), rtol);
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

void part_healing(const Options& o) {
  auto csv = open_csv(o, "spectrum_healing.csv",
                      "spectrum,p,G0_over_G,v0_taumax_over_a1,t_hold,mu_pre,mu_peak,healing,"
                      "t_peak,Fx_peak,FN_peak,FN_hold,error_estimate");
  std::printf("\n# 3. Slide-hold-slide healing at fixed depth (run_spectrum, rtol %g): 6 terms a "
              "decade apart, tau_k = 1e-5..1, G_k ~ tau_k^p, sum G_k = G0 - G; beta = healing "
              "per decade of hold [mu in a1/R]\n",
              o.rtol);
  struct Run {
    double p, ratio, zeta; // p = NaN: sqrt_linear_spectrum
  };
  const Run runs[] = {{0.0, 100.0, 1e6},  {0.0, 100.0, 1e3},   {0.0, 10.0, 1e6},
                      {-0.1, 100.0, 1e6}, {-0.15, 100.0, 1e6}, {-0.25, 100.0, 1e6},
                      {-0.5, 100.0, 1e6}, {0.25, 100.0, 1e6},  {NAN, 100.0, 1e6}};
  for (int i = 1; i <= 9; ++i) {
    if (o.healing_run != 0 && o.healing_run != i) continue;
    const Run& run = runs[i - 1];
    char name[96];
    if (std::isnan(run.p))
      std::snprintf(name, sizeof name, "sqrt-linear G0/G=%g v0tau6/a1=%g", run.ratio, run.zeta);
    else
      std::snprintf(name, sizeof name, "p=%g G0/G=%g v0tau6/a1=%g", run.p, run.ratio, run.zeta);
    std::ostringstream label;
    label << "6x,";
    if (std::isnan(run.p))
      label << "sqrt";
    else
      label << run.p;
    label << "," << run.ratio << "," << run.zeta;
    const Rheology r = std::isnan(run.p) ? sqrt_linear_spectrum(6, run.ratio)
                                         : decade_spectrum(6, run.ratio, run.p);
    healing_series(name, r, run.zeta, o.rtol, -6, 4, csv, label.str());
  }
}

} // namespace

namespace {

// ------------------------------------- 4. the direct effect without a dashpot

/// Linear interpolation of mu in log t over the samples of segment 0 (t > 0).
double mu_at(const Series& s, std::size_t n, double t) {
  for (std::size_t k = 2; k < n; ++k)
    if (s.t[k] >= t) {
      const double f = std::log(t / s.t[k - 1]) / std::log(s.t[k] / s.t[k - 1]);
      return s.mu[k - 1] + f * (s.mu[k] - s.mu[k - 1]);
    }
  return s.mu[n - 1];
}

void direct_effect(const char* name, const Rheology& r, double v, double rtol, std::ostream& csv) {
  Case c = make_case(r, false);
  const double v1 = 10.0 * v, tmin = r.branches.front().tau;
  c.history.v0 = v;
  c.history.segments = {Segment{v1, std::max(40.0 / v1, 10.0 * r.branches.back().tau)}};
  c.sampling.samples = 1201;
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 12.0;
  SpectrumOptions so;
  so.rtol = rtol;
  const RunResult res = run_spectrum(c, so);
  const Series& s = res.series;
  const std::size_t n = s.size();
  for (std::size_t k = 0; k < n; ++k)
    csv << name << "," << s.t[k] / tmin << "," << s.mu[k] << "," << s.mu[k] - s.pre.mu << "\n";
  const std::size_t imax =
      static_cast<std::size_t>(std::max_element(s.mu.begin(), s.mu.end()) - s.mu.begin());
  std::printf("  %-22s mu_pre %.6g  mu(0+)-mu_pre %.2e  peak %.6g at t/tau_min %.3g (travel "
              "%.3g a1)  final %.6g  err %.1e\n    mu(t)-mu_pre at t/tau_min:",
              name, s.pre.mu, s.mu[0] - s.pre.mu, s.mu[imax], s.t[imax] / tmin, v1 * s.t[imax],
              s.mu[n - 1], res.info.error_estimate);
  for (double f : {1e-4, 1e-3, 1e-2, 1e-1, 1.0, 3.0, 10.0})
    std::printf(" %g: %.4g", f, mu_at(s, n, f * tmin) - s.pre.mu);
  std::printf(
      "\n    jump share (mu(t)-mu_pre)/(peak-mu_pre) at t/tau_min 0.1, 1, 3: %.3f %.3f %.3f\n",
      (mu_at(s, n, 0.1 * tmin) - s.pre.mu) / (s.mu[imax] - s.pre.mu),
      (mu_at(s, n, tmin) - s.pre.mu) / (s.mu[imax] - s.pre.mu),
      (mu_at(s, n, 3.0 * tmin) - s.pre.mu) / (s.mu[imax] - s.pre.mu));
}

void part_direct(const Options& o) {
  auto csv = open_csv(o, "spectrum_direct.csv", "spectrum,t_over_tau_min,mu_over_a1R,dmu");
  std::printf("\n# 4. Velocity step up v -> 10 v at fixed depth, tau = 0 (no parallel dashpot); "
              "z = v tau_min/a1 before the step\n");
  for (double z : {0.01, 0.1, 1.0, 10.0}) {
    char name[64];
    std::snprintf(name, sizeof name, "SLS G0/G=10 z=%g", z);
    direct_effect(name, decade_spectrum(1, 10.0), z, o.rtol, csv);
  }
  for (double z : {0.01, 0.1, 1.0}) {
    char name[64];
    std::snprintf(name, sizeof name, "6x G0/G=100 z=%g", z);
    direct_effect(name, decade_spectrum(6, 100.0), z / 1e-5, o.rtol, csv);
  }
}

// ------------------------------------------------------ 5. Lee-Radok creep

/// J(t) by the fixed Talbot inversion (Abate and Valko 2004) of
/// J_bar(s) = 1 / (s^2 G_bar(s)), G_bar(s) = G / s + sum G_k tau_k / (1 + s tau_k).
double talbot_J(const Rheology& r, double t) {
  using cd = std::complex<double>;
  const auto Jbar = [&r](cd s) {
    cd gbar = r.G / s;
    for (const Branch& b : r.branches)
      gbar += b.G * b.tau / (1.0 + s * b.tau);
    return 1.0 / (s * s * gbar);
  };
  const int M = 24;
  const double rr = 2.0 * M / (5.0 * t);
  double sum = 0.5 * std::exp(rr * t) * Jbar(cd(rr, 0.0)).real();
  for (int k = 1; k < M; ++k) {
    const double th = k * M_PI / M, cot = 1.0 / std::tan(th);
    const cd s = rr * th * cd(cot, 1.0);
    const cd sigma(1.0, th + (th * cot - 1.0) * cot);
    sum += (std::exp(t * s) * Jbar(s) * sigma).real();
  }
  return rr / M * sum;
}

/// d^(3/2)(t) = X(t) from the Lee-Radok integral C = int_0^t G(t - t') dX(t'),
/// C = 3 F0 / (16 sqrt R), X(0+) = C / G0, X piecewise linear on the grid
/// (product integration, the exponentials integrated exactly; second order).
std::vector<double> hereditary_X(const Rheology& r, double C, const std::vector<double>& t) {
  const double g0 = r.G0();
  std::vector<double> I(r.branches.size(), 0.0), X;
  double x = C / g0, prev = 0.0;
  for (double tn : t) {
    const double dt = tn - prev;
    double lhs = r.G * dt, rhs = C - r.G * x;
    for (std::size_t k = 0; k < r.branches.size(); ++k) {
      const Branch& b = r.branches[k];
      const double e = std::exp(-dt / b.tau);
      lhs += b.G * b.tau * (-std::expm1(-dt / b.tau));
      rhs -= b.G * (C / g0 * std::exp(-tn / b.tau) + e * I[k]);
      I[k] *= e;
    }
    const double slope = rhs / lhs;
    for (std::size_t k = 0; k < r.branches.size(); ++k)
      I[k] += slope * r.branches[k].tau * (-std::expm1(-dt / r.branches[k].tau));
    x += slope * dt;
    X.push_back(x);
    prev = tn;
  }
  return X;
}

/// Largest |d_hereditary / d_creep - 1| with `per` grid points per decade.
double hereditary_error(const Case& c, double C, double lo, double hi, int per) {
  const std::vector<double> t = logspace(lo, hi, per);
  const std::vector<double> X = hereditary_X(c.rheology, C, t);
  double e = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i)
    e = std::max(e, std::abs(std::cbrt(X[i] * X[i]) / creep_depth(c, t[i]) - 1.0));
  return e;
}

void creep_row(const char* name, const Rheology& r, std::ostream& csv) {
  const Case c = make_case(r, true);
  const double C = 3.0 * c.loading.F0 / (16.0 * std::sqrt(c.indenter.R));
  const double lo = 1e-4 * r.branches.front().tau, hi = 1e4 * r.branches.back().tau;
  const std::vector<double> t = logspace(lo, hi, 400);
  const std::vector<double> X = hereditary_X(r, C, t);
  double e_talbot = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double d = creep_depth(c, t[i]);
    const double d_t = std::cbrt(std::pow(C * talbot_J(r, t[i]), 2.0));
    e_talbot = std::max(e_talbot, std::abs(d_t / d - 1.0));
    if (i % 10 == 0)
      csv << name << "," << t[i] << "," << d << "," << d_t << "," << std::cbrt(X[i] * X[i]) << "\n";
  }
  std::printf("  %-14s d(0+) %.6g  d(inf) %.6g  max |d/d_creep - 1| over %zu times %g..%g: Talbot "
              "%.1e; hereditary, 100/200/400/800 per decade: %.1e %.1e %.1e %.1e\n",
              name, creep_depth(c, lo), creep_depth(c, 1e3 * hi), t.size(), lo, hi, e_talbot,
              hereditary_error(c, C, lo, hi, 100), hereditary_error(c, C, lo, hi, 200),
              hereditary_error(c, C, lo, hi, 400), hereditary_error(c, C, lo, hi, 800));
}

void part_creep(const Options& o) {
  auto csv = open_csv(o, "spectrum_creep.csv", "spectrum,t,d_creep,d_talbot,d_hereditary");
  std::printf("\n# 5. Lee-Radok creep under a step load F0 = 16/3 (a0 = d0 = 1 with G = 1): "
              "creep_depth against two independent computations\n");
  creep_row("SLS G0/G=10", decade_spectrum(1, 10.0), csv);
  creep_row("6x G0/G=100", decade_spectrum(6, 100.0), csv);
  creep_row("6x G0/G=1e4", decade_spectrum(6, 1e4), csv);
}

} // namespace

namespace {

[[noreturn]] void bad(const std::string& option, const std::string& what) {
  std::fprintf(stderr, "mdrmap_spectrum_physics: --%s %s\n", option.c_str(), what.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::printf("usage: mdrmap_spectrum_physics --out DIR [--pib FILE] [--part 1..5] "
                  "[--rtol R] [--healing-run 1..9]\n");
      std::exit(0);
    }
    if (i + 1 >= argc) bad(a.size() > 2 ? a.substr(2) : a, "needs a value");
    const std::string v = argv[++i];
    if (a == "--out")
      o.out = v;
    else if (a == "--pib")
      o.pib = v;
    else if (a == "--part") {
      o.part = std::atoi(v.c_str());
      if (o.part < 1 || o.part > 5) bad("part", "must be 1, 2, 3, 4 or 5");
    } else if (a == "--rtol") {
      o.rtol = std::atof(v.c_str());
      if (!(o.rtol > 0.0 && o.rtol <= 0.1)) bad("rtol", "must be in (0, 0.1]");
    } else if (a == "--healing-run") {
      o.healing_run = std::atoi(v.c_str());
      if (o.healing_run < 1 || o.healing_run > 9) bad("healing-run", "must be 1 to 9");
    } else
      bad(a.size() > 2 ? a.substr(2) : a,
          "is not an option (--out, --pib, --part, --rtol, --healing-run)");
  }
  if (o.out.empty()) bad("out", "is required: the directory the CSV files go into");
  return o;
}

} // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  try {
    const std::function<void(const Options&)> parts[] = {part_sls, part_width, part_healing,
                                                         part_direct, part_creep};
    for (int k = 1; k <= 5; ++k)
      if (o.part == 0 || o.part == k) {
        parts[k - 1](o);
        std::fflush(stdout);
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mdrmap_spectrum_physics: %s\n", e.what());
    return 1;
  }
  return 0;
}
