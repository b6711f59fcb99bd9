#include "study/compute.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/analytic.hpp"

namespace mdrmap::study {
namespace {

void fill_state(io::CaseRow& row, const char* group, const char* when, const State& st) {
  const std::string g = group, w = when;
  row.values[io::field_index(g + "/FN_" + w)] = st.FN;
  row.values[io::field_index(g + "/Fx_" + w)] = st.Fx;
  row.values[io::field_index(g + "/mu_" + w)] = st.mu;
  row.values[io::field_index(g + "/a2_" + w)] = st.a2;
}

// (sim - analytic) / |analytic|; 0 when both vanish (tau = 0: F_x = mu = 0).
double residual(double sim, double an) {
  if (an == 0.0) return sim == 0.0 ? 0.0 : (sim > 0.0 ? 1.0 : -1.0);
  return (sim - an) / std::abs(an);
}

} // namespace

io::CaseRow compute_case(const StudyConfig& cfg, const StepRow& s, SolverKind kind,
                         bool timeseries) {
  io::CaseRow row;
  row.values.assign(io::row_fields().size(), 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const Case c = case_for(cfg, s);
    // The analytic estimates exist for every valid case.
    const State an_pre = analytic::stationary(c, s.v);
    const State an_jump = analytic::jump(c, s.v, s.v1);
    const State an_post = analytic::stationary(c, s.v1);
    fill_state(row, "analytic", "pre", an_pre);
    fill_state(row, "analytic", "jump", an_jump);
    fill_state(row, "analytic", "post", an_post);
    const double lim[4] = {analytic::FN_inf(c, s.v), analytic::Fx_inf(c, s.v), analytic::mu_inf(c),
                           analytic::mu_post_drop_limit(c)};
    const char* lim_names[4] = {"FN_inf", "Fx_inf", "mu_inf", "mu_post_drop"};
    for (int i = 0; i < 4; ++i)
      row.values[io::field_index(std::string("analytic/") + lim_names[i])] = lim[i];

    RunResult r = run_case(c, kind, cfg.run.rtol);
    const Series& x = r.series;
    const State jump = x.at(0), post = x.at(x.size() - 1);
    fill_state(row, "results", "pre", x.pre);
    fill_state(row, "results", "jump", jump);
    fill_state(row, "results", "post", post);
    row.values[io::field_index("results/error_estimate")] = r.info.error_estimate;
    const State sims[3] = {x.pre, jump, post}, ans[3] = {an_pre, an_jump, an_post};
    const char* when[3] = {"pre", "jump", "post"};
    for (int i = 0; i < 3; ++i) {
      const State res{residual(sims[i].FN, ans[i].FN), residual(sims[i].Fx, ans[i].Fx),
                      residual(sims[i].mu, ans[i].mu), residual(sims[i].a2, ans[i].a2)};
      fill_state(row, "residuals", when[i], res);
    }
    // distance of the case from the limits: before the step vs v -> inf
    // (eqs. 12-14), just after it vs the start-stop value 3/4 sqrt(d/R)
    const double lim_sim[4] = {x.pre.FN, x.pre.Fx, x.pre.mu, jump.mu};
    for (int i = 0; i < 4; ++i)
      row.values[io::field_index(std::string("residuals/") + lim_names[i])] =
          residual(lim_sim[i], lim[i]);
    for (double v : row.values)
      if (!std::isfinite(v)) throw std::runtime_error("the solver returned a non-finite value");
    if (timeseries) {
      row.t = x.t, row.FN = x.FN, row.Fx = x.Fx, row.mu = x.mu, row.a2 = x.a2;
      for (const auto* vec : {&row.FN, &row.Fx, &row.mu, &row.a2})
        for (double v : *vec)
          if (!std::isfinite(v)) throw std::runtime_error("the solver returned a non-finite value");
    }
    row.status = 1;
  } catch (const std::exception& e) {
    std::fill(row.values.begin(), row.values.end(), 0.0);
    row.t.clear(), row.FN.clear(), row.Fx.clear(), row.mu.clear(), row.a2.clear();
    row.status = -1;
    row.message = e.what();
  }
  row.values[io::field_index("results/wall_seconds")] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

} // namespace mdrmap::study
