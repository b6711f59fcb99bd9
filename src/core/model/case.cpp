#include "core/model/case.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/model/params.hpp"
#include "core/model/row_limits.hpp"

namespace mdrmap {

std::string format_number(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

double History::start(std::size_t k) const {
  double t = 0.0;
  for (std::size_t i = 0; i < k && i < segments.size(); ++i)
    t += segments[i].T;
  return t;
}

double Sampling::inner_offset(long j, double T) const {
  if (spacing == Spacing::Linear) // T j overflowed (T near the largest double): the fraction first
    return T * (static_cast<double>(j) / static_cast<double>(samples - 1));
  // samples >= 3 here; j = 1 .. samples - 2 lie strictly inside (0, T)
  const double frac = static_cast<double>(samples - 1 - j) / static_cast<double>(samples - 2);
  return T * std::pow(10.0, -decades * frac);
}

double Case::a0() const {
  return indenter.hertz_radius(loading.F0, rheology.G);
}

std::size_t Case::total_samples() const {
  return first_sample(history.size());
}

std::size_t Case::first_sample(std::size_t k) const {
  if (sampling.at.empty()) return k * static_cast<std::size_t>(sampling.samples);
  std::size_t n = 0;
  for (std::size_t i = 0; i < k && i < sampling.at.size(); ++i)
    n += sampling.at[i].size();
  return n;
}

namespace {

void check_history(const History& h) {
  if (h.segments.empty()) throw InvalidInput("history", "must have at least one segment W:T");
  if (h.segments.size() > kMaxSegments)
    throw InvalidInput("history", "has " + std::to_string(h.segments.size()) +
                                      " segments; at most " + std::to_string(kMaxSegments) +
                                      " are allowed");
  for (std::size_t k = 0; k < h.segments.size(); ++k) {
    try {
      segment_velocity_spec().check(h.segments[k].w);
      segment_duration_spec().check(h.segments[k].T);
    } catch (const InvalidInput& e) {
      throw InvalidInput("history",
                         "segment " + std::to_string(k + 1) + ": " + e.option() + " " + e.what());
    }
  }
  if (!std::isfinite(h.end()))
    throw InvalidInput("history", "the segments' durations add up to more than a double holds");
  for (std::size_t k = 0; k < h.segments.size(); ++k)
    if (!std::isfinite(h.segments[k].w * h.segments[k].T))
      throw InvalidInput("history", "segment " + std::to_string(k + 1) +
                                        ": the slip W T = " + format_number(h.segments[k].w) +
                                        " x " + format_number(h.segments[k].T) +
                                        " overflows; shorten the segment or rescale the units");
}

/// Explicit instants (Sampling::at), where given: one list per segment, each
/// from 0 to the segment's duration, strictly increasing. Only a lab record
/// (--history-file) gives them.
void check_explicit_sampling(const Sampling& s, const History& h) {
  if (s.at.empty()) return;
  if (s.at.size() != h.size())
    throw InvalidInput("history-file", "gives output instants for " + std::to_string(s.at.size()) +
                                           " segments of a history of " + std::to_string(h.size()));
  for (std::size_t k = 0; k < h.size(); ++k) {
    const std::vector<double>& a = s.at[k];
    bool ok = a.size() >= 2 && a.front() == 0.0 && a.back() == h.segments[k].T;
    for (std::size_t j = 1; ok && j < a.size(); ++j)
      ok = a[j] > a[j - 1];
    if (!ok)
      throw InvalidInput("history-file", "segment " + std::to_string(k + 1) +
                                             ": the output instants must rise strictly from 0 to "
                                             "the segment's duration " +
                                             format_number(h.segments[k].T));
  }
}

/// Exactly one parameter of each group (e.g. d or F0) is given (non-zero).
/// (No strings unless it fails: every case of a study passes here.)
void check_groups(const Case& c) {
  const auto same_group = [](const ParamSpec& p, const ParamSpec& q) {
    return q.one_of != nullptr && std::strcmp(q.one_of, p.one_of) == 0;
  };
  const char* checked = nullptr; // the group just checked (its members are adjacent)
  for (const auto& p : case_parameters()) {
    if (!p.one_of || (checked && std::strcmp(checked, p.one_of) == 0)) continue;
    checked = p.one_of;
    int given = 0;
    for (const auto& q : case_parameters())
      if (same_group(p, q)) given += q.get(c) != 0.0 ? 1 : 0;
    if (given == 1) continue;
    std::string names;
    for (const auto& q : case_parameters())
      if (same_group(p, q)) names += (names.empty() ? "--" : " or --") + std::string(q.name);
    throw InvalidInput(p.name, "give exactly one of " + names + " (the " + p.one_of + "), got " +
                                   std::to_string(given));
  }
}

/// Every parameter of the table in its range; a parameter of another
/// profile not given (0), a one_of group's other members 0 (check_groups).
/// One pass, one read of each: every case of a study passes here.
void check_parameters(const Case& c) {
  const Profile kind = c.indenter.profile;
  for (const auto& p : case_parameters()) {
    const double x = p.get(c);
    if (p.profile != nullptr && !p.applies_to(kind)) {
      if (x != 0.0)
        throw InvalidInput(p.name, std::string("applies to --profile ") + p.profile +
                                       " only; this case's profile is " + profile_name(kind));
      continue;
    }
    if (!p.one_of || x != 0.0) p.check(x);
  }
}

} // namespace

void validate_parts(const Case& c) {
  check_groups(c);
  check_parameters(c);
  check_profile_limits(c.indenter);
  validate(c.rheology);
  validate_history(c.history, c.sampling);
  if (uses_element_row(c)) check_element_row(c);
}

void validate_history(const History& h, const Sampling& s) {
  check_history(h);
  check_explicit_sampling(s, h);
}

double default_step_duration(double d, double R, double tau, double v, double v1) {
  if (tau > 0.0) return 6.0 * tau;
  const double w = (v1 > 0.0) ? std::min(v, v1) : v;
  return 6.0 * (std::sqrt(R) * std::sqrt(d)) / w;
}

Case step_case(double d, double R, double tau, double v, double v1, double G, double t_end,
               long samples) {
  Case c;
  c.loading.d = d;
  c.indenter = Parabola{R};
  c.rheology.tau = tau;
  c.rheology.G = G;
  c.history.v0 = v;
  const double T = t_end > 0.0 ? t_end : default_step_duration(d, R, tau, v, v1);
  c.history.segments = {Segment{v1, T}};
  c.sampling.samples = samples;
  return c;
}

void require_depth_control(const Case& c, const char* solver) {
  if (c.loading.by_force())
    throw InvalidInput("solver", std::string(solver) +
                                     " solves depth control only (--d); this case prescribes the "
                                     "normal load (--F0)");
}

void require_kelvin(const Case& c, const char* solver) {
  if (!c.rheology.kelvin())
    throw InvalidInput("prony", std::string(solver) +
                                    " solves the Kelvin foundation only (no Maxwell branches); "
                                    "this case has " +
                                    std::to_string(c.rheology.branches.size()));
}

void require_parabola(const Case& c, const char* solver) {
  if (!c.indenter.parabolic())
    throw InvalidInput(
        "profile", std::string(solver) + " solves the parabola only; this case's profile is " +
                       profile_name(c.indenter.profile) + " (row and baseline take every profile)");
}

double zeta(const Case& c, double w) {
  return w * c.rheology.tau / c.a1();
}

} // namespace mdrmap
