#include "study/compute.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/metrics/analytic.hpp"
#include "core/metrics/events.hpp"
#include "core/model/scales.hpp"

namespace mdrmap::study {
namespace {

// (sim - analytic) / |analytic|; 0 when both vanish (tau = 0: F_x = mu = 0).
double residual(double sim, double an) {
  if (an == 0.0) return sim == 0.0 ? 0.0 : (sim > 0.0 ? 1.0 : -1.0);
  return (sim - an) / std::abs(an);
}

// An event metric that may be undefined (NaN): the fill value then.
double defined_or_fill(double x) {
  return std::isnan(x) ? io::kFillValue : x;
}

// Writes a case's values at the layout's slots (RowLayout::slots(): the
// field names resolved once per layout, not per case).
class Filler {
public:
  using PerQuantity = io::RowSlots::PerQuantity;
  Filler(const io::RowLayout& L, std::vector<double>& v) : L_(L), v_(v) {}
  void put(std::size_t at, double x, std::size_t k = 0) { v_[at + k] = x; }
  // <group>/<q><suffix> for every quantity of the layout, at `at`
  void state(const PerQuantity& at, const State& s, std::size_t k = 0) {
    for (std::size_t q = 0; q < L_.quantities(); ++q)
      v_[at[q] + k] = L_.value(s, q);
  }
  // the fill value (undefined) at every quantity's slot
  void fill(const PerQuantity& at, std::size_t k = 0) {
    for (std::size_t q = 0; q < L_.quantities(); ++q)
      v_[at[q] + k] = io::kFillValue;
  }
  void residuals(const PerQuantity& at, const State& sim, const State& an, std::size_t k = 0) {
    for (std::size_t q = 0; q < L_.quantities(); ++q)
      v_[at[q] + k] = residual(L_.value(sim, q), L_.value(an, q));
  }

private:
  const io::RowLayout& L_;
  std::vector<double>& v_;
};

// The event metrics and states the map holds (the output table's), then the
// closed-form stationary state at the segment's velocity and the end's
// residual from it.
void fill_event(Filler& f, const io::RowSlots& S, const EventMetrics& e, std::size_t k) {
  for (const auto& [o, at] : S.event_metrics)
    f.put(at, o->may_be_undefined ? defined_or_fill(e.*(o->event)) : e.*(o->event), k);
  for (const auto& [o, at] : S.event_states)
    f.state(at, e.*(o->event_state), k);
  f.state(S.analytic_ss, e.ss_after, k);
  f.residuals(S.residuals_end, e.end, e.ss_after, k);
}

// The seed's corrected estimate of the first change at fixed depth (of the
// Kelvin foundation, its time shifted by aT), and the state's residual from
// it; undefined (the fill value) for a spectrum.
void fill_jump(Filler& f, const io::RowSlots& S, const Case& c, const State& after) {
  if (!c.rheology.kelvin()) {
    f.fill(S.analytic_jump);
    f.fill(S.residuals_jump);
    return;
  }
  Case shifted; // a copy only where aT shifts (most studies have none)
  if (c.rheology.aT != 1.0) {
    shifted = c;
    shifted.rheology = c.rheology.shifted();
  }
  const Case& k = c.rheology.aT != 1.0 ? shifted : c;
  const State jump = analytic::jump(k, c.history.v0, c.history.segments.front().w);
  f.state(S.analytic_jump, jump);
  f.residuals(S.residuals_jump, after, jump);
}

// The row of a solved case. Throws for a non-finite value.
void fill_row(io::CaseRow& row, const io::RowLayout& L, const Case& c, const RunResult& r) {
  const Series& x = r.series;
  const io::RowSlots& S = L.slots();
  const std::vector<EventMetrics> ev =
      event_metrics(c, x, r.transients, r.info.error_estimate, r.probes);
  Filler f(L, row.values);
  for (const auto& [o, at] : S.results)
    f.put(at, o->result(r.info, 0.0));
  f.state(S.results_pre, x.pre);
  const State& an_pre = ev.front().ss_before; // stationary at v0, closed form
  f.state(S.analytic_pre, an_pre);
  f.residuals(S.residuals_pre, x.pre, an_pre);
  for (std::size_t k = 0; k < ev.size(); ++k)
    fill_event(f, S, ev[k], k);
  if (!L.by_force()) fill_jump(f, S, c, x.at(0));
  const Scales sc = scales(c);
  for (const auto& [o, at] : S.scales)
    f.put(at, sc.*(o->scale));
  for (double v : row.values)
    if (!std::isfinite(v)) throw std::runtime_error("the solver returned a non-finite value");
}

void fill_series(io::CaseRow& row, const io::RowLayout& L, const Series& x) {
  row.series.clear();
  for (std::size_t s = 0; s < L.series().size(); ++s) {
    const std::vector<double>& samples = L.samples(x, s);
    for (double v : samples)
      if (!std::isfinite(v)) throw std::runtime_error("the solver returned a non-finite value");
    row.series.push_back(samples);
  }
}

} // namespace

io::RowLayout row_layout(const StudyConfig& cfg) {
  return io::RowLayout(cfg.segments(), cfg.by_force());
}

io::CaseRow compute_case(const StudyConfig& cfg, const io::RowLayout& layout, const Row& r,
                         SolverKind kind, bool timeseries, const volatile std::sig_atomic_t* stop) {
  io::CaseRow row;
  row.values.assign(layout.row_width(), 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const CheckedCase c = checked_case_for(cfg, r); // checked once: run_case takes it as is
    RunControl control;
    control.stop = stop;
    const RunResult res = run_case(c, kind, cfg.run.rtol, control);
    fill_row(row, layout, c.get(), res);
    if (timeseries) fill_series(row, layout, res.series);
    row.status = 1;
  } catch (const Interrupted&) {
    throw; // not a failure: the case stays pending
  } catch (const std::exception& e) {
    std::fill(row.values.begin(), row.values.end(), 0.0);
    row.series.clear();
    row.status = -1;
    row.message = e.what();
  }
  row.values[layout.slots().wall_seconds] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

} // namespace mdrmap::study
