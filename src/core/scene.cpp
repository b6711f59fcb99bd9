#include "core/scene.hpp"

#include <cmath>
#include <sstream>

namespace mdrmap {
std::string format_number(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

namespace {

std::string show(double x) {
  return format_number(x);
}

void require_positive(const char* name, double x) {
  if (!std::isfinite(x) || !(x > 0.0))
    throw InvalidInput(name, "must be a finite number > 0, got " + show(x));
}

void require_non_negative(const char* name, double x) {
  if (!std::isfinite(x) || !(x >= 0.0))
    throw InvalidInput(name, "must be a finite number >= 0, got " + show(x));
}

} // namespace

void validate(const Scene& s) {
  require_positive("d", s.d);
  require_positive("R", s.R);
  require_non_negative("tau", s.tau);
  require_positive("v", s.v);
  require_non_negative("v1", s.v1);
  require_positive("G", s.G);
  // Derived scales must be representable: a1 = sqrt(R d), the force scale
  // 16 G d^2 and v tau / a1.
  const double a1 = std::sqrt(s.R) * std::sqrt(s.d);
  if (!(a1 > 0.0) || !std::isfinite(a1))
    throw InvalidInput("d", "with R gives a contact radius sqrt(R d) = " + show(a1) +
                                " that is not representable; rescale the units");
  const double force_scale = s.d * s.d * s.G * 16.0;
  if (!std::isfinite(force_scale))
    throw InvalidInput("d", "with G gives a force scale 16 G d^2 = " + show(force_scale) +
                                " that is not representable; rescale the units");
  // forces far below it (mu F_N at small d/R) must not underflow to zero
  if (force_scale < 1e-280)
    throw InvalidInput("d", "with G gives a force scale 16 G d^2 = " + show(force_scale) +
                                " that underflows (below 1e-280); rescale the units");
  if (!std::isfinite(s.v * s.tau / a1) || !std::isfinite(s.v1 * s.tau / a1))
    throw InvalidInput("tau", "makes v tau / sqrt(R d) overflow; rescale the units");
}

void validate(const Protocol& p) {
  if (!std::isfinite(p.t_end) || !(p.t_end > 0.0))
    throw InvalidInput("t-end", "must be a finite number > 0, got " + show(p.t_end));
  if (p.samples < 2 || p.samples > kMaxSamples)
    throw InvalidInput("samples", "must be an integer from 2 to " + std::to_string(kMaxSamples) +
                                      ", got " + std::to_string(p.samples));
}

double contact_radius(const Scene& s) {
  return std::sqrt(s.R) * std::sqrt(s.d);
}
double zeta(const Scene& s) {
  return s.v * s.tau / contact_radius(s);
}
double zeta1(const Scene& s) {
  return s.v1 * s.tau / contact_radius(s);
}

double default_t_end(const Scene& s) {
  if (s.tau > 0.0) return 6.0 * s.tau;
  const double w = (s.v1 > 0.0) ? std::min(s.v, s.v1) : s.v;
  return 6.0 * contact_radius(s) / w;
}

} // namespace mdrmap
