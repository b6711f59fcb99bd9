#pragma once
// The friction-map file: one HDF5 file per study, written in parallel
// through MPI-IO.
//
// Layout: schema "mdrmap-map/2", described dataset by dataset in
// docs/reference/map-schema.md (N cases, K segments, S samples per segment):
//   /cases/{d|F0,R,tau,G,v} [N], /cases/{w,T} [N, K]   the cases as run
//   /results, /events, /analytic, /residuals           io::RowLayout: float64 [N] or [N, K]
//   /results/status                         int8 [N]   0 pending, 1 done, -1 failed
//   /timeseries/<q> [N, K S], /timeseries/segment [K S]  with timeseries = true
//   /failures/{case,message} [F]            the failed cases and why: F slots reserved
//                                           at creation, unused ones case = kNoFailure
//   /grid/<axis>, /provenance, /schema/<group>/<name>, root attributes
// Every dataset has `units` and `long_name` (CF) and a /schema entry; the
// dimension scales /case, /event, /sample name the dimensions for xarray.
//
// Crash and fault safety: the file is created collectively with parallel
// HDF5, every dataset allocated (early, contiguous), its blocks reserved on
// disk (posix_fallocate: the raw data is not written at creation), status
// zeroed and the file closed before any case runs: the whole map is on disk
// and valid from then on. The run writes raw rows only, by plain positional
// writes at the offsets of the datasets (RowWriter; no HDF5 state, nothing
// collective), values first and status last. So a process killed at any
// moment, or a rank whose write fails, leaves a file that opens, with every
// case marked done intact; and a failing device cannot hang the job in a
// collective close. A row's values are defined once its status is 1. The
// failed cases' messages go into /failures, also reserved at creation and
// written in place at the end of a run: nothing the run writes needs space
// that was not reserved when the map was created.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/model/case.hpp"
#include "io/case_row.hpp"
#include "io/h5.hpp"

namespace mdrmap::io {

/// A map that names an output quantity as mdrmap did before the output
/// table (core/outputs/output_table.hpp, OutputSpec::old_map_name): readable
/// (the Python module reads the old names as the new), not continued, so that
/// no map mixes the two spellings.
class OldOutputNames : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

inline constexpr const char* kSchema = "mdrmap-map/2";

/// /failures holds at most this many failed cases (the slots reserved at
/// creation: min(N, kMaxFailureSlots)); a failed case beyond them, or whose
/// failure is not recorded, is run again by --resume.
inline constexpr std::size_t kMaxFailureSlots = 100000;
/// Bytes of a /failures/message slot (a fixed-length string, NUL-padded; a
/// longer message is cut to kFailureMessageBytes - 1 bytes).
inline constexpr std::size_t kFailureMessageBytes = 256;
/// /failures/case of an unused slot.
inline constexpr std::uint64_t kNoFailure = ~std::uint64_t{0};
inline std::size_t failure_slots(std::size_t n_cases) {
  return n_cases < kMaxFailureSlots ? n_cases : kMaxFailureSlots;
}

struct Provenance {
  std::string program_version, git_commit, created_utc, command_line, units;
  std::string config_text, config_canonical;
  std::string material_card; ///< [run] material's text ("" without one: no dataset)
  int mpi_size = 1;
};

struct GridInfo {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  std::vector<int> logarithmic;
  std::vector<FieldInfo> info; ///< unit and meaning of each axis
};

struct MapSpec {
  std::size_t n_cases = 0;
  std::size_t segments = 1; ///< K
  long samples = 0;         ///< S, per segment
  bool by_force = false;
  bool timeseries = false;
  /// /cases/<name> [N]: the study's case parameters (e.g. F0, R, tau, G, v;
  /// a spectrum's G1, tau1, ..., aT, temperature), in column order: their
  /// paths "cases/<name>", units and meanings
  std::vector<FieldInfo> case_params;
  GridInfo grid; ///< empty for a case list
  RowLayout layout() const { return RowLayout(segments, by_force); }
};

/// Bytes the map file of `spec` takes on disk (every dataset is allocated and
/// its blocks reserved at creation, /failures included), with `text_bytes`
/// of provenance text; an upper bound within 256 KiB. A map that fits at
/// creation cannot run out of space later.
std::uint64_t map_file_bytes(const MapSpec& spec, std::size_t text_bytes);

/// Where the per-case datasets of a map lie in its file (byte offsets).
struct MapLayout {
  std::uint64_t n_cases = 0;
  std::uint64_t segments = 1;
  long samples = 0;
  bool by_force = false;
  bool timeseries = false;
  std::vector<std::uint64_t> fields; ///< RowLayout::fields() order
  std::uint64_t status = 0;          ///< int8 [N]
  std::vector<std::uint64_t> series; ///< RowLayout::series(): float64 [N, K S] (timeseries only)
  /// /failures: slots (0: a map without reserved /failures, whose failures
  /// are not recorded), bytes per message, offsets of /failures/case
  /// (uint64 [slots]) and /failures/message (string [slots])
  std::uint64_t failure_slots = 0, failure_width = 0, failure_case = 0, failure_message = 0;

  /// Flat form, to broadcast.
  std::vector<std::uint64_t> pack() const;
  static MapLayout unpack(const std::vector<std::uint64_t>& v);
};

/// A failed case and why.
struct Failure {
  std::uint64_t index = 0;
  std::string message;
};

class MapFile {
public:
  /// Cases [i0, i1) of the study into `out` and the values of their case
  /// parameters (MapSpec::case_params, case after case) into `params`
  /// (replacing the contents of both).
  using CaseRange = std::function<void(std::size_t i0, std::size_t i1, std::vector<Case>& out,
                                       std::vector<double>& params)>;
  /// Collective. Creates `path` (which must not exist) with every dataset
  /// allocated and its blocks reserved; every rank writes its share of
  /// /cases (taken by range in blocks: no rank holds every case; `cases` is
  /// called on every rank), rank 0 /grid and /timeseries/segment; the status
  /// is zero. The file is closed (complete and valid) on return.
  static void create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const CaseRange& cases);
  /// The same from a list of all the cases (tests, small studies); the case
  /// parameters must be entries of the core's table (their values read from
  /// the cases).
  static void create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const std::vector<Case>& cases);
  /// Serial, read-only: is `path` an HDF5 file with an mdrmap map schema
  /// (this one or an earlier one)? On false, `why` says what it is instead.
  static bool is_map(const std::string& path, std::string* why);
  /// Serial, read-only: the layout of a map, checked dataset by dataset
  /// (type, shape, contiguous storage inside the file), and its status
  /// column when `status` is given. Throws H5Error saying what is wrong (a
  /// map of an earlier schema: which one, and that it cannot be continued),
  /// OldOutputNames for a map with an output's old name (events/d_c).
  static MapLayout read_layout(const std::string& path, std::vector<std::int8_t>* status);
  /// Serial, read-only: the map's /failures (none when it has none).
  static std::vector<Failure> read_failures(const std::string& path);
  /// Serial: replaces the map's /failures with `failures` (RowWriter::
  /// write_failures, then close). Only while no RowWriter has the file open.
  static void write_failures(const std::string& path, const std::vector<Failure>& failures);
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
  /// Writes rows for cases first .. first + rows.size() - 1, every value
  /// first and the status last. Throws std::runtime_error naming the dataset
  /// and the system error (e.g. "No space left on device").
  void write_rows(std::size_t first, const std::vector<CaseRow>& rows);
  /// Replaces /failures with the first min(size, slots) of `failures` (in
  /// their order), in place: the messages first, then the case indices
  /// (unused slots kNoFailure). Returns how many were recorded; throws
  /// std::runtime_error as write_rows.
  std::size_t write_failures(const std::vector<Failure>& failures);
  /// Flushes to stable storage (fsync) and closes; throws on error.
  void close();

private:
  void pwrite_all(const void* data, std::size_t bytes, std::uint64_t offset,
                  const std::string& what);
  int fd_ = -1;
  std::string path_;
  MapLayout layout_;
  RowLayout rows_ = RowLayout(1, false); ///< the datasets of layout_'s rows
};

} // namespace mdrmap::io
