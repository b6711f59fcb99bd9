#include "core/solvers/load_baseline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/step_samples.hpp"

// The fixed-step element row under load control (docs/design.md, "Load control"). An
// element in contact at xi has u = d - g(xi), u' = d' - w g'(xi) and force
// 4 G dx (D - q(xi)) with D = d + tau d' and q = g + tau w g'. Over a contact
// set C of n elements the balance F0 = 4 G dx sum_C (D - q) gives
// D = (F0 / (4 G dx) + sum_C q) / n; elements with q > D would pull and leave,
// which lowers D, so the removal is repeated until no force is negative. Then
// d relaxes towards D exactly over the step (D held fixed: first order in dt).

namespace mdrmap {

namespace load_check {

double stationary_force(const Case& c, double d, double w) {
  Case cd = c;
  cd.loading.d = d;
  cd.loading.F0 = 0.0;
  return analytic::stationary(cd, w).FN;
}

double stationary_depth(const Case& c, double w) {
  const double F0 = c.loading.F0, a0 = c.a0(), d0 = a0 * a0 / c.indenter.as<Parabola>().R;
  auto f = [&](double d) { return stationary_force(c, d, w) - F0; };
  double hi = d0, fhi = f(hi);
  for (int k = 0; fhi < 0.0 && k < 200; ++k) // rounding at tau = 0 only
    fhi = f(hi *= 1.0 + 1e-12);
  if (fhi == 0.0) return hi;
  double lo = hi, flo = fhi;
  for (int k = 0; flo > 0.0 && k < 2000; ++k) { // F_N(d) >= 4G/R (2/3 a1^3 + w tau a1^2 / 2)
    hi = lo;
    fhi = flo;
    flo = f(lo *= 0.25);
  }
  if (flo == 0.0) return lo;
  if (!(flo < 0.0 && fhi > 0.0))
    throw std::runtime_error("load_check::stationary_depth: no bracket for the depth root");
  std::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(
      f, lo, hi, flo, fhi, boost::math::tools::eps_tolerance<double>(53), iters);
  return std::abs(f(r.first)) <= std::abs(f(r.second)) ? r.first : r.second;
}

State stationary_state(const Case& c, double w) {
  Case cd = c;
  cd.loading.d = stationary_depth(c, w);
  cd.loading.F0 = 0.0;
  return analytic::stationary(cd, w);
}

} // namespace load_check

namespace {

/// The fixed step and the length of the element row.
struct Grid {
  double dx = 0.0, dt = 0.0, a_lim = 0.0;
  std::vector<long> n_seg; ///< whole steps per segment
  long steps = 0;
  std::size_t n_elem = 0;
  long k0 = 0; ///< index of the element at xi = phase dx when s = 0
};

Grid make_grid(const Case& c, const LoadBaselineOptions& opt) {
  if (!(opt.cells_per_a0 >= 2.0) || !(opt.steps_per_cell > 0.0) || !(opt.dt >= 0.0) ||
      !(opt.depth_limit > 1.0))
    throw InvalidInput("cells-per-a0", "load baseline needs cells_per_a0 >= 2, steps_per_cell "
                                       "> 0, dt >= 0, depth_limit > 1");
  Grid g;
  g.dx = c.a0() / opt.cells_per_a0;
  g.a_lim = std::sqrt(opt.depth_limit) * c.a0();
  double wmax = c.history.v0, travel = 0.0, steps = 0.0;
  for (const auto& seg : c.history.segments) {
    wmax = std::max(wmax, seg.w);
    travel += seg.w * seg.T;
  }
  g.dt = opt.dt > 0.0 ? opt.dt : g.dx / (opt.steps_per_cell * wmax);
  for (const auto& seg : c.history.segments) {
    const double n = std::max(1.0, std::ceil(seg.T / g.dt * (1.0 - 1e-12)));
    if (!(n <= 1e9)) throw std::runtime_error("load baseline: too many steps");
    g.n_seg.push_back(static_cast<long>(n));
    steps += n;
  }
  const double k0 = std::ceil((g.a_lim + travel) / g.dx) + 2.0;
  const double n_elem = k0 + std::ceil(g.a_lim / g.dx) + 3.0;
  const double window = 2.0 * g.a_lim / g.dx;
  if (!(n_elem <= static_cast<double>(opt.max_elements)) || !(window * steps <= 2e11))
    throw std::runtime_error("load baseline: the case needs " + format_number(n_elem) +
                             " elements and " + format_number(steps) +
                             " steps; too expensive for the fixed-step method");
  g.steps = static_cast<long>(steps);
  g.k0 = static_cast<long>(k0);
  g.n_elem = static_cast<std::size_t>(n_elem);
  return g;
}

/// The element row over the whole travel path; only the window
/// [-a_lim, a_lim] in the indenter's frame is visited (ahead of it the
/// material is untouched, behind it it can never touch again while w >= 0).
class LoadRow {
public:
  LoadRow(const Case& c, const Grid& g, double phase, const RunControl& control)
      : c_(c), g_(g), control_(control), x0_((phase - static_cast<double>(g.k0)) * g.dx),
        u_(g.n_elem, 0.0), contact_(g.n_elem, 0) {}

  double depth() const { return d_; }
  long updates() const { return updates_; }

  /// Stationary sliding at v at depth d, at travel s = 0: contact on
  /// [-a1, a2(v)], behind it the stationary tail h(a2) exp(-(xi - a2)/(v tau)).
  void start_stationary(double d, double v) {
    Case cd = c_;
    cd.loading.d = d;
    d_ = d;
    const double a1 = cd.a1(), a2 = analytic::a2_stationary(cd, v);
    const double L = v * c_.rheology.tau, h2 = analytic::depth_at(cd, a2);
    for (std::size_t i = first(0.0); i < last(0.0); ++i) {
      const double x = xi(i, 0.0);
      contact_[i] = (x >= -a1 && x <= a2) ? 1 : 0;
      if (contact_[i])
        u_[i] = h(x);
      else if (x > a2)
        u_[i] = L > 0.0 ? h2 * std::exp(-(x - a2) / L) : 0.0;
    }
  }

  /// One step from travel s to s + w dt; dec = exp(-dt/tau).
  void step(double s, double w, double dt, double dec) {
    const double D = settle(s, w);
    d_ = D + (d_ - D) * dec;
    const double a1 = std::min(std::sqrt(c_.indenter.as<Parabola>().R * d_), g_.a_lim),
                 s1 = s + w * dt;
    for (std::size_t i = first(s1); i < last(s); ++i) {
      const double x = xi(i, s1), hx = h(x);
      const bool inside = std::abs(x) <= a1;
      if (contact_[i] && inside) {
        u_[i] = hx;
      } else {
        u_[i] *= dec;
        contact_[i] = (inside && u_[i] <= hx) ? 1 : 0;
        if (contact_[i]) u_[i] = hx;
      }
    }
    updates_ += static_cast<long>(last(s) - first(s1));
    charge(last(s) - first(s1) + 1);
    if (dec == 0.0) // relaxed within the step (tau = 0 or tau << dt): elastic balance
      while (relax_elastic(s1, w)) {
      }
    if (!(std::sqrt(c_.indenter.as<Parabola>().R * d_) <= g_.a_lim))
      throw std::runtime_error("load baseline: the depth left the window (a1 = " +
                               format_number(std::sqrt(c_.indenter.as<Parabola>().R * d_)) +
                               "); raise depth_limit");
  }

  /// The state at travel s and velocity w (after the force balance).
  State measure(double s, double w) {
    const double D = settle(s, w), G4 = 4.0 * c_.rheology.G * g_.dx;
    charge(last(s) - first(s));
    State st;
    st.a2 = -std::sqrt(c_.indenter.as<Parabola>().R * d_);
    for (std::size_t i = first(s); i < last(s); ++i) {
      if (!contact_[i]) continue;
      const double x = xi(i, s), p = G4 * (D - q(x, w));
      st.FN += p;
      st.Fx -= p * c_.indenter.slope(x);
      st.a2 = std::max(st.a2, x);
    }
    st.mu = st.Fx / st.FN;
    st.d = d_;
    st.a1 = std::sqrt(c_.indenter.as<Parabola>().R * d_);
    return st;
  }

private:
  const Case& c_;
  const Grid& g_;
  const RunControl& control_;
  double x0_, d_ = 0.0;
  std::vector<double> u_;
  std::vector<unsigned char> contact_;
  long updates_ = 0;

  void charge(std::size_t n) const { control_.charge(static_cast<double>(n), "load baseline"); }
  double xi(std::size_t i, double s) const { return x0_ + static_cast<double>(i) * g_.dx + s; }
  double h(double x) const { return d_ - c_.indenter.g(x); }
  double q(double x, double w) const {
    return c_.indenter.g(x) + c_.rheology.tau * w * c_.indenter.slope(x);
  }
  std::size_t index_at(double x, double s) const {
    const double k = std::floor((x - s - x0_) / g_.dx);
    return static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(u_.size())));
  }
  std::size_t first(double s) const { return index_at(-g_.a_lim, s); }
  std::size_t last(double s) const { return std::min(u_.size(), index_at(g_.a_lim, s) + 1); }

  /// D = d + tau d' from the force balance; elements with negative force
  /// leave first. With nothing in contact the indenter falls freely onto the
  /// first element it meets.
  double settle(double s, double w) {
    for (;;) {
      charge(last(s) - first(s) + 1);
      double n = 0.0, sq = 0.0;
      for (std::size_t i = first(s); i < last(s); ++i)
        if (contact_[i]) {
          n += 1.0;
          sq += q(xi(i, s), w);
        }
      if (n == 0.0) {
        touch_first(s);
        continue;
      }
      const double D = (c_.loading.F0 / (4.0 * c_.rheology.G * g_.dx) + sq) / n;
      bool left = false;
      for (std::size_t i = first(s); i < last(s); ++i)
        if (contact_[i] && q(xi(i, s), w) > D) {
          contact_[i] = 0;
          left = true;
        }
      if (!left) return D;
    }
  }

  /// With nothing left to relax, d = D: Newton's iteration on the convex
  /// force-depth relation (new contact at the new depth, then the balance
  /// again). Returns whether an element touched.
  bool relax_elastic(double s, double w) {
    d_ = settle(s, w);
    const double a1 = std::min(std::sqrt(c_.indenter.as<Parabola>().R * d_), g_.a_lim);
    charge(last(s) - first(s) + 1);
    bool touched = false;
    for (std::size_t i = first(s); i < last(s); ++i) {
      const double x = xi(i, s);
      if (contact_[i] || std::abs(x) > a1 || u_[i] > h(x)) continue;
      contact_[i] = 1;
      u_[i] = h(x);
      touched = true;
    }
    return touched;
  }

  void touch_first(double s) {
    charge(last(s) - first(s) + 1);
    double dmin = INFINITY;
    for (std::size_t i = first(s); i < last(s); ++i)
      dmin = std::min(dmin, u_[i] + c_.indenter.g(xi(i, s)));
    if (!(dmin <= c_.indenter.g(g_.a_lim)))
      throw std::runtime_error("load baseline: no element within the window to carry F0");
    d_ = std::max(d_, dmin);
    for (std::size_t i = first(s); i < last(s); ++i)
      if (u_[i] + c_.indenter.g(xi(i, s)) <= d_) {
        contact_[i] = 1;
        u_[i] = h(xi(i, s));
      }
  }
};

/// Steps of one segment: fixed steps of dt, except after an undeformed start.
/// There the depth grows as t^(2/3) from a contact of one element: d'' ~
/// t^(-4/3) is not integrable, so fixed steps converge at order 2/3 only, and
/// a first step of dt sinks the indenter onto one element far past the true
/// depth. Until t = tau the steps are graded, h = min(dt, t, dt sqrt(t/tau))
/// from t = tau (dx/a0)^3 / 100: no step longer than the time elapsed, and
/// sum h d'' finite, which restores first order in dt for about 2 tau/dt
/// extra steps (docs/design.md, "Load control").
struct Stepper {
  LoadRow& row;
  double tau;
  bool graded = false;  ///< after an undeformed start, until the elapsed time reaches tau
  double elapsed = 0.0; ///< time since the start while graded
  double t_first = 0.0; ///< the first graded step

  void step(double s, double w, double dt, double dec) {
    if (!graded) {
      row.step(s, w, dt, dec);
      return;
    }
    const double start = elapsed, end = elapsed + dt;
    double t = elapsed;
    auto sub = [&](double h) {
      row.step(s + w * (t - start), w, h, std::exp(-h / tau));
      t += h;
    };
    if (t == 0.0) sub(std::min(t_first, dt));
    while (end - t > 1e-12 * dt)
      sub(std::min({dt, t, dt * std::sqrt(t / tau), end - t}));
    elapsed = end;
    graded = elapsed < tau;
  }
};

RunResult run_once(const Case& c, const LoadBaselineOptions& opt, const RunControl& control) {
  const Grid g = make_grid(c, opt);
  LoadRow row(c, g, opt.phase, control);
  RunResult res;
  res.info.solver = "load_baseline";
  res.info.cells_per_a1 = opt.cells_per_a0;
  res.info.elements = static_cast<long>(g.n_elem);
  const double tau = c.rheology.tau;
  Stepper st{row, tau};
  if (opt.start == LoadBaselineStart::Stationary) {
    row.start_stationary(load_check::stationary_depth(c, c.history.v0), c.history.v0);
    res.series.pre = row.measure(0.0, c.history.v0);
  } else {
    st.graded = opt.graded_start && tau > 0.0;
    st.t_first = 1e-2 * tau * std::pow(opt.cells_per_a0, -3.0);
  }
  res.series.resize(c.total_samples());
  res.probes.assign(c.history.size(), Probes{});
  const ProbeRule rule = step_probe_rule(c);
  double s = 0.0;
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double dt = seg.T / static_cast<double>(g.n_seg[k]);
    const double dec = tau > 0.0 ? std::exp(-dt / tau) : 0.0, s0 = s;
    auto travel = [&](long n) { return s0 + seg.w * dt * static_cast<double>(n); };
    sample_steps(
        c, k, g.n_seg[k], dt, [&](long j) { st.step(travel(j), seg.w, dt, dec); },
        [&](long j) { return row.measure(travel(j), seg.w); }, rule, res.series, i, res.probes[k],
        control);
    s = travel(g.n_seg[k]);
  }
  res.info.steps = g.steps;
  res.info.element_updates = row.updates();
  return res;
}

} // namespace

RunResult run_load_baseline(const Case& c, const LoadBaselineOptions& opt) {
  validate(c);
  if (!c.loading.by_force())
    throw InvalidInput("solver", "the load-control baseline solves load control only (--F0); "
                                 "this case prescribes the depth (--d)");
  require_kelvin(c, "the load-control baseline");
  require_parabola(c, "the load-control baseline");
  const RunControl own;
  const RunControl& control = opt.control != nullptr ? *opt.control : own;
  RunResult res = run_once(c, opt, control);
  if (opt.estimate_error) {
    // First order in dx and dt: the difference to a run at half the
    // resolution in both is about the error.
    LoadBaselineOptions half = opt;
    half.cells_per_a0 = std::max(2.0, 0.5 * opt.cells_per_a0);
    half.dt = 2.0 * opt.dt;
    const RunResult coarse = run_once(c, half, control);
    res.info.error_estimate = case_error(coarse.series, res.series, c, 1e-12).max();
    res.info.steps += coarse.info.steps;
    res.info.element_updates += coarse.info.element_updates;
  }
  return res;
}

} // namespace mdrmap
