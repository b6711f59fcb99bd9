#pragma once
// The error control of the discrete solvers (docs/design.md, "The discrete
// solvers"): run at a resolution a1/dx, run a half-resolution companion with
// its elements at another phase, take the case error between the two as the
// estimate, and refine until it is below rtol. Shared by the element-row
// solvers (mdr; spectrum can call it the same way): they differ only in how
// one run goes, where they start and how fine they may go.
#include <functional>

#include "core/model/case.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// One run of a solver at one resolution and element phase.
struct ResolutionRun {
  Series series;
  long elements = 0; ///< elements held at once
  long steps = 0;    ///< time steps taken
  long updates = 0;  ///< element state updates
};

/// The samples of one run of an element-row solver over the case's history:
/// measure() before t = 0 (pre), then for each segment change(w) at its
/// start and, to each output instant, advance(dt, w) by the time since the
/// last one and measure() there.
template <class Change, class Advance, class Measure>
Series sample_history(const Case& c, Change change, Advance advance, Measure measure) {
  Series s;
  s.resize(c.total_samples());
  s.pre = measure();
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double t0 = c.history.start(k);
    change(seg.w);
    double prev = 0.0;
    for (long j = 0; j < c.sampling.samples; ++j, ++i) {
      const double off = c.sampling.offset(j, seg.T);
      advance(off - prev, seg.w);
      prev = off;
      s.set(i, t0 + off, static_cast<int>(k), measure());
    }
  }
  return s;
}

/// Runs the solver once at resolution `cells` (a1/dx) with element phase
/// `phase`.
using RunAtResolution = std::function<ResolutionRun(double cells, double phase)>;

/// How the error control proceeds.
struct Refinement {
  const char* solver = "";       ///< names the solver in RunInfo and in messages
  double cells = 0.0;            ///< starting resolution a1/dx
  double max_cells = 0.0;        ///< no refinement past it (the case is abandoned there)
  double rtol = 0.0;             ///< target case error
  double phase = 0.5;            ///< element phase of the fine runs
  bool adaptive = true;          ///< refine until the estimate is <= rtol (else one resolution)
  bool estimate = true;          ///< run the companion for an estimate even when not adaptive
  double rounding_level = 1e-11; ///< an estimate below this is rounding noise, not resolution
  /// Added to every estimate: the error the solver's own tolerances leave,
  /// which the companion shares (0: none).
  double tolerance_floor = 0.0;
  /// Where the difference to the companion lies in (rtol, 2 rtol], run a
  /// third resolution (a quarter, another phase) and credit the order the
  /// three show: with r the ratio of the coarser pair's difference to the
  /// finer pair's, the estimate is the difference over min(2, r - 1)
  /// (Richardson: at order p the fine run errs by the difference over
  /// 2^p - 1), unchanged where r <= 2 (order 1 or less observed).
  bool observed_order = false;
};

/// Phase of the companion: shifted by a non-commensurate fraction of a cell,
/// so that an error of a read-out that depends on where the grid falls is not
/// shared by both runs.
double companion_phase(double phase);

/// Runs `once` at r.cells (and the companion at r.cells / 2, companion_phase;
/// with observed_order, where it decides, a third at r.cells / 4) and refines
/// while adaptive and the estimate is above r.rtol: the series of
/// the finest run and its RunInfo (solver, rtol, error_estimate,
/// cells_per_a1, elements; steps, element_updates of all runs; refinements).
/// `c` is the case the estimate measures the series on (case_error). Throws
/// CaseAbandoned when the estimate stays above rtol: after 6 resolutions, at
/// max_cells, or once it stagnates as rounding noise.
RunResult refine(const Case& c, const Refinement& r, const RunAtResolution& once);

} // namespace mdrmap
