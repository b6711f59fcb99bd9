#pragma once
// The output table: every quantity mdrmap outputs, declared once with its one
// name (as the CSV of `mdrmap simulate`, the map of `mdrmap study`, the Python
// module and the docs all spell it), its dimension, its meaning, its group and
// how it is read from a result. The twin of the parameter table
// (core/model/params.hpp). The CSV's header, `# pre`, `# event` and first
// comment lines (app/csv_output.cpp), the map's rows and /schema
// (io/case_row.cpp), the Python result's dicts (src/python/module.cpp) and
// the reference page docs/reference/map-schema.md are generated from it: a
// new output quantity is one entry here plus its computation.
#include <cstddef>
#include <string>
#include <vector>

#include "core/metrics/events.hpp"
#include "core/model/params.hpp"
#include "core/model/scales.hpp"
#include "core/model/state.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// What an output quantity is a value of.
enum class OutputGroup {
  Series,     ///< a column of the time series: one value per output instant
  Event,      ///< an event metric: one value per segment (the change at its start)
  EventState, ///< a state per segment: every state quantity q as q_<name> (the CSV: mu only)
  Result,     ///< a per-case result of the run
  Scale,      ///< a scale of the case (core/model/scales.hpp), which the tools measure by
              ///< (the last: output_group_name() counts on it)
};

/// Where a quantity appears besides the docs; the Python module's result
/// holds what the CSV holds (series arrays, `pre`, `events`, `info` dicts).
enum OutputWhere : unsigned {
  kInCsv = 1U, ///< the CSV of `mdrmap simulate` and the Python result
  kInMap = 2U, ///< the map of `mdrmap study` (/timeseries, /events, /results)
};

struct OutputSpec {
  const char* name;    ///< its one spelling, e.g. "D_c" (for EventState: the instant, "after")
  Dim dim;             ///< dimension, as dim_name() names it (the map's `units`)
  OutputGroup group;   ///< what it is a value of
  unsigned where;      ///< OutputWhere bits
  const char* meaning; ///< one line, lower case, no final period (for EventState: of the instant)
  bool may_be_undefined = false;      ///< NaN where undefined (the map: its fill value)
  const char* old_map_name = nullptr; ///< its name in maps of mdrmap-map/2 before this table
  /// How it is read (the one that fits the group; the others nullptr):
  /// Series: its samples (nullptr for segment, the one int column: Series::segment)
  std::vector<double> Series::*column = nullptr;
  double State::*state = nullptr;        ///< Series: the member of a State (nullptr: t, segment)
  bool load_only = false;                ///< Series: moves under load control only
  double EventMetrics::*event = nullptr; ///< Event: its member of EventMetrics
  State EventMetrics::*event_state = nullptr; ///< EventState: its member of EventMetrics
  double (*result)(const RunInfo&, double wall_seconds) = nullptr; ///< Result
  double Scales::*scale = nullptr;                                 ///< Scale
};

/// Every output quantity, group after group, each group in its CSV order.
const std::vector<OutputSpec>& output_table();

/// The entry named `name` in `group`; throws std::logic_error (a name the
/// code spells that the table lacks is a bug).
const OutputSpec& output(OutputGroup group, const char* name);

/// The state quantities of the time series (FN, Fx, mu, a2, then d, a1 under
/// load): the Series entries with a State member, in table order.
std::vector<const OutputSpec*> state_outputs(bool load);

/// Sample k of a Series entry's column (segment: as a double).
double sample(const OutputSpec& column, const Series& s, std::size_t k);

/// "series", "event", "event_state", "result" or "scale": the group as the docs and
/// the Python module's output_table() name it.
const char* output_group_name(OutputGroup g);

/// The name of state quantity `q` at an EventState instant: "mu_after".
std::string event_state_name(const OutputSpec& q, const OutputSpec& instant);

} // namespace mdrmap
