#pragma once
// What a shape declares of each of its parameters (R of the parabola, beta
// of the cone, n and A of the power law): the entry of the parameter table
// (core/model/params.hpp) without its accessors, which the table forms from
// `member` (a parameter of a shape not chosen is 0: not given).
namespace mdrmap {

/// Physical dimension, in the user's consistent units.
/// WallClock: wall-clock time in seconds (an output's, never a case parameter's).
enum class Dim { Length, Time, Velocity, Stress, Force, Count, Number, WallClock };

template <class Shape> struct ShapeParam {
  const char* name;    ///< option / key name, e.g. "beta"
  const char* symbol;  ///< value placeholder in help text, e.g. "DEG"
  Dim dim;             ///< physical dimension
  double lo;           ///< lower bound
  bool lo_inclusive;   ///< the range is >= lo (true) or > lo (false)
  double hi;           ///< upper bound (infinity: none)
  bool hi_inclusive;   ///< the range is <= hi (true) or < hi (false)
  const char* meaning; ///< one line, lower case, no final period
  double Shape::*member;
};

} // namespace mdrmap
