// mdrmap_bench_history: work-precision benchmark of the solvers on velocity
// histories (history_case_set(), tests/cases/case_set.cpp).
//
//   mdrmap_bench_history [--quick] [--out DIR]
//
// For every solver setting and case: the case error against the continuum
// solution at rtol 1e-12, the solver's error estimate, and the median wall time
// of repeated calls. Prints a table and writes DIR/history.csv (one row per
// setting and case) and DIR/history.md (the summary table). Medians and ratios
// come from this one run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "stats.hpp"

namespace {

using mdrmap::Case;
using mdrmap::RunResult;

struct Setting {
  std::string name;
  std::function<RunResult(const Case&)> run;
};

struct CaseRow {
  std::string setting, name;
  std::size_t segments = 0, samples = 0;
  double err = 0, est = 0, seconds = 0;
  bool failed = false;
};

using mdrmap::bench::median;

/// Median wall time of `reps` calls, at least 20 ms of calls in all.
double time_median(const std::function<void()>& f, int reps) {
  std::vector<double> t;
  double total = 0.0;
  for (int i = 0; i < reps || total < 0.02; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
    t.push_back(s);
    total += s;
    if (i > 1000) break;
  }
  return median(t);
}

/// Element updates the fixed-step baseline needs (its step dx / largest
/// velocity over the whole history, elements over the travel): the benchmark
/// skips (counts as failed) cases beyond a budget, e.g. a hold of 1e6 tau.
double baseline_updates(const Case& c, double cells) {
  const double dx = c.a1() / cells;
  double wmax = c.history.v0, travel = 4.0 * c.a1();
  for (const auto& s : c.history.segments) {
    wmax = std::max(wmax, s.w);
    travel += s.w * s.T;
  }
  const double steps = c.history.end() / (dx / wmax) + 4.0 * c.a1() / dx;
  return steps * (travel / dx);
}

std::vector<Setting> settings(bool quick) {
  std::vector<Setting> out;
  out.push_back({"exact rtol=1e-6",
                 [](const Case& c) { return mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-6); }});
  out.push_back({"exact rtol=1e-12",
                 [](const Case& c) { return mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-12); }});
  for (double rtol : {1e-2, 1e-3, 1e-4}) {
    if (quick && rtol < 1e-3) continue;
    char name[32];
    std::snprintf(name, sizeof name, "row rtol=%.0e", rtol);
    out.push_back({name, [rtol](const Case& c) {
                     mdrmap::SpectrumOptions o;
                     o.rtol = rtol;
                     return mdrmap::run_spectrum(mdrmap::CheckedCase(c), o);
                   }});
  }
  if (!quick)
    out.push_back({"baseline a1/dx=200", [](const Case& c) {
                     mdrmap::SpectrumBaselineOptions o;
                     o.cells_per_a1 = 200;
                     if (baseline_updates(c, o.cells_per_a1) > 3e8)
                       throw std::runtime_error("over the benchmark's budget");
                     return mdrmap::run_spectrum_baseline(mdrmap::CheckedCase(c), o);
                   }});
  return out;
}

CaseRow measure(const Setting& st, const mdrmap::NamedCase& nc, const RunResult& ref, int reps) {
  CaseRow r;
  r.setting = st.name;
  r.name = nc.name;
  r.segments = nc.c.history.size();
  r.samples = nc.c.total_samples();
  try {
    const RunResult run = st.run(nc.c);
    r.err = mdrmap::case_error(run.series, ref.series, nc.c, 1e-12).max();
    r.est = run.info.error_estimate;
    r.seconds = time_median([&] { st.run(nc.c); }, reps);
  } catch (const std::exception&) {
    r.failed = true; // e.g. the baseline refuses a 1e6 tau hold
  }
  return r;
}

struct Summary {
  std::string setting;
  int cases = 0, failed = 0, est_low = 0;
  double max_err = 0, med_ms = 0, med_ms_3seg = 0, med_us_sample = 0;
};

Summary summarize(const std::string& setting, const std::vector<CaseRow>& rows) {
  Summary s;
  s.setting = setting;
  std::vector<double> ms, ms3, us;
  for (const auto& r : rows) {
    if (r.setting != setting) continue;
    ++s.cases;
    if (r.failed) {
      ++s.failed;
      continue;
    }
    s.max_err = std::max(s.max_err, r.err);
    if (r.est < r.err / 3.0) ++s.est_low;
    ms.push_back(1e3 * r.seconds);
    us.push_back(1e6 * r.seconds / static_cast<double>(r.samples));
    if (r.segments == 3) ms3.push_back(1e3 * r.seconds);
  }
  s.med_ms = median(ms);
  s.med_ms_3seg = median(ms3);
  s.med_us_sample = median(us);
  return s;
}

void write_outputs(const std::string& dir, const std::vector<CaseRow>& rows,
                   const std::vector<Summary>& sums, std::size_t n_cases) {
  std::ofstream csv(dir + "/history.csv");
  csv << "setting,case,segments,samples,error,error_estimate,median_seconds,failed\n";
  for (const auto& r : rows)
    csv << r.setting << ",\"" << r.name << "\"," << r.segments << "," << r.samples << "," << r.err
        << "," << r.est << "," << r.seconds << "," << (r.failed ? 1 : 0) << "\n";
  std::ofstream md(dir + "/history.md");
  md << "Velocity histories: " << n_cases
     << " cases of `history_case_set()`, 61 samples per segment; error against `exact` at "
        "rtol 1e-12; times are medians of repeated calls.\n\n"
     << "| setting | cases | failed | max error | estimate < error/3 | median ms/case | "
        "median ms, 3 segments | median us/sample |\n|---|---|---|---|---|---|---|---|\n";
  char line[256];
  for (const auto& s : sums) {
    std::snprintf(line, sizeof line, "| %s | %d | %d | %.1e | %d | %.3g | %.3g | %.3g |\n",
                  s.setting.c_str(), s.cases, s.failed, s.max_err, s.est_low, s.med_ms,
                  s.med_ms_3seg, s.med_us_sample);
    md << line;
  }
}

} // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else {
      std::fprintf(stderr, "usage: mdrmap_bench_history [--quick] [--out DIR]\n");
      return 2;
    }
  }
  const auto cases = mdrmap::history_case_set(61);
  std::vector<RunResult> refs;
  for (const auto& nc : cases)
    refs.push_back(mdrmap::run_exact(mdrmap::CheckedCase(nc.c), 1e-12));
  std::vector<CaseRow> rows;
  std::vector<Summary> sums;
  for (const auto& st : settings(quick)) {
    for (std::size_t i = 0; i < cases.size(); ++i)
      rows.push_back(measure(st, cases[i], refs[i], quick ? 1 : 5));
    sums.push_back(summarize(st.name, rows));
  }
  std::printf("%-20s %5s %6s %9s %8s %10s %12s %10s\n", "setting", "cases", "failed", "max_err",
              "est_low", "med_ms", "med_ms_3seg", "us/sample");
  for (const auto& s : sums)
    std::printf("%-20s %5d %6d %9.1e %8d %10.3g %12.3g %10.3g\n", s.setting.c_str(), s.cases,
                s.failed, s.max_err, s.est_low, s.med_ms, s.med_ms_3seg, s.med_us_sample);
  write_outputs(out, rows, sums, cases.size());
  return 0;
}
