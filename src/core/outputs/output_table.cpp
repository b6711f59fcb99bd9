#include "core/outputs/output_table.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace mdrmap {
namespace {

constexpr unsigned kBoth = kInCsv | kInMap;

using Metric = double EventMetrics::*;
using StateAt = State EventMetrics::*;
using Result = double (*)(const RunInfo&, double);

OutputSpec series(const char* name, Dim dim, const char* meaning,
                  std::vector<double> Series::*column, double State::*state = nullptr,
                  bool load_only = false) {
  OutputSpec o{name, dim, OutputGroup::Series, kBoth, meaning};
  o.column = column;
  o.state = state;
  o.load_only = load_only;
  return o;
}

OutputSpec metric(const char* name, Dim dim, unsigned where, const char* meaning, Metric get,
                  bool may_be_undefined = false, const char* old_map_name = nullptr) {
  OutputSpec o{name, dim, OutputGroup::Event, where, meaning};
  o.event = get;
  o.may_be_undefined = may_be_undefined;
  o.old_map_name = old_map_name;
  return o;
}

OutputSpec instant(const char* name, unsigned where, const char* meaning, StateAt at) {
  OutputSpec o{name, Dim::Number, OutputGroup::EventState, where, meaning};
  o.event_state = at;
  return o;
}

OutputSpec result(const char* name, Dim dim, unsigned where, const char* meaning, Result get) {
  OutputSpec o{name, dim, OutputGroup::Result, where, meaning};
  o.result = get;
  return o;
}

std::vector<OutputSpec> series_entries() {
  return {
      series("t", Dim::Time, "output instant, from the first change at t = 0", &Series::t),
      series("segment", Dim::Count, "the 0-based segment of each output instant", nullptr),
      series("FN", Dim::Force, "normal force", &Series::FN, &State::FN),
      series("Fx", Dim::Force, "friction force", &Series::Fx, &State::Fx),
      series("mu", Dim::Number, "friction coefficient Fx / FN", &Series::mu, &State::mu),
      series("a2", Dim::Length, "trailing edge a2 of the contact", &Series::a2, &State::a2),
      series("d", Dim::Length, "indentation depth", &Series::d, &State::d, true),
      series("a1", Dim::Length, "leading edge a1 of the contact", &Series::a1, &State::a1, true),
  };
}

const char* const kDc =
    "slip over which |mu - mu_ss(w)| first falls to 1/e of its value at the reference point "
    "(the change with a parallel dashpot, the peak without one), counted from there; "
    "undefined during a hold, without a transient, when the peak is the segment's end, when "
    "it does not fall that far within the segment, or when the transient overshoots mu_ss(w) "
    "by more than 1/e of that value";

std::vector<OutputSpec> extremum_entries() {
  const char* sol = " friction coefficient within the segment (from the solution, not the output "
                    "instants)";
  static const std::string largest = std::string("largest") + sol,
                           smallest = std::string("smallest") + sol;
  return {
      metric("mu_max", Dim::Number, kBoth, largest.c_str(), &EventMetrics::mu_max),
      metric("t_max", Dim::Time, kBoth, "time of mu_max since the change", &EventMetrics::t_max),
      metric("slip_max", Dim::Length, kBoth, "slip of mu_max since the change",
             &EventMetrics::slip_max),
      metric("mu_min", Dim::Number, kBoth, smallest.c_str(), &EventMetrics::mu_min),
      metric("t_min", Dim::Time, kBoth, "time of mu_min since the change", &EventMetrics::t_min),
      metric("slip_min", Dim::Length, kBoth, "slip of mu_min since the change",
             &EventMetrics::slip_min),
      metric("mu_peak", Dim::Number, kBoth,
             "the extremum on the side of the change: mu_max after a rise, mu_min after a drop "
             "or into a hold; mu just after the change where the segment shows no transient "
             "(within the error estimate)",
             &EventMetrics::mu_peak),
      metric("t_peak", Dim::Time, kBoth, "time of mu_peak since the change", &EventMetrics::t_peak),
      metric("slip_peak", Dim::Length, kBoth, "slip of mu_peak since the change",
             &EventMetrics::slip_peak),
  };
}

std::vector<OutputSpec> event_entries() {
  std::vector<OutputSpec> v = {
      metric("t", Dim::Time, kBoth,
             "time of the velocity change at the segment's start (the first at t = 0)",
             &EventMetrics::t),
      metric("w_before", Dim::Velocity, kInCsv, "velocity before the change (v for the first)",
             &EventMetrics::w_before),
      metric("w_after", Dim::Velocity, kInCsv, "velocity after the change (the segment's w)",
             &EventMetrics::w_after),
      metric("mu_before", Dim::Number, kBoth,
             "friction coefficient just before the change (the previous segment's last sample)",
             &EventMetrics::mu_before),
      instant("after", kBoth, "just after the change (the segment's first sample)",
              &EventMetrics::after),
  };
  for (OutputSpec& o : extremum_entries())
    v.push_back(o);
  const std::vector<OutputSpec> rest = {
      instant("end", kBoth, "at the segment's end (its last sample)", &EventMetrics::end),
      instant("ss_before", kInCsv,
              "in stationary sliding at the velocity before the change (closed form)",
              &EventMetrics::ss_before),
      instant("ss_after", kInCsv, "in stationary sliding at the segment's velocity (closed form)",
              &EventMetrics::ss_after),
      metric("D_c", Dim::Length, kBoth, kDc, &EventMetrics::d_c, true, "d_c"),
      metric("overshoot", Dim::Number, kBoth,
             "largest excursion of mu beyond mu_ss(w) on the side opposite to mu just after the "
             "change, relative to |mu - mu_ss(w)| just after the change; 0 for a one-sided "
             "transient",
             &EventMetrics::overshoot),
      metric("a", Dim::Number, kBoth,
             "direct effect (mu_direct - mu_before) / ln(w / w_before), mu_direct = mu_after "
             "with a parallel dashpot, mu_peak without one; undefined across a hold",
             &EventMetrics::a, true),
      metric("a_minus_b", Dim::Number, kBoth,
             "(mu_ss(w) - mu_ss(w_before)) / ln(w / w_before); undefined across a hold",
             &EventMetrics::a_minus_b, true),
      metric("b", Dim::Number, kBoth, "evolution effect a - (a - b); undefined across a hold",
             &EventMetrics::b, true),
      metric("healing", Dim::Number, kBoth,
             "static healing of a reslide after a hold: mu_max - mu_ss at the velocity before "
             "the hold; undefined for any other segment",
             &EventMetrics::healing, true),
  };
  v.insert(v.end(), rest.begin(), rest.end());
  return v;
}

std::vector<OutputSpec> result_entries() {
  return {
      result("error_estimate", Dim::Number, kBoth,
             "the solver's estimate of the case's relative error (docs/design.md, error metric)",
             [](const RunInfo& i, double) { return i.error_estimate; }),
      result("cells_per_a1", Dim::Number, kInCsv,
             "resolution a1 / dx of the final run (0 for the exact solver)",
             [](const RunInfo& i, double) { return i.cells_per_a1; }),
      result("elements", Dim::Count, kInCsv, "elements held in memory at once (peak, final run)",
             [](const RunInfo& i, double) { return static_cast<double>(i.elements); }),
      result("steps", Dim::Count, kInCsv, "time steps taken, all runs included",
             [](const RunInfo& i, double) { return static_cast<double>(i.steps); }),
      result("element_updates", Dim::Count, kInCsv, "element state updates, all runs included",
             [](const RunInfo& i, double) { return static_cast<double>(i.element_updates); }),
      result("root_solves", Dim::Count, kInCsv, "scalar root solves (the exact solver)",
             [](const RunInfo& i, double) { return static_cast<double>(i.root_solves); }),
      result("wall_seconds", Dim::WallClock, kBoth, "wall-clock time the case took, in seconds",
             [](const RunInfo&, double wall) { return wall; }),
  };
}

OutputSpec scale(const char* name, Dim dim, const char* meaning, double Scales::*member) {
  OutputSpec o{name, dim, OutputGroup::Scale, kBoth, meaning};
  o.scale = member;
  return o;
}

std::vector<OutputSpec> scale_entries() {
  return {
      scale("length", Dim::Length,
            "reference length: the leading edge a1 of the contact at the depth d; under load "
            "the Hertz radius a0 of the load F0 with the long-term modulus G "
            "(F0 = 16/3 G a0^3 / R)",
            &Scales::length),
      scale("depth", Dim::Length, "indentation depth of the reference contact (d, or a0^2 / R)",
            &Scales::depth),
      scale("force", Dim::Force,
            "elastic normal force of the reference contact with the long-term modulus G "
            "(16/3 G a^3 / R; the prescribed load F0 under load)",
            &Scales::force),
      scale("friction", Dim::Number,
            "friction scale: the profile's slope at the reference length over two (a / R for "
            "the parabola)",
            &Scales::friction),
      scale("time", Dim::Time,
            "time scale: the longest relaxation time of the material, shifted by aT (tau for "
            "the Kelvin foundation)",
            &Scales::time),
  };
}

} // namespace

const std::vector<OutputSpec>& output_table() {
  static const std::vector<OutputSpec> table = [] {
    std::vector<OutputSpec> t = series_entries();
    for (const auto& part : {event_entries(), result_entries(), scale_entries()})
      t.insert(t.end(), part.begin(), part.end());
    return t;
  }();
  return table;
}

const OutputSpec& output(OutputGroup group, const char* name) {
  for (const OutputSpec& o : output_table())
    if (o.group == group && std::strcmp(o.name, name) == 0) return o;
  throw std::logic_error(std::string("no output quantity ") + name);
}

std::vector<const OutputSpec*> state_outputs(bool load) {
  std::vector<const OutputSpec*> out;
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Series && o.state != nullptr && (load || !o.load_only))
      out.push_back(&o);
  return out;
}

double sample(const OutputSpec& column, const Series& s, std::size_t k) {
  return column.column != nullptr ? (s.*(column.column))[k] : static_cast<double>(s.segment[k]);
}

const char* output_group_name(OutputGroup g) {
  static const char* const names[] = {"series", "event", "event_state", "result", "scale"};
  static_assert(sizeof names / sizeof names[0] == static_cast<std::size_t>(OutputGroup::Scale) + 1,
                "one name per OutputGroup, in its order");
  return names[static_cast<std::size_t>(g)];
}

std::string event_state_name(const OutputSpec& q, const OutputSpec& instant) {
  return std::string(q.name) + "_" + instant.name;
}

} // namespace mdrmap
