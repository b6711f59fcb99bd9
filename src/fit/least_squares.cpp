#include "fit/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "fit/batch_cost.hpp"
#include "fit/transform.hpp"

namespace mdrmap::fit {
namespace {

double ssr_of(const std::vector<double>& r) {
  return std::inner_product(r.begin(), r.end(), r.begin(), 0.0);
}

/// The pre-search points: per parameter k values over its bounds (where both
/// are finite) or over search_decades either side of the start (log
/// parameters), the start alone otherwise; the start itself first.
std::vector<std::vector<double>> search_grid(const Transform& tr, const std::vector<double>& z0,
                                             const Options& opt) {
  const std::size_t n = tr.size();
  int k = std::max(1, opt.grid_points);
  auto total = [&](int kk) {
    double t = 1.0;
    for (std::size_t i = 0; i < n; ++i)
      t *= kk;
    return t;
  };
  while (k > 1 && total(k) > static_cast<double>(opt.max_grid))
    k -= 2;
  std::vector<std::vector<double>> axes(n);
  for (std::size_t i = 0; i < n; ++i) {
    double lo = tr.z_lo(i), hi = tr.z_hi(i);
    if (!(std::isfinite(lo) && std::isfinite(hi)) && tr.p[i].log) {
      const double span = opt.search_decades * std::log(10.0);
      lo = std::max(lo, z0[i] - span);
      hi = std::min(hi, z0[i] + span);
    }
    if (k == 1 || !(std::isfinite(lo) && std::isfinite(hi))) {
      axes[i] = {z0[i]};
      continue;
    }
    for (int j = 0; j < k; ++j)
      axes[i].push_back(lo + (hi - lo) * j / (k - 1));
  }
  std::vector<std::vector<double>> grid{z0};
  std::vector<std::size_t> idx(n, 0);
  for (;;) {
    std::vector<double> z(n);
    for (std::size_t i = 0; i < n; ++i)
      z[i] = axes[i][idx[i]];
    if (z != z0) grid.push_back(z);
    std::size_t i = 0;
    while (i < n && ++idx[i] == axes[i].size())
      idx[i++] = 0;
    if (i == n) break;
  }
  return grid;
}

/// The pre-search: its points (z), their residuals, the points that the
/// model took by cost, and the number of residuals.
struct PreSearch {
  std::vector<std::vector<double>> grid, r;
  std::vector<std::pair<double, std::size_t>> ranked;
  std::size_t m = 0;
};

PreSearch pre_search(const Transform& tr, const std::vector<double>& z0, CountingModel& counted,
                     const Options& opt) {
  PreSearch pre;
  pre.grid = search_grid(tr, z0, opt);
  std::vector<std::vector<double>> xs;
  for (const auto& z : pre.grid)
    xs.push_back(tr.x_of(z));
  pre.r = counted(xs);
  for (std::size_t k = 0; k < pre.r.size(); ++k)
    if (!pre.r[k].empty()) {
      pre.ranked.emplace_back(ssr_of(pre.r[k]), k);
      pre.m = pre.r[k].size();
    }
  if (pre.ranked.empty()) throw std::runtime_error("the model failed at every pre-search point");
  if (pre.m < tr.size() + 1)
    throw std::invalid_argument(std::to_string(pre.m) + " residuals for " +
                                std::to_string(tr.size()) +
                                " parameters; a fit needs more residuals than parameters");
  std::sort(pre.ranked.begin(), pre.ranked.end());
  return pre;
}

void check_input(const std::vector<FreeParameter>& params) {
  if (params.empty()) throw std::invalid_argument("no free parameters");
  for (const auto& p : params) {
    if (!(p.start >= p.lo && p.start <= p.hi))
      throw std::invalid_argument(p.name + ": the start is outside the bounds");
    if (p.log && !(p.start > 0.0))
      throw std::invalid_argument(p.name + ": a log parameter must start > 0");
  }
}

} // namespace

Result fit(const std::vector<FreeParameter>& params, Evaluator& model, const Options& opt) {
  check_input(params);
  const Transform tr(params);
  const std::size_t n = tr.size();
  std::vector<double> z0(n);
  for (std::size_t i = 0; i < n; ++i)
    z0[i] = tr.to_z(i, params[i].start);

  CountingModel counted{model};
  const PreSearch pre = pre_search(tr, z0, counted, opt);
  const auto& grid = pre.grid;
  const auto& r = pre.r;
  const auto& ranked = pre.ranked;
  const std::size_t m = pre.m;
  const BatchCost cost(tr, counted, m, opt.step);
  for (std::size_t k = 0; k < r.size(); ++k) // the pre-search's points are known
    if (!r[k].empty()) cost.remember(grid[k], r[k]);
  Run best;
  int iterations = 0;
  for (int s = 0; s < std::max(1, opt.starts) && s < static_cast<int>(ranked.size()); ++s) {
    Run run =
        levenberg_marquardt(tr, cost, grid[ranked[static_cast<std::size_t>(s)].second], opt, n);
    iterations += run.iterations;
    if (run.cost < best.cost) best = run;
  }

  // The Jacobian at the optimum, for the statistics.
  std::vector<double> r0(m), jac(m * n);
  double* jp[] = {jac.data()};
  const double* zp[] = {best.z.data()};
  if (!cost.Evaluate(zp, r0.data(), jp))
    throw std::runtime_error("the model failed next to the optimum");
  Result out;
  fill_statistics(tr, best.z, r0, jac, opt, out);
  if (out.undetermined.empty()) profile_intervals(tr, cost, best.z, opt, out);
  out.evaluations = counted.evaluations;
  out.batches = counted.batches;
  out.iterations += iterations;
  out.converged = best.converged;
  out.termination = best.termination;
  return out;
}

} // namespace mdrmap::fit
