#include "core/case.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/params.hpp"

namespace mdrmap {

std::string format_number(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

double Indenter::contact_radius(double d) const {
  return std::sqrt(R) * std::sqrt(d);
}

double History::start(std::size_t k) const {
  double t = 0.0;
  for (std::size_t i = 0; i < k && i < segments.size(); ++i)
    t += segments[i].T;
  return t;
}

double Sampling::offset(long j, double T) const {
  if (j <= 0) return 0.0;
  if (j >= samples - 1) return T;
  if (spacing == Spacing::Linear)
    return T * static_cast<double>(j) / static_cast<double>(samples - 1);
  // samples >= 3 here; j = 1 .. samples - 2 lie strictly inside (0, T)
  const double frac = static_cast<double>(samples - 1 - j) / static_cast<double>(samples - 2);
  return T * std::pow(10.0, -decades * frac);
}

double Case::a0() const {
  return std::cbrt(3.0 * loading.F0 * indenter.R / (16.0 * material.G));
}

std::size_t Case::total_samples() const {
  return history.size() * static_cast<std::size_t>(sampling.samples);
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
}

// Derived scales must be representable: the contact radius a (a1 = sqrt(R d),
// or a0 under load), the force scale 16 G d^2 (d0 = a0^2 / R under load) and
// w tau / a for every velocity of the history.
void check_scales(const Case& c) {
  const bool load = c.loading.by_force();
  const char* opt = load ? "FN" : "d";
  const double a = c.edge_scale();
  if (!(a > 0.0) || !std::isfinite(a))
    throw InvalidInput(opt, std::string(load ? "with R and G gives a Hertz radius a0 = "
                                             : "with R gives a contact radius sqrt(R d) = ") +
                                format_number(a) + " that is not representable; rescale the units");
  const double d = load ? a * a / c.indenter.R : c.loading.d;
  const double force_scale = d * d * c.material.G * 16.0;
  if (!std::isfinite(force_scale))
    throw InvalidInput(opt, "with G gives a force scale 16 G d^2 = " + format_number(force_scale) +
                                " that is not representable; rescale the units");
  // forces far below it (mu F_N at small d/R) must not underflow to zero
  if (force_scale < 1e-280)
    throw InvalidInput(opt, "with G gives a force scale 16 G d^2 = " + format_number(force_scale) +
                                " that underflows (below 1e-280); rescale the units");
  double wmax = c.history.v0;
  for (const auto& s : c.history.segments)
    wmax = std::max(wmax, s.w);
  if (!std::isfinite(wmax * c.material.tau / a))
    throw InvalidInput("tau", "makes v tau / sqrt(R d) overflow; rescale the units");
}

/// Exactly one parameter of each group (e.g. d or FN) is given (non-zero).
void check_groups(const Case& c) {
  for (const auto& p : case_parameters()) {
    if (!p.one_of) continue;
    std::string names;
    int given = 0;
    for (const auto& q : case_parameters()) {
      if (!q.one_of || std::string(q.one_of) != p.one_of) continue;
      names += names.empty() ? "" : " or ";
      names += std::string("--") + q.name;
      given += q.get(c) != 0.0 ? 1 : 0;
    }
    if (given != 1)
      throw InvalidInput(p.name, "give exactly one of " + names + " (the " + p.one_of + "), got " +
                                     std::to_string(given));
  }
}

} // namespace

void validate(const Case& c) {
  check_groups(c);
  for (const auto& p : case_parameters())
    if (!p.one_of || p.get(c) != 0.0) p.check(p.get(c)); // a group's other members are 0
  check_history(c.history);
  check_scales(c);
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
  c.indenter.R = R;
  c.material.tau = tau;
  c.material.G = G;
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
                                     "normal force (--FN)");
}

double zeta(const Case& c, double w) {
  return w * c.material.tau / c.a1();
}

} // namespace mdrmap
