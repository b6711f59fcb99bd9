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
  static const ParamSpec T{"T_over_tau",
                           "X",
                           Part::History,
                           Dim::Number,
                           0.0,
                           false,
                           kInf,
                           true,
                           nullptr,
                           0.0,
                           "a segment's duration over tau",
                           no_get,
                           no_set};
  return velocity ? w : T;
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
  for (const ParamSpec* p : study_parameters())
    if (name == p->name) {
      out.param = p;
      return true;
    }
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
      if (s.part != Part::Sampling && std::string(s.name) != "aT") out.push_back(&s);
    return out;
  }();
  return p;
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
  case Column::Kind::DurationOverTau:
    break;
  }
  return ratio_spec(false);
}

namespace {

/// The case parameters' slots in column order: the members of a one-of group
/// (the loading: d or FN) share one.
struct Slot {
  std::vector<const ParamSpec*> params;
  std::string names() const { // "d or FN"
    std::string s;
    for (const ParamSpec* p : params)
      s += (s.empty() ? "" : " or ") + std::string(p->name);
    return s;
  }
  bool required() const { return params.size() > 1 || params.front()->required; }
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

/// "a study needs d or FN, R, tau and v"
std::string needed() {
  std::vector<std::string> n;
  for (const Slot& s : slots())
    if (s.required()) n.push_back(s.names());
  std::string out = "a study needs ";
  for (std::size_t i = 0; i < n.size(); ++i)
    out += (i == 0 ? "" : i + 1 == n.size() ? " and " : ", ") + n[i];
  return out;
}

} // namespace

std::size_t column_rank(const Column& col) {
  const std::size_t params = slots().size();
  if (col.history()) {
    const bool duration =
        col.kind == Column::Kind::Duration || col.kind == Column::Kind::DurationOverTau;
    return params + 2 * (col.segment - 1) + (duration ? 1 : 0);
  }
  for (std::size_t r = 0; r < params; ++r)
    for (const ParamSpec* p : slots()[r].params)
      if (p == col.param) return r;
  throw std::logic_error("column_rank: not a study parameter");
}

std::vector<std::string> history_names(std::size_t k) {
  const std::string s = std::to_string(k);
  return {"w" + s, "w" + s + "_over_v", "T" + s, "T" + s + "_over_tau"};
}

void order_columns(std::vector<Axis>& axes, const std::string& where) {
  std::stable_sort(axes.begin(), axes.end(), [](const Axis& a, const Axis& b) {
    return column_rank(a.column) < column_rank(b.column);
  });
  std::size_t K = 0;
  for (const Axis& a : axes)
    K = std::max(K, a.column.segment);
  std::vector<const Axis*> at(slots().size() + 2 * K, nullptr);
  for (const Axis& a : axes) {
    const Axis*& slot = at[column_rank(a.column)];
    if (slot)
      throw ConfigError(a.option(), where + "both " + slot->name + " (" + slot->option() +
                                        ") and " + a.name + " (" + a.option() +
                                        ") are given; they set the same thing, give only one");
    slot = &a;
  }
  const std::size_t P = slots().size();
  for (std::size_t r = 0; r < P; ++r)
    if (!at[r] && slots()[r].required())
      throw ConfigError(std::string("grid.") + slots()[r].params.front()->name,
                        where + "no " + slots()[r].names() + "; " + needed());
  if (K == 0)
    throw ConfigError("history.w1", where + "no history; give the segments w1 (or w1_over_v) and "
                                            "T1 (or T1_over_tau), ... in [history] or as columns "
                                            "of the case list, or the seed's v1");
  for (std::size_t k = 1; k <= K; ++k)
    for (std::size_t j = 0; j < 2; ++j)
      if (!at[slots().size() + 2 * (k - 1) + j]) {
        const auto names = history_names(k);
        throw ConfigError("history." + names[2 * j],
                          where + "segment " + std::to_string(k) + " of " + std::to_string(K) +
                              " has no " + (j == 0 ? "velocity" : "duration") + "; give " +
                              names[2 * j] + " or " + names[2 * j + 1]);
      }
  for (std::size_t r = 0; r < P; ++r)
    if (!at[r]) { // an optional parameter (G): its table default unless given
      const ParamSpec& p = *slots()[r].params.front();
      Axis d;
      d.name = p.name;
      d.section = "grid";
      d.spec = format_number(p.fallback);
      d.values = {p.fallback};
      parse_column(p.name, d.column);
      std::size_t before = 0; // its place in column order
      while (before < axes.size() && column_rank(axes[before].column) < r)
        ++before;
      axes.insert(axes.begin() + static_cast<std::ptrdiff_t>(before), d);
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
