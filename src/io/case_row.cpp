#include "io/case_row.hpp"

#include <algorithm>
#include <stdexcept>

namespace mdrmap::io {
namespace {

// The quantities of a state and the instants they are taken at: the names of
// the map's fields and their meanings come from these tables together.
struct Quantity {
  const char* name;
  const char* unit;
  const char* meaning;
};
const Quantity kQuantities[] = {
    {"FN", "force", "normal force"},
    {"Fx", "force", "friction force"},
    {"mu", "number", "friction coefficient Fx / FN"},
    {"a2", "length", "trailing edge a2 of the contact"},
};

struct Instant {
  const char* name;
  const char* simulated; ///< results/<q>_<name>
  const char* analytic;  ///< analytic/<q>_<name>
  const char* residual;  ///< what residuals/<q>_<name> measures
};
const Instant kInstants[] = {
    {"pre", "in stationary sliding at v before the step",
     "in stationary sliding at v before the step (exact)",
     "numerical error of the stationary state before the step"},
    {"jump", "just after the step (t = 0+)",
     "just after the step (t = 0+), the corrected estimate (eqs. 15-16)",
     "numerical error just after the step"},
    {"post", "at the end of the window (t = t_end)", "in stationary sliding at v1 (exact)",
     "distance of the state at t_end from stationary sliding at v1 (physics, not error)"},
};

// Limits: analytic/<name> and residuals/<name> (sim: the simulated value the
// residual compares with it).
struct Limit {
  const char* name;
  const char* unit;
  const char* meaning;
  const char* sim;
  const char* residual;
};
const Limit kLimits[] = {
    {"FN_inf", "force", "normal force in the limit v -> inf (eqs. 12-14)", "FN_pre",
     "distance of the state before the step from the v -> inf limit (physics, not error)"},
    {"Fx_inf", "force", "friction force in the limit v -> inf (eqs. 12-14)", "Fx_pre",
     "distance of the state before the step from the v -> inf limit (physics, not error)"},
    {"mu_inf", "number", "friction coefficient in the limit v -> inf: 4/3 sqrt(d/R)", "mu_pre",
     "distance of the state before the step from the v -> inf limit (physics, not error)"},
    {"mu_post_drop", "number", "friction coefficient right after a stop: 3/4 sqrt(d/R)", "mu_jump",
     "distance of mu just after the step from the start-stop value (physics, not error)"},
};

std::string residual_meaning(const std::string& field, const std::string& measures) {
  return "(sim - analytic) / |analytic| of " + field + ": " + measures;
}

std::vector<FieldInfo> make_fields() {
  std::vector<FieldInfo> f;
  for (const char* group : {"results", "analytic", "residuals"}) {
    const std::string g = group;
    for (const Instant& w : kInstants)
      for (const Quantity& q : kQuantities) {
        const std::string name = std::string(q.name) + "_" + w.name;
        if (g == "results")
          f.push_back({g + "/" + name, q.unit, std::string(q.meaning) + " " + w.simulated});
        else if (g == "analytic")
          f.push_back({g + "/" + name, q.unit, std::string(q.meaning) + " " + w.analytic});
        else
          f.push_back({g + "/" + name, "number", residual_meaning(name, w.residual)});
      }
  }
  f.push_back(
      {"results/error_estimate", "number",
       "the solver's estimate of the case's relative error (docs/design.md, error metric)"});
  f.push_back({"results/wall_seconds", "s", "wall-clock time the case took, in seconds"});
  for (const Limit& l : kLimits) {
    f.push_back({std::string("analytic/") + l.name, l.unit, l.meaning});
    f.push_back({std::string("residuals/") + l.name, "number",
                 residual_meaning(l.name, std::string(l.residual) + ", sim = results/" + l.sim)});
  }
  return f;
}

std::vector<FieldInfo> make_others() {
  std::vector<FieldInfo> f;
  f.push_back({"results/status", "code", "1 done, 0 pending (not yet computed), -1 failed"});
  f.push_back({"results/message", "text", "why a case failed (empty otherwise)"});
  f.push_back({"timeseries/t", "time", "output instant, from the step at t = 0 to t_end"});
  for (const Quantity& q : kQuantities)
    f.push_back({std::string("timeseries/") + q.name, q.unit,
                 std::string(q.meaning) + " at the output instants t"});
  return f;
}

} // namespace

const std::vector<FieldInfo>& row_field_info() {
  static const std::vector<FieldInfo> f = make_fields();
  return f;
}

const std::vector<FieldInfo>& other_result_info() {
  static const std::vector<FieldInfo> f = make_others();
  return f;
}

const std::vector<std::string>& row_fields() {
  static const std::vector<std::string> f = [] {
    std::vector<std::string> names;
    for (const FieldInfo& i : row_field_info())
      names.push_back(i.path);
    return names;
  }();
  return f;
}

std::size_t field_index(const std::string& name) {
  const auto& f = row_fields();
  const auto it = std::find(f.begin(), f.end(), name);
  if (it == f.end()) throw std::out_of_range("no map field " + name);
  return static_cast<std::size_t>(it - f.begin());
}

const FieldInfo& result_info(const std::string& path) {
  for (const auto* table : {&row_field_info(), &other_result_info()})
    for (const FieldInfo& i : *table)
      if (i.path == path) return i;
  throw std::out_of_range("no map dataset " + path);
}

} // namespace mdrmap::io
