#pragma once
// One case's row of the friction map, as computed (study/compute.hpp) and as
// written (io/map_file.hpp): MPI- and HDF5-free.
#include <cstdint>
#include <string>
#include <vector>

namespace mdrmap::io {

/// Per-case float64 fields, as "group/name", in the order of CaseRow::values.
const std::vector<std::string>& row_fields();
/// Index of a field in row_fields(); throws std::out_of_range.
std::size_t field_index(const std::string& name);

struct CaseRow {
  std::vector<double> values; ///< row_fields().size() values
  std::int8_t status = 0;
  std::string message;
  std::vector<double> t, FN, Fx, mu, a2; ///< time series (when the map stores them)
};

} // namespace mdrmap::io
