#include "core/solvers/spectrum_baseline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/metrics/error_metric.hpp"
#include "core/metrics/stationary.hpp"
#include "core/solvers/step_samples.hpp"

namespace mdrmap {
namespace {

constexpr const char* kName = "baseline";

/// The element row over the whole travel path: u, q_1..q_N per element.
struct Row {
  const Case& c;
  const RunControl& control;
  double a1, dx, x0; // lab position of element i: x0 + i dx; xi = x + s
  std::size_t N;
  std::vector<double> u, q;
  std::vector<unsigned char> contact;
  long updates = 0;
  double aw = 0.0;          // the window: every a1 the run reaches
  double d = 0.0, dd = 0.0; // depth and its rate (fixed depth: d, 0)

  double h(double x) const { return d - c.indenter.g(x); }
  void set_depth(double dn, double rate) {
    d = dn;
    dd = rate;
    a1 = c.indenter.leading_edge(d);
  }
  double xi(std::size_t i, double s) const { return x0 + static_cast<double>(i) * dx + s; }
  double force(std::size_t i, double x, double w) const { // per 4 dx
    const Rheology& r = c.rheology;
    double p = r.G * u[i] + r.G * r.tau * (dd - w * c.indenter.slope(x));
    for (std::size_t k = 0; k < N; ++k)
      p += r.branches[k].G * (u[i] - q[i * N + k]);
    return p;
  }
  // elements that can touch: the rest lies ahead (untouched) or behind a1 (never again)
  std::pair<std::size_t, std::size_t> range(double s) const {
    const double lo = std::floor((-aw - s - x0) / dx) - 1.0,
                 hi = std::ceil((aw - s - x0) / dx) + 1.0;
    const double n = static_cast<double>(u.size());
    return {static_cast<std::size_t>(std::clamp(lo, 0.0, n)),
            static_cast<std::size_t>(std::clamp(hi, 0.0, n))};
  }

  void step(double s, double w, double dt, const std::vector<double>& e) {
    const Rheology& r = c.rheology;
    const auto [lo, hi] = range(s);
    control.charge(static_cast<double>(hi - lo), kName);
    updates += static_cast<long>(hi - lo);
    for (std::size_t i = lo; i < hi; ++i) {
      const double x = xi(i, s), hx = h(x);
      // (not &q[i * N]: without branches q is empty)
      double* qi = q.data() + i * N;
      if (!contact[i]) { // implicit force balance with the relaxed branches
        double num = r.G * r.tau * u[i] / dt, den = r.G + r.G * r.tau / dt;
        for (std::size_t k = 0; k < N; ++k) {
          num += r.branches[k].G * e[k] * qi[k];
          den += r.branches[k].G * e[k];
        }
        u[i] = num / den;
        if (u[i] <= hx && x >= -a1 && x <= a1) contact[i] = 1;
      }
      if (contact[i]) u[i] = hx;
      for (std::size_t k = 0; k < N; ++k)
        qi[k] = u[i] + (qi[k] - u[i]) * e[k];
      if (contact[i] && (force(i, x, w) < 0.0 || x > a1)) contact[i] = 0;
    }
  }
  void change(double s, double w) {
    const auto [lo, hi] = range(s);
    control.charge(static_cast<double>(hi - lo), kName);
    for (std::size_t i = lo; i < hi; ++i)
      if (contact[i] && force(i, xi(i, s), w) < 0.0) contact[i] = 0;
  }
  State measure(double s, double w) const {
    const auto [lo, hi] = range(s);
    control.charge(static_cast<double>(hi - lo), kName);
    double sN = 0.0, sX = 0.0, a2 = -a1;
    for (std::size_t i = lo; i < hi; ++i) {
      if (!contact[i]) continue;
      const double x = xi(i, s), f = force(i, x, w);
      sN += f;
      sX += f * (-c.indenter.slope(x));
      a2 = std::max(a2, x);
    }
    State st;
    st.FN = 4.0 * dx * sN;
    st.Fx = 4.0 * dx * sX;
    st.mu = st.Fx / st.FN;
    st.d = d;
    st.a1 = a1;
    st.a2 = a2;
    return st;
  }
};

/// Under load: each step's end depth d1 balances F_N = F0 (the dashpot sees
/// (d1 - d0) / dt), found by the Illinois method on a bracket (F_N increases
/// with d1); elements in the step's range are restored before each trial.
struct LoadBalance {
  Row& row;
  double F0;
  std::vector<double> u, q;
  std::vector<unsigned char> contact;

  void step(double s, double w, double dt, const std::vector<double>& e) {
    const auto [lo, hi] = row.range(s);
    const std::size_t N = row.N;
    u.assign(row.u.begin() + static_cast<long>(lo), row.u.begin() + static_cast<long>(hi));
    q.assign(row.q.begin() + static_cast<long>(lo * N), row.q.begin() + static_cast<long>(hi * N));
    contact.assign(row.contact.begin() + static_cast<long>(lo),
                   row.contact.begin() + static_cast<long>(hi));
    const double d0 = row.d;
    auto f = [&](double d1) {
      std::copy(u.begin(), u.end(), row.u.begin() + static_cast<long>(lo));
      std::copy(q.begin(), q.end(), row.q.begin() + static_cast<long>(lo * N));
      std::copy(contact.begin(), contact.end(), row.contact.begin() + static_cast<long>(lo));
      row.set_depth(d1, (d1 - d0) / dt);
      row.step(s, w, dt, e);
      return row.measure(s, w).FN - F0;
    };
    double a = d0, fa = f(a), b = a, fb = fa, step = 1e-3 * d0;
    for (int n = 0; fa * fb > 0.0; ++n) { // bracket
      if (n > 80) throw std::runtime_error("baseline: no depth balances the load");
      a = b;
      fa = fb;
      b = fa < 0.0 ? a + step : std::max(0.5 * a, a - step);
      fb = f(b);
      step *= 2.0;
    }
    for (int n = 0; n < 200 && std::abs(b - a) > 1e-13 * d0; ++n) { // Illinois
      const double x = b - fb * (b - a) / (fb - fa), fx = f(x);
      if (fx * fb < 0.0) {
        a = b;
        fa = fb;
      } else {
        fa *= 0.5;
      }
      b = x;
      fb = fx;
      if (fx == 0.0) break;
    }
    if (row.d != b) f(b);
  }

  /// A velocity change with a dashpot: the depth rate that keeps F_N = F0 at
  /// the instant (elements whose force turns negative let go), by bisection.
  void change(double s, double w) {
    if (!(row.c.rheology.tau > 0.0)) {
      row.change(s, w);
      return;
    }
    const auto [lo, hi] = row.range(s);
    contact.assign(row.contact.begin() + static_cast<long>(lo),
                   row.contact.begin() + static_cast<long>(hi));
    auto f = [&](double dd) {
      std::copy(contact.begin(), contact.end(), row.contact.begin() + static_cast<long>(lo));
      row.dd = dd;
      row.change(s, w);
      return row.measure(s, w).FN - F0;
    };
    const double unit = row.d / row.c.rheology.tau;
    double a = row.dd, b = a, fb = f(b), step = unit;
    for (int n = 0; n < 200 && f(a) * fb > 0.0; ++n) {
      a = b;
      b = fb < 0.0 ? b + step : b - step;
      fb = f(b);
      step *= 2.0;
    }
    if (a > b) std::swap(a, b);
    for (int n = 0; n < 200 && b - a > 1e-13 * unit; ++n) {
      const double m = 0.5 * (a + b);
      (f(m) < 0.0 ? a : b) = m;
    }
    f(0.5 * (a + b));
  }
};

RunResult run_once(const Case& c, const SpectrumBaselineOptions& o, const RunControl& control) {
  if (!(o.cells_per_a1 >= 2.0) || !(o.spinup_travel >= 2.5) || !(o.steps_per_cell > 0.0))
    throw InvalidInput("cells-per-a1", "baseline needs cells_per_a1 >= 2, spin-up >= 2.5 a1");
  const bool load = c.loading.by_force();
  const double v0 = c.history.v0;
  const double d_start = load ? stationary_load_depth(c, v0) : c.loading.d;
  const double a1 = c.indenter.leading_edge(d_start), dx = a1 / o.cells_per_a1;
  const double aw = load ? 1.1 * std::max(a1, c.a0()) : a1; // (a1 <= a0 under load)
  double wmax = v0;
  for (const auto& seg : c.history.segments)
    wmax = std::max(wmax, seg.w);
  const double dt0 = dx / (o.steps_per_cell * wmax);
  const auto n_pre = static_cast<long>(std::ceil(o.spinup_travel * aw / (v0 * dt0)));
  double travel = v0 * dt0 * static_cast<double>(n_pre), steps = static_cast<double>(n_pre);
  for (const auto& seg : c.history.segments) {
    travel += seg.w * seg.T;
    steps += std::max(1.0, std::ceil(seg.T / dt0));
  }
  const double n_elem = std::ceil((2.0 * aw + travel) / dx) + 4.0;
  if (!(n_elem <= static_cast<double>(o.max_elements)) || !(steps <= 1e9))
    throw CaseAbandoned("baseline: the case needs " + format_number(n_elem) + " elements and " +
                        format_number(steps) +
                        " steps; too expensive for the fixed-step method (use --solver auto "
                        "or row)");
  const std::size_t N = c.rheology.branches.size();
  const auto ne = static_cast<std::size_t>(n_elem);
  const double s_pre = -v0 * dt0 * static_cast<double>(n_pre);
  // lab positions x0 + i dx cover every material point that passes [-aw, aw]
  // while s runs from s_pre to its end, travel + s_pre
  Row row{c,
          control,
          a1,
          dx,
          -aw - (travel + s_pre) - 2.0 * dx,
          N,
          std::vector<double>(ne, 0.0),
          std::vector<double>(ne * N, 0.0),
          std::vector<unsigned char>(ne, 0),
          0};
  row.aw = aw;
  row.set_depth(d_start, 0.0);
  LoadBalance balance{row, c.loading.F0, {}, {}, {}};
  auto step = [&](double s, double w, double dt, const std::vector<double>& e) {
    if (load) {
      balance.step(s, w, dt, e);
    } else {
      row.step(s, w, dt, e);
    }
  };
  auto decays = [&](double dt) {
    std::vector<double> e(N);
    for (std::size_t k = 0; k < N; ++k)
      e[k] = std::exp(-dt / c.rheology.branches[k].tau);
    return e;
  };
  RunResult res;
  res.info.solver = kName;
  res.info.cells_per_a1 = o.cells_per_a1;
  res.info.elements = static_cast<long>(ne);
  const std::vector<double> e0 = decays(dt0);
  for (long k = 1; k <= n_pre; ++k)
    step(s_pre + v0 * dt0 * static_cast<double>(k), v0, dt0, e0);
  res.series.pre = row.measure(0.0, v0);
  res.series.resize(c.total_samples());
  res.probes.assign(c.history.size(), Probes{});
  const ProbeRule rule = step_probe_rule(c);
  double sp = 0.0;
  long nsteps = n_pre;
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const long n = static_cast<long>(std::max(1.0, std::ceil(seg.T / dt0)));
    const double dt = seg.T / static_cast<double>(n), sp0 = sp;
    const std::vector<double> e = decays(dt);
    if (load) {
      balance.change(sp, seg.w);
    } else {
      row.change(sp, seg.w);
    }
    sample_steps(
        c, k, n, dt,
        [&](long j) { step(sp0 + seg.w * dt * static_cast<double>(j + 1), seg.w, dt, e); },
        [&](long j) { return row.measure(sp0 + seg.w * dt * static_cast<double>(j), seg.w); }, rule,
        res.series, i, res.probes[k], control);
    sp = sp0 + seg.w * seg.T;
    nsteps += n;
  }
  res.info.steps = nsteps;
  res.info.element_updates = row.updates;
  return res;
}

} // namespace

RunResult run_spectrum_baseline(const CheckedCase& checked, const SpectrumBaselineOptions& o) {
  const Case& given = checked.get();
  Case c = given;
  c.rheology = given.rheology.shifted();
  const RunControl own;
  const RunControl& control = o.control != nullptr ? *o.control : own;
  RunResult res = run_once(c, o, control);
  if (o.estimate_error) { // first order: the difference to half resolution is about the error
    SpectrumBaselineOptions half = o;
    half.cells_per_a1 = std::max(2.0, 0.5 * o.cells_per_a1);
    const RunResult coarse = run_once(c, half, control);
    res.info.error_estimate = case_error(coarse.series, res.series, c, 1e-12).max();
    res.info.steps += coarse.info.steps;
    res.info.element_updates += coarse.info.element_updates;
  }
  return res;
}

} // namespace mdrmap
