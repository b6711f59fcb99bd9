#include "app/study_options.hpp"

#include "core/model/case.hpp"
#include "core/model/params.hpp"

namespace mdrmap::app {
namespace {

/// The overrides of the run's keys (and the seed's step, the temperature):
/// option, key, the value's placeholder in the help.
const char* const kRunOverrides[][3] = {{"samples", "run.samples", "N"},
                                        {"rtol", "run.rtol", "E"},
                                        {"solver", "run.solver", "NAME"},
                                        {"t-end-over-tau", "run.t_end_over_tau", "X"},
                                        {"timeseries", "run.timeseries", "true|false"},
                                        {"G", "run.G", "G"},
                                        {"v1", "grid.v1", "SPEC"},
                                        {"v1-over-v", "grid.v1_over_v", "SPEC"},
                                        {"temperature", "grid.temperature", "SPEC"},
                                        {"wlf", "run.wlf", "C1:C2:TREF"},
                                        {"material", "run.material", "FILE"},
                                        {"profile", "run.profile", "P"}};

} // namespace

const std::vector<StudyOverride>& study_overrides() {
  static const auto all = [] {
    std::vector<StudyOverride> o;
    for (const auto& ov : kRunOverrides)
      o.push_back({ov[0], ov[1], ov[2]});
    for (const ParamSpec& p : case_parameters())
      if (p.part != Part::Sampling && std::string(p.name) != "G")
        o.push_back({p.name, std::string("grid.") + p.name, "SPEC"});
    for (const ParamAlias& a : parameter_aliases())
      o.push_back({a.alias, std::string("grid.") + a.alias, "SPEC"});
    for (const ParamSpec* p : {&branch_modulus_spec(), &branch_time_spec()})
      for (std::size_t k = 1; k <= kMaxBranches; ++k) // a spectrum's terms: --G1 .. --tau32
        o.push_back({p->name + std::to_string(k), "grid." + (p->name + std::to_string(k)), "SPEC"});
    return o;
  }();
  return all;
}

} // namespace mdrmap::app
