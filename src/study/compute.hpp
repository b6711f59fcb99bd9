#pragma once
// One case of a study, computed into its map row (schema mdrmap-map/2): the
// solver's stationary start, the event metrics of every velocity change, the
// closed-form stationary states (and at fixed depth the seed's corrected jump
// estimate), and the residuals between the two. No MPI calls, no printing,
// no file access: the runner hands out the cases and writes the rows.
#include <csignal>

#include "core/solvers/dispatch.hpp"
#include "io/case_row.hpp"
#include "study/config.hpp"

namespace mdrmap::study {

/// The layout of the rows of a study's map.
io::RowLayout row_layout(const StudyConfig& cfg);

/// One case, as a map row: the row becomes its Case (case_for) and runs with
/// run.rtol within the default work budget. Never throws for a failing case:
/// the row is marked failed with the message (a non-finite value, a case past
/// its budget or one that cannot meet rtol fail it too). `stop` (the study's
/// stop flag, may be null) is polled while the case runs: once it is set the
/// case throws Interrupted (it has no row; the caller leaves it pending).
io::CaseRow compute_case(const StudyConfig& cfg, const io::RowLayout& layout, const Row& r,
                         SolverKind kind, bool timeseries,
                         const volatile std::sig_atomic_t* stop = nullptr);

} // namespace mdrmap::study
