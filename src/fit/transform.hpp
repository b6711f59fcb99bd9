#pragma once
// The transformed coordinates of the free parameters (internal to the fit
// library): z = ln x for a log parameter, z = x / scale otherwise, the
// scale being the bounds' span where both are finite, else max(|start|, 1).
#include <cmath>
#include <vector>

#include "fit/least_squares.hpp"

namespace mdrmap::fit {

struct Transform {
  std::vector<FreeParameter> p;
  std::vector<double> scale;

  explicit Transform(const std::vector<FreeParameter>& params) : p(params) {
    for (const auto& q : p) {
      const bool bounded = std::isfinite(q.lo) && std::isfinite(q.hi);
      scale.push_back(q.log ? 1.0 : bounded ? q.hi - q.lo : std::fmax(std::fabs(q.start), 1.0));
    }
  }
  std::size_t size() const { return p.size(); }
  double to_z(std::size_t i, double x) const { return p[i].log ? std::log(x) : x / scale[i]; }
  double to_x(std::size_t i, double z) const { return p[i].log ? std::exp(z) : z * scale[i]; }
  double z_lo(std::size_t i) const {
    if (p[i].log) return p[i].lo > 0.0 ? std::log(p[i].lo) : -INFINITY;
    return p[i].lo / scale[i];
  }
  double z_hi(std::size_t i) const {
    if (p[i].log) return std::isfinite(p[i].hi) ? std::log(p[i].hi) : INFINITY;
    return p[i].hi / scale[i];
  }
  std::vector<double> x_of(const std::vector<double>& z) const {
    std::vector<double> x(z.size());
    for (std::size_t i = 0; i < z.size(); ++i)
      x[i] = to_x(i, z[i]);
    return x;
  }
  std::vector<double> z_of(const std::vector<double>& x) const {
    std::vector<double> z(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      z[i] = to_z(i, x[i]);
    return z;
  }
};

/// Counts what reaches the Evaluator.
struct CountingModel {
  Evaluator& model;
  std::size_t evaluations = 0, batches = 0;
  std::vector<std::vector<double>> operator()(const std::vector<std::vector<double>>& x) {
    ++batches;
    evaluations += x.size();
    return model.evaluate(x);
  }
};

/// The statistics at the optimum z (transformed) with its weighted residuals
/// r0 and Jacobian J (row-major m x n, d r / d z): fills the parameters,
/// correlation, singular values, undetermined directions, sigma, rms.
void fill_statistics(const Transform& tr, const std::vector<double>& z,
                     const std::vector<double>& r0, const std::vector<double>& jac,
                     const Options& opt, Result& out);

} // namespace mdrmap::fit
