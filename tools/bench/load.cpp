// mdrmap_bench_load: work-precision benchmark of the load-control solver
// (run_load, src/core/solvers/load.hpp) on the load-controlled histories of
// load_case_set() (tests/cases/load_case_set.cpp); issue 11's cost criterion.
//
//   mdrmap_bench_load [--quick] [--out DIR] [--command TEXT] [--max-call-seconds S]
//
// Part 1, every case: run_load at rtol 1e-2, 1e-3, 1e-4 (--quick: 1e-3); the
// case error against a reference run, the run's error estimate and the median
// wall time of repeated calls. Reference: run_load at 4x the resolution of the
// rtol-1e-4 run, time_tol 1e-9, no companion; for the zeta0 = 1e6 cases
// time_tol 1e-8 (the rounding of D ~ 2 L a1 / R shows at 1e-9).
//
// Part 2, three 3-segment histories, side by side in this run: a ladder of the
// fixed-step element row (baseline, run_spectrum_baseline, a1/dx doubling from 12.5 until a
// call would take over --max-call-seconds) and a ladder of the load solver
// (rtol 1e-1 .. 1e-5, and fixed a/dx and time steps), errors against the same
// reference. For each baseline point: the load solver's time at that error,
// log-log interpolated on its work-precision front, and the cost ratio.
//
// Prints the tables and writes DIR/load.csv (one row per setting and case) and
// DIR/load.md (the markdown section tools/bench.sh appends to bench.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/load_case_set.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/load.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "stats.hpp"

namespace {

using mdrmap::Case;
using mdrmap::NamedCase;
using mdrmap::RunResult;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

using mdrmap::bench::median;

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

/// "1e-03" -> "1e-3".
std::string short_e(double x) {
  std::string s = fmt("%.0e", x);
  const auto p = s.find("e-0");
  if (p != std::string::npos) s.erase(p + 2, 1);
  const auto q = s.find("e+0");
  if (q != std::string::npos) s.erase(q + 1, 2);
  return s;
}

std::string loadavg() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  if (!(f >> a >> b >> c)) return "unknown";
  return a + " " + b + " " + c;
}

/// Median wall time of at least `reps` calls and 20 ms of calls, after one
/// call already timed at `first` seconds: a call over `single` seconds is
/// timed once (that first call), and repetition stops after `budget` seconds.
struct Timing {
  double seconds = 0.0;
  int calls = 0;
};

Timing time_median(const std::function<void()>& f, double first, int reps, double single = 1.0,
                   double budget = 3.0) {
  if (first > single) return {first, 1};
  std::vector<double> t;
  double total = 0.0;
  for (int i = 0; i < reps || total < 0.02; ++i) {
    const auto a = Clock::now();
    f();
    const double s = seconds_since(a);
    t.push_back(s);
    total += s;
    if (i > 1000 || total > budget) break;
  }
  return {median(t), static_cast<int>(t.size())};
}

bool is_stiff(const std::string& name) {
  return name.find("zeta0=1e6") != std::string::npos;
}
bool is_3seg(const std::string& name) {
  return name.rfind("3seg", 0) == 0;
}

/// One measured setting on one case (a row of load.csv).
struct Row {
  std::string part, setting, name;
  double rtol = 0, cells = 0; ///< rtol (0: fixed resolution); a_ref/dx or a0/dx
  double err = 0, est = 0, seconds = 0;
  long updates = 0, steps = 0;
  int calls = 0, refinements = 0;
  bool failed = false;
  std::string what; ///< the exception, if failed
  // part 2, baseline rows: the load solver at the same error
  double load_s = std::nan(""), ratio = std::nan("");
  std::string how; ///< interp, bound (>=), extrap
  double load_s_rtol = std::nan(""), ratio_rtol = std::nan("");
  std::string how_rtol;
};

/// Runs `run` once for its error (against `ref`) and estimate, then times it.
Row measure(const std::string& part, const std::string& setting, const NamedCase& nc,
            const RunResult* ref, const std::function<RunResult()>& run, int reps) {
  Row r;
  r.part = part;
  r.setting = setting;
  r.name = nc.name;
  if (!ref) {
    r.failed = true;
    r.what = "no reference";
    return r;
  }
  try {
    const auto a = Clock::now();
    const RunResult res = run();
    const double first = seconds_since(a);
    r.err = mdrmap::case_error(res.series, ref->series, nc.c, 1e-12).max();
    r.est = res.info.error_estimate;
    r.updates = res.info.element_updates;
    r.steps = res.info.steps;
    r.refinements = res.info.refinements;
    if (r.cells == 0.0) r.cells = res.info.cells_per_a1;
    const Timing tm = time_median([&] { run(); }, first, reps);
    r.seconds = tm.seconds;
    r.calls = tm.calls;
  } catch (const std::exception& e) {
    r.failed = true;
    r.what = e.what();
  }
  return r;
}

// ---------------------------------------------------------------- part 1

struct Summary {
  double rtol = 0;
  int cases = 0, failed = 0, est_low = 0, n3 = 0;
  double max_err = 0, max_err_rtol = 0, med_ms = 0, med_ms_3seg = 0, max_ms = 0;
  std::string max_ms_case;
};

Summary summarize(double rtol, const std::vector<Row>& rows) {
  Summary s;
  s.rtol = rtol;
  std::vector<double> ms, ms3;
  for (const auto& r : rows) {
    if (r.part != "rtol" || r.rtol != rtol) continue;
    ++s.cases;
    if (r.failed) {
      ++s.failed;
      continue;
    }
    s.max_err = std::max(s.max_err, r.err);
    if (r.est < r.err / 3.0) ++s.est_low;
    ms.push_back(1e3 * r.seconds);
    if (is_3seg(r.name)) ms3.push_back(1e3 * r.seconds);
    if (1e3 * r.seconds > s.max_ms) {
      s.max_ms = 1e3 * r.seconds;
      s.max_ms_case = r.name;
    }
  }
  s.max_err_rtol = s.max_err / rtol;
  s.med_ms = median(ms);
  s.med_ms_3seg = median(ms3);
  s.n3 = static_cast<int>(ms3.size());
  return s;
}

// ---------------------------------------------------------------- part 2

struct Point {
  double err, t;
};

/// The load solver's work-precision front: the points no cheaper point beats
/// in error, by increasing time (so by decreasing error).
std::vector<Point> front(std::vector<Point> p) {
  std::sort(p.begin(), p.end(), [](const Point& a, const Point& b) { return a.t < b.t; });
  std::vector<Point> out;
  for (const auto& q : p)
    if (q.err > 0.0 && (out.empty() || q.err < out.back().err)) out.push_back(q);
  return out;
}

/// The front's time at error e: "interp" (log-log between the two points
/// around e), "bound" (e is above the front's largest error: its cheapest
/// point is already more accurate, so the time at e is at most that), or
/// "extrap" (below the smallest error: log-log through the last two points).
double time_at(const std::vector<Point>& f, double e, std::string& how) {
  if (f.empty() || !(e > 0.0)) {
    how = "none";
    return std::nan("");
  }
  if (e >= f.front().err) {
    how = "bound";
    return f.front().t;
  }
  std::size_t i = 0;
  while (i + 1 < f.size() && f[i + 1].err > e)
    ++i;
  if (i + 1 >= f.size()) {
    how = "extrap";
    if (f.size() < 2) return f.back().t;
    i = f.size() - 2;
  } else {
    how = "interp";
  }
  const Point &a = f[i], &b = f[i + 1];
  const double s = std::log(e / a.err) / std::log(b.err / a.err);
  return a.t * std::exp(s * std::log(b.t / a.t));
}

struct LoadSetting {
  std::string name;
  double rtol;       ///< > 0: the adaptive mode with its companion
  double cells, dtt; ///< else fixed a_ref/dx and h/tau, no companion
};

std::vector<LoadSetting> load_ladder(bool quick) {
  std::vector<LoadSetting> out;
  for (double rtol : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5}) {
    if (quick && (rtol == 1e-2 || rtol == 1e-4)) continue;
    out.push_back({"load rtol=" + short_e(rtol), rtol, 0.0, 0.0});
  }
  // fixed steps: h = tau (capped at the sample spacing) at a/dx = 1, 2, 4; then
  // shorter steps at a/dx = 4 (the errors of the fixed-step baseline's range)
  const double fixed[][2] = {{1, 1}, {2, 1}, {4, 1}, {4, 0.03}, {4, 0.01}, {4, 0.003}, {4, 0.001}};
  for (const auto& f : fixed) {
    if (quick && f[1] < 0.005) continue;
    out.push_back({"load a/dx=" + fmt("%g", f[0]) + " h/tau=" + fmt("%g", f[1]), 0.0, f[0], f[1]});
  }
  return out;
}

mdrmap::LoadOptions load_options(const LoadSetting& s) {
  mdrmap::LoadOptions o;
  if (s.rtol > 0.0) {
    o.rtol = s.rtol;
  } else {
    o.cells = s.cells;
    o.dt_over_tau = s.dtt;
    o.estimate_error = false;
  }
  return o;
}

struct RatioSummary {
  std::string name;
  int points = 0, interp = 0, bound = 0, extrap = 0, fine = 0;
  double med = std::nan(""), min = std::nan(""), min_fine = std::nan(""), min_bound = std::nan("");
  double med_rtol = std::nan(""), min_rtol = std::nan("");
  double min_fine_rtol = std::nan(""); ///< at error <= fine_err, bounds included
  bool min_fine_rtol_bound = false;
};

/// Ratios over the baseline rows of part 2 (of one case, or all if name empty).
/// "fine": the points at error <= fine_err (where the solver is used).
RatioSummary ratio_summary(const std::string& name, const std::vector<Row>& rows, double fine_err) {
  RatioSummary s;
  s.name = name;
  std::vector<double> all, fine, bounds, rt;
  for (const auto& r : rows) {
    if (r.part != "baseline" || r.failed || (!name.empty() && r.name != name)) continue;
    ++s.points;
    if (r.how == "interp") {
      ++s.interp;
      all.push_back(r.ratio);
      if (r.err <= fine_err) fine.push_back(r.ratio);
    } else if (r.how == "bound") {
      ++s.bound;
      bounds.push_back(r.ratio);
    } else if (r.how == "extrap") {
      ++s.extrap;
      all.push_back(r.ratio);
      if (r.err <= fine_err) fine.push_back(r.ratio);
    }
    if (r.how_rtol == "interp" || r.how_rtol == "extrap") rt.push_back(r.ratio_rtol);
    if (r.err <= fine_err && !std::isnan(r.ratio_rtol) &&
        !(r.ratio_rtol >= s.min_fine_rtol)) { // (also when still nan)
      s.min_fine_rtol = r.ratio_rtol;
      s.min_fine_rtol_bound = r.how_rtol == "bound";
    }
  }
  auto mn = [](const std::vector<double>& v) {
    return v.empty() ? std::nan("") : *std::min_element(v.begin(), v.end());
  };
  s.fine = static_cast<int>(fine.size());
  s.med = median(all);
  s.min = mn(all);
  s.min_fine = mn(fine);
  s.min_bound = mn(bounds);
  s.med_rtol = median(rt);
  s.min_rtol = mn(rt);
  return s;
}

std::string g3(double x) {
  return std::isnan(x) ? "-" : fmt("%.3g", x);
}
std::string e2(double x) {
  return std::isnan(x) ? "-" : fmt("%.2e", x);
}
std::string pass(bool ok) {
  return ok ? "**PASS**" : "**FAIL**";
}

std::string ratio_cell(double ratio, const std::string& how) {
  if (std::isnan(ratio)) return "-";
  if (how == "bound") return ">= " + fmt("%.3g", ratio) + " (bound)";
  if (how == "extrap") return fmt("%.3g", ratio) + " (EXTRAPOLATED)";
  return fmt("%.3g", ratio);
}

std::string csv_quote(const std::string& s) {
  return "\"" + s + "\"";
}

} // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out = ".", command;
  double max_call = 20.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else if (a == "--command" && i + 1 < argc) {
      command = argv[++i];
    } else if (a == "--max-call-seconds" && i + 1 < argc) {
      max_call = std::stod(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: mdrmap_bench_load [--quick] [--out DIR] [--command TEXT] "
                           "[--max-call-seconds S]\n");
      return 2;
    }
  }
  if (quick && max_call > 0.5) max_call = 0.5;
  if (command.empty()) command = std::string("mdrmap_bench_load") + (quick ? " --quick" : "");
  const auto t_start = Clock::now();
  const std::string load_start = loadavg();
  const int reps = quick ? 1 : 5;
  const double ref_rtol = quick ? 1e-3 : 1e-4; // the run whose resolution the reference scales
  const double fine_err = 1e-3;                // errors where the solver is used: rtol 1e-3
  std::vector<double> rtols = {1e-2, 1e-3, 1e-4};
  if (quick) rtols = {1e-3};

  // ---- references
  const auto cases = mdrmap::load_case_set(61);
  std::vector<RunResult> refs(cases.size());
  std::vector<bool> have_ref(cases.size(), false);
  std::vector<std::string> ref_note(cases.size());
  std::vector<double> ref_seconds(cases.size(), 0.0);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& nc = cases[i];
    const auto a = Clock::now();
    try {
      mdrmap::LoadOptions o;
      o.rtol = ref_rtol;
      const double cells = mdrmap::run_load(mdrmap::CheckedCase(nc.c), o).info.cells_per_a1;
      const bool stiff = is_stiff(nc.name);
      mdrmap::LoadOptions r;
      r.cells = 4.0 * cells;
      r.time_tol = stiff ? 1e-8 : 1e-9;
      r.estimate_error = false;
      refs[i] = mdrmap::run_load(mdrmap::CheckedCase(nc.c), r);
      have_ref[i] = true;
      ref_note[i] = fmt("a/dx=%g", r.cells) + " time_tol=" + short_e(r.time_tol);
    } catch (const std::exception& e) {
      ref_note[i] = std::string("reference failed: ") + e.what();
    }
    ref_seconds[i] = seconds_since(a);
    std::fprintf(stderr, "bench_load: reference %-40s %s (%.2f s)\n", nc.name.c_str(),
                 ref_note[i].c_str(), ref_seconds[i]);
  }
  auto ref_of = [&](std::size_t i) { return have_ref[i] ? &refs[i] : nullptr; };

  // ---- part 1: every case at the rtol ladder
  std::vector<Row> rows;
  for (double rtol : rtols)
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const auto& nc = cases[i];
      mdrmap::LoadOptions o;
      o.rtol = rtol;
      Row r = measure(
          "rtol", "load rtol=" + short_e(rtol), nc, ref_of(i),
          [&] { return mdrmap::run_load(mdrmap::CheckedCase(nc.c), o); }, reps);
      r.rtol = rtol;
      rows.push_back(r);
      std::fprintf(stderr, "bench_load: rtol %-6s %-40s err %.2e est %.2e %9.3f ms%s\n",
                   short_e(rtol).c_str(), nc.name.c_str(), r.err, r.est, 1e3 * r.seconds,
                   r.failed ? (" FAILED: " + r.what).c_str() : "");
    }
  std::vector<Summary> sums;
  for (double rtol : rtols)
    sums.push_back(summarize(rtol, rows));

  // ---- part 2: side by side with the fixed-step baseline
  std::vector<std::string> wp_cases = {"3seg up 10x and back, zeta0=1",
                                       "3seg down 10x and back, zeta0=0.1",
                                       "3seg slide-hold-slide hold=1 tau"};
  std::vector<std::string> base_stop; // why each baseline ladder stopped
  for (const auto& name : wp_cases) {
    std::size_t i = 0;
    while (i < cases.size() && cases[i].name != name)
      ++i;
    if (i == cases.size()) {
      base_stop.push_back(name + ": not in load_case_set()");
      continue;
    }
    const auto& nc = cases[i];
    std::vector<Point> all, rtol_only;
    for (const auto& ls : load_ladder(quick)) {
      const mdrmap::LoadOptions o = load_options(ls);
      Row r = measure(
          "load", ls.name, nc, ref_of(i),
          [&] { return mdrmap::run_load(mdrmap::CheckedCase(nc.c), o); }, reps);
      r.rtol = ls.rtol;
      if (ls.rtol == 0.0) r.cells = ls.cells;
      if (!r.failed) {
        all.push_back({r.err, r.seconds});
        if (ls.rtol > 0.0) rtol_only.push_back({r.err, r.seconds});
      }
      std::fprintf(stderr, "bench_load: %-30s %-24s err %.2e %9.3f ms\n", name.c_str(),
                   ls.name.c_str(), r.err, 1e3 * r.seconds);
      rows.push_back(r);
    }
    const auto f_all = front(all), f_rtol = front(rtol_only);
    // the baseline: a1/dx doubling; stop after a call over max_call seconds,
    // or before one expected over it (cost ~ (a1/dx)^2: 4x per doubling)
    double last = 0.0;
    std::string stop = "ladder end";
    for (double cpa = 12.5; cpa <= 1e6; cpa *= 2.0) {
      if (last > max_call) {
        stop = "a call took " + fmt("%.1f", last) + " s > " + fmt("%g", max_call) + " s";
        break;
      }
      if (4.0 * last > max_call) {
        stop =
            "next call expected ~" + fmt("%.0f", 4.0 * last) + " s > " + fmt("%g", max_call) + " s";
        break;
      }
      mdrmap::SpectrumBaselineOptions b;
      b.cells_per_a1 = cpa;
      b.estimate_error = false; // the cheapest baseline: the ratio errs low
      // (no work budget: the ladder stops on time, --max-call-seconds)
      Row r = measure(
          "baseline", "baseline a1/dx=" + fmt("%g", cpa), nc, ref_of(i),
          [&] {
            mdrmap::RunControl unbounded;
            unbounded.max_work = std::numeric_limits<double>::infinity();
            mdrmap::SpectrumBaselineOptions bb = b;
            bb.control = &unbounded;
            return mdrmap::run_spectrum_baseline(mdrmap::CheckedCase(nc.c), bb);
          },
          reps);
      r.cells = cpa;
      if (r.failed) {
        std::fprintf(stderr, "bench_load: %-30s baseline a1/dx=%-8g FAILED: %s\n", name.c_str(),
                     cpa, r.what.c_str());
        rows.push_back(r);
        if (r.what.find("too expensive") != std::string::npos) {
          stop = "too expensive at a1/dx=" + fmt("%g", cpa);
          break;
        }
        continue;
      }
      last = r.seconds;
      r.load_s = time_at(f_all, r.err, r.how);
      r.ratio = r.seconds / r.load_s;
      r.load_s_rtol = time_at(f_rtol, r.err, r.how_rtol);
      r.ratio_rtol = r.seconds / r.load_s_rtol;
      std::fprintf(stderr,
                   "bench_load: %-30s baseline a1/dx=%-8g err %.2e %9.3f ms; load %.3f ms (%s), "
                   "ratio %.3g\n",
                   name.c_str(), cpa, r.err, 1e3 * r.seconds, 1e3 * r.load_s, r.how.c_str(),
                   r.ratio);
      rows.push_back(r);
    }
    base_stop.push_back(name + ": " + stop);
  }
  std::vector<RatioSummary> rsums;
  for (const auto& name : wp_cases)
    rsums.push_back(ratio_summary(name, rows, fine_err));
  rsums.push_back(ratio_summary("", rows, fine_err));
  rsums.back().name = "all three";
  const double wall = seconds_since(t_start);
  const std::string load_end = loadavg();

  // ---- the tables
  std::printf("Part 1: run_load on %zu cases of load_case_set() (61 samples per segment)\n",
              cases.size());
  std::printf("%-7s %5s %6s %9s %9s %7s %9s %11s %9s  %s\n", "rtol", "cases", "failed", "max_err",
              "err/rtol", "est_low", "med_ms", "med_ms_3seg", "max_ms", "slowest case");
  for (const auto& s : sums)
    std::printf("%-7s %5d %6d %9.2e %9.3g %7d %9.3g %11.3g %9.4g  %s\n", short_e(s.rtol).c_str(),
                s.cases, s.failed, s.max_err, s.max_err_rtol, s.est_low, s.med_ms, s.med_ms_3seg,
                s.max_ms, s.max_ms_case.c_str());
  std::printf("\nPart 2: side by side with the fixed-step baseline (same reference)\n");
  for (const auto& name : wp_cases) {
    std::printf("%s\n  %-26s %9s %10s %10s %12s %s\n", name.c_str(), "setting", "error", "est",
                "ms", "load ms@err", "ratio");
    for (const auto& r : rows) {
      if ((r.part != "load" && r.part != "baseline") || r.name != name) continue;
      if (r.failed) {
        std::printf("  %-26s failed: %s\n", r.setting.c_str(), r.what.c_str());
        continue;
      }
      std::printf("  %-26s %9.2e %10s %10.4g %12s %s\n", r.setting.c_str(), r.err,
                  r.part == "load" && r.rtol > 0 ? e2(r.est).c_str() : "-", 1e3 * r.seconds,
                  r.part == "baseline" ? g3(1e3 * r.load_s).c_str() : "",
                  r.part == "baseline" ? ratio_cell(r.ratio, r.how).c_str() : "");
    }
  }
  std::printf("\nCost ratio baseline/load at equal error (interpolated points; bounds apart)\n");
  std::printf("%-36s %6s %6s %6s %6s %9s %9s %12s %12s\n", "case", "points", "interp", "bound",
              "extrap", "median", "min", "min@<=1e-3", "min bound");
  for (const auto& s : rsums)
    std::printf("%-36s %6d %6d %6d %6d %9s %9s %12s %12s\n", s.name.c_str(), s.points, s.interp,
                s.bound, s.extrap, g3(s.med).c_str(), g3(s.min).c_str(), g3(s.min_fine).c_str(),
                g3(s.min_bound).c_str());
  std::printf("\nwall time %.1f s; load average %s (start), %s (end)\n", wall, load_start.c_str(),
              load_end.c_str());

  // ---- load.csv
  std::ofstream csv(out + "/load.csv");
  csv << "part,setting,case,rtol,cells,error,error_estimate,median_seconds,calls,element_updates,"
         "steps,refinements,failed,load_seconds_at_error,ratio,ratio_how,load_seconds_at_error_"
         "rtol_ladder,"
         "ratio_rtol_ladder,ratio_rtol_ladder_how\n";
  for (const auto& r : rows)
    csv << r.part << "," << r.setting << "," << csv_quote(r.name) << "," << r.rtol << "," << r.cells
        << "," << r.err << "," << r.est << "," << r.seconds << "," << r.calls << "," << r.updates
        << "," << r.steps << "," << r.refinements << "," << (r.failed ? 1 : 0) << ","
        << (std::isnan(r.load_s) ? "" : fmt("%.6g", r.load_s)) << ","
        << (std::isnan(r.ratio) ? "" : fmt("%.6g", r.ratio)) << "," << r.how << ","
        << (std::isnan(r.load_s_rtol) ? "" : fmt("%.6g", r.load_s_rtol)) << ","
        << (std::isnan(r.ratio_rtol) ? "" : fmt("%.6g", r.ratio_rtol)) << "," << r.how_rtol << "\n";

  // ---- load.md
  std::ostringstream md;
  md << "## Load control (" << command << ", mdrmap_bench_load)\n\n";
  int n3 = 0;
  for (const auto& nc : cases)
    n3 += is_3seg(nc.name) ? 1 : 0;
  md << cases.size() << " load-controlled histories of `load_case_set()` ("
     << "tests/cases/load_case_set.cpp), " << n3
     << " of them with three segments, 61 samples per segment. Error: "
        "`case_error(run, ref, c, 1e-12).max()` (the load-control contract of "
        "docs/design.md, \"Error metric\") against a reference `run_load` at "
     << (quick ? "4x the a/dx of the rtol-1e-3 run (--quick)" : "4x the a/dx of the rtol-1e-4 run")
     << ", time_tol 1e-9, no companion; for the two zeta0=1e6 cases time_tol 1e-8 (the "
        "rounding of D ~ 2 L a1 / R shows at 1e-9). "
        "Times: median wall time of repeated calls (at least "
     << reps
     << " and 20 ms of calls; a call over 1 s is timed once, repetition stops after 3 s). "
        "One thread; wall "
     << fmt("%.0f", wall) << " s; load average " << load_start << " at the start, " << load_end
     << " at the end (other work on the machine inflates times).\n\n";
  md << "### Cost per case (run_load at its rtol, all cases)\n\n"
        "| rtol | cases | failed | max error | max error/rtol | estimate < error/3 | median "
        "ms/case | median ms, 3 segments | max ms (case) "
        "|\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : sums)
    md << "| " << short_e(s.rtol) << " | " << s.cases << " | " << s.failed << " | "
       << fmt("%.2e", s.max_err) << " | " << fmt("%.3g", s.max_err_rtol) << " | " << s.est_low
       << " | " << fmt("%.3g", s.med_ms) << " | " << fmt("%.3g", s.med_ms_3seg) << " (" << s.n3
       << " cases) | " << fmt("%.4g", s.max_ms) << " (" << s.max_ms_case << ") |\n";
  {
    std::ostringstream notes;
    for (const auto& r : rows) {
      if (r.part != "rtol") continue;
      if (r.failed)
        notes << "- failed: " << r.name << ", rtol " << short_e(r.rtol) << ": " << r.what << "\n";
      else if (r.est < r.err / 3.0)
        notes << "- estimate below error/3: " << r.name << ", rtol " << short_e(r.rtol)
              << ": error " << fmt("%.2e", r.err) << ", estimate " << fmt("%.2e", r.est) << "\n";
      else if (r.err > r.rtol)
        notes << "- error above rtol: " << r.name << ", rtol " << short_e(r.rtol) << ": error "
              << fmt("%.2e", r.err) << ", estimate " << fmt("%.2e", r.est) << "\n";
      if (!r.failed && is_3seg(r.name) &&
          ((r.rtol == 1e-3 && r.seconds > 0.010) || (r.rtol == 1e-4 && r.seconds > 0.050)))
        notes << "- 3-segment case over the per-case target: " << r.name << ", rtol "
              << short_e(r.rtol) << ": " << fmt("%.4g", 1e3 * r.seconds) << " ms, " << r.steps
              << " steps, " << r.updates << " element updates, " << r.refinements
              << " resolution(s) tried\n";
    }
    for (std::size_t i = 0; i < cases.size(); ++i)
      if (!have_ref[i]) notes << "- " << cases[i].name << ": " << ref_note[i] << "\n";
    if (!notes.str().empty()) md << "\n" << notes.str();
  }

  md << "\n### Side by side with the fixed-step solver\n\n"
        "`run_spectrum_baseline` (elements over the whole travel path, first order in dx and dt, "
        "dt = dx / largest velocity, no companion run: its cheapest form) at a1/dx doubling "
        "from 12.5 until a call takes over "
     << fmt("%g", max_call)
     << " s (cost ~ (a1/dx)^2: the ladder stops before a call expected to take longer); the load "
        "solver at rtol "
        "1e-1..1e-5 (with its companion) and at fixed a/dx and fixed steps h/tau (no companion; "
        "h is capped at the sample spacing). Same reference as above. For each baseline point, "
        "`load ms` is the load solver's time at the baseline's error, log-log interpolated on "
        "its work-precision front (all its settings); `>= (bound)`: the baseline error is above "
        "the load solver's largest, so the cheapest load point is already more accurate and "
        "the ratio is at least that; `EXTRAPOLATED` would mark an error below the load "
        "ladder. `ratio, rtol ladder`: the same against the rtol settings only.\n\n";
  for (const auto& name : wp_cases) {
    md << "**" << name
       << "**\n\n| setting | error | estimate | ms | load ms at equal error | "
          "ratio | ratio, rtol ladder |\n|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
      if ((r.part != "load" && r.part != "baseline") || r.name != name) continue;
      if (r.failed) {
        md << "| " << r.setting << " | failed: " << r.what << " | | | | | |\n";
        continue;
      }
      const bool b = r.part == "baseline";
      md << "| " << r.setting << " | " << fmt("%.2e", r.err) << " | "
         << (r.rtol > 0 ? fmt("%.2e", r.est) : "-") << " | " << fmt("%.4g", 1e3 * r.seconds)
         << " | " << (b ? g3(1e3 * r.load_s) : "") << " | " << (b ? ratio_cell(r.ratio, r.how) : "")
         << " | " << (b ? ratio_cell(r.ratio_rtol, r.how_rtol) : "") << " |\n";
    }
    md << "\n";
  }
  md << "Baseline ladders stopped: ";
  for (std::size_t k = 0; k < base_stop.size(); ++k)
    md << (k ? "; " : "") << base_stop[k];
  md << ".\n\n| cost ratio baseline/load at equal error | points | interpolated | bounds | "
        "extrapolated | median | min | min at error <= 1e-3 | min bound | median, rtol ladder | "
        "min, rtol ladder | min at error <= 1e-3, rtol ladder |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : rsums)
    md << "| " << s.name << " | " << s.points << " | " << s.interp << " | " << s.bound << " | "
       << s.extrap << " | " << g3(s.med) << " | " << g3(s.min) << " | " << g3(s.min_fine) << " | "
       << g3(s.min_bound) << " | " << g3(s.med_rtol) << " | " << g3(s.min_rtol) << " | "
       << (s.min_fine_rtol_bound ? ">= " : "") << g3(s.min_fine_rtol) << " |\n";
  md << "\n(`>=`: a bound, the rtol ladder's loosest point already more accurate than the "
        "baseline point.)\n";

  md << "\n### Load-control targets (issue 11)\n\n| criterion | target | measured | result "
        "|\n|---|---|---|---|\n";
  for (const auto& s : sums) {
    if (s.rtol != 1e-3 && s.rtol != 1e-4) continue;
    const double target = s.rtol == 1e-3 ? 10.0 : 50.0;
    int over = 0;
    for (const auto& r : rows)
      if (r.part == "rtol" && r.rtol == s.rtol && is_3seg(r.name) && !r.failed &&
          1e3 * r.seconds > target)
        ++over;
    md << "| rtol " << short_e(s.rtol) << ": median ms per 3-segment case | <= " << target << " | "
       << fmt("%.3g", s.med_ms_3seg) << " (" << over << " of " << s.n3 << " cases over " << target
       << " ms) | " << pass(s.med_ms_3seg <= target) << " |\n";
  }
  const RatioSummary& tot = rsums.back();
  md << "| cost vs fixed-step at equal accuracy, errors <= 1e-3 (" << tot.fine
     << " points, min) | >= 100x | " << g3(tot.min_fine) << " | "
     << (tot.fine > 0 ? pass(tot.min_fine >= 100.0) : "no points") << " |\n";
  md << "| the same at every interpolated point, the coarse errors included ("
     << tot.interp + tot.extrap << " points, min / median) | >= 100x | " << g3(tot.min) << " / "
     << g3(tot.med) << " | " << (tot.interp + tot.extrap > 0 ? pass(tot.min >= 100.0) : "no points")
     << " |\n";
  md << "\nCommand: `" << command << "`; the program: `mdrmap_bench_load --out DIR"
     << (quick ? " --quick" : "") << "`.\n";
  std::ofstream(out + "/load.md") << md.str();
  return 0;
}
