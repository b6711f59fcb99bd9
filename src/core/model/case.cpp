#include "core/model/case.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/metrics/analytic.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/metrics/profile_stationary.hpp"
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

// The range of the contact radius (any length the contact forces are formed
// from): its powers up to a^4 stay normal doubles.
constexpr double kMinRadius = 1e-75, kMaxRadius = 1e75;
// The largest w tau and w tau a^3 the stationary formulas form (sums of a few
// of them must not overflow).
constexpr double kMaxProduct = 1e306;
// Forces below this have lost digits to underflow.
constexpr double kMinForce = 1e-290;

/// What makes the contact of radius a1 = sqrt(R d) at depth d sliding at w
/// unrepresentable ("" if nothing): its radius, the products w tau, w tau a1^3,
/// or the forces of its stationary state.
std::string contact_problem(const Case& at_depth, double w) {
  const double a = at_depth.a1(), L = w * at_depth.rheology.tau;
  if (!(a >= kMinRadius) || !(a <= kMaxRadius))
    return "a contact radius a1 = " + format_number(a) + ", outside [1e-75, 1e75]";
  if (!(L <= kMaxProduct) || !(L * a * a * a <= kMaxProduct))
    return "w tau = " + format_number(L) + " at a1 = " + format_number(a) +
           ": w tau or w tau a1^3 above 1e306 (an overflow)";
  const State st = at_depth.indenter.parabolic() ? analytic::stationary(at_depth, w)
                                                 : profile_stationary(at_depth, w);
  if (!std::isfinite(st.FN) || !std::isfinite(st.Fx) || !std::isfinite(st.mu) ||
      !(st.FN >= kMinForce))
    return "contact forces F_N = " + format_number(st.FN) + ", F_x = " + format_number(st.Fx) +
           " that are not representable";
  return "";
}

/// contact_problem of the stationary contact at w: of the case itself at
/// fixed depth (no copy), under load of the case at its stationary depth.
std::string stationary_contact_problem(const Case& c, double w) {
  if (!c.loading.by_force()) return contact_problem(c, w);
  const double d = c.indenter.parabolic() ? stationary_depth(c, w) : profile_stationary_depth(c, w);
  return contact_problem(at_depth(c, d), w);
}

/// The option a velocity of the history stands for: a segment's W is the
/// history's; v0 is blamed on tau (v0 tau / a is the same for any v0 and tau).
InvalidInput velocity_problem(const History& h, std::size_t k, const std::string& what) {
  if (k == 0) return InvalidInput("tau", "with v = " + format_number(h.v0) + " " + what);
  return InvalidInput("history", "segment " + std::to_string(k) +
                                     ": W = " + format_number(h.segments[k - 1].w) + " " + what);
}

// The velocities of the history (k = 0: v0, k >= 1: segment k): w tau / a
// representable for each, and the stationary contact at the fastest one
// (the largest forces, under load the smallest contact) too.
void check_velocities(const Case& c, double a) {
  const History& h = c.history;
  std::size_t fastest = 0;
  for (std::size_t k = 0; k <= h.size(); ++k) {
    const double w = k == 0 ? h.v0 : h.segments[k - 1].w;
    if (!std::isfinite(w * c.rheology.tau / a))
      throw velocity_problem(
          h, k, "makes w tau / a (a = " + format_number(a) + ") overflow; rescale the units");
    if (w > (fastest == 0 ? h.v0 : h.segments[fastest - 1].w)) fastest = k;
  }
  const double w = fastest == 0 ? h.v0 : h.segments[fastest - 1].w;
  if (const std::string p = stationary_contact_problem(c, w); !p.empty())
    throw velocity_problem(h, fastest, "gives " + p + "; rescale the units");
}

/// "with R gives a contact radius sqrt(R d) = " and the like: the words
/// before the contact radius of the case's loading and profile.
std::string contact_radius_words(const Case& c) {
  const bool load = c.loading.by_force();
  return c.indenter.visit([load](const auto& s) -> std::string {
    return load ? s.load_radius_words : s.depth_radius_words;
  });
}

// Derived scales must be representable: the contact radius a (a1 = sqrt(R d),
// or a0 under load) within [1e-75, 1e75], the force scale 16 G d^2 (d0 =
// a0^2 / R under load), w tau / a for every velocity of the history, and the
// stationary contact at rest and at the fastest velocity (radius, products,
// forces; see contact_problem).
void check_scales(const Case& c) {
  const bool load = c.loading.by_force();
  const char* opt = load ? "F0" : "d";
  const double a = c.edge_scale();
  const std::string radius = contact_radius_words(c);
  if (!(a > 0.0) || !std::isfinite(a))
    throw InvalidInput(opt,
                       radius + format_number(a) + " that is not representable; rescale the units");
  if (const double most = c.indenter.max_radius(); !(a < most))
    throw InvalidInput(opt, radius + format_number(a) + ", not below the profile's largest " +
                                format_number(most) + " (the sphere's radius); lower it");
  const double d = load ? c.indenter.g(a) : c.loading.d;
  const double force_scale = d * d * c.rheology.G * 16.0;
  if (!std::isfinite(force_scale))
    throw InvalidInput(opt, "with G gives a force scale 16 G d^2 = " + format_number(force_scale) +
                                " that is not representable; rescale the units");
  // forces far below it (mu F_N at small d/R) must not underflow to zero
  if (force_scale < 1e-280)
    throw InvalidInput(opt, "with G gives a force scale 16 G d^2 = " + format_number(force_scale) +
                                " that underflows (below 1e-280); rescale the units");
  if (!(a >= kMinRadius) || !(a <= kMaxRadius))
    throw InvalidInput(opt, radius + format_number(a) +
                                " outside [1e-75, 1e75], where its powers overflow or underflow; "
                                "rescale the units");
  if (const std::string p = stationary_contact_problem(c, 0.0); !p.empty())
    throw InvalidInput(opt, "gives at rest " + p + "; rescale the units");
  check_velocities(c, a);
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

/// The Kelvin case whose scales bound those of `c`: the glassy modulus G0
/// and the longest (shifted) time, so that its stationary forces are at least
/// the spectrum's. `c` itself (no copy) where it is Kelvin and unshifted.
const Case& kelvin_bound(const Case& c, Case& storage) {
  if (c.rheology.kelvin() && c.rheology.aT == 1.0) return c;
  storage = c;
  storage.rheology = Rheology{c.rheology.G0(), c.rheology.longest_time(), {}, 1.0};
  return storage;
}

} // namespace

void validate(const Case& c) {
  check_groups(c);
  check_parameters(c);
  check_profile_limits(c.indenter);
  validate(c.rheology);
  check_history(c.history);
  check_explicit_sampling(c.sampling, c.history);
  if (uses_element_row(c)) check_element_row(c);
  Case storage;
  check_scales(kelvin_bound(c, storage));
}

CheckedCase CheckedCase::with_durations(const std::vector<Segment>& segments) && {
  std::vector<Segment>& own = c_.history.segments;
  if (segments.size() != own.size())
    throw std::logic_error("CheckedCase::with_durations: " + std::to_string(segments.size()) +
                           " segments for a history of " + std::to_string(own.size()));
  for (std::size_t k = 0; k < own.size(); ++k) {
    if (segments[k].w != own[k].w)
      throw std::logic_error("CheckedCase::with_durations: the velocities differ");
    own[k].T = segments[k].T;
  }
  check_history(c_.history);
  check_explicit_sampling(c_.sampling, c_.history);
  return CheckedCase(std::move(c_), Trusted{});
}

CheckedCase CheckedCase::shifted() const {
  Case c = c_;
  c.rheology = c_.rheology.shifted();
  return CheckedCase(std::move(c), Trusted{});
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
    throw InvalidInput("profile", std::string(solver) +
                                      " solves the parabola only; this case's profile is " +
                                      profile_name(c.indenter.profile) +
                                      " (row and baseline take every profile)");
}

double zeta(const Case& c, double w) {
  return w * c.rheology.tau / c.a1();
}

} // namespace mdrmap
