// The map's groups and datasets as Markdown (docs/reference/map-schema.md),
// from the declarations the map writer uses: the study's case parameters
// (study/case_columns.hpp), the rows of a case and the time series
// (io::RowLayout, at fixed depth and under load), the other datasets and the
// root attributes (io/case_row.hpp).
#include <cctype>
#include <string>
#include <vector>

#include "app/reference_pages.hpp"
#include "core/model/params.hpp"
#include "io/case_row.hpp"
#include "io/map_file.hpp"
#include "study/case_columns.hpp"
#include "study/config.hpp"

namespace mdrmap::app {
namespace {

/// A table cell: '|' escaped, each option ("--profile") as code, which a
/// browser neither breaks at its hyphens nor typesets as a dash.
std::string cell(std::string s) {
  for (std::size_t i = s.find('|'); i != std::string::npos; i = s.find('|', i + 2))
    s.replace(i, 1, "\\|");
  for (std::size_t i = s.find("--"); i != std::string::npos; i = s.find("--", i)) {
    std::size_t end = i + 2;
    while (end < s.size() && (std::isalnum(static_cast<unsigned char>(s[end])) || s[end] == '-'))
      ++end;
    if (end == i + 2) {
      i = end;
      continue;
    }
    s.insert(end, "`");
    s.insert(i, "`");
    i = end + 2;
  }
  return s;
}

const char* kTableHead =
    "| dataset | type, shape | unit | where | meaning |\n|---|---|---|---|---|\n";

std::string row(const io::FieldInfo& f, const std::string& type, const std::string& where) {
  return "| `/" + f.path + "` | " + type + " | " + f.unit + " | " + where + " | " +
         cell(f.meaning) + " |\n";
}

/// When a case parameter's dataset is in a map.
std::string where_param(const std::string& name) {
  if (name == "temperature") return "a temperature column";
  const ParamSpec* p = find_parameter(name);
  if (p == nullptr) return "";
  if (p->one_of) return p->dim == Dim::Force ? "under load" : "at fixed depth";
  if (p->profile) return std::string("profile = ") + p->profile;
  if (name == "aT") return "aT given";
  return "every map";
}

/// /cases: every column a study may have (the spectrum's first term for all).
std::string cases_table() {
  study::StudyConfig c;
  std::vector<std::string> names;
  for (const ParamSpec& p : case_parameters())
    if (p.part != Part::Sampling) names.push_back(p.name);
  names.insert(names.end(), {"G1", "tau1", "temperature"});
  for (const std::string& n : names) {
    study::Axis a;
    a.name = n;
    study::parse_column(n, a.column);
    c.axes.push_back(a);
  }
  std::string s = kTableHead;
  for (io::FieldInfo f : study::case_parameter_info(c)) {
    const std::string name = f.path.substr(6);
    std::string where = where_param(name);
    if (name == "G1" || name == "tau1") {
      f.path.back() = 'k';
      f.meaning.replace(f.meaning.find("term 1"), 6, "term k");
      where = "a spectrum: k = 1..N";
    } else if (name == "aT" && f.meaning.find("as the temperature") != std::string::npos) {
      where = "a temperature column";
    }
    s += row(f, "float64 `[N]`", where);
  }
  for (const char* n : {"w", "T"})
    s += row(io::segment_case_info(n), "float64 `[N, K]`", "every map");
  return s;
}

/// The field of `layout` at `path`, or nullptr.
const io::RowField* field(const io::RowLayout& layout, const std::string& path) {
  for (const io::RowField& f : layout.fields())
    if (f.info.path == path) return &f;
  return nullptr;
}

/// The rows' datasets of `group` at fixed depth and under load (twice where
/// the meaning differs).
std::string row_table(const std::string& group) {
  const io::RowLayout depth(1, false), load(1, true);
  std::string s = kTableHead;
  const auto in_group = [&](const io::RowField& f) {
    return f.info.path.compare(0, group.size() + 1, group + "/") == 0;
  };
  const auto same = [](const io::RowField* a, const io::RowField& b) {
    return a != nullptr && a->info.meaning == b.info.meaning && a->info.unit == b.info.unit;
  };
  const auto type = [](const io::RowField& f) {
    return std::string("float64 `") + (f.per_event ? "[N, K]" : "[N]") + "`" +
           (f.may_be_undefined ? ", fill" : "");
  };
  for (const io::RowField& f : depth.fields())
    if (in_group(f))
      s += row(f.info, type(f), same(field(load, f.info.path), f) ? "every map" : "at fixed depth");
  for (const io::RowField& f : load.fields())
    if (in_group(f) && !same(field(depth, f.info.path), f)) s += row(f.info, type(f), "under load");
  return s;
}

std::string other_row(const std::string& path, const std::string& type, const std::string& where) {
  return row(io::other_info(path), type, where);
}

std::string timeseries_table() {
  const io::RowLayout depth(1, false), load(1, true);
  std::string s = kTableHead;
  for (const io::FieldInfo& f : load.series()) {
    bool both = false;
    for (const io::FieldInfo& g : depth.series())
      both = both || g.path == f.path;
    s += row(f, "float64 `[N, K*S]`", both ? "timeseries = true" : "timeseries = true, under load");
  }
  return s + other_row("timeseries/segment", "int32 `[K*S]`", "timeseries = true");
}

std::string attributes_table() {
  std::string s = "| attribute | type | meaning |\n|---|---|---|\n";
  for (const io::RootAttribute& a : io::root_attributes())
    s += "| `" + std::string(a.name) + "` | " + a.type + " | " + cell(a.meaning) + " |\n";
  return s;
}

} // namespace

std::string map_reference_markdown() {
  std::string s = std::string(R"(# Map schema reference

<!-- Generated by `mdrmap help --markdown map-schema`; do not edit. Regenerate with
     cmake --build build --target reference_docs
     (ctest -R docs_map_reference fails when this page is out of date). -->

The groups and datasets of a map file (schema `)") +
                  io::kSchema + R"(`), generated by the program from
the declarations its writer uses (`src/io/case_row.cpp`, the study's columns
of `src/study/case_columns.cpp` and the core's parameter table). Every dataset
carries the attributes `units` and `long_name` (the unit and meaning below),
and the map repeats them under `/schema/<group>/<name>` (attributes `unit`
and `meaning`). What the datasets mean and how to read them:
[maps in Python](../maps.md#what-a-map-holds).

`N` cases, `K` segments, `S` samples per segment; event `k` (0-based) is the
velocity change at the start of segment `k + 1`. "fill": where undefined,
the dataset holds the netCDF default fill value `9.969209968386869e36` and
says so in `_FillValue` (no dataset holds NaN). Units are dimensions of the
study's consistent units (`force/length^2`: a modulus).

## Output quantities

Every quantity mdrmap outputs has one name, the same in the CSV of `mdrmap
simulate`, its Python result `r = mdrmap.simulate(...)` and the map (the
output table, `src/core/outputs/output_table.cpp`):

)" + output_quantities_markdown() +
                  R"(
## Root attributes

)" + attributes_table();
  s += "\n## /cases\n\nThe cases as run: the study's columns (only those it gives) and each "
       "segment's velocity and duration.\n\n" +
       cases_table();
  s += "\n## /results\n\n" + row_table("results") +
       other_row("results/status", "int8 `[N]`", "every map");
  for (const char* g : {"events", "analytic", "residuals", "scales"})
    s += "\n## /" + std::string(g) + "\n\n" + row_table(g);
  s += "\n## /timeseries\n\n" + timeseries_table();
  s += "\n## /failures\n\n`F = min(N, " + std::to_string(io::kMaxFailureSlots) +
       ")` slots reserved when the map is created; an unused slot has case `2^64 - 1`.\n\n" +
       kTableHead + other_row("failures/case", "uint64 `[F]`", "every map") +
       other_row("failures/message",
                 "string(" + std::to_string(io::kFailureMessageBytes) + ") `[F]`", "every map");
  s += "\n## /grid\n\nGrid studies: `/grid/<axis>`, float64 `[n]`, each axis's values, named as "
       "the config's key, with its unit and meaning (those of its column, as in `/cases` and "
       "the [config reference](config.md)); the group's attributes `axes`, `shape` and `log` "
       "give the axes in case order, their lengths and which are logarithmic.\n";
  s += "\n## /provenance\n\nText datasets (bytes, each with a dimension of its own; no `units` "
       "or `/schema` entry).\n\n" +
       std::string(kTableHead);
  for (const io::FieldInfo& f : io::provenance_info())
    s += row(f, "uint8 `[bytes]`", "every map");
  s += row(io::material_card_info(), "uint8 `[bytes]`", "a study with `[run] material`");
  return s;
}

} // namespace mdrmap::app
