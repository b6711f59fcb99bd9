// mdrmap_bench_spectrum: work-precision benchmark of the spectrum solver
// (core/solvers/spectrum.hpp) against its fixed-step brute-force counterpart
// (spectrum_baseline.hpp), and of the Kelvin paths through it (issue 19's
// cost criterion).
//
//   mdrmap_bench_spectrum [--quick] [--out DIR]
//
// Scenes at fixed depth, three-segment history (a tenfold step up, a hold of
// 100 tau_ref, a reslide at v0): a 6-term spectrum (tau = 0, equal G_k a
// decade apart), the standard linear solid (tau = 0, G1 = 9 G) and the Kelvin
// foundation. For each: the case error against the solver at rtol 1e-7, the
// estimate, and the median wall time at rtol 1e-3 and 1e-4; the brute-force
// solver at the resolution where its error first falls to the spectrum
// solver's error at rtol 1e-3 (a1/dx doubled from 32), and the ratio of their
// times; for the Kelvin scene also mdr and exact. Prints the table and writes
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
#include "core/solvers/exact.hpp"
#include "core/solvers/mdr.hpp"
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
  c.indenter.R = 10.0; // a1 = 1
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

std::vector<Scene> scenes() {
  std::vector<Branch> six;
  for (int k = 0; k < 6; ++k)
    six.push_back({1.0, std::pow(10.0, k - 5)}); // 1e-5 .. 1, longest 1
  return {{"6-term spectrum", three_segments(0.0, six)},
          {"standard linear solid", three_segments(0.0, {{9.0, 1.0}})},
          {"Kelvin", three_segments(1.0, {})}};
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
  const RunResult r = run_spectrum(s.c, o);
  const double sec = time_median([&] { run_spectrum(s.c, o); }, reps);
  char name[64];
  std::snprintf(name, sizeof name, "spectrum rtol %g", rtol);
  return {s.name, name, err_of(r, ref, s.c), r.info.error_estimate, 1e3 * sec};
}

/// The brute-force solver at the first a1/dx (doubling from 32) whose error
/// is at most `target`, or its finest try.
Line baseline_line(const Scene& s, const RunResult& ref, double target, bool quick) {
  SpectrumBaselineOptions o;
  o.estimate_error = false;
  RunResult r;
  double err = 0.0;
  const double finest = quick ? 256 : 8192;
  for (o.cells_per_a1 = 32; o.cells_per_a1 <= finest; o.cells_per_a1 *= 2) {
    r = run_spectrum_baseline(s.c, o);
    err = err_of(r, ref, s.c);
    if (err <= target) break;
  }
  if (o.cells_per_a1 > finest) o.cells_per_a1 /= 2;
  const double sec = time_median([&] { run_spectrum_baseline(s.c, o); }, 1);
  char name[64];
  std::snprintf(name, sizeof name, "brute force a1/dx %g", o.cells_per_a1);
  return {s.name, name, err, 0.0, 1e3 * sec};
}

std::vector<Line> kelvin_lines(const Scene& s, const RunResult& ref, int reps) {
  MdrOptions m;
  m.rtol = 1e-3;
  const RunResult rm = run_mdr(s.c, m);
  const RunResult re = run_exact(s.c, 1e-3);
  return {{s.name, "mdr rtol 0.001", err_of(rm, ref, s.c), rm.info.error_estimate,
           1e3 * time_median([&] { run_mdr(s.c, m); }, reps)},
          {s.name, "exact rtol 0.001", err_of(re, ref, s.c), re.info.error_estimate,
           1e3 * time_median([&] { run_exact(s.c, 1e-3); }, reps)}};
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
    SpectrumOptions fine;
    fine.rtol = quick ? 1e-5 : 1e-7;
    const RunResult ref = run_spectrum(s.c, fine);
    const Line a = spectrum_line(s, ref, 1e-3, reps);
    lines.push_back(a);
    lines.push_back(spectrum_line(s, ref, 1e-4, reps));
    const Line b = baseline_line(s, ref, a.err, quick);
    lines.push_back(b);
    lines.push_back({s.name, "brute force / spectrum time", 0, 0, b.ms / a.ms});
    if (s.c.rheology.kelvin())
      for (const Line& k : kelvin_lines(s, ref, reps))
        lines.push_back(k);
  }
  std::ofstream md(out + "/spectrum.md");
  md << "| scene | solver | error | estimate | median ms |\n|---|---|---|---|---|\n";
  std::printf("%-22s %-30s %10s %10s %12s\n", "scene", "solver", "error", "estimate", "median ms");
  for (const Line& l : lines) {
    std::printf("%-22s %-30s %10.3g %10.3g %12.4g\n", l.scene.c_str(), l.solver.c_str(), l.err,
                l.est, l.ms);
    md << "| " << l.scene << " | " << l.solver << " | " << l.err << " | " << l.est << " | " << l.ms
       << " |\n";
  }
  return 0;
}
