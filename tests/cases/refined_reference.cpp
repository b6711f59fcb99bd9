#include "cases/refined_reference.hpp"

#include <algorithm>
#include <ctime>
#include <utility>
#include <vector>

#include "core/metrics/error_metric.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"

namespace mdrmap {

double cpu_ms() {
  return 1e3 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

RunResult fixed_resolution(const Case& c, double cells) {
  // a reference may spend more than a case's default budget: the spectrum
  // solver charges 1 + N/4 units per element sub-step of N branches, and the
  // polyisobutylene drop-hold-reslide under load at a/dx 256 takes 1.8e9
  // units (17 s CPU)
  RunControl reference_budget;
  reference_budget.max_work = 4.0 * RunControl::kDefaultMaxWork;
  SpectrumOptions o;
  o.cells_per_a1 = cells;
  o.rtol = 1e-7; // edge to 1e-9 a1, load balance to 1e-11 F0
  o.estimate_error = false;
  o.control = &reference_budget;
  return run_spectrum(CheckedCase(c), o);
}

double run_difference(const Series& coarse, const Series& fine, const Case& c) {
  return case_error(coarse, fine, c, 1e-12).max();
}

Reference refine(const Case& c, double goal) {
  const bool load = c.loading.by_force();
  const double n0 = load ? 32.0 : 256.0, n_max = load ? 1024.0 : 8192.0;
  Reference ref;
  const double t0 = cpu_ms();
  std::vector<Series> runs;
  std::vector<double> diffs;
  for (double n = n0; n <= n_max; n *= 2.0) {
    try {
      runs.push_back(fixed_resolution(c, n).series);
    } catch (const CaseAbandoned&) { // past the work budget: the bound so far stands
      break;
    }
    ref.cells = n;
    if (runs.size() >= 2) diffs.push_back(run_difference(runs[runs.size() - 2], runs.back(), c));
    if (diffs.size() < 2) continue;
    const double d1 = diffs[diffs.size() - 2], d2 = diffs.back();
    ref.ratio = d1 / d2;
    if (d2 <= kReferenceNoise)
      ref.bound = kReferenceNoise;
    else
      ref.bound = ref.ratio > 1.5 ? d2 / (std::min(ref.ratio, 4.0) - 1.0)
                                  : std::numeric_limits<double>::infinity();
    if (ref.bound <= goal) break;
  }
  ref.series = std::move(runs.back());
  ref.ms = cpu_ms() - t0;
  return ref;
}

CheckedRun adaptive_run(const Case& c, double rtol, const Series& reference) {
  SpectrumOptions o;
  o.rtol = rtol;
  CheckedRun out;
  const double t0 = cpu_ms();
  try {
    const RunResult r = run_spectrum(CheckedCase(c), o);
    out.ms = cpu_ms() - t0;
    out.error = case_error(r.series, reference, c).max();
    out.estimate = r.info.error_estimate;
    out.cells = r.info.cells_per_a1;
  } catch (const CaseAbandoned& e) {
    out.abandoned = true;
    out.what = e.what();
    out.ms = cpu_ms() - t0;
  }
  return out;
}

std::vector<double> brute_force_errors(const Case& c, const Series& reference,
                                       const std::vector<double>& cells) {
  std::vector<double> err;
  for (double n : cells) {
    SpectrumBaselineOptions b;
    b.cells_per_a1 = n;
    b.estimate_error = false;
    err.push_back(case_error(run_spectrum_baseline(CheckedCase(c), b).series, reference, c).max());
  }
  return err;
}

} // namespace mdrmap
