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

/// What a per-case dataset of the map holds, for the map's /schema group and
/// the datasets' `units` and `long_name` attributes.
struct FieldInfo {
  std::string path;    ///< "group/name" in the map, e.g. "results/mu_jump"
  std::string unit;    ///< a dimension name as core/params.hpp's dim_name: "force", "number", ...
  std::string meaning; ///< one line, lower case, no final period
};

/// Unit and meaning of every row_fields() entry, in that order; generated
/// from the same table as the names.
const std::vector<FieldInfo>& row_field_info();
/// The per-case datasets besides row_fields(): results/status,
/// results/message and the time series timeseries/{t,FN,Fx,mu,a2}.
const std::vector<FieldInfo>& other_result_info();
/// The entry of `path` in row_field_info() or other_result_info(); throws
/// std::out_of_range.
const FieldInfo& result_info(const std::string& path);

struct CaseRow {
  std::vector<double> values; ///< row_fields().size() values
  std::int8_t status = 0;
  std::string message;
  std::vector<double> t, FN, Fx, mu, a2; ///< time series (when the map stores them)
};

} // namespace mdrmap::io
