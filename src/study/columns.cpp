#include "study/columns.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

double no_get(const Case&) {
  return 0.0;
}
void no_set(Case&, double) {}

constexpr double kInf = std::numeric_limits<double>::infinity();

const ParamSpec& ratio_spec(bool velocity) {
  static const ParamSpec w{"w_over_v",
                           "X",
                           Part::History,
                           Dim::Number,
                           0.0,
                           true,
                           kInf,
                           true,
                           nullptr,
                           0.0,
                           "a segment's velocity over v; 0 is a hold",
                           no_get,
                           no_set};
  static const ParamSpec T{
      "T_over_tau",
      "X",
      Part::History,
      Dim::Number,
      0.0,
      false,
      kInf,
      true,
      nullptr,
      0.0,
      "a segment's duration over the case's time scale (tau; aT max(tau, tauk) with a "
      "spectrum or a shift)",
      no_get,
      no_set};
  return velocity ? w : T;
}

/// The temperature's range: any finite number (the WLF constants say more).
const ParamSpec& temperature_spec() {
  static const ParamSpec t{
      "temperature",
      "TEMP",
      Part::Material,
      Dim::Number,
      -kInf,
      false,
      kInf,
      true,
      nullptr,
      0.0,
      "temperature, in the unit of the WLF constants of [run] wlf, which give the "
      "shift factor aT at it",
      no_get,
      no_set};
  return t;
}

/// Gk or tauk: the term k (1..kMaxBranches, no leading 0) of a spectrum column.
bool branch_column(const std::string& name, Column& out) {
  const ParamSpec* specs[] = {&branch_modulus_spec(), &branch_time_spec()};
  for (const ParamSpec* spec : specs) {
    const std::string stem = spec->name;
    if (name.size() <= stem.size() || name.compare(0, stem.size(), stem) != 0) continue;
    const std::string digits = name.substr(stem.size());
    if (digits.size() > 2 || digits[0] == '0') return false;
    std::size_t k = 0;
    for (const char ch : digits) {
      if (ch < '0' || ch > '9') return false;
      k = 10 * k + static_cast<std::size_t>(ch - '0');
    }
    if (k > kMaxBranches) return false;
    out.kind = spec == specs[0] ? Column::Kind::BranchModulus : Column::Kind::BranchTime;
    out.branch = k;
    return true;
  }
  return false;
}

/// "12" -> 12; false unless the text is 1 to 5 digits without a leading 0.
bool segment_number(const std::string& s, std::size_t& k) {
  if (s.empty() || s.size() > 5 || s[0] == '0') return false;
  k = 0;
  for (const char ch : s) {
    if (ch < '0' || ch > '9') return false;
    k = 10 * k + static_cast<std::size_t>(ch - '0');
  }
  return k <= kMaxSegments;
}

} // namespace

bool parse_column(const std::string& name, Column& out) {
  out = Column{};
  const std::string canonical = canonical_parameter_name(name); // FN: F0
  for (const ParamSpec* p : study_parameters())
    if (canonical == p->name) {
      out.param = p;
      return true;
    }
  if (name == "temperature") {
    out.kind = Column::Kind::Temperature;
    return true;
  }
  if (branch_column(name, out)) return true;
  if (name == "v1" || name == "v1_over_v") { // the seed's step
    out.kind = name == "v1" ? Column::Kind::Velocity : Column::Kind::VelocityOverV;
    out.segment = 1;
    return true;
  }
  if (name.empty() || (name[0] != 'w' && name[0] != 'T')) return false;
  const bool velocity = name[0] == 'w';
  const char* suffix = velocity ? "_over_v" : "_over_tau";
  std::string digits = name.substr(1);
  bool relative = false;
  const std::size_t n = std::strlen(suffix);
  if (digits.size() > n && digits.compare(digits.size() - n, n, suffix) == 0) {
    digits.resize(digits.size() - n);
    relative = true;
  }
  if (!segment_number(digits, out.segment)) return false;
  using K = Column::Kind;
  out.kind = velocity ? (relative ? K::VelocityOverV : K::Velocity)
                      : (relative ? K::DurationOverTau : K::Duration);
  return true;
}

namespace detail {

const std::vector<const ParamSpec*>& study_parameters() {
  static const std::vector<const ParamSpec*> p = [] {
    std::vector<const ParamSpec*> out;
    for (const ParamSpec& s : case_parameters())
      if (s.part != Part::Sampling) out.push_back(&s);
    return out;
  }();
  return p;
}

bool only_where_given(const ParamSpec& p) {
  if (p.profile) return true; // an indenter's: required with its profile, else not given
  return p.part == Part::Material && std::strcmp(p.name, "aT") == 0;
}

std::string column_name(const Column& col) {
  switch (col.kind) {
  case Column::Kind::Param:
    return col.param->name;
  case Column::Kind::BranchModulus:
    return branch_modulus_spec().name + std::to_string(col.branch);
  case Column::Kind::BranchTime:
    return branch_time_spec().name + std::to_string(col.branch);
  case Column::Kind::Temperature:
    return temperature_spec().name;
  default:
    break;
  }
  return history_names(col.segment)[col.kind == Column::Kind::Velocity        ? 0
                                    : col.kind == Column::Kind::VelocityOverV ? 1
                                    : col.kind == Column::Kind::Duration      ? 2
                                                                              : 3];
}

std::string stored_name(const Axis& a) {
  return a.column.kind == Column::Kind::Param ? column_name(a.column) : a.name;
}

std::string column_meaning(const Column& col) {
  const std::string meaning = column_spec(col).meaning;
  if (col.history()) return "segment " + std::to_string(col.segment) + ": " + meaning;
  if (col.spectrum()) return "term " + std::to_string(col.branch) + ": " + meaning;
  return meaning;
}

const ParamSpec& column_spec(const Column& col) {
  switch (col.kind) {
  case Column::Kind::Param:
    return *col.param;
  case Column::Kind::Velocity:
    return segment_velocity_spec();
  case Column::Kind::Duration:
    return segment_duration_spec();
  case Column::Kind::VelocityOverV:
    return ratio_spec(true);
  case Column::Kind::BranchModulus:
    return branch_modulus_spec();
  case Column::Kind::BranchTime:
    return branch_time_spec();
  case Column::Kind::Temperature:
    return temperature_spec();
  case Column::Kind::DurationOverTau:
    break;
  }
  return ratio_spec(false);
}

namespace {

/// The case parameters' slots in column order: the members of a one-of group
/// (the loading: d or F0) share one.
struct Slot {
  std::vector<const ParamSpec*> params;
  std::string names() const { // "d or F0"
    std::string s;
    for (const ParamSpec* p : params)
      s += (s.empty() ? "" : " or ") + std::string(p->name);
    return s;
  }
  bool required(Profile profile) const {
    const ParamSpec& p = *params.front();
    return params.size() > 1 || (p.required && p.applies_to(profile));
  }
};

const std::vector<Slot>& slots() {
  static const std::vector<Slot> out = [] {
    std::vector<Slot> v;
    for (const ParamSpec* p : study_parameters()) {
      if (p->one_of && !v.empty() && v.back().params.front()->one_of &&
          std::string(v.back().params.front()->one_of) == p->one_of)
        v.back().params.push_back(p);
      else
        v.push_back(Slot{{p}});
    }
    return v;
  }();
  return out;
}

/// "a study needs d or F0, R, tau and v" (of the parabola)
std::string needed(Profile profile) {
  std::vector<std::string> n;
  for (const Slot& s : slots())
    if (s.required(profile)) n.push_back(s.names());
  std::string out = "a study needs ";
  for (std::size_t i = 0; i < n.size(); ++i)
    out += (i == 0 ? "" : i + 1 == n.size() ? " and " : ", ") + n[i];
  return out;
}

} // namespace

namespace {

constexpr std::size_t kBranchPlaces = 2 * kMaxBranches;

/// The slot r of a table parameter by name.
std::size_t slot_of(const char* name) {
  for (std::size_t r = 0; r < slots().size(); ++r)
    for (const ParamSpec* p : slots()[r].params)
      if (std::strcmp(p->name, name) == 0) return r;
  throw std::logic_error(std::string("slot_of: not a study parameter: ") + name);
}

/// The place of parameter slot r in column order: the spectrum's terms
/// follow the long-term modulus G.
std::size_t slot_rank(std::size_t r) {
  return r <= slot_of("G") ? r : r + kBranchPlaces;
}

/// The parameter slot at rank `rank`, or slots().size() for a term's place.
std::size_t slot_at(std::size_t rank) {
  for (std::size_t r = 0; r < slots().size(); ++r)
    if (slot_rank(r) == rank) return r;
  return slots().size();
}

} // namespace

std::size_t column_rank(const Column& col) {
  const std::size_t params = slots().size() + kBranchPlaces;
  if (col.history()) {
    const bool duration =
        col.kind == Column::Kind::Duration || col.kind == Column::Kind::DurationOverTau;
    return params + 2 * (col.segment - 1) + (duration ? 1 : 0);
  }
  if (col.spectrum())
    return slot_rank(slot_of("G")) + 1 + 2 * (col.branch - 1) +
           (col.kind == Column::Kind::BranchTime ? 1 : 0);
  if (col.kind == Column::Kind::Temperature) return slot_rank(slot_of("aT")); // instead of aT
  for (std::size_t r = 0; r < slots().size(); ++r)
    for (const ParamSpec* p : slots()[r].params)
      if (p == col.param) return slot_rank(r);
  throw std::logic_error("column_rank: not a study parameter");
}

std::vector<std::string> history_names(std::size_t k) {
  const std::string s = std::to_string(k);
  return {"w" + s, "w" + s + "_over_v", "T" + s, "T" + s + "_over_tau"};
}

namespace {

/// Every term 1..N of a spectrum has both its modulus and its time (N the
/// highest term given). `at` is indexed by rank.
void check_spectrum(const std::vector<const Axis*>& at, const std::string& where) {
  const std::size_t first = slot_rank(slot_of("G")) + 1;
  std::size_t N = 0;
  for (std::size_t k = 1; k <= kMaxBranches; ++k)
    if (at[first + 2 * (k - 1)] || at[first + 2 * (k - 1) + 1]) N = k;
  if (N > 0 && !at[first - 1])
    throw ConfigError("grid.G", where + "a spectrum (G1, tau1, ...) needs the long-term (rubbery) "
                                        "modulus G > 0 (key G or a column G); it has no default "
                                        "beside a spectrum");
  for (std::size_t k = 1; k <= N; ++k)
    for (std::size_t j = 0; j < 2; ++j) {
      if (at[first + 2 * (k - 1) + j]) continue;
      const std::string G = branch_modulus_spec().name + std::to_string(k),
                        tau = branch_time_spec().name + std::to_string(k);
      const Axis* other = at[first + 2 * (k - 1) + 1 - j];
      throw ConfigError(std::string("grid.") + (j == 0 ? G : tau),
                        where + (other ? "term " + std::to_string(k) + " of the spectrum has " +
                                             other->name + " but no " + (j == 0 ? G : tau) +
                                             "; a term takes its modulus and its time"
                                       : "the spectrum has terms up to " + std::to_string(N) +
                                             " but no " + G + " and " + tau +
                                             "; give the terms 1 to N, each with both"));
    }
}

/// An optional parameter's column (G) with its table default, at its place.
void add_default(std::vector<Axis>& axes, const ParamSpec& p, std::size_t rank) {
  Axis d;
  d.name = p.name;
  d.section = "grid";
  d.spec = format_number(p.fallback);
  d.values = {p.fallback};
  d.by_default = true;
  parse_column(p.name, d.column);
  std::size_t before = 0; // its place in column order
  while (before < axes.size() && column_rank(axes[before].column) < rank)
    ++before;
  axes.insert(axes.begin() + static_cast<std::ptrdiff_t>(before), d);
}

} // namespace

void order_columns(std::vector<Axis>& axes, const std::string& where, Profile profile) {
  std::stable_sort(axes.begin(), axes.end(), [](const Axis& a, const Axis& b) {
    return column_rank(a.column) < column_rank(b.column);
  });
  std::size_t K = 0;
  for (const Axis& a : axes)
    K = std::max(K, a.column.segment);
  const std::size_t P = slots().size() + kBranchPlaces;
  std::vector<const Axis*> at(P + 2 * K, nullptr);
  for (const Axis& a : axes) {
    const Axis*& slot = at[column_rank(a.column)];
    if (slot)
      throw ConfigError(a.option(), where + "both " + slot->name + " (" + slot->option() +
                                        ") and " + a.name + " (" + a.option() +
                                        ") are given; they set the same thing, give only one");
    slot = &a;
  }
  for (std::size_t r = 0; r < slots().size(); ++r)
    if (!at[slot_rank(r)] && slots()[r].required(profile))
      throw ConfigError(std::string("grid.") + slots()[r].params.front()->name,
                        where + "no " + slots()[r].names() + "; " + needed(profile) +
                            (profile == Profile::of<Parabola>()
                                 ? std::string()
                                 : std::string(" (the ") + profile_name(profile) + ")"));
  check_spectrum(at, where);
  if (K == 0)
    throw ConfigError("history.w1", where + "no history; give the segments w1 (or w1_over_v) and "
                                            "T1 (or T1_over_tau), ... in [history] or as columns "
                                            "of the case list, or the seed's v1");
  for (std::size_t k = 1; k <= K; ++k)
    for (std::size_t j = 0; j < 2; ++j)
      if (!at[P + 2 * (k - 1) + j]) {
        const auto names = history_names(k);
        throw ConfigError("history." + names[2 * j],
                          where + "segment " + std::to_string(k) + " of " + std::to_string(K) +
                              " has no " + (j == 0 ? "velocity" : "duration") + "; give " +
                              names[2 * j] + " or " + names[2 * j + 1]);
      }
  for (std::size_t rank = 0; rank < P; ++rank) {
    const std::size_t r = slot_at(rank);
    if (r == slots().size() || at[rank]) continue;
    const ParamSpec& p = *slots()[r].params.front();
    if (!only_where_given(p)) add_default(axes, p, rank); // G: its table default
  }
}

std::string grid_shape(const StudyConfig& c) {
  std::string s;
  for (const auto& a : c.axes) {
    if (!s.empty()) s += " x ";
    s += a.name + " " + std::to_string(a.values.size());
  }
  return s;
}

} // namespace detail
} // namespace mdrmap::study
