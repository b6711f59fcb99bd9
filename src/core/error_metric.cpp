#include "core/error_metric.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mdrmap {
namespace {

double rel_max(const std::vector<double>& q, const std::vector<double>& ref, double floor = 0.0) {
  double num = 0.0, den = floor;
  for (std::size_t k = 0; k < q.size(); ++k) {
    num = std::max(num, std::abs(q[k] - ref[k]));
    den = std::max(den, std::abs(ref[k]));
  }
  if (den == 0.0) return num; // reference identically zero (e.g. F_x for tau = 0)
  return num / den;
}

} // namespace

double CaseError::max() const {
  return std::max({FN, Fx, mu, a2});
}

CaseError case_error(const Series& run, const Series& ref, double a1) {
  if (run.size() != ref.size()) throw std::invalid_argument("case_error: series sizes differ");
  CaseError e;
  e.FN = rel_max(run.FN, ref.FN);
  e.Fx = rel_max(run.Fx, ref.Fx);
  e.mu = rel_max(run.mu, ref.mu);
  double a2 = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k)
    a2 = std::max(a2, std::abs(run.a2[k] - ref.a2[k]));
  e.a2 = a2 / a1;
  return e;
}

CaseError case_error(const Series& run, const Series& ref, const Case& c, double floor_rel) {
  CaseError e = case_error(run, ref, c.a1());
  const double mu_scale = std::sqrt(c.loading.d / c.indenter.R);
  double fn_max = 0.0, fx_max = 0.0, mu_max = 0.0;
  for (std::size_t k = 0; k < ref.size(); ++k) {
    fn_max = std::max(fn_max, std::abs(ref.FN[k]));
    fx_max = std::max(fx_max, std::abs(ref.Fx[k]));
    mu_max = std::max(mu_max, std::abs(ref.mu[k]));
  }
  const double fx_scale = fn_max * mu_scale;
  if (fx_max == 0.0 || floor_rel > 0.0)
    e.Fx = rel_max(run.Fx, ref.Fx, fx_max == 0.0 ? fx_scale : floor_rel * fx_scale);
  if (mu_max == 0.0 || floor_rel > 0.0)
    e.mu = rel_max(run.mu, ref.mu, mu_max == 0.0 ? mu_scale : floor_rel * mu_scale);
  return e;
}

} // namespace mdrmap
