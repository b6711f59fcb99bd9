// mdrmap_bench_spectrum: work-precision benchmark of the spectrum solver
// (core/solvers/spectrum.hpp) against its fixed-step brute-force counterpart
// (spectrum_baseline.hpp), and of the Kelvin paths through it (issue 19's
// cost criterion).
//
//   mdrmap_bench_spectrum [--quick] [--out DIR]
//
// Scenes with a three-segment history (a tenfold step up, a hold of 100
// tau_ref, a reslide at v0): a 6-term spectrum (tau = 0, equal G_k a decade
// apart), the standard linear solid (tau = 0, G1 = 9 G) and the Kelvin
// foundation, each at fixed depth and under the load of its stationary
// sliding at v0 at that depth. For each: the case error against the solver at
// rtol 1e-7 (under load 1e-6; --quick: 1e-5), the estimate, and the median
// wall time at rtol 1e-3 and 1e-4; the brute-force solver at a1/dx 64, 128
// and 256 (fixed depth; under load 16, 32, 64), its observed order p and cost
// exponent q over them, the resolution where its error would equal the
// spectrum solver's at rtol 1e-3 and its time there, N^q extrapolated (it is
// not run there: at fixed depth a1/dx of several thousand, tens of minutes),
// and the ratio of that time to the spectrum solver's; for the Kelvin scenes
// also exact (depth) or kelvin_load (load). Prints the table and writes
// DIR/spectrum.md. Medians and ratios come from this one run.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/metrics/error_metric.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/load.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "stats.hpp"

namespace {

using namespace mdrmap;

struct Scene {
  std::string name;
  Case c;
};

Case three_segments(double tau, std::vector<Branch> branches) {
  Case c;
  c.loading.d = 0.1;
  c.indenter.as<Parabola>().R = 10.0; // a1 = 1
  c.rheology.G = 1.0;
  c.rheology.tau = tau;
  c.rheology.branches = std::move(branches);
  const double t_ref = c.rheology.longest_time() > 0 ? c.rheology.longest_time() : 1.0;
  c.history.v0 = 1.0 / t_ref; // v0 t_ref / a1 = 1
  c.history.segments = {
      {10.0 * c.history.v0, 2.0 * t_ref}, {0.0, 100.0 * t_ref}, {c.history.v0, 4.0 * t_ref}};
  c.sampling.samples = 61;
  return c;
}

/// The scene under the load of its stationary sliding at v0 (same contact).
Case under_load(Case c) {
  c.loading.F0 = spectrum_stationary(c, c.history.v0).FN;
  c.loading.d = 0.0;
  return c;
}

std::vector<Scene> scenes() {
  std::vector<Branch> six;
  for (int k = 0; k < 6; ++k)
    six.push_back({1.0, std::pow(10.0, k - 5)}); // 1e-5 .. 1, longest 1
  const std::vector<Scene> depth = {{"6-term spectrum", three_segments(0.0, six)},
                                    {"standard linear solid", three_segments(0.0, {{9.0, 1.0}})},
                                    {"Kelvin", three_segments(1.0, {})}};
  std::vector<Scene> all = depth;
  for (const Scene& s : depth)
    all.push_back({s.name + " load", under_load(s.c)});
  return all;
}

/// Median wall time of repeated calls: at least `reps` calls and 50 ms of
/// calls, at most 3 s.
double time_median(const std::function<void()>& f, int reps) {
  std::vector<double> t;
  double total = 0.0;
  for (int i = 0; (i < reps || total < 0.05) && total < 3.0; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
    total += t.back();
  }
  return bench::median(t);
}

struct Line {
  std::string scene, solver;
  double err = 0, est = 0, ms = 0;
};

double err_of(const RunResult& r, const RunResult& ref, const Case& c) {
  return case_error(r.series, ref.series, c, 1e-12).max();
}

Line spectrum_line(const Scene& s, const RunResult& ref, double rtol, int reps) {
  SpectrumOptions o;
  o.rtol = rtol;
  RunResult r;
  try {
    r = run_spectrum(CheckedCase(s.c), o);
  } catch (const CaseAbandoned&) { // over the work budget: said, not timed
    char name[64];
    std::snprintf(name, sizeof name, "spectrum rtol %g: over its budget", rtol);
    return {s.name, name, NAN, NAN, NAN};
  }
  const double sec = time_median([&] { run_spectrum(CheckedCase(s.c), o); }, reps);
  char name[64];
  std::snprintf(name, sizeof name, "spectrum rtol %g", rtol);
  return {s.name, name, err_of(r, ref, s.c), r.info.error_estimate, 1e3 * sec};
}

/// The reference: at fixed depth the solver at rtol 1e-7 (--quick 1e-5);
/// under load the load solver there on the Kelvin foundation, else the
/// spectrum solver at a fixed a1/dx of 256 (--quick 128; second order: a
/// small fraction of the error at rtol 1e-3, which runs at 32 to 50).
RunResult reference(const Case& c, bool quick) {
  const double rtol = quick ? 1e-5 : 1e-7;
  if (c.loading.by_force() && c.rheology.kelvin()) {
    LoadOptions l;
    l.rtol = rtol;
    return run_load(CheckedCase(c), l);
  }
  SpectrumOptions o;
  o.rtol = rtol;
  RunControl budget;
  budget.max_work = 1e12;
  o.control = &budget;
  if (c.loading.by_force()) {
    o.cells_per_a1 = quick ? 128 : 256;
    o.estimate_error = false;
  }
  return run_spectrum(CheckedCase(c), o);
}

/// The brute-force solver at three resolutions (doubling from n0): a line
/// each, then its observed order p and cost exponent q over the last two and
/// its time where its error would be `target` (N^q extrapolated; an estimate,
/// not a run), the resolution in the line's name.
std::vector<Line> baseline_lines(const Scene& s, const RunResult& ref, double target, double n0) {
  SpectrumBaselineOptions o;
  o.estimate_error = false;
  RunControl budget; // (under load at a1/dx 64: several 1e9 updates)
  budget.max_work = 1e12;
  o.control = &budget;
  std::vector<Line> out;
  double err[3], ms[3];
  for (int i = 0; i < 3; ++i) {
    o.cells_per_a1 = n0 * std::pow(2.0, i);
    err[i] = err_of(run_spectrum_baseline(CheckedCase(s.c), o), ref, s.c);
    ms[i] = 1e3 * time_median([&] { run_spectrum_baseline(CheckedCase(s.c), o); }, 1);
    char name[64];
    std::snprintf(name, sizeof name, "brute force a1/dx %g", o.cells_per_a1);
    out.push_back({s.name, name, err[i], 0.0, ms[i]});
  }
  const double p = std::log2(err[1] / err[2]), q = std::log2(ms[2] / ms[1]);
  const double grow = std::pow(err[2] / target, 1.0 / p); // resolution factor past the last
  char name[96];
  std::snprintf(name, sizeof name, "brute force p %.2f q %.2f at a1/dx %.0f (extrap.)", p, q,
                o.cells_per_a1 * grow);
  out.push_back({s.name, name, target, 0.0, ms[2] * std::pow(grow, q)});
  return out;
}

std::vector<Line> kelvin_lines(const Scene& s, const RunResult& ref, int reps) {
  if (s.c.loading.by_force()) {
    LoadOptions l;
    l.rtol = 1e-3;
    const RunResult r = run_load(CheckedCase(s.c), l);
    return {{s.name, "kelvin_load rtol 0.001", err_of(r, ref, s.c), r.info.error_estimate,
             1e3 * time_median([&] { run_load(CheckedCase(s.c), l); }, reps)}};
  }
  const RunResult re = run_exact(CheckedCase(s.c), 1e-3);
  return {{s.name, "exact rtol 0.001", err_of(re, ref, s.c), re.info.error_estimate,
           1e3 * time_median([&] { run_exact(CheckedCase(s.c), 1e-3); }, reps)}};
}

} // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out = ".";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick"))
      quick = true;
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
      out = argv[++i];
  }
  const int reps = quick ? 1 : 5;
  std::vector<Line> lines;
  for (const Scene& s : scenes()) {
    const bool load = s.c.loading.by_force();
    const RunResult ref = reference(s.c, quick);
    const Line a = spectrum_line(s, ref, 1e-3, reps);
    lines.push_back(a);
    lines.push_back(spectrum_line(s, ref, 1e-4, reps));
    for (const Line& b : baseline_lines(s, ref, a.err, load ? 16.0 : 64.0))
      lines.push_back(b);
    lines.push_back({s.name, "brute force (extrap.) / spectrum", 0, 0, lines.back().ms / a.ms});
    if (s.c.rheology.kelvin())
      for (const Line& k : kelvin_lines(s, ref, reps))
        lines.push_back(k);
  }
  std::ofstream md(out + "/spectrum.md");
  md << "| scene | solver | error | estimate | median ms |\n|---|---|---|---|---|\n";
  std::printf("%-27s %-46s %10s %10s %12s\n", "scene", "solver", "error", "estimate", "median ms");
  for (const Line& l : lines) {
    std::printf("%-27s %-46s %10.3g %10.3g %12.4g\n", l.scene.c_str(), l.solver.c_str(), l.err,
                l.est, l.ms);
    md << "| " << l.scene << " | " << l.solver << " | " << l.err << " | " << l.est << " | " << l.ms
       << " |\n";
  }
  return 0;
}
