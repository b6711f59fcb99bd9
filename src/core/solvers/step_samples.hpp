#pragma once
// How a fixed-step solver (the baselines) samples a segment of n equal steps:
// each output instant at the step end nearest to it, and the probes of the
// event metrics (refine.hpp, ProbeRule) at the first step end at or after
// each of the rule's instants, so that the metrics depend on the steps and
// not on the output instants (docs/design.md, "Event metrics").
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/refine.hpp"

namespace mdrmap {

/// The probe rule of a fixed-step solver's case: the first probe at
/// kFirstProbe of its shortest time scale (refine.hpp), then ratio kProbeRatio.
inline ProbeRule step_probe_rule(const Case& c) {
  return ProbeRule{kFirstProbe * shortest_time(c, c.edge_scale()), kProbeRatio};
}

/// Segment k of c in n steps of dt: step(j) takes step j + 1 (from j dt to
/// (j + 1) dt), measure(j) is the state after j steps. Writes the segment's
/// samples into `series` from index i (advanced past them) and, where the
/// segment changes the velocity, its probes into `probes` (mu(0+), the rule's
/// instants on the step grid, the segment's end); reports each sample to
/// `control`. Returns after all n steps.
template <class Step, class Measure>
void sample_steps(const Case& c, std::size_t k, long n, double dt, Step step, Measure measure,
                  const ProbeRule& rule, Series& series, std::size_t& i, Probes& probes,
                  const RunControl& control) {
  const Segment& seg = c.history.segments[k];
  const double t0 = c.history.start(k);
  const bool probing =
      c.history.before(k) != seg.w && std::isfinite(rule.first) && rule.first > 0.0;
  // the first step end at or after t (never step 0 after the start)
  auto at_or_after = [&](double t) {
    const double j = std::min(std::ceil(t / dt * (1.0 - 1e-12)), static_cast<double>(n));
    return std::max(static_cast<long>(j), 1L);
  };
  long next = n + 1; // the next step end to probe (n + 1: none)
  auto probe = [&](long j) {
    probes.t.push_back(j == n ? seg.T : dt * static_cast<double>(j));
    probes.mu.push_back(measure(j).mu);
    if (j == n) {
      next = n + 1;
      return;
    }
    double t = dt * static_cast<double>(j);
    do
      t = rule.next(t);
    while (at_or_after(t) <= j);
    next = at_or_after(t);
  };
  if (probing) probe(0);
  long done = 0;
  auto advance = [&](long target) {
    for (; done < target; ++done) {
      step(done);
      if (done + 1 == next) probe(done + 1);
    }
  };
  for (long j = 0; j < c.sampling.count(k); ++j, ++i) {
    const double off = c.sampling.offset(k, j, seg.T);
    advance(std::min(n, static_cast<long>(std::llround(off / dt))));
    series.set(i, t0 + off, static_cast<int>(k), measure(done));
    control.report(i + 1, series.size());
  }
  advance(n); // (the last sample ends the segment already)
}

} // namespace mdrmap
