#include "core/model/params.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <utility>

namespace mdrmap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Accessors of the table. Each is a plain function so that the table is a
// constant array of values (no captures).
double get_d(const Case& c) {
  return c.loading.d;
}
void set_d(Case& c, double x) {
  c.loading.d = x;
}
double get_tau(const Case& c) {
  return c.rheology.tau;
}
void set_tau(Case& c, double x) {
  c.rheology.tau = x;
}
double get_G(const Case& c) {
  return c.rheology.G;
}
void set_G(Case& c, double x) {
  c.rheology.G = x;
}
double get_aT(const Case& c) {
  return c.rheology.aT;
}
void set_aT(Case& c, double x) {
  c.rheology.aT = x;
}
double get_v0(const Case& c) {
  return c.history.v0;
}
void set_v0(Case& c, double x) {
  c.history.v0 = x;
}
double get_samples(const Case& c) {
  return static_cast<double>(c.sampling.samples);
}
void set_samples(Case& c, double x) {
  c.sampling.samples = static_cast<long>(x);
}
double get_decades(const Case& c) {
  return c.sampling.decades;
}
void set_decades(Case& c, double x) {
  c.sampling.decades = x;
}
double get_F0(const Case& c) {
  return c.loading.F0;
}
void set_F0(Case& c, double x) {
  c.loading.F0 = x;
}
// A shape's parameter I, read and set whatever the case's profile.
template <class S, std::size_t I> double get_shape(const Case& c) {
  return c.indenter.as<S>().*(S::parameters()[I].member);
}
template <class S, std::size_t I> void set_shape(Case& c, double x) {
  c.indenter.as<S>().*(S::parameters()[I].member) = x;
}

template <class S, std::size_t... I>
void add_shape(std::vector<ParamSpec>& table, std::index_sequence<I...>) {
  constexpr auto ps = S::parameters();
  (table.push_back(ParamSpec{ps[I].name, ps[I].symbol, Part::Indenter, ps[I].dim, ps[I].lo,
                             ps[I].lo_inclusive, ps[I].hi, true, nullptr, 0.0, ps[I].meaning,
                             get_shape<S, I>, set_shape<S, I>, S::name, ps[I].hi_inclusive}),
   ...);
}

/// The parameters of the shapes numbered from..to-1, in the table's order.
template <std::size_t... K>
void add_shapes(std::vector<ParamSpec>& table, std::size_t from, std::size_t to,
                std::index_sequence<K...>) {
  auto add = [&](auto shape, std::size_t k) {
    using S = decltype(shape);
    if (k >= from && k < to)
      add_shape<S>(table, std::make_index_sequence<S::parameters().size()>());
  };
  (add(std::tuple_element_t<K, Shapes>{}, K), ...);
}

void add_shapes(std::vector<ParamSpec>& table, std::size_t from, std::size_t to) {
  add_shapes(table, from, to, std::make_index_sequence<kShapeCount>());
}

double no_get(const Case&) {
  return 0.0;
}
void no_set(Case&, double) {}

} // namespace

const char* dim_name(Dim d) {
  switch (d) {
  case Dim::Length:
    return "length";
  case Dim::Time:
    return "time";
  case Dim::Velocity:
    return "length/time";
  case Dim::Stress:
    return "force/length^2";
  case Dim::Force:
    return "force";
  case Dim::Count:
    return "count";
  case Dim::Number:
    return "number";
  case Dim::WallClock:
    return "wall-clock time";
  }
  return "?";
}

bool ParamSpec::applies_to(Profile p) const {
  return profile == nullptr || std::strcmp(profile, profile_name(p)) == 0;
}

std::string ParamSpec::allowed() const {
  if (integer()) return "an integer from " + format_number(lo) + " to " + format_number(hi);
  std::string s = "a finite number";
  if (std::isfinite(lo)) s += (lo_inclusive ? " >= " : " > ") + format_number(lo);
  if (std::isfinite(hi))
    s += (std::isfinite(lo) ? (hi_inclusive ? " and <= " : " and < ")
                            : (hi_inclusive ? " <= " : " < ")) +
         format_number(hi);
  return s;
}

void ParamSpec::refuse(double x) const {
  throw InvalidInput(name, "must be " + allowed() + ", got " + format_number(x));
}

const std::vector<ParamSpec>& case_parameters() {
  // the loading, the first shape's parameters (the seed's d, R, tau, v), the
  // material and the history, the other shapes', the sampling
  static const std::vector<ParamSpec> table = [] {
    std::vector<ParamSpec> t = {
        {"d", "D", Part::Loading, Dim::Length, 0.0, false, kInf, false, "loading", 0.0,
         "indentation depth (depth control)", get_d, set_d},
        {"F0", "F0", Part::Loading, Dim::Force, 0.0, false, kInf, false, "loading", 0.0,
         "prescribed normal load (load control: the depth follows it)", get_F0, set_F0}};
    add_shapes(t, 0, 1);
    t.insert(t.end(),
             {{"tau", "TAU", Part::Material, Dim::Time, 0.0, true, kInf, true, nullptr, 0.0,
               "relaxation time eta/G of the foundation's dashpot; 0 is the purely elastic limit "
               "(with --prony: no parallel dashpot)",
               get_tau, set_tau},
              {"G", "G", Part::Material, Dim::Stress, 0.0, false, kInf, false, nullptr, 1.0,
               "long-term shear modulus of the foundation (with --prony: the rubbery modulus)",
               get_G, set_G},
              {"aT", "A", Part::Material, Dim::Number, 0.0, false, kInf, false, nullptr, 1.0,
               "time-temperature shift factor: multiplies tau and every relaxation time of --prony",
               get_aT, set_aT},
              {"v", "V0", Part::History, Dim::Velocity, 0.0, false, kInf, true, nullptr, 0.0,
               "sliding velocity of the stationary sliding before t = 0", get_v0, set_v0}});
    add_shapes(t, 1, kShapeCount);
    t.insert(t.end(),
             {{"samples", "N", Part::Sampling, Dim::Count, 2.0, true,
               static_cast<double>(kMaxSamples), false, nullptr, 201.0,
               "output instants per segment, from its start to its end", get_samples, set_samples},
              {"log-decades", "D", Part::Sampling, Dim::Number, 0.0, false, 300.0, false, nullptr,
               4.0, "with --spacing log: the first instant after a segment's start is T 10^-D",
               get_decades, set_decades}});
    return t;
  }();
  return table;
}

const ParamSpec& segment_velocity_spec() {
  static const ParamSpec s{"w",
                           "W",
                           Part::History,
                           Dim::Velocity,
                           0.0,
                           true,
                           kInf,
                           true,
                           nullptr,
                           0.0,
                           "sliding velocity of a segment; 0 is a hold",
                           no_get,
                           no_set};
  return s;
}

const ParamSpec& segment_duration_spec() {
  static const ParamSpec s{
      "T",     "T", Part::History,           Dim::Time, 0.0,   false, kInf, true,
      nullptr, 0.0, "duration of a segment", no_get,    no_set};
  return s;
}

const ParamSpec& branch_modulus_spec() {
  static const ParamSpec s{"G",
                           "GK",
                           Part::Material,
                           Dim::Stress,
                           0.0,
                           false,
                           kInf,
                           true,
                           nullptr,
                           0.0,
                           "shear modulus of a Maxwell branch (a Prony term)",
                           no_get,
                           no_set};
  return s;
}

const ParamSpec& branch_time_spec() {
  static const ParamSpec s{"tau",
                           "TAUK",
                           Part::Material,
                           Dim::Time,
                           0.0,
                           false,
                           kInf,
                           true,
                           nullptr,
                           0.0,
                           "relaxation time of a Maxwell branch (a Prony term)",
                           no_get,
                           no_set};
  return s;
}

const std::vector<ParamAlias>& parameter_aliases() {
  // FN: the prescribed load's name before it was told apart from the
  // measured normal force FN of the results
  static const std::vector<ParamAlias> aliases = {{"FN", "F0"}};
  return aliases;
}

std::string canonical_parameter_name(const std::string& name) {
  for (const auto& a : parameter_aliases())
    if (name == a.alias) return a.name;
  return name;
}

const ParamAlias* alias_of(const std::string& name) {
  for (const auto& a : parameter_aliases())
    if (name == a.name) return &a;
  return nullptr;
}

std::string two_spellings(const ParamAlias& a, const std::string& prefix) {
  return prefix + a.name + " and " + prefix + a.alias + " are the same parameter (" + a.alias +
         " is the old spelling of " + a.name + "); give only one";
}

const ParamSpec* find_parameter(const std::string& name) {
  const std::string canonical = canonical_parameter_name(name);
  for (const auto& p : case_parameters())
    if (canonical == p.name) return &p;
  return nullptr;
}

} // namespace mdrmap
