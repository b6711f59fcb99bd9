#include "io/case_row.hpp"

#include <cstring>
#include <stdexcept>

#include "core/model/params.hpp"

namespace mdrmap::io {
namespace {

// The quantities of a state: the names of the map's fields and their
// meanings come from this table and the instants below together; the
// quantities that move under load only come last.
struct Quantity {
  const char* name;
  const char* unit;
  const char* meaning;
  bool load_only;                       ///< moves under load control only (fixed at depth control)
  double State::*value;                 ///< its member of a State
  std::vector<double> Series::*samples; ///< and of a Series
};
const Quantity kQuantities[] = {
    {"FN", "force", "normal force", false, &State::FN, &Series::FN},
    {"Fx", "force", "friction force", false, &State::Fx, &Series::Fx},
    {"mu", "number", "friction coefficient Fx / FN", false, &State::mu, &Series::mu},
    {"a2", "length", "trailing edge a2 of the contact", false, &State::a2, &Series::a2},
    {"d", "length", "indentation depth", true, &State::d, &Series::d},
    {"a1", "length", "leading edge a1 of the contact", true, &State::a1, &Series::a1},
};

std::string residual(const std::string& sim, const std::string& an, const std::string& measures) {
  return "(" + sim + " - " + an + ") / |" + an + "|: " + measures;
}

} // namespace

RowLayout::RowLayout(std::size_t segments, bool by_force) : K_(segments), by_force_(by_force) {
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
  series_.push_back({"timeseries/t", "time", "output instant, from the first change at t = 0"});
  for_each_quantity([&](const Quantity& q) {
    series_.push_back({std::string("timeseries/") + q.name, q.unit,
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
  s.error_estimate = at("results/error_estimate");
  s.wall_seconds = at("results/wall_seconds");
  s.results_pre = per_quantity("results", "_pre");
  s.analytic_pre = per_quantity("analytic", "_pre");
  s.residuals_pre = per_quantity("residuals", "_pre");
  s.event_t = at("events/t");
  s.mu_before = at("events/mu_before");
  s.mu_peak = at("events/mu_peak");
  s.t_peak = at("events/t_peak");
  s.slip_peak = at("events/slip_peak");
  s.mu_max = at("events/mu_max");
  s.t_max = at("events/t_max");
  s.slip_max = at("events/slip_max");
  s.mu_min = at("events/mu_min");
  s.t_min = at("events/t_min");
  s.slip_min = at("events/slip_min");
  s.healing = at("events/healing");
  s.a = at("events/a");
  s.b = at("events/b");
  s.a_minus_b = at("events/a_minus_b");
  s.d_c = at("events/d_c");
  s.overshoot = at("events/overshoot");
  s.events_after = per_quantity("events", "_after");
  s.events_end = per_quantity("events", "_end");
  s.analytic_ss = per_quantity("analytic", "_ss");
  s.residuals_end = per_quantity("residuals", "_end");
  s.scale_length = at("scales/length");
  s.scale_depth = at("scales/depth");
  s.scale_force = at("scales/force");
  s.scale_friction = at("scales/friction");
  s.scale_time = at("scales/time");
  if (by_force_) return; // the seed's jump estimate: at fixed depth only
  s.analytic_jump = per_quantity("analytic", "_jump");
  s.residuals_jump = per_quantity("residuals", "_jump");
}

void RowLayout::add(const std::string& path, const char* unit, const std::string& meaning,
                    bool per_event, bool may_be_undefined) {
  fields_.push_back({{path, unit, meaning}, per_event, may_be_undefined});
}

template <class F> void RowLayout::for_each_quantity(F f) const {
  for (std::size_t q = 0; q < quantities(); ++q)
    f(kQuantities[q]);
}

std::size_t RowLayout::quantities() const {
  std::size_t n = 0;
  for (const Quantity& q : kQuantities)
    n += (by_force_ || !q.load_only) ? 1 : 0;
  return n;
}

const char* RowLayout::quantity(std::size_t q) const {
  return kQuantities[q].name;
}

double RowLayout::value(const State& s, std::size_t q) const {
  return s.*(kQuantities[q].value);
}

const std::vector<double>& RowLayout::samples(const Series& x, std::size_t s) const {
  return s == 0 ? x.t : x.*(kQuantities[s - 1].samples);
}

std::string RowLayout::stationary() const {
  return by_force_ ? "in stationary sliding under the load F0 at " : "in stationary sliding at ";
}

void RowLayout::add_results() {
  add("results/error_estimate", "number",
      "the solver's estimate of the case's relative error (docs/design.md, error metric)");
  add("results/wall_seconds", "s", "wall-clock time the case took, in seconds");
  for_each_quantity([&](const Quantity& q) {
    add(std::string("results/") + q.name + "_pre", q.unit,
        std::string(q.meaning) + " " + stationary() + "v before t = 0, as solved");
  });
}

void RowLayout::add_events() {
  add("events/t", "time", "time of the velocity change at the segment's start (the first at t = 0)",
      true);
  for_each_quantity([&](const Quantity& q) {
    add(std::string("events/") + q.name + "_after", q.unit,
        std::string(q.meaning) + " just after the change (the segment's first sample)", true);
  });
  add("events/mu_before", "number",
      "friction coefficient just before the change (the previous segment's last sample)", true);
  for (const char* which : {"max", "min"}) {
    const std::string m = which;
    add("events/mu_" + m, "number",
        std::string(m == "max" ? "largest" : "smallest") +
            " friction coefficient within the segment (from the solution, not the output "
            "instants)",
        true);
    add("events/t_" + m, "time", "time of mu_" + m + " since the change", true);
    add("events/slip_" + m, "length", "slip of mu_" + m + " since the change", true);
  }
  add("events/mu_peak", "number",
      "the extremum on the side of the change: mu_max after a rise, mu_min after a drop or into "
      "a hold; mu just after the change where the segment shows no transient (within the error "
      "estimate)",
      true);
  add("events/t_peak", "time", "time of mu_peak since the change", true);
  add("events/slip_peak", "length", "slip of mu_peak since the change", true);
  add("events/healing", "number",
      "static healing of a reslide after a hold: mu_max - mu_ss at the velocity before the "
      "hold; undefined for any other segment",
      true, true);
  for_each_quantity([&](const Quantity& q) {
    add(std::string("events/") + q.name + "_end", q.unit,
        std::string(q.meaning) + " at the segment's end (its last sample)", true);
  });
  add("events/a", "number",
      "direct effect (mu_direct - mu_before) / ln(w / w_before), mu_direct = mu_after with a "
      "parallel dashpot, mu_peak without one; undefined across a hold",
      true, true);
  add("events/b", "number", "evolution effect a - (a - b); undefined across a hold", true, true);
  add("events/a_minus_b", "number",
      "(mu_ss(w) - mu_ss(w_before)) / ln(w / w_before); undefined across a hold", true, true);
  add("events/d_c", "length",
      "slip over which |mu - mu_ss(w)| first falls to 1/e of its value at the reference point "
      "(the change with a parallel dashpot, the peak without one), counted from there; "
      "undefined during a hold, without a transient, when the peak is the segment's end, when "
      "it does not fall that far within the segment, or when the transient overshoots mu_ss(w) "
      "by more than 1/e of that value",
      true, true);
  add("events/overshoot", "number",
      "largest excursion of mu beyond mu_ss(w) on the side opposite to mu just after the change, "
      "relative to |mu - mu_ss(w)| just after the change; 0 for a one-sided transient",
      true);
}

void RowLayout::add_closed_forms() {
  for_each_quantity([&](const Quantity& q) {
    add(std::string("analytic/") + q.name + "_pre", q.unit,
        std::string(q.meaning) + " " + stationary() + "v (closed form)");
  });
  for_each_quantity([&](const Quantity& q) {
    add(std::string("analytic/") + q.name + "_ss", q.unit,
        std::string(q.meaning) + " " + stationary() + "the segment's velocity (closed form)", true);
  });
  if (by_force_) return; // the seed's jump estimate: at fixed depth
  for_each_quantity([&](const Quantity& q) {
    add(std::string("analytic/") + q.name + "_jump", q.unit,
        std::string(q.meaning) +
            " just after the first change (t = 0+), the corrected estimate (eqs. 15-16) of the "
            "Kelvin foundation; undefined for a relaxation spectrum",
        false, true);
  });
}

void RowLayout::add_scales() {
  add("scales/length", "length",
      by_force_ ? "reference length: the Hertz radius a0 of the load F0 with the long-term "
                  "modulus G (F0 = 16/3 G a0^3 / R)"
                : "reference length: the leading edge a1 of the contact at the depth d");
  add("scales/depth", "length", "indentation depth of the reference contact (d, or a0^2 / R)");
  add("scales/force", "force",
      "elastic normal force of the reference contact with the long-term modulus G "
      "(16/3 G a^3 / R; the prescribed load F0 under load)");
  add("scales/friction", "number",
      "friction scale: the profile's slope at the reference length "
      "over two (a / R for the parabola)");
  add("scales/time", "time",
      "time scale: the longest relaxation time of the material, shifted by aT (tau for the "
      "Kelvin foundation)");
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
      {"timeseries/segment", "count", "the 0-based segment of each output instant"},
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
