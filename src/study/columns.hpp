#pragma once
// Private to the study config: the columns a study may have (the core's
// parameter table and the history's segments), their order and ranges, and
// the checks that a set of columns makes whole cases.
#include <string>
#include <vector>

#include "core/model/params.hpp"
#include "study/config.hpp"

namespace mdrmap::study::detail {

/// The table's case parameters a study sets (not the sampling): d, F0, R,
/// tau, G, aT, v, in the table's order.
const std::vector<const ParamSpec*>& study_parameters();

/// Whether an optional parameter is a column only where the study gives it
/// (aT, which a temperature column may set instead), rather than always with
/// its table default (G, a column of every study since the first schema).
/// The spectrum's Gk, tauk and the temperature are always only where given.
bool only_where_given(const ParamSpec& p);

/// The canonical name of a column (a table parameter's, G3, tau3,
/// temperature, wK, wK_over_v, TK, TK_over_tau): its /cases dataset.
std::string column_name(const Column& col);

/// The name a column has in the map (/cases, /grid) and in the canonical
/// text a resume compares: a table parameter's own name (F0 where the key
/// is its old spelling FN), any other column's as written (the seed's v1).
std::string stored_name(const Axis& a);

/// The meaning of a column (its range entry's), "segment k: " or "term k: "
/// before it for a history segment's or a spectrum term's.
std::string column_meaning(const Column& col);

/// The range a column's values must be in: the table's entry, the segment
/// velocity's or duration's, or (relative columns) a ratio's.
const ParamSpec& column_spec(const Column& col);

/// Position of a column in column order: the case parameters in the table's
/// order (a one-of group, the loading d or F0, in one place; temperature in
/// aT's place): the loading 0, R 1, tau 2, G 3, then the spectrum's terms G1
/// 4, tau1 5, ..., G32 66, tau32 67, then aT (or temperature) 68, v 69; then
/// P + 2 (k - 1) for wk and P + 1 + 2 (k - 1) for Tk, P = 70 the number of
/// parameter places.
std::size_t column_rank(const Column& col);

/// The names a history column of segment k may have.
std::vector<std::string> history_names(std::size_t k);

/// Sorts the columns into column order and checks that they make cases:
/// exactly one loading, the profile's required parameters (R for the
/// parabola, beta for the cone, n and A for the power law), tau and v (an
/// optional parameter, G, added with its table default when missing; aT and
/// the other profiles' parameters only where given), the spectrum's
/// terms 1..N each with its modulus and its time, and for
/// every segment 1..K exactly one velocity and one duration. `where` locates
/// a message. Throws ConfigError naming the column.
void order_columns(std::vector<Axis>& axes, const std::string& where,
                   Profile profile = Profile::of<Parabola>());

/// The shape text "F0 3 x R 1 x ..." of a grid.
std::string grid_shape(const StudyConfig& c);

} // namespace mdrmap::study::detail
