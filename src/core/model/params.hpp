#pragma once
// The parameter table: every scalar parameter of a case, declared once with
// its name (as the command line and config files spell it), dimension,
// allowed range and meaning. Validation, `simulate`'s options and its help
// text are generated from it; a new parameter is one entry here plus the
// physics that uses it.
#include <cmath>
#include <string>
#include <vector>

#include "core/model/case.hpp"

namespace mdrmap {

/// "length", "time", "length/time", "force/length^2", "count", "number",
/// "wall-clock time".
const char* dim_name(Dim d);

/// Which part of a case a parameter belongs to.
enum class Part { Indenter, Material, Loading, History, Sampling };

struct ParamSpec {
  const char* name;    ///< option / key name, e.g. "tau"
  const char* symbol;  ///< value placeholder in help text, e.g. "TAU"
  Part part;           ///< the part of the case it sets
  Dim dim;             ///< physical dimension
  double lo;           ///< lower bound
  bool lo_inclusive;   ///< the range is >= lo (true) or > lo (false)
  double hi;           ///< upper bound (infinity: none), inclusive unless hi_inclusive is false
  bool required;       ///< the case cannot be built without it
  const char* one_of;  ///< nullptr, or a group (e.g. "loading") of which exactly one is given
  double fallback;     ///< default when not required
  const char* meaning; ///< one line, lower case, no final period
  double (*get)(const Case&);
  void (*set)(Case&, double);
  /// nullptr, or the indenter profile (profile_name) the parameter belongs
  /// to: it applies to (and `required` means required for) that profile only,
  /// and is 0 (not given) for the others.
  const char* profile = nullptr;
  bool hi_inclusive = true; ///< the range is <= hi (true) or < hi (false)

  bool integer() const { return dim == Dim::Count; }
  /// "a finite number > 0" / "an integer from 2 to 100000000" ...
  std::string allowed() const;
  /// Whether x is in the range (an integer where the dimension is a count).
  bool contains(double x) const {
    const bool above = lo_inclusive ? x >= lo : x > lo;
    const bool below = hi_inclusive ? x <= hi : x < hi;
    return std::isfinite(x) && above && below && (!integer() || x == std::floor(x));
  }
  /// Whether the parameter applies to a case with this indenter profile.
  bool applies_to(Profile p) const;
  /// Throws InvalidInput(name, "must be <allowed>, got <x>"). (Inline: every
  /// case of a study passes here many times.)
  void check(double x) const {
    if (!contains(x)) refuse(x);
  }
  /// Throws InvalidInput(name, "must be <allowed>, got <x>").
  [[noreturn]] void refuse(double x) const;
};

/// The scalar parameters of a case: the loading, the first shape's (the
/// parabola's R) and the material, the history's v0, the other shapes'
/// parameters (beta, n, A: each shape declares its own, core/model/shapes/),
/// then the sampling. (The help texts group them by `part`, in this order
/// within a part.)
const std::vector<ParamSpec>& case_parameters();

/// The parameters of one history segment ("w" velocity, "T" duration): the
/// tokens of a history "W1:T1,W2:T2,..." are checked against them.
const ParamSpec& segment_velocity_spec();
const ParamSpec& segment_duration_spec();

/// The parameters of one Maxwell branch k of the rheology ("G" modulus,
/// "tau" time; spelled Gk, tauk as keys, G1:TAU1,... in --prony).
const ParamSpec& branch_modulus_spec();
const ParamSpec& branch_time_spec();

/// An old spelling a parameter of the table is still read under, wherever a
/// user names a case parameter (options, config keys, case-list columns,
/// Python keywords); outputs use the table's name only.
struct ParamAlias {
  const char* alias; ///< the old spelling, e.g. "FN"
  const char* name;  ///< the table's name, e.g. "F0" (the prescribed load)
};

/// Every alias of the table: FN for F0.
const std::vector<ParamAlias>& parameter_aliases();

/// The table's name of `name`: the name an alias stands for ("FN" -> "F0"),
/// any other name as it is.
std::string canonical_parameter_name(const std::string& name);

/// The alias of the table's parameter `name`, or nullptr.
const ParamAlias* alias_of(const std::string& name);

/// The refusal of both spellings: "<prefix>F0 and <prefix>FN are the same
/// parameter (FN is the old spelling of F0); give only one".
std::string two_spellings(const ParamAlias& a, const std::string& prefix);

/// The entry named `name` (or an alias of it), or nullptr.
const ParamSpec* find_parameter(const std::string& name);

} // namespace mdrmap
