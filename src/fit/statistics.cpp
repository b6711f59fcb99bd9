// The statistics of a least-squares optimum from the weighted Jacobian in
// the transformed coordinates (fit/transform.hpp): J = U S V^T; the
// covariance sigma^2 V S^-2 V^T, sigma^2 = SSR / (m - n) unless the
// residuals were weighted by their standard deviations (sigma = 1); a
// direction v_k whose 95% half-width t sigma / s_k exceeds
// Options::flat_halfwidth is not determined by the data: its parameters
// (those with a large component in v_k) get no interval.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Dense>
#include <boost/math/distributions/students_t.hpp>

#include "fit/transform.hpp"

namespace mdrmap::fit {
namespace {

/// Components of an undetermined direction at or above this share of its
/// largest one name a parameter in it.
constexpr double kFlatComponent = 0.3;

/// The covariance in z of the directions the data determine; `flat` marks
/// the parameters of the others (a large component in one).
Eigen::MatrixXd covariance(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd, const Options& opt,
                           const Result& out, std::vector<bool>& flat) {
  const Eigen::VectorXd s = svd.singularValues();
  const Eigen::MatrixXd V = svd.matrixV();
  const Eigen::Index n = V.rows();
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double half = s(k) > 0.0 ? out.t_quantile * out.sigma / s(k) : INFINITY;
    if (!(half <= opt.flat_halfwidth)) {
      const double big = V.col(k).cwiseAbs().maxCoeff();
      for (Eigen::Index i = 0; i < n; ++i)
        if (std::fabs(V(i, k)) >= kFlatComponent * big) flat[static_cast<std::size_t>(i)] = true;
      continue;
    }
    cov += (out.sigma * out.sigma / (s(k) * s(k))) * V.col(k) * V.col(k).transpose();
  }
  return cov;
}

/// Parameter i's value, standard error and covariance interval.
ParameterResult parameter_result(const Transform& tr, const std::vector<double>& z, std::size_t i,
                                 double var_z, bool flat, double t) {
  ParameterResult p;
  p.name = tr.p[i].name;
  p.value = tr.to_x(i, z[i]);
  p.at_bound = z[i] <= tr.z_lo(i) || z[i] >= tr.z_hi(i);
  const double sz = flat ? NAN : std::sqrt(var_z);
  p.stderr_ = sz * (tr.p[i].log ? p.value : tr.scale[i]);
  p.ci95_lo = flat ? NAN : tr.to_x(i, z[i] - t * sz);
  p.ci95_hi = flat ? NAN : tr.to_x(i, z[i] + t * sz);
  p.cov_lo = p.ci95_lo;
  p.cov_hi = p.ci95_hi;
  return p;
}

} // namespace

void fill_statistics(const Transform& tr, const std::vector<double>& z,
                     const std::vector<double>& r0, const std::vector<double>& jac,
                     const Options& opt, Result& out) {
  const auto n = static_cast<Eigen::Index>(tr.size());
  const auto m = static_cast<Eigen::Index>(r0.size());
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
      jac.data(), m, n);
  out.residuals = r0;
  out.m = r0.size();
  out.ssr = std::inner_product(r0.begin(), r0.end(), r0.begin(), 0.0);
  out.rms = std::sqrt(out.ssr / static_cast<double>(m));
  const double dof = static_cast<double>(m - n);
  out.sigma = opt.known_sd ? 1.0 : std::sqrt(out.ssr / dof);
  out.t_quantile = boost::math::quantile(boost::math::students_t(dof), 0.975);

  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  out.singular_values.assign(s.data(), s.data() + n);
  std::vector<bool> flat(tr.size(), false);
  const Eigen::MatrixXd cov = covariance(svd, opt, out, flat);
  for (std::size_t i = 0; i < tr.size(); ++i)
    if (flat[i]) out.undetermined.push_back(tr.p[i].name);

  out.correlation.assign(tr.size(), std::vector<double>(tr.size(), NAN));
  out.parameters.clear();
  for (std::size_t i = 0; i < tr.size(); ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    out.parameters.push_back(parameter_result(tr, z, i, cov(ii, ii), flat[i], out.t_quantile));
    for (std::size_t j = 0; j < tr.size(); ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      if (!flat[i] && !flat[j])
        out.correlation[i][j] = cov(ii, jj) / std::sqrt(cov(ii, ii) * cov(jj, jj));
    }
  }
}

} // namespace mdrmap::fit
