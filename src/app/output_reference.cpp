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

/// Where an output of a group is: in the CSV and the Python result (the
/// name between csv_before and csv_after where name_in_csv), in the map
/// (map_prefix and the name).
struct Places {
  OutputGroup group;
  const char* csv_before;
  bool name_in_csv;
  const char* csv_after;
  const char* map_prefix;
};
const Places kPlaces[] = {
    {OutputGroup::Series, "column; `r.", true, "`", "/timeseries/"},
    {OutputGroup::Event, "`# event`; `r.events[k]`", false, "", "/events/"},
    {OutputGroup::EventState, "`# event` (`mu_", true, "`); `r.events[k]`", "/events/<q>_"},
    {OutputGroup::Result, "first line; `r.info`", false, "", "/results/"},
    {OutputGroup::Scale, "`# scales`; `r.scales`", false, "", "/scales/"},
};

/// "CSV; Python | map" cells of o.
std::string places(const OutputSpec& o) {
  for (const Places& p : kPlaces) {
    if (p.group != o.group) continue;
    const std::string csv = std::string(p.csv_before) + (p.name_in_csv ? o.name : "") + p.csv_after;
    return ((o.where & kInCsv) != 0 ? csv : "") + " | " +
           ((o.where & kInMap) != 0 ? "`" + std::string(p.map_prefix) + o.name + "`" : "");
  }
  return " | ";
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
    s += "| `" + name + "` | " + output_group_name(o.group) + " | " + unit + " | " + places(o) +
         " | " + escaped(o.meaning) + " |\n";
    if (o.old_map_name != nullptr)
      old += (old.empty() ? "`/events/" : ", `/events/") + std::string(o.old_map_name) +
             "` (now `" + o.name + "`)";
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
