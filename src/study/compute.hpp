#pragma once
// One case of a study, computed into its map row: the solver's states before
// the step, just after it and at the end of the window, the corrected
// analytic estimates and limits, and the residuals between the two. No MPI
// calls, no printing, no file access: the runner hands out the cases and
// writes the rows. (The row type is io::CaseRow, the map file's row.)
#include "core/solver.hpp"
#include "io/case_row.hpp"
#include "study/config.hpp"

namespace mdrmap::study {

/// One case, as a map row (results, analytic estimates, residuals): the row
/// becomes its Case (case_for) and runs with run.rtol. Never throws for a
/// failing solver: the row is marked failed with the message.
io::CaseRow compute_case(const StudyConfig& cfg, const StepRow& r, SolverKind kind,
                         bool timeseries);

} // namespace mdrmap::study
