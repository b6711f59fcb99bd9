#pragma once
// One run of `mdrmap simulate`: the solver on a checked case, the event
// metrics of its velocity changes and, for a solver other than the default,
// its error against a reference; and the named records of the result (the
// names of the CSV's `# event` and `# pre` lines). Shared by the command
// line (csv_output.hpp prints it) and the Python module (src/python hands it
// over as numpy arrays and dicts), so both give the same numbers bit for bit.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "case/case_input.hpp"
#include "core/metrics/events.hpp"
#include "core/model/case.hpp"
#include "core/model/state.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/dispatch.hpp"

namespace mdrmap::cases {

/// Everything the comment lines report besides the series itself.
struct SimulateRecord {
  std::string version;                  ///< program version (kVersion)
  std::string commit;                   ///< git commit (kGitCommit)
  std::string solver;                   ///< name of the solver that ran
  double rtol = 0.0;                    ///< requested tolerance
  RunInfo info;                         ///< cost and error estimate of the run
  double wall_seconds = 0.0;            ///< wall time of the run
  Case c;                               ///< the case as run (durations resolved)
  std::optional<double> error_vs_exact; ///< case error against the reference below
  std::string reference = "exact";      ///< solver of the reference run
  double reference_rtol = 0.0;          ///< its rtol
  std::vector<EventMetrics> events;     ///< one per segment
};

struct Simulation {
  SimulateRecord record;
  Series series;
};

/// Runs the case as `mdrmap simulate` does. Throws what run_case throws
/// (InvalidInput for a solver that does not handle the loading, CaseAbandoned,
/// Interrupted) and std::bad_alloc.
Simulation simulate(const CaseInput& in, const RunControl& control = RunControl{});

/// A named number of a record (named by the output table,
/// core/outputs/output_table.hpp).
using Field = std::pair<std::string, double>;

/// The numbers of the `# event` line after k, in the table's order: its
/// Event entries shown in the CSV and mu at its EventState instants
/// (mu_after, mu_end, mu_ss_before, mu_ss_after); where D_c is undefined
/// the line adds D_c_undefined=REASON (EventMetrics::d_c_undefined).
std::vector<Field> event_fields(const EventMetrics& e);

/// The key of the reason D_c is undefined: "D_c_undefined" (the table's
/// name of D_c and "_undefined").
std::string d_c_undefined_key();

/// The fields of the `# pre` line: FN, Fx, mu, a2; under load also d, a1.
std::vector<Field> state_fields(const State& s, bool load);

/// The per-case results of the first comment line (error_estimate, ...,
/// wall_seconds), in the table's order; the counts as exact doubles.
std::vector<Field> result_fields(const RunInfo& info, double wall_seconds);

} // namespace mdrmap::cases
