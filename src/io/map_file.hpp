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
// Self-description (compatible additions to mdrmap-map/1; maps without them
// are still maps of this schema):
//   /schema/<group>/<name>                  group, attributes unit, meaning (strings)
//       for every dataset of /cases, /results, /analytic, /residuals,
//       /timeseries and /grid, in the order of creation; units are dimension
//       names ("length", "force", "number", ...): the case parameters' from
//       the core's parameter table (core/params.hpp), the results' from
//       io/case_row.hpp's table
//   the same on each of those datasets as CF attributes units, long_name
//   /case, /sample                          HDF5 dimension scales (netCDF-4
//       dimensions without a variable; extent 0, unlimited: no data), attached
//       to axis 0 of every per-case dataset and axis 1 of the time series, so
//       that xarray (engine h5netcdf) names the dimensions case and sample
//   /grid/<axis>                            also a dimension scale named <axis>:
//       xarray shows the axes as coordinates of group /grid
//
// Crash and fault safety: the file is created collectively with parallel
// HDF5, every dataset allocated (early, contiguous, zero-filled) and the file
// closed before any case runs: the whole map is on disk and valid from then
// on. The run writes raw rows only, by plain positional writes at the offsets
// of the datasets (RowWriter; no HDF5 state, nothing collective), values
// first and status last. So a process killed at any moment, or a rank whose
// write fails, leaves a file that opens, with every case marked done intact;
// and a failing device cannot hang the job in a collective close.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/case_row.hpp"
#include "io/h5.hpp"
#include "study/config.hpp"

namespace mdrmap::io {

inline constexpr const char* kSchema = "mdrmap-map/1";
inline constexpr std::size_t kMessageLen = 160;

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

/// Bytes the map file of `spec` takes on disk (all datasets are allocated and
/// zero-filled at creation), with `text_bytes` of provenance text; an upper
/// bound within 128 KiB. The file is written in full before any case runs, so
/// a map that fits at creation cannot run out of space later.
std::uint64_t map_file_bytes(const MapSpec& spec, std::size_t text_bytes);

/// Where the per-case datasets of a map lie in its file (byte offsets).
struct MapLayout {
  std::uint64_t n_cases = 0;
  long samples = 0;
  bool timeseries = false;
  std::vector<std::uint64_t> fields; ///< row_fields() order, float64 [N]
  std::uint64_t status = 0;          ///< int8 [N]
  std::uint64_t message = 0;         ///< kMessageLen-byte strings [N]
  std::vector<std::uint64_t> series; ///< t, FN, Fx, mu, a2: float64 [N, S] (timeseries only)

  /// Flat form, to broadcast.
  std::vector<std::uint64_t> pack() const;
  static MapLayout unpack(const std::vector<std::uint64_t>& v);
};

class MapFile {
public:
  /// Cases [i0, i1) of the study into `out` (replacing its contents).
  using CaseRange =
      std::function<void(std::size_t i0, std::size_t i1, std::vector<study::StepRow>& out)>;
  /// Collective. Creates `path` (which must not exist) with every dataset
  /// allocated and zero-filled; rank 0 writes /cases (the rows' fields, taken
  /// by range in blocks: no rank holds every case) and /grid. The file is
  /// closed (complete and valid) on return.
  static void create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const CaseRange& cases);
  /// The same from a list of all the cases (tests, small studies).
  static void create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const std::vector<study::StepRow>& cases);
  /// Serial, read-only: is `path` an HDF5 file with an mdrmap map schema?
  /// On false, `why` says what it is instead.
  static bool is_map(const std::string& path, std::string* why);
  /// Serial, read-only: the layout of a map, checked dataset by dataset
  /// (type, shape, contiguous storage inside the file), and its status
  /// column when `status` is given. Throws H5Error saying what is wrong.
  static MapLayout read_layout(const std::string& path, std::vector<std::int8_t>* status);
};

/// Writes rows into a created map at the offsets of its layout (positional
/// writes on a file descriptor; local to the calling process).
class RowWriter {
public:
  RowWriter() = default;
  /// Opens `path` for writing (never creates or truncates it).
  RowWriter(const std::string& path, MapLayout layout);
  RowWriter(const RowWriter&) = delete;
  RowWriter& operator=(const RowWriter&) = delete;
  ~RowWriter();

  bool timeseries() const { return layout_.timeseries; }
  /// Takes an exclusive POSIX record lock on the whole file (held until
  /// close; HDF5 readers, which use flock, are not blocked). Returns false
  /// when another process holds one, with its pid in `holder` (0 if remote);
  /// true also where the file system has no locks.
  bool lock(long* holder);
  /// Writes rows for cases first .. first + rows.size() - 1, every value
  /// first and the status last. Throws std::runtime_error naming the dataset
  /// and the system error (e.g. "No space left on device").
  void write_rows(std::size_t first, const std::vector<CaseRow>& rows);
  /// Flushes to stable storage (fsync) and closes; throws on error.
  void close();

private:
  void pwrite_all(const void* data, std::size_t bytes, std::uint64_t offset,
                  const std::string& what);
  int fd_ = -1;
  std::string path_;
  MapLayout layout_;
};

} // namespace mdrmap::io
