#include "study/case_columns.hpp"

#include "core/model/params.hpp"
#include "study/columns.hpp"

namespace mdrmap::study {

using namespace detail;

std::vector<io::FieldInfo> case_parameter_info(const StudyConfig& c) {
  std::vector<io::FieldInfo> out;
  for (const Axis& a : c.axes) {
    if (a.column.history()) continue;
    const ParamSpec& spec = column_spec(a.column);
    out.push_back({"cases/" + column_name(a.column), dim_name(spec.dim), column_meaning(a.column)});
    if (a.column.kind == Column::Kind::Temperature) {
      const ParamSpec& aT = *find_parameter("aT");
      out.push_back({std::string("cases/") + aT.name, dim_name(aT.dim),
                     std::string(aT.meaning) + ", as the temperature gives it by [run] wlf"});
    }
  }
  return out;
}

void append_case_parameters(const StudyConfig& c, const Row& r, const Case& run,
                            std::vector<double>& out) {
  for (std::size_t i = 0; i < c.axes.size() && i < r.size(); ++i) {
    if (c.axes[i].column.history()) continue;
    out.push_back(r[i]);
    if (c.axes[i].column.kind == Column::Kind::Temperature) out.push_back(run.rheology.aT);
  }
}

} // namespace mdrmap::study
