#include "fit/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include <ceres/ceres.h>

#include "fit/transform.hpp"

namespace mdrmap::fit {
namespace {

/// The residuals at z and, when asked, the forward-difference Jacobian: the
/// point and its n shifted copies go to the Evaluator as one batch. A shift
/// that would cross an upper bound goes the other way. Residuals already
/// known for a point are not evaluated again.
class BatchCost final : public ceres::CostFunction {
public:
  BatchCost(const Transform& tr, CountingModel& model, std::size_t m, double step)
      : tr_(tr), model_(model), step_(step) {
    set_num_residuals(static_cast<int>(m));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(tr.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const std::size_t n = tr_.size();
    const std::vector<double> z(parameters[0], parameters[0] + n);
    std::vector<std::vector<double>> points{z};
    std::vector<double> h(n, 0.0);
    if (jacobians != nullptr && jacobians[0] != nullptr)
      for (std::size_t j = 0; j < n; ++j) {
        h[j] = z[j] + step_ > tr_.z_hi(j) ? -step_ : step_;
        std::vector<double> zj = z;
        zj[j] += h[j];
        points.push_back(zj);
      }
    const auto r = evaluate(points);
    for (const auto& ri : r)
      if (ri.size() != static_cast<std::size_t>(num_residuals())) return false;
    std::copy(r[0].begin(), r[0].end(), residuals);
    if (points.size() > 1)
      for (std::size_t i = 0; i < r[0].size(); ++i)
        for (std::size_t j = 0; j < n; ++j)
          jacobians[0][i * n + j] = (r[j + 1][i] - r[0][i]) / h[j];
    return true;
  }

  /// Keeps the residuals r of the point z.
  void remember(const std::vector<double>& z, const std::vector<double>& r) const { cache_[z] = r; }

  /// The residuals of each point (in z), from the cache where known.
  std::vector<std::vector<double>> evaluate(const std::vector<std::vector<double>>& z) const {
    std::vector<std::vector<double>> out(z.size()), todo;
    std::vector<std::size_t> where;
    for (std::size_t k = 0; k < z.size(); ++k) {
      const auto it = cache_.find(z[k]);
      if (it != cache_.end()) {
        out[k] = it->second;
      } else {
        where.push_back(k);
        todo.push_back(tr_.x_of(z[k]));
      }
    }
    if (!todo.empty()) {
      const auto r = model_(todo);
      for (std::size_t k = 0; k < where.size(); ++k) {
        out[where[k]] = r.at(k);
        cache_[z[where[k]]] = r.at(k);
      }
    }
    return out;
  }

private:
  const Transform& tr_;
  CountingModel& model_;
  double step_;
  mutable std::map<std::vector<double>, std::vector<double>> cache_;
};

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

struct Run {
  std::vector<double> z;
  double cost = INFINITY;
  int iterations = 0;
  bool converged = false;
  std::string termination;
};

Run levenberg_marquardt(const Transform& tr, const BatchCost& cost_template, std::vector<double> z,
                        const Options& opt) {
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  auto* cost = const_cast<BatchCost*>(&cost_template);
  problem.AddResidualBlock(cost, nullptr, z.data());
  for (std::size_t i = 0; i < tr.size(); ++i) {
    const int ii = static_cast<int>(i);
    if (std::isfinite(tr.z_lo(i))) problem.SetParameterLowerBound(z.data(), ii, tr.z_lo(i));
    if (std::isfinite(tr.z_hi(i))) problem.SetParameterUpperBound(z.data(), ii, tr.z_hi(i));
  }
  ceres::Solver::Options so;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = opt.max_iterations;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.num_threads = 1;
  // The cost is a simulation's: relative changes below the difference
  // step's reach are its noise, not progress.
  so.function_tolerance = 1e-3 * opt.step * opt.step;
  so.parameter_tolerance = 1e-2 * opt.step;
  so.gradient_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  Run r;
  r.z = z;
  r.cost = 2.0 * summary.final_cost;
  r.iterations = static_cast<int>(summary.iterations.size());
  r.converged = summary.termination_type == ceres::CONVERGENCE;
  r.termination = summary.message;
  return r;
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
  const auto grid = search_grid(tr, z0, opt);
  std::vector<std::vector<double>> xs;
  for (const auto& z : grid)
    xs.push_back(tr.x_of(z));
  const auto r = counted(xs);
  std::vector<std::pair<double, std::size_t>> ranked;
  std::size_t m = 0;
  for (std::size_t k = 0; k < r.size(); ++k)
    if (!r[k].empty()) {
      ranked.emplace_back(ssr_of(r[k]), k);
      m = r[k].size();
    }
  if (ranked.empty()) throw std::runtime_error("the model failed at every pre-search point");
  if (m < n + 1)
    throw std::invalid_argument(std::to_string(m) + " residuals for " + std::to_string(n) +
                                " parameters; a fit needs more residuals than parameters");
  std::sort(ranked.begin(), ranked.end());

  const BatchCost cost(tr, counted, m, opt.step);
  for (std::size_t k = 0; k < r.size(); ++k) // the pre-search's points are known
    if (!r[k].empty()) cost.remember(grid[k], r[k]);
  Run best;
  int iterations = 0;
  for (int s = 0; s < std::max(1, opt.starts) && s < static_cast<int>(ranked.size()); ++s) {
    Run run = levenberg_marquardt(tr, cost, grid[ranked[static_cast<std::size_t>(s)].second], opt);
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
  out.evaluations = counted.evaluations;
  out.batches = counted.batches;
  out.iterations = iterations;
  out.converged = best.converged;
  out.termination = best.termination;
  return out;
}

} // namespace mdrmap::fit
