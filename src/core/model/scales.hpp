#pragma once
// The scales of a case, built from its model parts: what the error metric,
// the event metrics, the map and the Python tools measure lengths, times,
// forces and friction by (docs/design.md, "Scales"). One place computes the
// Hertz-type scales; nothing else does.
#include "core/model/case.hpp"

namespace mdrmap {

struct Scales {
  /// Reference length: the leading edge a1 (g(a1) = d) at fixed depth, the
  /// Hertz radius a0 of the prescribed load under load control (with the
  /// long-term modulus G: F0 = 4 G int (g(a0) - g), 16/3 G a0^3 / R for the
  /// parabola).
  double length = 0.0;
  /// The indentation depth that goes with it: d, or d0 = g(a0) under load.
  double depth = 0.0;
  /// The elastic normal force of that contact with the long-term modulus:
  /// 4 G int (g(a) - g) over [-a, a], 16/3 G a^3 / R for the parabola (F0
  /// itself under load).
  double force = 0.0;
  /// Friction scale: the profile's slope at the reference length over two
  /// (a / R for the parabola, (pi/4) tan(beta) for the cone).
  double friction = 0.0;
  /// Time scale: the element's longest relaxation time, shifted
  /// (Rheology::longest_time(): tau for the Kelvin foundation); 0 when
  /// nothing relaxes.
  double time = 0.0;
};

Scales scales(const Case& c);

} // namespace mdrmap
