#include "core/baseline.hpp"

#include "core/error_metric.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

// The straightforward method, deliberately plain: every element of the travel
// path is stored and visited at every step; one fixed step dt = dx / v;
// contact changes are detected at step ends (first order in dt); forces are
// raw element sums and a2 is the last element in contact (first order in dx).
// Free relaxation is still exact (exp(-dt/tau)) so that the method is stable
// for dt >> tau; the paper's explicit update would not be.

namespace mdrmap {

namespace {

RunResult run_baseline_once(const Scene& s, const Protocol& p, const BaselineOptions& opt) {
  validate(p);
  if (!(opt.cells_per_a1 >= 2.0) || !(opt.spinup_travel >= 2.0) || !(opt.steps_per_cell > 0.0))
    throw InvalidInput("cells-per-a1", "baseline needs cells_per_a1 >= 2, spin-up >= 2 a1");
  const double a1 = analytic::a1(s);
  const double dx = a1 / opt.cells_per_a1;
  const double dt = dx / (opt.steps_per_cell * s.v);
  const double n_pre_d = std::ceil(opt.spinup_travel * a1 / (s.v * dt));
  const double n_post_d = std::ceil(p.t_end / dt);
  const double travel = s.v * dt * n_pre_d + s.v1 * dt * n_post_d;
  const double n_elem_d = std::ceil((2.0 * a1 + travel) / dx) + 4.0;
  if (!std::isfinite(n_elem_d) || !std::isfinite(n_pre_d) || !std::isfinite(n_post_d))
    throw std::runtime_error("baseline: the scene's length and time scales are too far apart "
                             "for the fixed-step method (step counts not representable)");
  if (!(n_elem_d <= static_cast<double>(opt.max_elements)) || !(n_post_d <= 1e9) ||
      !(n_pre_d <= 1e9) || !(n_elem_d * (n_post_d + n_pre_d) <= 1e12))
    throw std::runtime_error("baseline: the scene needs " + format_number(n_elem_d) +
                             " elements and " + format_number(n_post_d) +
                             " steps after the step; too expensive for the fixed-step method");
  const auto n_elem = static_cast<std::size_t>(n_elem_d);
  const auto n_post = static_cast<long>(n_post_d);
  const auto n_pre = static_cast<long>(n_pre_d);

  // Lab positions: x_i = x0 + i dx; the indenter coordinate is xi = x + s(t),
  // with s(0) = 0 at the velocity step.
  const double s_start = -s.v * dt * static_cast<double>(n_pre);
  const double x0 = -a1 - s.v1 * dt * n_post_d - 2.0 * dx;
  std::vector<double> u(n_elem, 0.0);
  std::vector<unsigned char> contact(n_elem, 0);
  const double dec = s.tau > 0.0 ? std::exp(-dt / s.tau) : 0.0;
  auto h = [&](double x) { return (a1 - x) * (a1 + x) / s.R; };

  auto step = [&](double sp, double w) {
    for (std::size_t i = 0; i < n_elem; ++i) {
      const double xi = x0 + static_cast<double>(i) * dx + sp;
      const double hi = h(xi);
      if (contact[i]) {
        if (hi - s.tau * w * 2.0 * xi / s.R < 0.0 || xi > a1) contact[i] = 0; // force < 0
        u[i] = hi;
      } else {
        u[i] *= dec;
        if (hi >= u[i] && xi >= -a1 && xi <= a1) {
          contact[i] = 1;
          u[i] = hi;
        }
      }
    }
  };
  auto measure = [&](double sp, double w) {
    State st;
    double sN = 0.0, sX = 0.0, a2 = -a1;
    for (std::size_t i = 0; i < n_elem; ++i) {
      if (!contact[i]) continue;
      const double xi = x0 + static_cast<double>(i) * dx + sp;
      const double f = 4.0 * s.G * (h(xi) - s.tau * w * 2.0 * xi / s.R);
      sN += f;
      sX += f * (-2.0 * xi / s.R);
      a2 = std::max(a2, xi);
    }
    st.FN = sN * dx;
    st.Fx = sX * dx;
    st.mu = st.Fx / st.FN;
    st.a2 = a2;
    return st;
  };

  RunResult res;
  res.info.solver = "baseline";
  res.info.cells_per_a1 = opt.cells_per_a1;
  res.info.elements = static_cast<long>(n_elem);
  for (long k = 1; k <= n_pre; ++k)
    step(s_start + s.v * dt * static_cast<double>(k), s.v);
  res.series.pre = measure(0.0, s.v);
  // The step itself takes no time: elements whose force turns negative at v1
  // let go, nothing relaxes.
  for (std::size_t i = 0; i < n_elem; ++i) {
    const double xi = x0 + static_cast<double>(i) * dx;
    if (contact[i] && h(xi) - s.tau * s.v1 * 2.0 * xi / s.R < 0.0) contact[i] = 0;
  }
  const auto n = static_cast<std::size_t>(p.samples);
  res.series.resize(n);
  long done = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = p.time(static_cast<long>(k));
    const auto target = static_cast<long>(std::llround(t / dt)); // nearest step
    for (; done < std::min(target, n_post); ++done)
      step(s.v1 * dt * static_cast<double>(done + 1), s.v1);
    res.series.set(k, t, measure(s.v1 * dt * static_cast<double>(done), s.v1));
  }
  res.info.steps = n_pre + done;
  res.info.element_updates = static_cast<long>(n_elem) * (n_pre + done + 1);
  return res;
}

} // namespace

RunResult run_baseline(const Scene& s, const Protocol& p, const BaselineOptions& opt) {
  validate(s);
  validate(p);
  RunResult res = run_baseline_once(s, p, opt);
  if (opt.estimate_error) {
    // First order: the difference to a half-resolution run is about the error.
    BaselineOptions half = opt;
    half.cells_per_a1 = std::max(2.0, 0.5 * opt.cells_per_a1);
    const RunResult coarse = run_baseline_once(s, p, half);
    res.info.error_estimate = case_error(coarse.series, res.series, s, 1e-12).max();
    res.info.steps += coarse.info.steps;
    res.info.element_updates += coarse.info.element_updates;
  }
  return res;
}

} // namespace mdrmap
