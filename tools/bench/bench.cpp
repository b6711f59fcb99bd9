// mdrmap_bench: work-precision benchmark of the solvers (issue 3).
//
// Runs each solver at a ladder of accuracy settings over the fixed hard case
// set (cases/case_set.hpp, 42 one-step scenes, each as step_case builds it:
// the default window 6 tau, 201 samples), measures for every (setting, scene) the wall time of one
// call (median of repeats) and the case error against the continuum solution at rtol 1e-12, and
// writes
//   - a summary CSV (one row per setting and case subset),
//   - a per-case CSV (one row per setting and scene),
//   - a Markdown report: machine, tables, the cost targets, peak RSS.
// The fixed-step baseline is run only on the scenes where it is affordable
// (see baseline_updates); every other solver is reported on that same subset
// too, so ratios compare like with like.
//
// Peak memory is measured in child processes (this program re-executed with
// --rss-probe NAME): each child runs one case and exits; the parent reads its
// ru_maxrss from wait4.
//
// Usage: mdrmap_bench --help
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cases/case_set.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "mdrmap/version.hpp"
#include "stats.hpp"

namespace {

using namespace mdrmap;
using Clock = std::chrono::steady_clock;

constexpr const char* kUsage = R"(mdrmap_bench: work-precision benchmark of the mdrmap solvers.

Usage:
  mdrmap_bench [--quick] [--out-dir DIR] [--machine-file FILE] [--command TEXT]
  mdrmap_bench --profile SETTING [--repeat N]
  mdrmap_bench --rss-probe NAME
  mdrmap_bench --help

Options:
  --quick              smoke run (seconds): every scene, short ladders, one
                       timed call per (setting, scene)
  --out-dir DIR        where bench.csv, bench_cases.csv and bench.md go
                       (default: out/bench)
  --machine-file FILE  text describing the machine (lscpu, compiler), copied
                       into bench.md
  --command TEXT       the command line to quote in bench.md
  --profile SETTING    run one setting over the case set without references
                       or output, for a profiler (valgrind --tool=callgrind,
                       perf record): row (rtol 1e-3), auto (simulate default,
                       rtol 1e-4), exact (rtol 1e-10), baseline (a1/dx = 500,
                       on the baseline subset)
  --repeat N           passes over the case set in --profile mode (default 1)
  --rss-probe NAME     internal: run one memory probe and print its result
)";

// ---------------------------------------------------------------------------
// Case set and the baseline subset

struct BenchCase {
  std::string name;
  Case input; ///< the scene: one step, its window and samples
  RunResult ref;
  bool baseline_ok = false;      ///< in the baseline subset
  double baseline_updates = 0.0; ///< element updates of the baseline at a1/dx = 500
};

constexpr double kBaselineTopCells = 500.0;     // the costliest baseline rung
constexpr double kBaselineUpdateBudget = 2.0e8; // element updates allowed at that rung

// Element updates of the baseline at `cells` = a1/dx with default options
// (SpectrumBaselineOptions: spin-up 4 a1, dt = dx / max(v, v1), each segment cut into
// whole steps): elements over the whole travel path, each visited at every step.
double baseline_updates(const Case& c, double cells) {
  const double a1 = c.a1(), dx = a1 / cells, v = c.history.v0;
  double wmax = v;
  for (const Segment& seg : c.history.segments)
    wmax = std::max(wmax, seg.w);
  const double dt = dx / wmax;
  const double n_pre = std::ceil(4.0 * a1 / (v * dt));
  double steps = n_pre, travel = v * dt * n_pre;
  for (const Segment& seg : c.history.segments) {
    steps += std::max(1.0, std::ceil(seg.T / dt));
    travel += seg.w * seg.T;
  }
  const double n_elem = std::ceil((2.0 * a1 + travel) / dx) + 4.0;
  return n_elem * steps;
}

std::vector<BenchCase> make_cases(bool with_reference) {
  std::vector<BenchCase> out;
  const auto set = hard_case_set();
  for (std::size_t i = 0; i < set.size(); ++i) {
    BenchCase c;
    c.name = set[i].name;
    c.input = set[i].c;
    if (with_reference) c.ref = run_exact(CheckedCase(c.input), 1e-12);
    c.baseline_updates = baseline_updates(c.input, kBaselineTopCells);
    c.baseline_ok = c.baseline_updates <= kBaselineUpdateBudget;
    out.push_back(std::move(c));
  }
  return out;
}

// ---------------------------------------------------------------------------
// Settings: one solver at one accuracy setting

using Runner = std::function<RunResult(const Case&)>;

struct Setting {
  std::string solver; ///< family: exact, auto, row, baseline
  std::string label;  ///< e.g. "rtol=1e-04", "a1/dx=500"
  double param = 0;   ///< rtol or a1/dx
  double rtol = 0;    ///< tolerance promised (0: none, fixed resolution)
  bool subset_only = false;
  Runner run;
};

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

Setting exact_setting(double rtol) {
  return {"exact", "rtol=" + fmt("%.0e", rtol),
          rtol,    rtol,
          false,   [rtol](const Case& c) { return run_exact(CheckedCase(c), rtol); }};
}

Setting auto_setting(double rtol) {
  return {
      "auto", "rtol=" + fmt("%.0e", rtol),
      rtol,   rtol,
      false,  [rtol](const Case& c) { return run_case(CheckedCase(c), SolverKind::Auto, rtol); }};
}

Setting row_setting(double rtol) {
  return {"row", "rtol=" + fmt("%.0e", rtol), rtol, rtol, false, [rtol](const Case& c) {
            SpectrumOptions o;
            o.rtol = rtol;
            return run_spectrum(CheckedCase(c), o);
          }};
}

Setting baseline_setting(double cells) {
  return {"baseline", "a1/dx=" + fmt("%g", cells), cells, 0.0, true, [cells](const Case& c) {
            SpectrumBaselineOptions o; // the method alone: no half-resolution companion
            o.cells_per_a1 = cells;
            o.estimate_error = false;
            return run_spectrum_baseline(CheckedCase(c), o);
          }};
}

std::vector<Setting> make_settings(bool quick) {
  std::vector<Setting> out;
  const std::vector<double> exact_rtols =
      quick ? std::vector<double>{1e-3, 1e-6, 1e-10}
            : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-12};
  for (double r : exact_rtols)
    out.push_back(exact_setting(r));
  out.push_back(auto_setting(1e-4)); // `mdrmap simulate` at its defaults
  const std::vector<double> row_rtols = quick ? std::vector<double>{1e-2, 1e-3, 1e-4}
                                              : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-6, 1e-8};
  for (double r : row_rtols)
    out.push_back(row_setting(r));
  const std::vector<double> bcells =
      quick ? std::vector<double>{50, 500} : std::vector<double>{50, 100, 200, 500};
  for (double n : bcells)
    out.push_back(baseline_setting(n));
  return out;
}

// ---------------------------------------------------------------------------
// Measurement

struct TimingPolicy {
  int min_reps = 3;        ///< at least this many timed calls ...
  double min_total = 2e-3; ///< ... and at least this much time in total (s) ...
  double max_total = 0.5;  ///< ... unless the calls so far took this long (expensive runs)
  int max_reps = 2000;
};

struct CaseResult {
  bool covered = false; ///< false: the solver refused the scene (too expensive)
  std::string note;     ///< the refusal
  double seconds = 0;   ///< median wall time of one call
  int reps = 0;
  double error = 0;
  double estimate = 0;
  double cells = 0;
  long elements = 0;
};

using mdrmap::bench::median;

CaseResult measure(const Setting& st, const BenchCase& c, const TimingPolicy& pol) {
  CaseResult r;
  std::vector<double> times;
  RunResult last;
  double total = 0.0;
  try {
    do {
      const auto t0 = Clock::now();
      RunResult run = st.run(c.input);
      const auto t1 = Clock::now();
      const double dt = std::chrono::duration<double>(t1 - t0).count();
      times.push_back(dt);
      total += dt;
      last = std::move(run);
    } while (static_cast<int>(times.size()) < pol.max_reps && total < pol.max_total &&
             (static_cast<int>(times.size()) < pol.min_reps || total < pol.min_total));
  } catch (const std::runtime_error& e) { // the baseline refuses scenes it cannot afford
    r.note = e.what();
    return r;
  }
  r.covered = true;
  r.seconds = median(times);
  r.reps = static_cast<int>(times.size());
  r.error = case_error(last.series, c.ref.series, c.input).max();
  r.estimate = last.info.error_estimate;
  r.cells = last.info.cells_per_a1;
  r.elements = last.info.elements;
  return r;
}

// Honesty of the error estimate: estimate / true error (infinite when the
// true error is zero).
double est_ratio(const CaseResult& r) {
  if (r.error == 0.0) return std::numeric_limits<double>::infinity();
  return r.estimate / r.error;
}

struct Row {
  const Setting* setting = nullptr;
  std::string subset; ///< "all" or "baseline-subset"
  int cases = 0, covered = 0;
  double median_s = NAN, max_s = NAN, total_s = 0;
  double max_err = NAN, median_err = NAN, min_ratio = NAN;
  std::string worst_err_case, worst_ratio_case;
  bool meets_rtol = true;    ///< max error <= rtol (settings that promise one)
  bool honest = true;        ///< 3 * estimate >= error on every covered case
  bool has_estimate = false; ///< some run reported a non-zero error estimate
};

Row summarize(const Setting& st, const std::vector<BenchCase>& cases,
              const std::vector<CaseResult>& res, bool subset) {
  Row row;
  row.setting = &st;
  row.subset = subset ? "baseline-subset" : "all";
  std::vector<double> t, e;
  double worst = -1.0, min_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (subset && !cases[i].baseline_ok) continue;
    if (!subset && st.subset_only) continue;
    ++row.cases;
    const CaseResult& r = res[i];
    if (!r.covered) continue;
    ++row.covered;
    t.push_back(r.seconds);
    e.push_back(r.error);
    row.total_s += r.seconds;
    if (r.error > worst) worst = r.error, row.worst_err_case = cases[i].name;
    const double q = est_ratio(r);
    if (q < min_ratio) min_ratio = q, row.worst_ratio_case = cases[i].name;
    if (3.0 * r.estimate < r.error) row.honest = false;
    if (r.estimate > 0.0) row.has_estimate = true;
  }
  if (row.covered > 0) {
    row.median_s = median(t);
    row.max_s = *std::max_element(t.begin(), t.end());
    row.max_err = worst;
    row.median_err = median(e);
    row.min_ratio = min_ratio;
    if (st.rtol > 0.0) row.meets_rtol = worst <= st.rtol;
  }
  return row;
}

// ---------------------------------------------------------------------------
// Memory probes (child processes)

struct Probe {
  std::string name;
  std::string what;
  std::function<RunResult()> run; ///< empty: the idle floor
};

// d = 1e-3, R = 1, tau = 1: the step zeta_ -> v1_over_v zeta_, default window
// (6 tau) and samples (201).
Case probe_case(double zeta_, double v1_over_v) {
  const double d = 1e-3, R = 1.0, tau = 1.0;
  const double v = zeta_ * std::sqrt(R * d) / tau;
  return step_case(d, R, tau, v, v1_over_v * v);
}

RunResult probe_row(const Case& c, double cells) {
  SpectrumOptions o;
  o.rtol = 1e-3;
  if (cells > 0) {
    o.cells_per_a1 = cells;
    o.estimate_error = false;
  }
  return run_spectrum(CheckedCase(c), o);
}

// steps_per_cell < 1: a coarser time step than the baseline's dx / max(v, v1),
// for a memory probe whose run at the proper step would take minutes.
RunResult probe_baseline(const Case& c, double steps_per_cell = 1.0) {
  SpectrumBaselineOptions o;
  o.cells_per_a1 = kBaselineTopCells;
  o.estimate_error = false;
  o.steps_per_cell = steps_per_cell;
  return run_spectrum_baseline(CheckedCase(c), o);
}

std::vector<Probe> make_probes() {
  // Reference scene: zeta = v tau / a1 = 1, drop to v1/v = 0.1: the indenter
  // travels 0.6 a1 after the step. v1/v = 1e-8: 6e-8 a1. Long travel:
  // v1 tau / a1 = 1e8 (zeta = 1e9, v1/v = 0.1): 6e8 a1.
  const Case shrt = probe_case(1.0, 0.1), slow = probe_case(1.0, 1e-8), lng = probe_case(1e9, 0.1),
             b600 = probe_case(1.0, 100.0);
  std::vector<Probe> p;
  p.push_back({"idle", "no run: the process floor", {}});
  p.push_back({"row-short", "row rtol 1e-3, zeta 1, v1/v 0.1 (travel 0.6 a1)",
               [=] { return probe_row(shrt, 0); }});
  p.push_back(
      {"row-v1v-1e-8", "row rtol 1e-3, zeta 1, v1/v 1e-8", [=] { return probe_row(slow, 0); }});
  p.push_back({"row-long", "row rtol 1e-3, v1 tau/a1 1e8 (travel 6e8 a1)",
               [=] { return probe_row(lng, 0); }});
  p.push_back(
      {"row1e4-short", "row a1/dx 1e4, zeta 1, v1/v 0.1", [=] { return probe_row(shrt, 1e4); }});
  p.push_back({"row1e4-v1v-1e-8", "row a1/dx 1e4, zeta 1, v1/v 1e-8",
               [=] { return probe_row(slow, 1e4); }});
  p.push_back({"row1e4-long", "row a1/dx 1e4, v1 tau/a1 1e8", [=] { return probe_row(lng, 1e4); }});
  p.push_back({"baseline-short", "baseline a1/dx 500, zeta 1, v1/v 0.1 (travel 4.6 a1)",
               [=] { return probe_baseline(shrt); }});
  // memory only: at the baseline's dt = dx / v1 this run needs ~1.5e11 element
  // updates; dt = dx / v (steps_per_cell = v/v1) holds the same elements
  p.push_back({"baseline-travel600",
               "baseline a1/dx 500, zeta 1, v1/v 100 (travel 604 a1; dt = dx/v, memory only)",
               [=] { return probe_baseline(b600, 0.01); }});
  p.push_back(
      {"baseline-long", "baseline a1/dx 500, v1 tau/a1 1e8", [=] { return probe_baseline(lng); }});
  return p;
}

// In the child: run the probe, print one line of key=value pairs.
int run_probe(const std::string& name) {
  for (const Probe& p : make_probes()) {
    if (p.name != name) continue;
    if (!p.run) {
      std::printf("status=ok elements=0 cells=0\n");
      return 0;
    }
    try {
      const RunResult r = p.run();
      std::printf("status=ok elements=%ld cells=%g\n", r.info.elements, r.info.cells_per_a1);
    } catch (const std::runtime_error& e) {
      std::printf("status=refused elements=0 cells=0 note=%s\n", e.what());
    }
    return 0;
  }
  std::fprintf(stderr, "mdrmap_bench: unknown --rss-probe '%s'\n", name.c_str());
  return 2;
}

struct ProbeResult {
  const Probe* probe = nullptr;
  long rss_kib = -1;
  std::string output;
  bool ok = false;
};

std::string self_exe() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw std::runtime_error("cannot read /proc/self/exe");
  buf[n] = '\0';
  return buf;
}

ProbeResult spawn_probe(const std::string& exe, const Probe& probe) {
  ProbeResult out;
  out.probe = &probe;
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    dup2(fd[1], STDOUT_FILENO);
    close(fd[0]);
    close(fd[1]);
    std::string a0 = exe, a1 = "--rss-probe", a2 = probe.name;
    char* argv[] = {a0.data(), a1.data(), a2.data(), nullptr};
    execv(exe.c_str(), argv);
    _exit(127);
  }
  close(fd[1]);
  char buf[512];
  ssize_t n;
  while ((n = read(fd[0], buf, sizeof buf)) > 0)
    out.output.append(buf, static_cast<std::size_t>(n));
  close(fd[0]);
  int status = 0;
  struct rusage ru {};
  if (wait4(pid, &status, 0, &ru) != pid) throw std::runtime_error("wait4 failed");
  out.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  out.rss_kib = ru.ru_maxrss; // Linux: KiB
  while (!out.output.empty() && out.output.back() == '\n')
    out.output.pop_back();
  return out;
}

std::string field(const std::string& line, const std::string& key) {
  const std::string k = key + "=";
  const auto pos = line.find(k);
  if (pos == std::string::npos) return "";
  const auto start = pos + k.size();
  if (key == "note") return line.substr(start);
  return line.substr(start, line.find(' ', start) - start);
}

// ---------------------------------------------------------------------------
// Machine description

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---------------------------------------------------------------------------
// Output

std::string e2(double x) { // errors: as they are, rounding level included
  if (std::isnan(x)) return "-";
  return fmt("%.2e", x);
}

std::string ms(double seconds) {
  if (std::isnan(seconds)) return "-";
  const double m = seconds * 1e3;
  if (m >= 100) return fmt("%.0f", m);
  if (m >= 10) return fmt("%.1f", m);
  if (m >= 1) return fmt("%.2f", m);
  return fmt("%.3f", m);
}

std::string ratio_str(double q) {
  if (std::isnan(q)) return "-";
  if (std::isinf(q)) return "inf";
  return fmt("%.2g", q);
}

void write_summary_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "solver,setting,param,rtol,subset,cases,covered,median_time_s,max_time_s,total_time_s,"
       "max_error,median_error,min_estimate_over_error,meets_rtol,honest,worst_error_case,"
       "worst_estimate_case\n";
  f.precision(6);
  for (const Row& r : rows) {
    const Setting& s = *r.setting;
    f << s.solver << ',' << s.label << ',' << s.param << ',' << s.rtol << ',' << r.subset << ','
      << r.cases << ',' << r.covered << ',' << r.median_s << ',' << r.max_s << ',' << r.total_s
      << ',' << r.max_err << ',' << r.median_err << ',' << r.min_ratio << ','
      << (r.meets_rtol ? 1 : 0) << ',' << (r.honest ? 1 : 0) << ",\"" << r.worst_err_case << "\",\""
      << r.worst_ratio_case << "\"\n";
  }
}

void write_cases_csv(const std::string& path, const std::vector<Setting>& settings,
                     const std::vector<BenchCase>& cases,
                     const std::vector<std::vector<CaseResult>>& res) {
  std::ofstream f(path);
  f << "solver,setting,case,name,baseline_subset,covered,time_s,reps,error,error_estimate,"
       "cells_per_a1,elements\n";
  f.precision(6);
  for (std::size_t s = 0; s < settings.size(); ++s)
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const CaseResult& r = res[s][i];
      if (settings[s].subset_only && !cases[i].baseline_ok) continue;
      f << settings[s].solver << ',' << settings[s].label << ',' << i << ",\"" << cases[i].name
        << "\"," << (cases[i].baseline_ok ? 1 : 0) << ',' << (r.covered ? 1 : 0) << ',' << r.seconds
        << ',' << r.reps << ',' << r.error << ',' << r.estimate << ',' << r.cells << ','
        << r.elements << '\n';
    }
}

void md_table(std::ostream& o, const std::vector<Row>& rows, const std::string& subset) {
  o << "| solver | setting | scenes run | median ms/case | max ms/case | max error | median "
       "error | min estimate/error | within rtol |\n"
       "|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    if (r.subset != subset) continue;
    const Setting& s = *r.setting;
    o << "| " << s.solver << " | " << s.label << " | " << r.covered << '/' << r.cases << " | "
      << ms(r.median_s) << " | " << ms(r.max_s) << " | " << e2(r.max_err) << " | "
      << e2(r.median_err) << " | " << (r.has_estimate ? ratio_str(r.min_ratio) : "none") << " | "
      << (s.rtol > 0 ? (r.meets_rtol ? "yes" : "**no**") : "-") << " |\n";
  }
}

const Row* find_row(const std::vector<Row>& rows, const std::string& solver,
                    const std::string& label, const std::string& subset) {
  for (const Row& r : rows)
    if (r.setting->solver == solver && r.setting->label == label && r.subset == subset) return &r;
  return nullptr;
}

// ---------------------------------------------------------------------------
// Profile mode

int run_profile(const std::string& which, int repeat) {
  const auto cases = make_cases(false);
  Setting st;
  if (which == "row")
    st = row_setting(1e-3);
  else if (which == "auto")
    st = auto_setting(1e-4);
  else if (which == "exact")
    st = exact_setting(1e-10);
  else if (which == "baseline")
    st = baseline_setting(kBaselineTopCells);
  else {
    std::fprintf(stderr, "mdrmap_bench: --profile takes row, auto, exact or baseline\n");
    return 2;
  }
  const auto t0 = Clock::now();
  double checksum = 0.0;
  int runs = 0;
  for (int k = 0; k < repeat; ++k)
    for (const BenchCase& c : cases) {
      if (st.subset_only && !c.baseline_ok) continue;
      const RunResult r = st.run(c.input);
      checksum += r.series.FN.back();
      ++runs;
    }
  const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("profile %s %s: %d runs in %.3f s (%.3f ms/run), checksum %.6g\n", st.solver.c_str(),
              st.label.c_str(), runs, secs, 1e3 * secs / runs, checksum);
  return 0;
}

// ---------------------------------------------------------------------------

// Honesty of the error estimates of one solver family.
struct Honesty {
  std::string family;
  int runs = 0, below = 0, without = 0; ///< runs, runs with estimate < error/3, estimate == 0
  double min_ratio = std::numeric_limits<double>::infinity();
  std::string where;
};

std::vector<Honesty> honesty_by_family(const std::vector<Setting>& settings,
                                       const std::vector<BenchCase>& cases,
                                       const std::vector<std::vector<CaseResult>>& res) {
  std::vector<Honesty> out;
  for (std::size_t s = 0; s < settings.size(); ++s) {
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const Honesty& h) { return h.family == settings[s].solver; });
    if (it == out.end()) {
      out.push_back({settings[s].solver, 0, 0, 0, std::numeric_limits<double>::infinity(), ""});
      it = out.end() - 1;
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const CaseResult& r = res[s][i];
      if (!r.covered) continue;
      ++it->runs;
      if (r.estimate == 0.0) ++it->without;
      if (3.0 * r.estimate < r.error) ++it->below;
      const double q = est_ratio(r);
      if (q < it->min_ratio)
        it->min_ratio = q, it->where = settings[s].label + ", '" + cases[i].name + "'";
    }
  }
  return out;
}

int run_bench(bool quick, const std::string& out_dir, const std::string& machine_file,
              const std::string& command) {
  const auto t_start = Clock::now();
  std::fprintf(stderr, "bench: references (run_exact at rtol 1e-12) ...\n");
  const auto cases = make_cases(true);
  const auto settings = make_settings(quick);
  TimingPolicy pol;
  if (quick) pol.min_reps = 1, pol.min_total = 0.0;
  int n_subset = 0;
  for (const BenchCase& c : cases)
    n_subset += c.baseline_ok ? 1 : 0;

  std::vector<std::vector<CaseResult>> res(settings.size());
  for (std::size_t s = 0; s < settings.size(); ++s) {
    const auto t0 = Clock::now();
    res[s].resize(cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
      if (settings[s].subset_only && !cases[i].baseline_ok) continue;
      res[s][i] = measure(settings[s], cases[i], pol);
    }
    std::fprintf(stderr, "bench: %-10s %-12s %6.1f s\n", settings[s].solver.c_str(),
                 settings[s].label.c_str(),
                 std::chrono::duration<double>(Clock::now() - t0).count());
  }

  std::vector<Row> rows;
  for (std::size_t s = 0; s < settings.size(); ++s) {
    if (!settings[s].subset_only) rows.push_back(summarize(settings[s], cases, res[s], false));
  }
  for (std::size_t s = 0; s < settings.size(); ++s)
    rows.push_back(summarize(settings[s], cases, res[s], true));
  const auto honesty = honesty_by_family(settings, cases, res);

  // Memory probes.
  std::fprintf(stderr, "bench: memory probes ...\n");
  const std::string exe = self_exe();
  const auto probes = make_probes();
  std::vector<ProbeResult> pres;
  for (const Probe& p : probes)
    pres.push_back(spawn_probe(exe, p));
  auto probe_rss = [&](const std::string& name) -> long {
    for (const auto& r : pres)
      if (r.probe->name == name) return r.rss_kib;
    return -1;
  };

  // Cost ratio, all from this run: baseline at the top rung against the
  // simulate default, on the baseline subset.
  const std::string top = "a1/dx=" + fmt("%g", kBaselineTopCells);
  std::size_t sb = settings.size(), sa = settings.size();
  for (std::size_t s = 0; s < settings.size(); ++s) {
    if (settings[s].solver == "baseline" && settings[s].label == top) sb = s;
    if (settings[s].solver == "auto") sa = s;
  }
  const Row* base_top = find_row(rows, "baseline", top, "baseline-subset");
  const Row* auto_sub = find_row(rows, "auto", "rtol=1e-04", "baseline-subset");
  const Row* row3 = find_row(rows, "row", "rtol=1e-03", "all");
  const double cost_ratio =
      (base_top && auto_sub) ? base_top->median_s / auto_sub->median_s : std::nan("");
  // per scene: measured on the subset; a cost model (measured seconds per
  // element update times the element updates) for every scene
  std::vector<double> case_ratio, per_update, model_ratio;
  int case_ratio_ok = 0, model_ratio_ok = 0;
  if (sb < settings.size() && sa < settings.size()) {
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (cases[i].baseline_ok && res[sb][i].covered) {
        const double q = res[sb][i].seconds / res[sa][i].seconds;
        case_ratio.push_back(q);
        case_ratio_ok += q >= 1000.0 ? 1 : 0;
        per_update.push_back(res[sb][i].seconds / cases[i].baseline_updates);
      }
    const double c = median(per_update);
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const double q = c * cases[i].baseline_updates / res[sa][i].seconds;
      model_ratio.push_back(q);
      model_ratio_ok += q >= 1000.0 ? 1 : 0;
    }
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - t_start).count();

  // ---- outputs
  std::filesystem::create_directories(out_dir);
  const std::string csv = out_dir + "/bench.csv", ccsv = out_dir + "/bench_cases.csv",
                    mdp = out_dir + "/bench.md";
  write_summary_csv(csv, rows);
  write_cases_csv(ccsv, settings, cases, res);

  std::ostringstream md;
  md << "### Machine\n\n";
  md << "- CPU: " << cpu_model() << ", " << std::thread::hardware_concurrency()
     << " logical cores (the benchmark runs on one)\n";
  md << "- Compiler: " << __VERSION__ << " ("
#ifdef NDEBUG
     << "optimised, NDEBUG"
#else
     << "assertions on: not a Release build"
#endif
     << ")\n";
  md << "- mdrmap " << kVersion << ", commit " << kGitCommit << "; measured " << utc_now()
     << (quick ? "; **--quick smoke run: not the documented figures**" : "") << "\n";
  md << "- Benchmark wall time: " << fmt("%.0f", elapsed) << " s\n";
  if (!machine_file.empty()) {
    const std::string m = read_file(machine_file);
    if (!m.empty()) md << "\n```\n" << m << (m.back() == '\n' ? "" : "\n") << "```\n";
  }
  md << "\nCommand: `" << (command.empty() ? "mdrmap_bench" : command) << "`\n\n";

  md << "### Case set and method\n\n";
  md << cases.size()
     << " scenes of `hard_case_set()` (tests/cases/case_set.cpp), default protocol ("
     << "t_end = 6 tau, or 6 a1 / min(v, v1) for tau = 0; 201 samples). Error: the case error of "
        "docs/design.md, \"Error metric\" (largest relative deviation of F_N, F_x, mu; a2 in units "
        "of a1) against `run_exact` at rtol 1e-12 (so the exact row at 1e-12 is the reference "
        "itself). "
        "Time: wall time of one solver call (std::chrono::steady_clock), the median of "
     << (quick ? "1 call" : "at least 3 calls (repeated until 2 ms, at most until 0.5 s)")
     << " per scene, then the median over scenes. `min estimate/error` is the smallest ratio of "
        "the run's `error_estimate` to its true error over the scenes (honest if >= 1/3; `none`: "
        "the solver reports no estimate). `auto` is `mdrmap simulate` at its defaults "
        "(`run_case(SolverKind::Auto, 1e-4)`). row is the element row at N = 0 branches.\n\n";
  md << "The fixed-step baseline (`run_spectrum_baseline`: elements over the whole travel path, dt "
        "= "
        "dx/max(v, v1), spin-up of 4 a1 from an undeformed foundation) costs about (a1/dx)^2 (6 + "
        "6 zeta1) (4 + 6 zeta) max(1, v1/v) element updates (zeta = v tau/a1, zeta1 = v1 tau/a1; "
        "for tau = 0 the window is 6 a1/min(v, v1)); it is run on the "
     << n_subset << " scenes where it needs at most " << fmt("%.0e", kBaselineUpdateBudget)
     << " updates at a1/dx = " << kBaselineTopCells
     << " (the baseline subset). Every solver is reported on that subset too.\n\n";

  md << "### All " << cases.size() << " scenes\n\n";
  md_table(md, rows, "all");
  md << "\n### Baseline subset (" << n_subset << " scenes)\n\n";
  md_table(md, rows, "baseline-subset");
  md << "\nScenes of the baseline subset: ";
  bool first = true;
  for (const BenchCase& c : cases)
    if (c.baseline_ok) md << (first ? "`" : ", `") << c.name << "`", first = false;
  md << ".\n\n";

  // ---- targets
  md << "### Targets (issue 3)\n\n| target | measured | met |\n|---|---|---|\n";
  auto rtol_target = [&](const std::string& solver, double lo, double hi, const char* text) {
    double worst_q = 0;
    std::string worst;
    bool ok = true;
    for (const Row& r : rows)
      if (r.subset == "all" && r.setting->solver == solver && r.setting->rtol >= lo * 0.99 &&
          r.setting->rtol <= hi * 1.01) {
        ok = ok && r.meets_rtol;
        if (r.max_err / r.setting->rtol >= worst_q)
          worst_q = r.max_err / r.setting->rtol, worst = r.setting->label;
      }
    md << "| " << text << " | largest max-error/rtol " << fmt("%.2g", worst_q) << " (" << worst
       << ") | " << (ok ? "yes" : "**no**") << " |\n";
  };
  rtol_target("exact", 1e-10, 1e-3, "exact: max error <= rtol, every rtol 1e-3 ... 1e-10");
  rtol_target("row", 1e-4, 1e-2, "row (N = 0): max error <= rtol, rtol 1e-2, 1e-3, 1e-4");
  // Honesty of the estimates over a group of settings.
  auto honesty_target = [&](const char* text, const std::function<bool(const Setting&)>& in) {
    int runs = 0, below = 0;
    double qmin = std::numeric_limits<double>::infinity();
    std::string where, scenes;
    for (std::size_t s = 0; s < settings.size(); ++s) {
      if (!in(settings[s])) continue;
      for (std::size_t i = 0; i < cases.size(); ++i) {
        const CaseResult& r = res[s][i];
        if (!r.covered) continue;
        ++runs;
        if (3.0 * r.estimate < r.error) {
          ++below;
          if (scenes.find("'" + cases[i].name + "'") == std::string::npos)
            scenes += (scenes.empty() ? "" : ", ") + ("'" + cases[i].name + "'");
        }
        if (est_ratio(r) < qmin)
          qmin = est_ratio(r),
          where = settings[s].solver + " " + settings[s].label + ", '" + cases[i].name + "'";
      }
    }
    if (runs == 0) return; // not in this run's ladders (--quick)
    md << "| " << text << " | " << below << " of " << runs << " runs below";
    if (below > 0 && below <= 10) md << " (scenes " << scenes << ")";
    md << "; smallest estimate/error " << ratio_str(qmin) << " (" << where << ") | "
       << (below == 0 ? "yes" : "**no**") << " |\n";
  };
  auto near = [](double x, double lo, double hi) { return x >= lo * 0.99 && x <= hi * 1.01; };
  honesty_target("error_estimate >= error / 3 at the target tolerances: exact (every rtol), "
                 "auto, row rtol 1e-2 ... 1e-4",
                 [&](const Setting& st) {
                   return st.solver == "exact" || st.solver == "auto" ||
                          (st.solver == "row" && near(st.rtol, 1e-4, 1e-2));
                 });
  honesty_target("(beyond the targets) error_estimate >= error / 3, row rtol < 1e-4",
                 [&](const Setting& st) { return st.solver == "row" && st.rtol < 1e-4 * 0.99; });
  honesty_target("(beyond the targets) error_estimate >= error / 3, the "
                 "baseline (see the table below)",
                 [&](const Setting& st) { return st.rtol == 0.0; });
  md << "| simulate default (auto, rtol 1e-4) >= 1000x cheaper per scene than the baseline at "
        "a1/dx = 500 | median "
     << ms(base_top ? base_top->median_s : NAN) << " ms / "
     << ms(auto_sub ? auto_sub->median_s : NAN) << " ms = **" << fmt("%.3g", cost_ratio)
     << "x** on the " << case_ratio.size() << " subset scenes; per scene "
     << fmt("%.3g",
            case_ratio.empty() ? NAN : *std::min_element(case_ratio.begin(), case_ratio.end()))
     << "x ... "
     << fmt("%.3g",
            case_ratio.empty() ? NAN : *std::max_element(case_ratio.begin(), case_ratio.end()))
     << "x, >= 1000x on " << case_ratio_ok << " of " << case_ratio.size()
     << "; baseline median error " << e2(base_top ? base_top->median_err : NAN) << " | "
     << (cost_ratio >= 1000 ? "yes" : "**no**") << " |\n";
  md << "| row rtol 1e-3: median <= 10 ms per scene | " << ms(row3 ? row3->median_s : NAN)
     << " ms (slowest scene " << ms(row3 ? row3->max_s : NAN) << " ms) | "
     << (row3 && row3->median_s <= 10e-3 ? "yes" : "**no**") << " |\n";
  {
    const long r0 = probe_rss("row-short"), r1 = probe_rss("row-v1v-1e-8"),
               r2 = probe_rss("row-long");
    const long big0 = probe_rss("row1e4-short"), big1 = probe_rss("row1e4-v1v-1e-8"),
               big2 = probe_rss("row1e4-long");
    // "the same": within a 256 KiB page-rounding noise or 5 %
    auto same = [](long a, long b) { return std::labs(a - b) <= std::max(256L, a / 20); };
    const bool mem_ok =
        r0 > 0 && same(r0, r1) && same(r0, r2) && same(big0, big1) && same(big0, big2);
    md << "| row memory per scene independent of travel and of v1/v | peak RSS KiB, rtol 1e-3: "
       << r0 << " (travel 0.6 a1), " << r1 << " (v1/v = 1e-8), " << r2
       << " (v1 tau/a1 = 1e8); at a1/dx = 1e4: " << big0 << ", " << big1 << ", " << big2 << " | "
       << (mem_ok ? "yes" : "**no**") << " |\n";
  }

  md << "\n### Error estimates by solver family\n\n"
        "| family | runs | estimate < error/3 | estimate = 0 | smallest estimate/error | where "
        "|\n|---|---|---|---|---|---|\n";
  for (const Honesty& h : honesty)
    md << "| " << h.family << " | " << h.runs << " | " << h.below << " | " << h.without << " | "
       << ratio_str(h.min_ratio) << " | " << h.where << " |\n";
  md << "\nError-controlled runs (exact, auto, row at rtol) whose estimate is below a third of "
        "the true error:";
  bool any = false;
  for (std::size_t s = 0; s < settings.size(); ++s) {
    const std::string& f = settings[s].solver;
    if (f != "exact" && f != "auto" && f != "row") continue;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const CaseResult& r = res[s][i];
      if (!r.covered || 3.0 * r.estimate >= r.error) continue;
      md << (any ? "" : "\n\n") << "- " << f << " " << settings[s].label << ", '" << cases[i].name
         << "': error " << e2(r.error) << ", estimate " << e2(r.estimate) << ", a1/dx " << r.cells
         << "\n";
      any = true;
    }
  }
  md << (any ? "\n" : " none.\n\n");

  md << "### Cost against the baseline, per scene\n\n"
        "Measured on the baseline subset (baseline at a1/dx = "
     << kBaselineTopCells << ", simulate default = auto rtol 1e-4):\n\n"
     << "| scene | baseline ms | its error | auto ms | ratio |\n|---|---|---|---|---|\n";
  if (sb < settings.size() && sa < settings.size())
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (cases[i].baseline_ok && res[sb][i].covered)
        md << "| " << cases[i].name << " | " << ms(res[sb][i].seconds) << " | "
           << e2(res[sb][i].error) << " | " << ms(res[sa][i].seconds) << " | "
           << fmt("%.3g", res[sb][i].seconds / res[sa][i].seconds) << " |\n";
  if (!per_update.empty()) {
    std::vector<double> mr = model_ratio;
    md << "\nCost model (not a measurement): the baseline's time per element update, median over "
          "the subset, is "
       << fmt("%.3g", 1e9 * median(per_update)) << " ns. Times the element updates each of the "
       << cases.size() << " scenes would need at a1/dx = " << kBaselineTopCells
       << ", over the measured simulate-default time, that gives a median ratio of "
       << fmt("%.3g", median(mr)) << "x over all scenes, >= 1000x on " << model_ratio_ok << " of "
       << mr.size() << ".\n";
  }

  md << "\n### Peak memory (one child process per probe, ru_maxrss)\n\n"
        "| probe | peak RSS KiB | above idle KiB | elements held | a1/dx "
        "|\n|---|---|---|---|---|\n";
  const long idle = probe_rss("idle");
  for (const auto& r : pres) {
    const std::string status = field(r.output, "status");
    md << "| " << r.probe->what << " | " << r.rss_kib << " | " << (r.rss_kib - idle) << " | ";
    if (!r.ok)
      md << "probe failed | - |\n";
    else if (status == "refused")
      md << "refused: " << field(r.output, "note") << " | - |\n";
    else
      md << field(r.output, "elements") << " | " << field(r.output, "cells") << " |\n";
  }
  std::ofstream(mdp) << md.str();
  for (const std::string& f : {csv, ccsv, mdp})
    if (!std::filesystem::exists(f)) throw std::runtime_error("could not write " + f);
  std::fprintf(stderr, "bench: wrote %s, %s, %s (%.0f s)\n", csv.c_str(), ccsv.c_str(), mdp.c_str(),
               elapsed);
  std::cout << md.str();
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out_dir = "out/bench", machine_file, command, profile, probe;
  int repeat = 1;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--help" || a == "-h") {
        std::fputs(kUsage, stdout);
        return 0;
      } else if (a == "--quick") {
        quick = true;
      } else if (a == "--out-dir") {
        out_dir = value();
      } else if (a == "--machine-file") {
        machine_file = value();
      } else if (a == "--command") {
        command = value();
      } else if (a == "--profile") {
        profile = value();
      } else if (a == "--repeat") {
        repeat = std::stoi(value());
      } else if (a == "--rss-probe") {
        probe = value();
      } else {
        throw std::invalid_argument("unknown option '" + a + "' (see --help)");
      }
    }
    if (!probe.empty()) return run_probe(probe);
    if (!profile.empty()) return run_profile(profile, std::max(1, repeat));
    return run_bench(quick, out_dir, machine_file, command);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mdrmap_bench: %s\n", e.what());
    return 2;
  }
}
