// The output quantities as Markdown (a section of docs/reference/map-schema.md),
// from the output table (core/outputs/output_table.hpp): each quantity's one
// name, as the CSV of `mdrmap simulate`, the Python result and the map spell
// it, and the old names maps of earlier versions used.
#include <string>

#include "app/reference_pages.hpp"
#include "core/model/params.hpp"
#include "core/outputs/output_table.hpp"

namespace mdrmap::app {
namespace {

const char* group_text(OutputGroup g) {
  switch (g) {
  case OutputGroup::Series:
    return "time series";
  case OutputGroup::Event:
    return "event metric";
  case OutputGroup::EventState:
    return "event state";
  case OutputGroup::Result:
    return "per-case result";
  }
  return "?";
}

/// Where o is: the CSV line or column and the Python result, the map's path.
std::string csv_place(const OutputSpec& o) {
  if ((o.where & kInCsv) == 0) return "";
  switch (o.group) {
  case OutputGroup::Series:
    return "column; `r." + std::string(o.name) + "`";
  case OutputGroup::Event:
    return "`# event`; `r.events[k]`";
  case OutputGroup::EventState:
    return "`# event` (`mu_" + std::string(o.name) + "`); `r.events[k]`";
  case OutputGroup::Result:
    return "first line; `r.info`";
  }
  return "";
}

std::string map_place(const OutputSpec& o) {
  if ((o.where & kInMap) == 0) return "";
  switch (o.group) {
  case OutputGroup::Series:
    return std::string("`/timeseries/") + o.name + "`";
  case OutputGroup::Event:
    return std::string("`/events/") + o.name + "`";
  case OutputGroup::EventState:
    return std::string("`/events/<q>_") + o.name + "`";
  case OutputGroup::Result:
    return std::string("`/results/") + o.name + "`";
  }
  return "";
}

std::string escaped(std::string s) {
  for (std::size_t i = s.find('|'); i != std::string::npos; i = s.find('|', i + 2))
    s.replace(i, 1, "\\|");
  return s;
}

} // namespace

std::string output_quantities_markdown() {
  std::string s =
      "| name | group | unit | CSV; Python | map | meaning |\n|---|---|---|---|---|---|\n";
  std::string old;
  for (const OutputSpec& o : output_table()) {
    const std::string name =
        o.group == OutputGroup::EventState ? std::string("<q>_") + o.name : std::string(o.name);
    const char* unit = o.group == OutputGroup::EventState ? "that of q" : dim_name(o.dim);
    s += "| `" + name + "` | " + group_text(o.group) + " | " + unit + " | " + csv_place(o) + " | " +
         map_place(o) + " | " + escaped(o.meaning) + " |\n";
    if (o.old_map_name != nullptr)
      old += std::string("`/events/") + o.old_map_name + "` (now `" + o.name + "`)";
  }
  return s +
         "\n`<q>` is each state quantity of the time series (`FN`, `Fx`, `mu`, `a2`; under "
         "load also `d`, `a1`); the CSV's `# event` line and the Python result's events "
         "give `mu_<instant>` only, the map every `<q>_<instant>`. Maps written before "
         "these names were one hold " +
         old +
         ": the Python module (`mdrmap.open_map`, the tools) reads them under today's name; "
         "`mdrmap study --resume` refuses to continue them.\n";
}

} // namespace mdrmap::app
