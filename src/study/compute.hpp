#pragma once
// One case of a study, computed into its map row (schema mdrmap-map/2): the
// solver's stationary start, the event metrics of every velocity change, the
// closed-form stationary states (and at fixed depth the seed's corrected jump
// estimate), and the residuals between the two. No MPI calls, no printing,
// no file access: the runner hands out the cases and writes the rows.
#include "core/solver.hpp"
#include "io/case_row.hpp"
#include "study/config.hpp"

namespace mdrmap::study {

/// The layout of the rows of a study's map.
io::RowLayout row_layout(const StudyConfig& cfg);

/// One case, as a map row: the row becomes its Case (case_for) and runs with
/// run.rtol. Never throws for a failing case: the row is marked failed with
/// the message (a non-finite value fails the case too).
io::CaseRow compute_case(const StudyConfig& cfg, const io::RowLayout& layout, const Row& r,
                         SolverKind kind, bool timeseries);

} // namespace mdrmap::study
