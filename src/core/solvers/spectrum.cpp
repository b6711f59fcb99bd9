#include "core/solvers/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/metrics/error_metric.hpp"
#include "core/solvers/spectrum_law.hpp"
#include "core/solvers/spectrum_row.hpp"

namespace mdrmap {
namespace {

constexpr const char* kName = "spectrum";
constexpr double kMaxCells = 2e5; // window memory: 4e5 elements of up to 33 doubles

struct SingleRun {
  Series series;
  long elements = 0, steps = 0, updates = 0;
};

SingleRun run_once(const Case& c, const spectrum::Law& law, double cells, double phase,
                   const SpectrumOptions& o, const RunControl& control) {
  double travel = 2.0 * cells + 8.0;
  for (const auto& seg : c.history.segments)
    travel += seg.w * seg.T / (c.a1() / cells);
  if (!(travel < 1e18))
    throw CaseAbandoned("spectrum: the indenter travels " + format_number(travel) +
                        " cells over the history, more than the element row can count (1e18)");
  spectrum::Row row(c, law, cells, phase, o.sub_travel, 1e-2 * o.rtol, control, kName);
  row.start_stationary(c.history.v0);
  SingleRun out;
  out.series.resize(c.total_samples());
  out.series.pre = row.measure();
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double t0 = c.history.start(k);
    row.change_velocity(seg.w);
    double prev = 0.0;
    for (long j = 0; j < c.sampling.samples; ++j, ++i) {
      const double off = c.sampling.offset(j, seg.T);
      row.advance(off - prev);
      prev = off;
      out.series.set(i, t0 + off, static_cast<int>(k), row.measure());
    }
  }
  out.elements = static_cast<long>(row.capacity());
  out.steps = row.steps();
  out.updates = row.updates();
  return out;
}

// An estimate below this is rounding noise of the two runs, not a resolution error.
constexpr double kRoundingLevel = 1e-11;

} // namespace

RunResult run_spectrum(const Case& given, const SpectrumOptions& o) {
  validate(given);
  if (given.loading.by_force())
    throw InvalidInput("solver", "spectrum solves depth control only (--d); under load control "
                                 "(--FN) use a Kelvin solver");
  const bool adaptive = !(o.cells_per_a1 > 0.0);
  if (adaptive) validate_rtol(o.rtol);
  if (!(o.sub_travel > 0.0) || !(o.sub_travel <= 2.0))
    throw InvalidInput("sub-travel", "must be in (0, 2] (a1 per sub-step)");
  Case c = given;
  c.rheology = given.rheology.shifted();
  const spectrum::Law law(c.rheology);
  double cells =
      adaptive ? std::clamp(std::ceil(1.0 / std::sqrt(o.rtol)), 16.0, kMaxCells) : o.cells_per_a1;
  if (!(cells >= 4.0) || cells > kMaxCells)
    throw InvalidInput("cells-per-a1", "must be between 4 and 2e5");
  RunResult res;
  res.info.solver = kName;
  res.info.rtol = o.rtol;
  const double companion_phase = std::fmod(o.phase + 0.381966, 1.0);
  const RunControl own;
  const RunControl& control = o.control != nullptr ? *o.control : own;
  double prev_est = 0.0;
  for (int attempt = 0;; ++attempt) {
    SingleRun fine = run_once(c, law, cells, o.phase, o, control);
    res.info.steps += fine.steps;
    res.info.element_updates += fine.updates;
    res.info.refinements = attempt + 1;
    double est = 0.0;
    if (o.estimate_error || adaptive) {
      // second order: the difference to the half-resolution companion (other
      // element phase) is ~3 times the fine run's error; reported whole
      SingleRun coarse = run_once(c, law, 0.5 * cells, companion_phase, o, control);
      res.info.steps += coarse.steps;
      res.info.element_updates += coarse.updates;
      est = case_error(coarse.series, fine.series, c, 1e-12).max() +
            64.0 * std::numeric_limits<double>::epsilon();
    }
    res.series = std::move(fine.series);
    res.info.error_estimate = est;
    res.info.cells_per_a1 = cells;
    res.info.elements = fine.elements;
    const bool stagnant = attempt > 0 && est > 0.5 * prev_est && est < kRoundingLevel;
    prev_est = est;
    if (!adaptive || est <= o.rtol) break;
    if (stagnant || attempt >= 5 || cells >= kMaxCells)
      throw CaseAbandoned("spectrum: the error estimate " + format_number(est) +
                          " stays above rtol " + format_number(o.rtol) + " after " +
                          std::to_string(attempt + 1) + " resolutions (a1/dx up to " +
                          format_number(cells) + "); the case cannot meet rtol with this solver");
    cells = std::min(kMaxCells, std::ceil(cells * std::max(1.5, 1.2 * std::sqrt(est / o.rtol))));
  }
  return res;
}

} // namespace mdrmap
