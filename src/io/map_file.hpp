#pragma once
// The friction-map file: one HDF5 file per study, written in parallel
// through MPI-IO.
//
// Layout (schema "mdrmap-map/1"; N cases, S samples):
//   /cases/{d,R,tau,v,v1,G}                 float64 [N]   case order of the config
//   /results/{FN,Fx,mu,a2}_{pre,jump,post}  float64 [N]   before the step, t = 0+, t_end
//   /results/{error_estimate,wall_seconds}  float64 [N]
//   /results/status                         int8    [N]   0 pending, 1 done, -1 failed
//   /results/message                        string  [N]   why a case failed ("" otherwise)
//   /analytic/{FN,Fx,mu,a2}_{pre,jump,post} float64 [N]   the corrected estimates
//   /analytic/{FN_inf,Fx_inf,mu_inf,mu_post_drop}         limits (eqs. 12-14; 3/4 sqrt(d/R))
//   /residuals/<same names>                 float64 [N]   (sim - analytic) / |analytic|
//   /timeseries/{t,FN,Fx,mu,a2}             float64 [N,S] when asked
//   /grid/<axis>                            float64 [n_i] grid studies; attrs axes, shape, log
//   /provenance/{config_text,config_canonical}  uint8 text
//   root attributes: mdrmap_schema, program_version, git_commit, created_utc,
//   command_line, mpi_size, units, config_text (when short), n_cases, samples
//
// Crash safety: every dataset is created and allocated (early, contiguous,
// zero-filled) and the metadata flushed before any case runs; afterwards only
// raw data is written, at fixed offsets, values first and status last. A
// process killed at any moment leaves a file that opens, with every case
// marked done intact.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "io/h5.hpp"

namespace mdrmap::io {

inline constexpr const char* kSchema = "mdrmap-map/1";
inline constexpr std::size_t kMessageLen = 160;

/// Per-case float64 fields, as "group/name", in the order of CaseRow::values.
const std::vector<std::string>& row_fields();
/// Index of a field in row_fields(); throws std::out_of_range.
std::size_t field_index(const std::string& name);

struct Provenance {
  std::string program_version, git_commit, created_utc, command_line, units;
  std::string config_text, config_canonical;
  int mpi_size = 1;
};

struct GridInfo {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  std::vector<int> logarithmic;
};

struct MapSpec {
  std::size_t n_cases = 0;
  long samples = 0;
  bool timeseries = false;
  GridInfo grid; ///< empty for a case list
};

struct CaseRow {
  std::vector<double> values; ///< row_fields().size() values
  std::int8_t status = 0;
  std::string message;
  std::vector<double> t, FN, Fx, mu, a2; ///< time series (when the map stores them)
};

class MapFile {
public:
  /// Collective. Creates `path` (which must not exist) with every dataset;
  /// rank 0 writes /cases and /grid. Metadata is flushed before returning.
  static MapFile create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                        const Provenance& prov, const std::vector<Scene>& cases);
  /// Collective. Opens an existing map for writing (resume).
  static MapFile open(MPI_Comm comm, const std::string& path);
  /// Serial, read-only: is `path` an HDF5 file with an mdrmap map schema?
  /// On false, `why` says what it is instead.
  static bool is_map(const std::string& path, std::string* why);

  MapFile(MapFile&&) = default;
  MapFile& operator=(MapFile&&) = default;
  ~MapFile();

  std::size_t n_cases() const { return n_; }
  long samples() const { return samples_; }
  bool timeseries() const { return timeseries_; }
  std::string config_canonical() const;
  std::vector<std::int8_t> read_status() const;

  /// Independent I/O: writes rows for cases first .. first + rows.size() - 1,
  /// every value first and the status last.
  void write_rows(std::size_t first, const std::vector<CaseRow>& rows);
  /// Collective: flush and close, reporting errors.
  void close();

private:
  MapFile() = default;
  void open_datasets();
  MPI_Comm comm_ = MPI_COMM_NULL;
  Handle file_, dxpl_;
  std::vector<Handle> fields_;
  Handle status_, message_, msg_type_;
  std::vector<Handle> series_;
  std::size_t n_ = 0;
  long samples_ = 0;
  bool timeseries_ = false;
  std::string path_;
};

} // namespace mdrmap::io
