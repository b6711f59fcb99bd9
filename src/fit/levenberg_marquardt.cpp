#include <algorithm>

#include "fit/batch_cost.hpp"

namespace mdrmap::fit {

Run levenberg_marquardt(const Transform& tr, const BatchCost& cost_template, std::vector<double> z,
                        const Options& opt, std::size_t fixed) {
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
  cost_template.fix(fixed);
  if (fixed < tr.size())
    problem.SetManifold(z.data(), new ceres::SubsetManifold(static_cast<int>(tr.size()),
                                                            {static_cast<int>(fixed)}));
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
  cost_template.fix(tr.size());
  Run r;
  r.z = z;
  r.cost = 2.0 * summary.final_cost;
  r.iterations = static_cast<int>(summary.iterations.size());
  r.converged = summary.termination_type == ceres::CONVERGENCE;
  r.termination = summary.message;
  return r;
}

} // namespace mdrmap::fit
