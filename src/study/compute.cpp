#include "study/compute.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/analytic.hpp"
#include "core/events.hpp"

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

class Filler {
public:
  Filler(const io::RowLayout& L, std::vector<double>& v) : L_(L), v_(v) {}
  void put(const std::string& path, double x, std::size_t k = 0) { v_[L_.at(path, k)] = x; }
  // group/<q><suffix> for every quantity of the layout
  void state(const std::string& group, const std::string& suffix, const State& s,
             std::size_t k = 0) {
    for (std::size_t q = 0; q < L_.quantities(); ++q)
      put(group + "/" + L_.quantity(q) + suffix, L_.value(s, q), k);
  }
  void residuals(const std::string& suffix, const State& sim, const State& an, std::size_t k = 0) {
    for (std::size_t q = 0; q < L_.quantities(); ++q)
      put(std::string("residuals/") + L_.quantity(q) + suffix,
          residual(L_.value(sim, q), L_.value(an, q)), k);
  }

private:
  const io::RowLayout& L_;
  std::vector<double>& v_;
};

void fill_event(Filler& f, const EventMetrics& e, const State& after, std::size_t k) {
  f.put("events/t", e.t, k);
  f.state("events", "_after", after, k);
  f.put("events/mu_before", e.mu_before, k);
  f.put("events/mu_peak", e.mu_peak, k);
  f.put("events/t_peak", e.t_peak, k);
  f.put("events/slip_peak", e.slip_peak, k);
  f.state("events", "_end", e.end, k);
  f.put("events/a", defined_or_fill(e.a), k);
  f.put("events/b", defined_or_fill(e.b), k);
  f.put("events/a_minus_b", defined_or_fill(e.a_minus_b), k);
  f.put("events/d_c", defined_or_fill(e.d_c), k);
  f.state("analytic", "_ss", e.ss_after, k);
  f.residuals("_end", e.end, e.ss_after, k);
}

// The row of a solved case. Throws for a non-finite value.
void fill_row(io::CaseRow& row, const io::RowLayout& L, const Case& c, const RunResult& r) {
  const Series& x = r.series;
  const std::vector<EventMetrics> ev = event_metrics(c, x);
  Filler f(L, row.values);
  f.put("results/error_estimate", r.info.error_estimate);
  f.state("results", "_pre", x.pre);
  const State& an_pre = ev.front().ss_before; // stationary at v0, closed form
  f.state("analytic", "_pre", an_pre);
  f.residuals("_pre", x.pre, an_pre);
  const auto S = static_cast<std::size_t>(c.sampling.samples);
  for (std::size_t k = 0; k < ev.size(); ++k)
    fill_event(f, ev[k], x.at(k * S), k);
  if (!L.by_force()) { // the seed's corrected estimate of the first change
    const State jump = analytic::jump(c, c.history.v0, c.history.segments.front().w);
    f.state("analytic", "_jump", jump);
    f.residuals("_jump", x.at(0), jump);
  }
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
                         SolverKind kind, bool timeseries) {
  io::CaseRow row;
  row.values.assign(layout.row_width(), 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const Case c = case_for(cfg, r);
    const RunResult res = run_case(c, kind, cfg.run.rtol);
    fill_row(row, layout, c, res);
    if (timeseries) fill_series(row, layout, res.series);
    row.status = 1;
  } catch (const std::exception& e) {
    std::fill(row.values.begin(), row.values.end(), 0.0);
    row.series.clear();
    row.status = -1;
    row.message = e.what();
  }
  row.values[layout.at("results/wall_seconds")] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

} // namespace mdrmap::study
