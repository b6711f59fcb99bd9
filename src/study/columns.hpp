#pragma once
// Private to the study config: the columns a study may have (the core's
// parameter table and the history's segments), their order and ranges, and
// the checks that a set of columns makes whole cases.
#include <string>
#include <vector>

#include "core/model/params.hpp"
#include "study/config.hpp"

namespace mdrmap::study::detail {

/// The table's case parameters a study sets (not the sampling): d, FN, R,
/// tau, G, v, in the table's order.
const std::vector<const ParamSpec*>& study_parameters();

/// The range a column's values must be in: the table's entry, the segment
/// velocity's or duration's, or (relative columns) a ratio's.
const ParamSpec& column_spec(const Column& col);

/// Position of a column in column order: the case parameters in the table's
/// order (a one-of group, the loading d or FN, in one place): the loading 0,
/// R 1, tau 2, G 3, v 4; then P + 2 (k - 1) for wk and P + 1 + 2 (k - 1) for
/// Tk, P the number of parameter places.
std::size_t column_rank(const Column& col);

/// The names a history column of segment k may have.
std::vector<std::string> history_names(std::size_t k);

/// Sorts the columns into column order and checks that they make cases:
/// exactly one loading, R, tau and v (an optional parameter, G, added with
/// its table default when missing), and for
/// every segment 1..K exactly one velocity and one duration. `where` locates
/// a message. Throws ConfigError naming the column.
void order_columns(std::vector<Axis>& axes, const std::string& where);

/// The shape text "FN 3 x R 1 x ..." of a grid.
std::string grid_shape(const StudyConfig& c);

} // namespace mdrmap::study::detail
