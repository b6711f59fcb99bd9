#pragma once
// Internal to the fit library: the cost Ceres sees (residuals and a
// forward-difference Jacobian evaluated as one batch, cached per point) and
// one Levenberg-Marquardt run, optionally with one parameter held fixed (a
// profile of the cost).
#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <ceres/ceres.h>

#include "fit/transform.hpp"

namespace mdrmap::fit {

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
        if (j == fixed_) continue;
        h[j] = z[j] + step_ > tr_.z_hi(j) ? -step_ : step_;
        std::vector<double> zj = z;
        zj[j] += h[j];
        points.push_back(zj);
      }
    const auto r = evaluate(points);
    for (const auto& ri : r)
      if (ri.size() != static_cast<std::size_t>(num_residuals())) return false;
    std::copy(r[0].begin(), r[0].end(), residuals);
    if (jacobians != nullptr && jacobians[0] != nullptr)
      for (std::size_t i = 0; i < r[0].size(); ++i)
        for (std::size_t j = 0, col = 1; j < n; ++j)
          jacobians[0][i * n + j] = j == fixed_ ? 0.0 : (r[col++][i] - r[0][i]) / h[j];
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

  /// Holds parameter i fixed (its Jacobian column 0, not evaluated); n: none.
  void fix(std::size_t i) const { fixed_ = i; }

private:
  const Transform& tr_;
  mutable std::size_t fixed_ = static_cast<std::size_t>(-1);
  CountingModel& model_;
  double step_;
  mutable std::map<std::vector<double>, std::vector<double>> cache_;
};

struct Run {
  std::vector<double> z;
  double cost = INFINITY;
  int iterations = 0;
  bool converged = false;
  std::string termination;
};

/// Levenberg-Marquardt from z (parameter `fixed` held, if < n).
Run levenberg_marquardt(const Transform& tr, const BatchCost& cost, std::vector<double> z,
                        const Options& opt, std::size_t fixed);

/// The profile bounds of the 95% intervals where the covariance's do not
/// hold (fit/profile.cpp): updates out.parameters' ci95 and method.
void profile_intervals(const Transform& tr, const BatchCost& cost, const std::vector<double>& z,
                       const Options& opt, Result& out);

} // namespace mdrmap::fit
