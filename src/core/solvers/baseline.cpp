#include "core/solvers/baseline.hpp"

#include "core/metrics/error_metric.hpp"
#include "core/solvers/step_samples.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

// The straightforward method, deliberately plain: every element of the travel
// path is stored and visited at every step; one fixed step dt = dx / (largest
// velocity of the history);
// contact changes are detected at step ends (first order in dt); forces are
// raw element sums and a2 is the last element in contact (first order in dx).
// Free relaxation is still exact (exp(-dt/tau)) so that the method is stable
// for dt >> tau; the paper's explicit update would not be.

namespace mdrmap {

namespace {

/// Step counts of the fixed-step run: dt = dx / (steps_per_cell * the
/// largest velocity of the history), each segment cut into whole steps.
struct Grid {
  double dt = 0.0;
  long n_pre = 0;
  std::vector<long> n_seg;
  double travel = 0.0; ///< over the spin-up and the history
  std::size_t n_elem = 0;
};

Grid make_grid(const Case& c, const BaselineOptions& opt) {
  if (!(opt.cells_per_a1 >= 2.0) || !(opt.spinup_travel >= 2.0) || !(opt.steps_per_cell > 0.0))
    throw InvalidInput("cells-per-a1", "baseline needs cells_per_a1 >= 2, spin-up >= 2 a1");
  const double a1 = c.a1(), dx = a1 / opt.cells_per_a1, v0 = c.history.v0;
  double wmax = v0;
  for (const auto& seg : c.history.segments)
    wmax = std::max(wmax, seg.w);
  Grid g;
  g.dt = dx / (opt.steps_per_cell * wmax);
  const double n_pre = std::ceil(opt.spinup_travel * a1 / (v0 * g.dt));
  double steps = n_pre, travel = v0 * g.dt * n_pre;
  std::vector<double> n_seg;
  for (const auto& seg : c.history.segments) {
    n_seg.push_back(std::max(1.0, std::ceil(seg.T / g.dt)));
    steps += n_seg.back();
    travel += seg.w * seg.T;
  }
  const double n_elem = std::ceil((2.0 * a1 + travel) / dx) + 4.0;
  if (!std::isfinite(n_elem) || !std::isfinite(steps))
    throw std::runtime_error("baseline: the case's length and time scales are too far apart "
                             "for the fixed-step method (step counts not representable)");
  if (!(n_elem <= static_cast<double>(opt.max_elements)) || !(steps <= 1e9) ||
      !(n_elem * steps <= 1e12))
    throw std::runtime_error("baseline: the case needs " + format_number(n_elem) +
                             " elements and " + format_number(steps) +
                             " steps; too expensive for the fixed-step method");
  g.n_pre = static_cast<long>(n_pre);
  for (double n : n_seg)
    g.n_seg.push_back(static_cast<long>(n));
  g.travel = travel;
  g.n_elem = static_cast<std::size_t>(n_elem);
  return g;
}

/// The element row over the whole travel path.
struct Row {
  const Case& c;
  const RunControl& control;
  double a1, dx, x0;
  std::vector<double> u;
  std::vector<unsigned char> contact;

  double h(double x) const { return (a1 - x) * (a1 + x) / c.indenter.as<Parabola>().R; }
  double force(double xi, double w) const { // per element / dx
    return 4.0 * c.rheology.G * (h(xi) - c.rheology.tau * w * c.indenter.slope(xi));
  }
  double xi(std::size_t i, double sp) const { return x0 + static_cast<double>(i) * dx + sp; }

  void step(double sp, double w, double dec) {
    control.charge(static_cast<double>(u.size()), "baseline");
    for (std::size_t i = 0; i < u.size(); ++i) {
      const double x = xi(i, sp), hi = h(x);
      if (contact[i]) {
        if (force(x, w) < 0.0 || x > a1) contact[i] = 0;
        u[i] = hi;
      } else {
        u[i] *= dec;
        if (hi >= u[i] && x >= -a1 && x <= a1) {
          contact[i] = 1;
          u[i] = hi;
        }
      }
    }
  }
  /// A velocity change takes no time: elements whose force turns negative let go.
  void change(double sp, double w) {
    control.charge(static_cast<double>(u.size()), "baseline");
    for (std::size_t i = 0; i < u.size(); ++i)
      if (contact[i] && force(xi(i, sp), w) < 0.0) contact[i] = 0;
  }
  State measure(double sp, double w) const {
    control.charge(static_cast<double>(u.size()), "baseline");
    double sN = 0.0, sX = 0.0, a2 = -a1;
    for (std::size_t i = 0; i < u.size(); ++i) {
      if (!contact[i]) continue;
      const double x = xi(i, sp), f = force(x, w);
      sN += f;
      sX += f * (-c.indenter.slope(x));
      a2 = std::max(a2, x);
    }
    State st;
    st.FN = sN * dx;
    st.Fx = sX * dx;
    st.mu = st.Fx / st.FN;
    st.d = c.loading.d;
    st.a1 = a1;
    st.a2 = a2;
    return st;
  }
};

RunResult run_baseline_once(const Case& c, const BaselineOptions& opt, const RunControl& control) {
  const Grid g = make_grid(c, opt);
  const double a1 = c.a1(), dx = a1 / opt.cells_per_a1, v0 = c.history.v0;
  // Lab positions x_i = x0 + i dx; the indenter coordinate is xi = x + s(t),
  // with s = 0 at the first change.
  Row row{c,
          control,
          a1,
          dx,
          -a1 - (g.travel - v0 * g.dt * static_cast<double>(g.n_pre)) - 2.0 * dx,
          std::vector<double>(g.n_elem, 0.0),
          std::vector<unsigned char>(g.n_elem, 0)};
  auto decay = [&](double dt) {
    return c.rheology.tau > 0.0 ? std::exp(-dt / c.rheology.tau) : 0.0;
  };
  RunResult res;
  res.info.solver = "baseline";
  res.info.cells_per_a1 = opt.cells_per_a1;
  res.info.elements = static_cast<long>(g.n_elem);
  const double s_start = -v0 * g.dt * static_cast<double>(g.n_pre);
  for (long k = 1; k <= g.n_pre; ++k)
    row.step(s_start + v0 * g.dt * static_cast<double>(k), v0, decay(g.dt));
  res.series.pre = row.measure(0.0, v0);
  res.series.resize(c.total_samples());
  res.probes.assign(c.history.size(), Probes{});
  const ProbeRule rule = step_probe_rule(c);
  double sp = 0.0;
  long steps = g.n_pre;
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double dt = seg.T / static_cast<double>(g.n_seg[k]), dec = decay(dt);
    const double sp0 = sp;
    row.change(sp, seg.w);
    sample_steps(
        c, k, g.n_seg[k], dt,
        [&](long j) { row.step(sp0 + seg.w * dt * static_cast<double>(j + 1), seg.w, dec); },
        [&](long j) { return row.measure(sp0 + seg.w * dt * static_cast<double>(j), seg.w); }, rule,
        res.series, i, res.probes[k], control);
    sp = sp0 + seg.w * seg.T;
    steps += g.n_seg[k];
  }
  res.info.steps = steps;
  res.info.element_updates = static_cast<long>(g.n_elem) * (steps + 1);
  return res;
}

} // namespace

RunResult run_baseline(const Case& s, const BaselineOptions& opt) {
  validate(s);
  require_depth_control(s, "baseline");
  require_kelvin(s, "baseline");
  require_parabola(s, "baseline");
  const RunControl own;
  const RunControl& control = opt.control != nullptr ? *opt.control : own;
  RunResult res = run_baseline_once(s, opt, control);
  if (opt.estimate_error) {
    // First order: the difference to a half-resolution run is about the error.
    BaselineOptions half = opt;
    half.cells_per_a1 = std::max(2.0, 0.5 * opt.cells_per_a1);
    const RunResult coarse = run_baseline_once(s, half, control);
    res.info.error_estimate = case_error(coarse.series, res.series, s, 1e-12).max();
    res.info.steps += coarse.info.steps;
    res.info.element_updates += coarse.info.element_updates;
  }
  return res;
}

} // namespace mdrmap
