#include "io/case_row.hpp"

#include <cstring>
#include <stdexcept>

#include "core/model/params.hpp"

namespace mdrmap::io {
namespace {

using Quantity = OutputSpec; // a state quantity of the output table

/// "results/", "scales/" or "events/": the group of the map that holds o's row values.
std::string group_of(const OutputSpec& o) {
  if (o.group == OutputGroup::Scale) return "scales/";
  return o.group == OutputGroup::Result ? "results/" : "events/";
}

std::string residual(const std::string& sim, const std::string& an, const std::string& measures) {
  return "(" + sim + " - " + an + ") / |" + an + "|: " + measures;
}

} // namespace

RowLayout::RowLayout(std::size_t segments, bool by_force)
    : K_(segments), by_force_(by_force), quantities_(state_outputs(by_force)) {
  add_results();
  add_events();
  add_closed_forms();
  add_residuals();
  add_scales();
  offsets_.push_back(0);
  for (std::size_t f = 0; f < fields_.size(); ++f) {
    offsets_.push_back(offsets_.back() + width(f));
    index_[fields_[f].info.path] = f;
  }
  const OutputSpec& t = output(OutputGroup::Series, "t");
  series_.push_back({std::string("timeseries/") + t.name, dim_name(t.dim), t.meaning});
  for_each_quantity([&](const Quantity& q) {
    series_.push_back({std::string("timeseries/") + q.name, dim_name(q.dim),
                       std::string(q.meaning) + " at the output instants t"});
  });
  resolve_slots();
}

RowSlots::PerQuantity RowLayout::per_quantity(const std::string& group, const char* suffix) const {
  RowSlots::PerQuantity out{};
  for (std::size_t q = 0; q < quantities(); ++q)
    out[q] = at(group + "/" + quantity(q) + suffix);
  return out;
}

void RowLayout::resolve_slots() {
  RowSlots& s = slots_;
  for (const OutputSpec& o : output_table()) {
    // (the time series are not in a row: series())
    if ((o.where & kInMap) == 0 || o.group == OutputGroup::Series) continue;
    const std::size_t slot = o.group == OutputGroup::EventState ? 0 : at(group_of(o) + o.name);
    if (o.group == OutputGroup::Result && o.dim == Dim::WallClock) s.wall_seconds = slot;
    if (o.group == OutputGroup::Result && o.dim != Dim::WallClock) s.results.emplace_back(&o, slot);
    if (o.group == OutputGroup::Event) s.event_metrics.emplace_back(&o, slot);
    if (o.group == OutputGroup::Scale) s.scales.emplace_back(&o, slot);
    if (o.group == OutputGroup::EventState)
      s.event_states.emplace_back(&o, per_quantity("events", (std::string("_") + o.name).c_str()));
  }
  s.results_pre = per_quantity("results", "_pre");
  s.analytic_pre = per_quantity("analytic", "_pre");
  s.residuals_pre = per_quantity("residuals", "_pre");
  s.analytic_ss = per_quantity("analytic", "_ss");
  s.residuals_end = per_quantity("residuals", "_end");
  if (by_force_) return; // the seed's jump estimate: at fixed depth only
  s.analytic_jump = per_quantity("analytic", "_jump");
  s.residuals_jump = per_quantity("residuals", "_jump");
}

void RowLayout::add(const std::string& path, const char* unit, const std::string& meaning,
                    bool per_event, bool may_be_undefined) {
  fields_.push_back({{path, unit, meaning}, per_event, may_be_undefined});
}

void RowLayout::add(const std::string& group, const OutputSpec& o) {
  const bool per_event = o.group == OutputGroup::Event || o.group == OutputGroup::EventState;
  if (o.group != OutputGroup::EventState) {
    add(group + "/" + o.name, dim_name(o.dim), o.meaning, per_event, o.may_be_undefined);
    return;
  }
  for_each_quantity([&](const Quantity& q) {
    add(group + "/" + event_state_name(q, o), dim_name(q.dim),
        std::string(q.meaning) + " " + o.meaning, true, o.may_be_undefined);
  });
}

template <class F> void RowLayout::for_each_quantity(F f) const {
  for (std::size_t q = 0; q < quantities(); ++q)
    f(*quantities_[q]);
}

const char* RowLayout::quantity(std::size_t q) const {
  return quantities_[q]->name;
}

double RowLayout::value(const State& s, std::size_t q) const {
  return s.*(quantities_[q]->state);
}

const std::vector<double>& RowLayout::samples(const Series& x, std::size_t s) const {
  return x.*(s == 0 ? output(OutputGroup::Series, "t").column : quantities_[s - 1]->column);
}

std::string RowLayout::stationary() const {
  return by_force_ ? "in stationary sliding under the load F0 at " : "in stationary sliding at ";
}

void RowLayout::add_results() {
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Result && (o.where & kInMap) != 0) add("results", o);
  for_each_quantity([&](const Quantity& q) {
    add(std::string("results/") + q.name + "_pre", dim_name(q.dim),
        std::string(q.meaning) + " " + stationary() + "v before t = 0, as solved");
  });
}

// The event metrics and states of the output table the map holds, in its order.
void RowLayout::add_events() {
  for (const OutputSpec& o : output_table())
    if ((o.group == OutputGroup::Event || o.group == OutputGroup::EventState) &&
        (o.where & kInMap) != 0)
      add("events", o);
}

void RowLayout::add_closed_forms() {
  for_each_quantity([&](const Quantity& q) {
    add(std::string("analytic/") + q.name + "_pre", dim_name(q.dim),
        std::string(q.meaning) + " " + stationary() + "v (closed form)");
  });
  for_each_quantity([&](const Quantity& q) {
    add(std::string("analytic/") + q.name + "_ss", dim_name(q.dim),
        std::string(q.meaning) + " " + stationary() + "the segment's velocity (closed form)", true);
  });
  if (by_force_) return; // the seed's jump estimate: at fixed depth
  for_each_quantity([&](const Quantity& q) {
    add(std::string("analytic/") + q.name + "_jump", dim_name(q.dim),
        std::string(q.meaning) +
            " just after the first change (t = 0+), the corrected estimate (eqs. 15-16) of the "
            "Kelvin foundation; undefined for a relaxation spectrum",
        false, true);
  });
}

void RowLayout::add_scales() {
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Scale) add("scales", o);
}

void RowLayout::add_residuals() {
  for_each_quantity([&](const Quantity& q) {
    const std::string n = std::string(q.name) + "_pre";
    add("residuals/" + n, "number",
        residual("results/" + n, "analytic/" + n,
                 "numerical error of the stationary state before t = 0"));
  });
  for_each_quantity([&](const Quantity& q) {
    add(std::string("residuals/") + q.name + "_end", "number",
        residual(std::string("events/") + q.name + "_end",
                 std::string("analytic/") + q.name + "_ss",
                 "distance of the segment's end from stationary sliding at its velocity (physics, "
                 "not error)"),
        true);
  });
  if (by_force_) return;
  for_each_quantity([&](const Quantity& q) {
    add(std::string("residuals/") + q.name + "_jump", "number",
        residual(std::string("events/") + q.name + "_after[0]",
                 std::string("analytic/") + q.name + "_jump",
                 "numerical error just after the first change"),
        false, true);
  });
}

std::size_t RowLayout::at(const std::string& path, std::size_t k) const {
  const auto it = index_.find(path);
  if (it == index_.end()) throw std::out_of_range("no map field " + path);
  if (k >= width(it->second))
    throw std::out_of_range("map field " + path + ": no event " + std::to_string(k));
  return offsets_[it->second] + k;
}

const std::vector<FieldInfo>& other_result_info() {
  static const std::vector<FieldInfo> f = {
      {"results/status", "code", "1 done, 0 pending (not yet computed), -1 failed"},
      {std::string("timeseries/") + output(OutputGroup::Series, "segment").name,
       dim_name(output(OutputGroup::Series, "segment").dim),
       output(OutputGroup::Series, "segment").meaning},
      {"failures/case", "count", "a failed case (0-based index)"},
      {"failures/message", "text", "why it failed"},
  };
  return f;
}

const FieldInfo& other_info(const std::string& path) {
  for (const FieldInfo& i : other_result_info())
    if (i.path == path) return i;
  throw std::out_of_range("no map dataset " + path);
}

FieldInfo segment_case_info(const std::string& name) {
  const ParamSpec& spec = name == "w" ? segment_velocity_spec() : segment_duration_spec();
  return {"cases/" + name, dim_name(spec.dim),
          std::string(spec.meaning) + " (absolute, as run), per segment"};
}

const std::vector<RootAttribute>& root_attributes() {
  static const std::vector<RootAttribute> a = {
      {"mdrmap_schema", "string", "the schema of the map (mdrmap-map/2)"},
      {"program_version", "string", "the version of the mdrmap that made the map"},
      {"git_commit", "string", "the commit it was built from"},
      {"created_utc", "string", "when the map was created (UTC, ISO 8601)"},
      {"command_line", "string", "the command line of the study"},
      {"units", "string", "the study's units, as its config names them"},
      {"loading", "string", "depth (fixed depth d) or force (prescribed load F0)"},
      {"mpi_size", "int64", "the number of MPI ranks that created the map"},
      {"n_cases", "int64", "N, the number of cases"},
      {"segments", "int64", "K, the number of history segments"},
      {"samples", "int64", "S, the samples per segment"},
      {"timeseries", "int64", "1 when /timeseries holds every sample, else 0"},
      {"config_text", "string",
       "the config as written (a long one: a pointer to /provenance/config_text)"}};
  return a;
}

const char* root_attribute(const char* name) {
  for (const RootAttribute& a : root_attributes())
    if (std::strcmp(a.name, name) == 0) return a.name;
  throw std::logic_error(std::string("no map root attribute ") + name);
}

const std::vector<FieldInfo>& provenance_info() {
  static const std::vector<FieldInfo> f = {
      {"provenance/config_text", "text", "the config file as written (dimension config_text_byte)"},
      {"provenance/config_canonical", "text",
       "the study as --resume compares it: columns, values and [run] settings in normal form "
       "(dimension config_canonical_byte)"}};
  return f;
}

const FieldInfo& material_card_info() {
  static const FieldInfo f{"provenance/material_card", "text",
                           "the material card of [run] material as read, an Abaqus card or "
                           "pyvisco's CSV (dimension material_card_byte); the map holds its "
                           "material"};
  return f;
}

} // namespace mdrmap::io
