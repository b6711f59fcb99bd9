#include "core/solvers/refine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/metrics/error_metric.hpp"
#include "core/numerics/run_control.hpp"

namespace mdrmap {
namespace {

constexpr int kMaxAttempt = 5; // the sixth resolution is the last

// With convergence of order p the difference to the companion is ~(2^p - 1)
// times the error of the fine run: reported whole. Where both runs are exact
// it is rounding noise of either sign: a rounding floor is added, as the
// exact solver does.
double estimate(const ResolutionRun& coarse, const ResolutionRun& fine, const Case& c) {
  return case_error(coarse.series, fine.series, c, 1e-12).max() +
         64.0 * std::numeric_limits<double>::epsilon();
}

void add_cost(RunInfo& info, const ResolutionRun& run) {
  info.steps += run.steps;
  info.element_updates += run.updates;
}

// The difference d0 between the fine run and its companion, credited with
// the order a third run at a quarter of the fine resolution shows
// (Refinement::observed_order); d0 where that run cannot be made or shows
// order 1 or less.
double credited(const Case& c, const RunAtResolution& once, double cells, double phase2,
                const ResolutionRun& coarse, double d0, RunInfo& info) {
  ResolutionRun third;
  try {
    third = once(0.25 * cells, companion_phase(phase2), cells);
  } catch (const CaseAbandoned&) {
    return d0;
  }
  add_cost(info, third);
  const double ratio = estimate(third, coarse, c) / d0;
  return ratio > 2.0 ? d0 / std::min(2.0, ratio - 1.0) : d0;
}

[[noreturn]] void abandon(const Refinement& r, double est, int attempt, double cells) {
  throw CaseAbandoned(std::string(r.solver) + ": the error estimate " + format_number(est) +
                      " stays above rtol " + format_number(r.rtol) + " after " +
                      std::to_string(attempt + 1) + " resolutions (a1/dx up to " +
                      format_number(cells) + "); the case cannot meet rtol with this solver");
}

} // namespace

double shortest_time(const Case& c, double a1) {
  double t = std::numeric_limits<double>::infinity();
  for (const Segment& seg : c.history.segments)
    if (seg.w > 0.0) t = std::min(t, a1 / seg.w);
  if (c.history.v0 > 0.0) t = std::min(t, a1 / c.history.v0);
  if (c.rheology.tau > 0.0) t = std::min(t, c.rheology.tau);
  for (const Branch& b : c.rheology.branches)
    t = std::min(t, b.tau);
  return t;
}

double companion_phase(double phase) {
  return std::fmod(phase + 0.381966, 1.0);
}

RunResult refine(const Case& c, const Refinement& r, const RunAtResolution& once) {
  RunResult res;
  res.info.solver = r.solver;
  res.info.rtol = r.rtol;
  const double phase2 = companion_phase(r.phase);
  double cells = r.cells, prev_est = 0.0;
  for (int attempt = 0;; ++attempt) {
    ResolutionRun fine = once(cells, r.phase, cells);
    add_cost(res.info, fine);
    res.info.refinements = attempt + 1;
    double est = 0.0;
    if (r.estimate || r.adaptive) {
      const ResolutionRun coarse = once(0.5 * cells, phase2, cells);
      add_cost(res.info, coarse);
      est = estimate(coarse, fine, c);
      const double floor = r.tolerance_floor;
      if (r.observed_order && r.adaptive && est + floor > r.rtol && est + floor <= 2.0 * r.rtol &&
          0.25 * cells >= 4.0)
        est = credited(c, once, cells, phase2, coarse, est, res.info);
      est += floor;
    }
    res.series = std::move(fine.series);
    res.probes = std::move(fine.probes);
    res.info.error_estimate = est;
    res.info.cells_per_a1 = cells;
    res.info.elements = fine.elements;
    // refining no longer helps once the estimate is rounding noise (it no
    // longer falls); an estimate above rtol after the last refinement fails
    const bool stagnant = attempt > 0 && est > 0.5 * prev_est && est < r.rounding_level;
    prev_est = est;
    if (!r.adaptive || est <= r.rtol) break;
    if (stagnant || attempt >= kMaxAttempt || cells >= r.max_cells) abandon(r, est, attempt, cells);
    cells = std::min(r.max_cells, std::ceil(cells * std::max(1.5, 1.2 * std::sqrt(est / r.rtol))));
  }
  return res;
}

} // namespace mdrmap
