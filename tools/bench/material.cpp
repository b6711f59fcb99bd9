// mdrmap_bench_material: what a real material over a lab test costs, and how
// that cost grows with the distance slid (issue 35's scenes).
//
//   mdrmap_bench_material [--quick] [--reps N] [--pib FILE] [--out DIR]
//
// Scenes, each solved as `mdrmap simulate` solves it (run_case, solver auto),
// 201 samples a segment, at rtol 1e-3:
// - an elastomer: 11 Prony terms G_k = 89/11 (G = 1, G0/G = 90) at tau_k =
//   1e-9 .. 10 s, no parallel dashpot, a sphere R = 0.05 (mm, s, MPa, N),
//   the velocity-step test --v 0.1 --history 1:5,0.1:20,1:5 (about 470
//   contact radii of travel) under the load F0 = 0.01 and at the depth
//   d = 0.005, and a slide-hold-slide test under load with a 100 s hold;
// - polyisobutylene: the 30-term series of jobs/examples/pib_prony.csv (18
//   decades of tau_k, G = 1e5 Pa), R = 1 mm, SI units, the same test at
//   v = 0.1 mm/s under the load of the depth 10 um at v and at that depth.
// For each scene and for the same test with every segment 10x longer: the
// case error against the same case at rtol 1e-5 (--quick: 1e-4; marked * where
// the work budget refuses that and the reference is at 10x it), the
// estimate, the median CPU time of --reps runs (default 3) and the growth
// (10x time over 1x time). Prints the table and writes DIR/material.md and
// DIR/material.csv. The side-by-side comparison with an older build's
// `mdrmap` is tools/bench/compare_builds.py.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/metrics/error_metric.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/solvers/dispatch.hpp"
#include "stats.hpp"

namespace {

using namespace mdrmap;

struct Scene {
  std::string name;
  Case c;
};

/// Every segment's duration times `stretch`.
Case stretched(Case c, double stretch) {
  for (Segment& s : c.history.segments)
    s.T *= stretch;
  return c;
}

Case elastomer(double F0, double d, std::vector<Segment> segments) {
  Case c;
  c.indenter.as<Parabola>().R = 0.05;
  c.rheology.G = 1.0;
  c.rheology.tau = 0.0;
  for (int k = -9; k <= 1; ++k)
    c.rheology.branches.push_back({89.0 / 11.0, std::pow(10.0, k)});
  c.loading.F0 = F0;
  c.loading.d = d;
  c.history.v0 = 0.1;
  c.history.segments = std::move(segments);
  c.sampling.samples = 201;
  return c;
}

/// The G,tau rows of a Prony CSV (comment lines start with '#').
std::vector<Branch> read_prony(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<Branch> b;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) { // G,tau
      header = false;
      continue;
    }
    std::istringstream s(line);
    double G = 0, tau = 0;
    char comma = 0;
    if (!(s >> G >> comma >> tau) || comma != ',') throw std::runtime_error("bad row in " + path);
    b.push_back({G, tau});
  }
  return b;
}

Case pib(const std::vector<Branch>& terms, bool load) {
  Case c;
  c.indenter.as<Parabola>().R = 1e-3;
  c.rheology.G = 1e5;
  c.rheology.tau = 0.0;
  c.rheology.branches = terms;
  c.loading.d = 1e-5;
  c.history.v0 = 1e-4;
  c.history.segments = {{1e-3, 5.0}, {1e-4, 20.0}, {1e-3, 5.0}};
  c.sampling.samples = 201;
  if (load) {
    c.loading.F0 = spectrum_stationary(c, c.history.v0).FN;
    c.loading.d = 0.0;
  }
  return c;
}

std::vector<Scene> scenes(const std::string& pib_file) {
  const std::vector<Segment> steps = {{1.0, 5.0}, {0.1, 20.0}, {1.0, 5.0}};
  std::vector<Scene> all = {
      {"elastomer, load", elastomer(0.01, 0.0, steps)},
      {"elastomer, depth", elastomer(0.0, 0.005, steps)},
      {"elastomer, SHS 100 s, load", elastomer(0.01, 0.0, {{1.0, 5.0}, {0.0, 100.0}, {1.0, 5.0}})}};
  if (!pib_file.empty()) {
    const std::vector<Branch> terms = read_prony(pib_file);
    all.push_back({"PIB 30 terms, load", pib(terms, true)});
    all.push_back({"PIB 30 terms, depth", pib(terms, false)});
  }
  return all;
}

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

struct Measured {
  bool ok = false;
  std::string why;
  double err = 0, est = 0, ms = 0;
  bool loose_ref = false; ///< the reference at 10x ref_rtol (ref_rtol was refused)
};

/// The reference run at ref_rtol, or at 10 ref_rtol where that is refused.
RunResult reference(const Case& c, double ref_rtol, bool& loose) {
  try {
    loose = false;
    return run_case(CheckedCase(c), SolverKind::Auto, ref_rtol);
  } catch (const std::exception&) {
    loose = true;
    return run_case(CheckedCase(c), SolverKind::Auto, 10.0 * ref_rtol);
  }
}

Measured measure(const Case& c, double ref_rtol, int reps) {
  Measured m;
  try {
    const RunResult ref = reference(c, ref_rtol, m.loose_ref);
    std::vector<double> t;
    RunResult r;
    for (int i = 0; i < reps; ++i) {
      const double a = cpu_seconds();
      r = run_case(CheckedCase(c), SolverKind::Auto, 1e-3);
      t.push_back(1e3 * (cpu_seconds() - a));
    }
    m.err = case_error(r.series, ref.series, c, 1e-12).max();
    m.est = r.info.error_estimate;
    m.ms = bench::median(t);
    m.ok = true;
  } catch (const std::exception& e) {
    m.why = e.what();
  }
  return m;
}

std::string cell(double x, const char* fmt, bool mark = false) {
  char b[32];
  std::snprintf(b, sizeof b, fmt, x);
  return std::string(b) + (mark ? "*" : "");
}

} // namespace

int main(int argc, char** argv) {
  std::string out = ".", pib_file = MDRMAP_SOURCE_DIR "/jobs/examples/pib_prony.csv";
  bool quick = false;
  int reps = 3;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick"))
      quick = true;
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
      out = argv[++i];
    else if (!std::strcmp(argv[i], "--pib") && i + 1 < argc)
      pib_file = argv[++i];
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else {
      std::fprintf(stderr,
                   "usage: mdrmap_bench_material [--quick] [--reps N] [--pib FILE] [--out DIR]\n");
      return 2;
    }
  }
  const double ref_rtol = quick ? 1e-4 : 1e-5;
  std::ofstream md(out + "/material.md"), csv(out + "/material.csv");
  md << "| scene | error | estimate | CPU ms | 10x: error | 10x: CPU ms | growth |\n"
     << "|---|---|---|---|---|---|---|\n";
  csv << "scene,error,estimate,cpu_ms,error_10x,estimate_10x,cpu_ms_10x,growth\n";
  std::printf("rtol 1e-3, error against rtol %.0e (*: %.0e where that is refused), CPU "
              "median of %d\n",
              ref_rtol, 10.0 * ref_rtol, reps);
  std::printf("%-28s %10s %9s %9s %11s %11s %7s\n", "scene", "error", "estimate", "CPU ms",
              "10x error", "10x CPU ms", "growth");
  for (const Scene& s : scenes(pib_file)) {
    const Measured a = measure(s.c, ref_rtol, reps);
    const Measured b = measure(stretched(s.c, 10.0), ref_rtol, reps);
    if (!a.ok || !b.ok) {
      std::printf("%-28s failed: %s\n", s.name.c_str(), (a.ok ? b.why : a.why).c_str());
      md << "| " << s.name << " | failed: " << (a.ok ? b.why : a.why) << " ||||||\n";
      continue;
    }
    const double growth = b.ms / a.ms;
    std::printf("%-28s %10s %9.2e %9.1f %11s %11.1f %7.2f\n", s.name.c_str(),
                cell(a.err, "%.2e", a.loose_ref).c_str(), a.est, a.ms,
                cell(b.err, "%.2e", b.loose_ref).c_str(), b.ms, growth);
    md << "| " << s.name << " | " << cell(a.err, "%.2g", a.loose_ref) << " | "
       << cell(a.est, "%.2g") << " | " << cell(a.ms, "%.1f") << " | "
       << cell(b.err, "%.2g", b.loose_ref) << " | " << cell(b.ms, "%.1f") << " | "
       << cell(growth, "%.2f") << " |\n";
    csv << '"' << s.name << "\"," << a.err << ',' << a.est << ',' << a.ms << ',' << b.err << ','
        << b.est << ',' << b.ms << ',' << growth << '\n';
  }
  return 0;
}
