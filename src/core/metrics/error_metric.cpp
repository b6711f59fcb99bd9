#include "core/metrics/error_metric.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/model/scales.hpp"

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
  return std::max({FN, Fx, mu, a2, d});
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

namespace {

/// The load-control parts of the contract (docs/design.md, "Error metric").
void load_errors(const Series& run, const Series& ref, const Case& c, CaseError& e) {
  const double F0 = c.loading.F0, a0 = c.a0();
  double fn = 0.0, edges = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k) {
    fn = std::max(fn, std::abs(run.FN[k] - F0));
    edges = std::max({edges, std::abs(run.a2[k] - ref.a2[k]), std::abs(run.a1[k] - ref.a1[k])});
  }
  e.FN = fn / F0;
  e.a2 = edges / a0;
  e.d = rel_max(run.d, ref.d);
}

} // namespace

// the parabola's as it always was, any other profile's from its Scales (with
// R = 0 the parabola's would be infinite: a floor that hid every F_x and mu
// difference of a cone or a power law)
double friction_scale(const Case& c) {
  if (!c.indenter.parabolic()) return scales(c).friction;
  const double d_scale =
      c.loading.by_force() ? c.a0() * c.a0() / c.indenter.as<Parabola>().R : c.loading.d;
  return std::sqrt(d_scale / c.indenter.as<Parabola>().R);
}

bool friction_resolved(const Case& c, double mu_max, double rtol) {
  // measured (cone beta 10 and parabola, v tau/a1 1e12..1e15): the error of
  // mu is up to 2.5 eps times the scale
  constexpr double kRoundingTerms = 4.0;
  const double floor = kRoundingTerms * std::numeric_limits<double>::epsilon() * friction_scale(c);
  return std::max(mu_max, kNegligibleFriction) * rtol >= floor;
}

CaseError case_error(const Series& run, const Series& ref, const Case& c, double floor_rel) {
  CaseError e = case_error(run, ref, c.edge_scale());
  if (c.loading.by_force()) load_errors(run, ref, c, e);
  const double mu_scale = friction_scale(c);
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
