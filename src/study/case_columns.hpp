#pragma once
// The case parameters a study's map stores in /cases: its columns that are
// not of the history, as written (the table's parameters, a spectrum's Gk,
// tauk, aT or the temperature), and the shift aT a temperature gave. Optional
// columns are there only where the study gives them, so the maps of studies
// without them are what they always were.
#include <vector>

#include "io/case_row.hpp"
#include "study/config.hpp"

namespace mdrmap::study {

/// The /cases datasets of the study's case parameters, in column order
/// (path "cases/<name>", unit, meaning): d or F0, R, tau, G, [G1, tau1, ...],
/// [aT | temperature, aT], v.
std::vector<io::FieldInfo> case_parameter_info(const StudyConfig& c);

/// Appends their values for the case of row `r` (`run` = case_for(c, r)):
/// the row's values of those columns, and run's aT after a temperature.
void append_case_parameters(const StudyConfig& c, const Row& r, const Case& run,
                            std::vector<double>& out);

} // namespace mdrmap::study
