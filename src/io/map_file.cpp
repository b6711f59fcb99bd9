#include "io/map_file.hpp"

#include <fcntl.h>
#include <hdf5_hl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <utility>

#include "core/model/params.hpp"
#include "core/outputs/output_table.hpp"

namespace mdrmap::io {
namespace {

Handle create_group(hid_t loc, const char* name) {
  return make_group(H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    std::string("creating group ") + name);
}

// Contiguous, allocated at creation, no timestamps: later writes touch raw
// data only, never metadata. Zero-filled only when `zero` (the status, small
// datasets written at once): the rest is written once, by the run.
Handle dataset_plist(const std::string& what, bool zero) {
  Handle dcpl = make_plist(H5Pcreate(H5P_DATASET_CREATE), what);
  check_status(H5Pset_layout(dcpl.id(), H5D_CONTIGUOUS), what);
  check_status(H5Pset_alloc_time(dcpl.id(), H5D_ALLOC_TIME_EARLY), what);
  check_status(H5Pset_fill_time(dcpl.id(), zero ? H5D_FILL_TIME_ALLOC : H5D_FILL_TIME_NEVER), what);
  check_status(H5Pset_obj_track_times(dcpl.id(), 0), what);
  return dcpl;
}

Handle create_dataset(hid_t loc, const std::string& name, hid_t type, std::vector<hsize_t> dims,
                      bool zero = true) {
  const std::string what = "creating dataset /" + name;
  Handle space =
      make_space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), what);
  Handle dcpl = dataset_plist(what, zero);
  return make_dataset(
      H5Dcreate2(loc, name.c_str(), type, space.id(), H5P_DEFAULT, dcpl.id(), H5P_DEFAULT), what);
}

// ---- self-description: /schema, CF attributes, dimension scales ----------------

// A group whose links iterate in creation order (h5py and xarray list them so).
// With `dense_attributes`, its attributes live in a fractal heap outside the
// object header (no 64 KiB limit: /grid's axes of 10000 segments).
Handle create_ordered_group(hid_t loc, const std::string& name, bool dense_attributes = false) {
  const std::string what = "creating group /" + name;
  Handle gcpl = make_plist(H5Pcreate(H5P_GROUP_CREATE), what);
  check_status(H5Pset_link_creation_order(gcpl.id(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
               what);
  if (dense_attributes) {
    check_status(H5Pset_attr_creation_order(gcpl.id(), H5P_CRT_ORDER_TRACKED), what);
    check_status(H5Pset_attr_phase_change(gcpl.id(), 0, 0), what);
  }
  return make_group(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl.id(), H5P_DEFAULT), what);
}

// Describes dataset `dset` (at info.path): CF attributes `units` and
// `long_name` on it (what xarray shows), and /schema/<path> with string
// attributes `unit` and `meaning` (the map's table of contents).
void cf_attributes(hid_t dset, const FieldInfo& info) {
  write_string_attr(dset, "units", info.unit);
  write_string_attr(dset, "long_name", info.meaning);
}

void schema_entry(hid_t file, const FieldInfo& info) {
  Handle g = create_ordered_group(file, "schema/" + info.path);
  write_string_attr(g.id(), "unit", info.unit);
  write_string_attr(g.id(), "meaning", info.meaning);
  g.close("closing /schema/" + info.path);
}

void describe(hid_t file, hid_t dset, const FieldInfo& info) {
  cf_attributes(dset, info);
  schema_entry(file, info);
}

// A netCDF-4 dimension without a variable (xarray's named dimension): an
// HDF5 dimension scale of extent 0 and unlimited maximum, so that it holds no
// data whatever the number of cases; its size is that of the datasets
// attached to it. Named `name` in `loc`.
Handle create_dimension(hid_t loc, const std::string& name, hsize_t size) {
  const std::string what = "creating dimension scale /" + name;
  const hsize_t zero = 0, unlimited = H5S_UNLIMITED, chunk = 1;
  Handle space = make_space(H5Screate_simple(1, &zero, &unlimited), what);
  Handle dcpl = make_plist(H5Pcreate(H5P_DATASET_CREATE), what);
  check_status(H5Pset_chunk(dcpl.id(), 1, &chunk), what);
  check_status(H5Pset_fill_time(dcpl.id(), H5D_FILL_TIME_NEVER), what);
  check_status(H5Pset_obj_track_times(dcpl.id(), 0), what);
  Handle d = make_dataset(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F32BE, space.id(), H5P_DEFAULT,
                                     dcpl.id(), H5P_DEFAULT),
                          what);
  // netCDF-4's mark of a dimension that is not a variable, with its length
  char len[32];
  std::snprintf(len, sizeof len, "%10llu", static_cast<unsigned long long>(size));
  const std::string label =
      std::string("This is a netCDF dimension but not a netCDF variable.") + len;
  check_status(H5DSset_scale(d.id(), label.c_str()), what);
  return d;
}

void attach(hid_t dset, hid_t scale, unsigned axis, const std::string& path) {
  check_status(H5DSattach_scale(dset, scale, axis), "attaching a dimension scale to /" + path);
}

// Writes a whole float64 dataset (independent I/O: rank 0 alone).
void write_doubles(hid_t dset, hid_t dxpl, const double* data, const std::string& what) {
  check_status(H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, dxpl, data), what);
}

// Writes rows [i0, i0 + count) of a [N] or [N, width] dataset (independent I/O).
template <class T>
void write_block(hid_t dset, hid_t mem_type, hid_t dxpl, hsize_t i0, hsize_t count, hsize_t width,
                 const T* data, const std::string& what) {
  const hsize_t start[2] = {i0, 0}, counts[2] = {count, width};
  Handle fspace = make_space(H5Dget_space(dset), what);
  const int rank = static_cast<int>(check(H5Sget_simple_extent_ndims(fspace.id()), what));
  check_status(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start, nullptr, counts, nullptr),
               what);
  Handle mspace = make_space(H5Screate_simple(rank, counts, nullptr), what);
  check_status(H5Dwrite(dset, mem_type, mspace.id(), fspace.id(), dxpl, data), what);
}

// /cases [begin, end) from the cases, taken by range in blocks of 16384
// (memory independent of the number of cases): the parameters, then w and T
// [N, K].
void write_cases(const std::vector<Handle>& sets, const std::vector<FieldInfo>& params, hid_t dxpl,
                 std::size_t begin, std::size_t end, std::size_t K,
                 const MapFile::CaseRange& cases) {
  constexpr std::size_t kBlock = 16384;
  std::vector<Case> rows;
  std::vector<double> values, col;
  const std::size_t P = params.size();
  for (std::size_t i0 = begin; i0 < end; i0 += kBlock) {
    const std::size_t i1 = std::min(end, i0 + kBlock);
    cases(i0, i1, rows, values);
    if (rows.size() != i1 - i0 || values.size() != rows.size() * P)
      throw std::invalid_argument("MapFile::create: case count");
    const hsize_t count = rows.size();
    for (std::size_t c = 0; c < P; ++c) {
      col.resize(rows.size());
      for (std::size_t i = 0; i < rows.size(); ++i)
        col[i] = values[i * P + c];
      write_block(sets[c].id(), H5T_NATIVE_DOUBLE, dxpl, i0, count, 1, col.data(),
                  "writing /" + params[c].path);
    }
    for (std::size_t j = 0; j < 2; ++j) {
      col.assign(rows.size() * K, 0.0);
      for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t k = 0; k < K && k < rows[i].history.size(); ++k)
          col[i * K + k] = j == 0 ? rows[i].history.segments[k].w : rows[i].history.segments[k].T;
      write_block(sets[params.size() + j].id(), H5T_NATIVE_DOUBLE, dxpl, i0, count, K, col.data(),
                  j == 0 ? "writing /cases/w" : "writing /cases/T");
    }
  }
}

// A text as a uint8 dataset `name` (at least one byte: NUL when empty) along
// a dimension of its own, `name`_byte (xarray opens the group without phony
// dimensions).
void write_text_dataset(hid_t loc, const std::string& name, const std::string& text) {
  const std::size_t n = std::max<std::size_t>(text.size(), 1);
  Handle dim = create_dimension(loc, name + "_byte", n);
  Handle d = create_dataset(loc, name, H5T_STD_U8LE, {n});
  attach(d.id(), dim.id(), 0, name);
  std::string buf = text.empty() ? std::string(1, '\0') : text;
  check_status(H5Dwrite(d.id(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()),
               "writing /" + name);
  d.close("closing /" + name);
  dim.close("closing /" + name + "_byte");
}

// The fixed-length string type of /failures/message.
Handle failure_message_type() {
  Handle type = make_type(H5Tcopy(H5T_C_S1), "string type");
  check_status(H5Tset_size(type.id(), kFailureMessageBytes), "string type");
  check_status(H5Tset_strpad(type.id(), H5T_STR_NULLTERM), "string type");
  return type;
}

Handle mpio_fapl(MPI_Comm comm, const std::string& what) {
  Handle fapl = make_plist(H5Pcreate(H5P_FILE_ACCESS), what);
  check_status(H5Pset_fapl_mpio(fapl.id(), comm, MPI_INFO_NULL), what);
  return fapl;
}

long long read_ll_attr(hid_t obj, const char* name) {
  const std::string what = std::string("attribute '") + name + "'";
  Handle a = make_attr(H5Aopen(obj, name, H5P_DEFAULT), what);
  long long v = 0;
  check_status(H5Aread(a.id(), H5T_NATIVE_LLONG, &v), what);
  return v;
}

} // namespace

std::uint64_t map_file_bytes(const MapSpec& spec, std::size_t text_bytes) {
  const std::uint64_t n = spec.n_cases, K = spec.segments;
  const RowLayout layout = spec.layout();
  std::uint64_t per_case =
      (spec.case_params.size() + 2 * K) * 8 + layout.row_width() * 8 + 1 /* status */;
  if (spec.timeseries)
    per_case += layout.series().size() * 8 * K * static_cast<std::uint64_t>(spec.samples);
  std::uint64_t grid = 0;
  for (const auto& v : spec.grid.values)
    grid += 8 * v.size();
  // /failures: its slots, reserved at creation
  const std::uint64_t failures = failure_slots(spec.n_cases) * (8 + kFailureMessageBytes);
  // superblock, object headers, attributes and B-trees: about 32 KiB measured,
  // plus about 100 KiB for /schema, the datasets' units and dimension scales;
  // a grid's axes: their datasets, descriptions and dimension scales (about
  // 1.1 KiB each measured, at 20004 axes)
  const std::uint64_t grid_headers = 2048 * static_cast<std::uint64_t>(spec.grid.names.size());
  return n * per_case + grid + failures + grid_headers +
         4 * K * static_cast<std::uint64_t>(spec.samples) +
         2 * static_cast<std::uint64_t>(text_bytes) + 256 * 1024;
}

void MapFile::create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const std::vector<Case>& cases) {
  if (cases.size() != spec.n_cases) throw std::invalid_argument("MapFile::create: case count");
  std::vector<const ParamSpec*> table;
  for (const FieldInfo& p : spec.case_params) {
    table.push_back(find_parameter(p.path.substr(p.path.find('/') + 1)));
    if (!table.back()) throw std::invalid_argument("MapFile::create: no parameter " + p.path);
  }
  create(comm, path, spec, prov,
         [&](std::size_t i0, std::size_t i1, std::vector<Case>& out, std::vector<double>& params) {
           out.assign(cases.begin() + static_cast<std::ptrdiff_t>(i0),
                      cases.begin() + static_cast<std::ptrdiff_t>(i1));
           params.clear();
           for (const Case& c : out)
             for (const ParamSpec* p : table)
               params.push_back(p->get(c));
         });
}

namespace {

// Root attributes and /provenance (collective: identical calls on every rank).
void write_header(hid_t f, const MapSpec& spec, const Provenance& prov) {
  const auto name = root_attribute; // each declared in io::root_attributes()
  write_string_attr(f, name("mdrmap_schema"), kSchema);
  write_string_attr(f, name("program_version"), prov.program_version);
  write_string_attr(f, name("git_commit"), prov.git_commit);
  write_string_attr(f, name("created_utc"), prov.created_utc);
  write_string_attr(f, name("command_line"), prov.command_line);
  write_string_attr(f, name("units"), prov.units);
  write_string_attr(f, name("loading"), spec.by_force ? "force" : "depth");
  write_scalar_attr(f, name("mpi_size"), prov.mpi_size);
  write_scalar_attr(f, name("n_cases"), static_cast<long long>(spec.n_cases));
  write_scalar_attr(f, name("segments"), static_cast<long long>(spec.segments));
  write_scalar_attr(f, name("samples"), spec.samples);
  write_scalar_attr(f, name("timeseries"), spec.timeseries ? 1 : 0);
  // an attribute must fit in the object header (64 KiB): long configs live in /provenance only
  write_string_attr(f, name("config_text"),
                    prov.config_text.size() < 48 * 1024 ? prov.config_text
                                                        : "(long: see /provenance/config_text)");
  Handle g = create_group(f, "provenance");
  for (const FieldInfo& t : provenance_info())
    write_text_dataset(
        f, t.path, t.path == "provenance/config_text" ? prov.config_text : prov.config_canonical);
  if (!prov.material_card.empty()) // a study with [run] material
    write_text_dataset(f, material_card_info().path, prov.material_card);
  g.close("closing /provenance");
}

// The named dimensions of a map (xarray).
struct Dimensions {
  Handle cases, events, samples;
};

// A per-case dataset [N] or [N, width], described, its dimensions attached.
Handle per_case(hid_t f, const Dimensions& dims, const FieldInfo& info, hid_t type, hsize_t n,
                hsize_t width, hid_t second, bool zero) {
  Handle d = width == 0 ? create_dataset(f, info.path, type, {n}, zero)
                        : create_dataset(f, info.path, type, {n, width}, zero);
  describe(f, d.id(), info);
  attach(d.id(), dims.cases.id(), 0, info.path);
  if (width != 0) attach(d.id(), second, 1, info.path);
  return d;
}

// /results, /events, /analytic, /residuals, /scales and /timeseries.
void create_results(hid_t f, const Dimensions& dims, const MapSpec& spec) {
  const RowLayout layout = spec.layout();
  const hsize_t n = spec.n_cases, K = spec.segments;
  for (const RowField& field : layout.fields()) {
    Handle d = per_case(f, dims, field.info, H5T_IEEE_F64LE, n, field.per_event ? K : 0,
                        dims.events.id(), false);
    if (field.may_be_undefined) write_double_attr(d.id(), "_FillValue", kFillValue);
    d.close("closing /" + field.info.path);
  }
  per_case(f, dims, other_info("results/status"), H5T_STD_I8LE, n, 0, -1, true)
      .close("closing /results/status");
  if (!spec.timeseries) return;
  const hsize_t S = K * static_cast<hsize_t>(spec.samples);
  for (const FieldInfo& info : layout.series())
    per_case(f, dims, info, H5T_IEEE_F64LE, n, S, dims.samples.id(), false)
        .close("closing /" + info.path);
}

// /failures: its slots reserved now (case kNoFailure: unused; the messages
// left unwritten, zero on disk), along a dimension `failure` of their own,
// and written in place by RowWriter::write_failures.
void create_failures(hid_t f, std::size_t n_cases) {
  const hsize_t slots = failure_slots(n_cases);
  Handle dim = create_dimension(f, "failures/failure", slots);
  {
    const std::string what = "creating dataset /failures/case";
    Handle space = make_space(H5Screate_simple(1, &slots, nullptr), what);
    Handle dcpl = dataset_plist(what, true);
    check_status(H5Pset_fill_value(dcpl.id(), H5T_NATIVE_UINT64, &kNoFailure), what);
    Handle d = make_dataset(H5Dcreate2(f, "failures/case", H5T_STD_U64LE, space.id(), H5P_DEFAULT,
                                       dcpl.id(), H5P_DEFAULT),
                            what);
    describe(f, d.id(), other_info("failures/case"));
    attach(d.id(), dim.id(), 0, "failures/case");
    d.close(what);
  }
  Handle type = failure_message_type();
  Handle m = create_dataset(f, "failures/message", type.id(), {slots}, false);
  describe(f, m.id(), other_info("failures/message"));
  attach(m.id(), dim.id(), 0, "failures/message");
  m.close("closing /failures/message");
  dim.close("closing /failures/failure");
}

// /grid/<axis>: the values of each axis, each a dimension scale of its own.
std::vector<Handle> create_grid(hid_t f, const GridInfo& grid) {
  std::vector<Handle> sets;
  if (grid.names.empty()) return sets;
  Handle g = create_ordered_group(f, "grid", true);
  std::string axes;
  std::vector<long long> shape, logs;
  for (std::size_t i = 0; i < grid.names.size(); ++i) {
    const std::string& a = grid.names[i];
    axes += (i ? "," : "") + a;
    shape.push_back(static_cast<long long>(grid.values[i].size()));
    logs.push_back(grid.logarithmic[i]);
    sets.push_back(create_dataset(f, "grid/" + a, H5T_IEEE_F64LE, {grid.values[i].size()}));
    describe(f, sets.back().id(), grid.info[i]);
    check_status(H5DSset_scale(sets.back().id(), a.c_str()),
                 "making /grid/" + a + " a dimension scale");
  }
  write_string_attr(g.id(), "axes", axes);
  write_int_array_attr(g.id(), "shape", shape);
  write_int_array_attr(g.id(), "log", logs);
  g.close("closing /grid");
  return sets;
}

// Reserves the file's blocks (its size is final at close): the raw data is
// written once, by the run, and cannot run out of space then.
void reserve_blocks(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno));
  struct stat st {};
  int err = ::fstat(fd, &st) == 0 ? ::posix_fallocate(fd, 0, st.st_size) : errno;
  if (err == EOPNOTSUPP || err == ENOSYS) err = 0; // no reservation here: a later write tells
  ::close(fd);
  if (err != 0)
    throw std::runtime_error("reserving " + std::to_string(st.st_size) + " bytes for '" + path +
                             "': " + std::strerror(err));
}

} // namespace

void MapFile::create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const CaseRange& cases) {
  if (spec.n_cases == 0 || spec.segments == 0)
    throw std::invalid_argument("MapFile::create: no cases");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  Handle fapl = mpio_fapl(comm, "creating " + path);
  Handle file = make_file(H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.id()),
                          "creating map file '" + path + "'");
  const hid_t f = file.id();
  const hsize_t n = spec.n_cases, K = spec.segments;
  write_header(f, spec, prov);
  // every object is closed before the file: a map is closed complete
  std::vector<const char*> groups = {"cases",    "results",   "events",
                                     "analytic", "residuals", "scales"};
  if (spec.timeseries) groups.push_back("timeseries");
  groups.push_back("failures");
  for (const char* group : groups)
    create_ordered_group(f, group).close(std::string("closing /") + group);
  {
    Handle schema = create_ordered_group(f, "schema");
    for (const char* group : groups)
      create_ordered_group(f, std::string("schema/") + group)
          .close(std::string("closing /schema/") + group);
    if (!spec.grid.names.empty()) create_ordered_group(f, "schema/grid").close("/schema/grid");
    schema.close("closing /schema");
  }
  Dimensions dims{create_dimension(f, "case", n), create_dimension(f, "event", K),
                  create_dimension(f, "sample", K * static_cast<hsize_t>(spec.samples))};
  const std::vector<FieldInfo>& params = spec.case_params;
  std::vector<Handle> case_sets;
  for (const FieldInfo& c : params)
    case_sets.push_back(per_case(f, dims, c, H5T_IEEE_F64LE, n, 0, -1, false));
  for (const char* c : {"w", "T"})
    case_sets.push_back(
        per_case(f, dims, segment_case_info(c), H5T_IEEE_F64LE, n, K, dims.events.id(), false));
  create_results(f, dims, spec);
  create_failures(f, spec.n_cases);
  Handle segment;
  if (spec.timeseries) {
    segment = create_dataset(f, "timeseries/segment", H5T_STD_I32LE,
                             {K * static_cast<hsize_t>(spec.samples)});
    describe(f, segment.id(), other_info("timeseries/segment"));
    attach(segment.id(), dims.samples.id(), 0, "timeseries/segment");
  }
  for (Handle* h : {&dims.cases, &dims.events, &dims.samples})
    h->close("closing a dimension scale");
  std::vector<Handle> grid_sets = create_grid(f, spec.grid);
  // Raw data known up front (independent I/O): every rank its share of
  // /cases, rank 0 the rest.
  Handle dxpl = make_plist(H5Pcreate(H5P_DATASET_XFER), "transfer property list");
  check_status(H5Pset_dxpl_mpio(dxpl.id(), H5FD_MPIO_INDEPENDENT), "independent transfer");
  int size = 1;
  MPI_Comm_size(comm, &size);
  const auto share = [&](int r) {
    return spec.n_cases * static_cast<std::size_t>(r) / static_cast<std::size_t>(size);
  };
  write_cases(case_sets, params, dxpl.id(), share(rank), share(rank + 1), spec.segments, cases);
  if (rank == 0) {
    for (std::size_t i = 0; i < grid_sets.size(); ++i)
      write_doubles(grid_sets[i].id(), dxpl.id(), spec.grid.values[i].data(), "writing /grid");
    if (segment) {
      std::vector<std::int32_t> seg;
      for (std::size_t k = 0; k < spec.segments; ++k)
        seg.insert(seg.end(), static_cast<std::size_t>(spec.samples), static_cast<std::int32_t>(k));
      check_status(
          H5Dwrite(segment.id(), H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, dxpl.id(), seg.data()),
          "writing /timeseries/segment");
    }
  }
  for (auto& h : case_sets)
    h.close("closing /cases");
  for (auto& h : grid_sets)
    h.close("closing /grid");
  if (segment) segment.close("closing /timeseries/segment");
  file.close("closing " + path);
  if (rank == 0) reserve_blocks(path);
}

bool MapFile::is_map(const std::string& path, std::string* why) {
  const htri_t h5 = H5Fis_hdf5(path.c_str());
  if (h5 <= 0) {
    H5Eclear2(H5E_DEFAULT);
    if (why) *why = "not an HDF5 file";
    return false;
  }
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) {
    H5Eclear2(H5E_DEFAULT);
    if (why) *why = "an HDF5 file that cannot be opened (corrupt, or locked by a running job)";
    return false;
  }
  Handle file(f, H5Fclose);
  try {
    if (has_attr(f, "mdrmap_schema")) {
      const std::string schema = read_string_attr(f, "mdrmap_schema");
      if (schema == kSchema || schema == "mdrmap-map/1") return true;
      if (why) *why = "an mdrmap map of another schema (" + schema + ")";
      return false;
    }
  } catch (const H5Error&) {
  }
  if (why) *why = "an HDF5 file that is not an mdrmap map";
  return false;
}

std::vector<std::uint64_t> MapLayout::pack() const {
  std::vector<std::uint64_t> v{n_cases,
                               segments,
                               static_cast<std::uint64_t>(samples),
                               by_force ? 1u : 0u,
                               timeseries ? 1u : 0u,
                               status,
                               fields.size(),
                               series.size(),
                               failure_slots,
                               failure_width,
                               failure_case,
                               failure_message};
  v.insert(v.end(), fields.begin(), fields.end());
  v.insert(v.end(), series.begin(), series.end());
  return v;
}

MapLayout MapLayout::unpack(const std::vector<std::uint64_t>& v) {
  constexpr std::size_t kHead = 12;
  if (v.size() < kHead || v.size() != kHead + v[6] + v[7])
    throw std::invalid_argument("MapLayout::unpack: bad size");
  MapLayout m;
  m.n_cases = v[0];
  m.segments = v[1];
  m.samples = static_cast<long>(v[2]);
  m.by_force = v[3] != 0;
  m.timeseries = v[4] != 0;
  m.status = v[5];
  m.failure_slots = v[8];
  m.failure_width = v[9];
  m.failure_case = v[10];
  m.failure_message = v[11];
  const auto nf = static_cast<long>(v[6]);
  m.fields.assign(v.begin() + kHead, v.begin() + kHead + nf);
  m.series.assign(v.begin() + kHead + nf, v.end());
  return m;
}

namespace {

// Offset of a dataset that the row writer may write into directly: of the
// expected type and shape, contiguous, allocated, inside the file.
std::uint64_t raw_offset(hid_t file, const std::string& name, hid_t want_type,
                         std::vector<hsize_t> want_dims, std::uint64_t file_size) {
  const std::string what = "/" + name;
  if (!has_link(file, name)) throw H5Error(what + " is missing");
  Handle d = make_dataset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "opening " + what);
  Handle type = make_type(H5Dget_type(d.id()), what);
  if (H5Tequal(type.id(), want_type) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw H5Error(what + " has an unexpected type");
  }
  Handle space = make_space(H5Dget_space(d.id()), what);
  const int rank = H5Sget_simple_extent_ndims(space.id());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank < 0 || H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr) != rank ||
      dims != want_dims)
    throw H5Error(what + " has an unexpected shape");
  Handle dcpl = make_plist(H5Dget_create_plist(d.id()), what);
  if (H5Pget_layout(dcpl.id()) != H5D_CONTIGUOUS || H5Pget_nfilters(dcpl.id()) != 0)
    throw H5Error(what + " is not stored contiguously");
  const haddr_t off = H5Dget_offset(d.id());
  const hsize_t bytes = H5Dget_storage_size(d.id());
  hsize_t expect = H5Tget_size(type.id());
  for (hsize_t x : want_dims)
    expect *= x;
  if (off == HADDR_UNDEF || bytes != expect || off + bytes > file_size) {
    H5Eclear2(H5E_DEFAULT);
    throw H5Error(what + " is not allocated inside the file (truncated?)");
  }
  d.close("closing " + what);
  return off;
}

// /failures as created by this version (slots reserved, contiguous) into
// m; a map whose /failures is not (an earlier version's) keeps 0 slots: its
// failures are not recorded, and --resume runs them again.
void read_failure_layout(hid_t f, std::uint64_t file_size, MapLayout& m) {
  const hsize_t slots = failure_slots(m.n_cases);
  if (!has_link(f, "failures/case") || !has_link(f, "failures/message")) return;
  try {
    Handle type = failure_message_type();
    const std::uint64_t at_case = raw_offset(f, "failures/case", H5T_STD_U64LE, {slots}, file_size);
    const std::uint64_t at_message =
        raw_offset(f, "failures/message", type.id(), {slots}, file_size);
    m.failure_slots = slots;
    m.failure_width = kFailureMessageBytes;
    m.failure_case = at_case;
    m.failure_message = at_message;
  } catch (const H5Error&) {
    H5Eclear2(H5E_DEFAULT);
  }
}

/// Throws OldOutputNames where the map has an output's old name in place of
/// its name (events/d_c for events/D_c).
void check_output_names(hid_t f, const std::string& path) {
  for (const OutputSpec& o : output_table()) {
    if (o.old_map_name == nullptr) continue;
    const std::string group = o.group == OutputGroup::Result ? "results/" : "events/";
    if (has_link(f, group + o.old_map_name) && !has_link(f, group + o.name))
      throw OldOutputNames("'" + path + "' holds /" + group + o.old_map_name +
                           ", the old name of /" + group + o.name +
                           " (an earlier mdrmap wrote it); continue it with that mdrmap or start "
                           "a new map (mdrmap.open_map reads it)");
  }
}

} // namespace

MapLayout MapFile::read_layout(const std::string& path, std::vector<std::int8_t>* status) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw H5Error("cannot stat '" + path + "': " + std::strerror(errno));
  const auto file_size = static_cast<std::uint64_t>(st.st_size);
  Handle file = make_file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                          "opening map file '" + path + "'");
  const hid_t f = file.id();
  const std::string schema =
      has_attr(f, "mdrmap_schema") ? read_string_attr(f, "mdrmap_schema") : "";
  if (schema == "mdrmap-map/1")
    throw H5Error("'" + path +
                  "' is an mdrmap-map/1 map, written by an earlier mdrmap; this one "
                  "continues " +
                  kSchema + " maps only");
  if (schema != kSchema) throw H5Error("'" + path + "' is not an mdrmap map of schema " + kSchema);
  {
    Handle fcpl = make_plist(H5Fget_create_plist(f), "file creation properties");
    hsize_t userblock = 0;
    check_status(H5Pget_userblock(fcpl.id(), &userblock), "file creation properties");
    if (userblock != 0) throw H5Error("'" + path + "' has a user block");
  }
  check_output_names(f, path);
  MapLayout m;
  const long long n = read_ll_attr(f, "n_cases"), samples = read_ll_attr(f, "samples"),
                  K = read_ll_attr(f, "segments");
  if (n < 1 || samples < 2 || K < 1 || K > static_cast<long long>(kMaxSegments))
    throw H5Error("attributes n_cases, segments or samples out of range");
  m.n_cases = static_cast<std::uint64_t>(n);
  m.segments = static_cast<std::uint64_t>(K);
  m.samples = static_cast<long>(samples);
  m.by_force = read_string_attr(f, "loading") == "force";
  m.timeseries = read_ll_attr(f, "timeseries") != 0;
  const hsize_t N = m.n_cases;
  const RowLayout layout(m.segments, m.by_force);
  for (const RowField& field : layout.fields())
    m.fields.push_back(
        raw_offset(f, field.info.path, H5T_IEEE_F64LE,
                   field.per_event ? std::vector<hsize_t>{N, m.segments} : std::vector<hsize_t>{N},
                   file_size));
  m.status = raw_offset(f, "results/status", H5T_STD_I8LE, {N}, file_size);
  if (m.timeseries)
    for (const FieldInfo& info : layout.series())
      m.series.push_back(raw_offset(f, info.path, H5T_IEEE_F64LE,
                                    {N, m.segments * static_cast<hsize_t>(m.samples)}, file_size));
  read_failure_layout(f, file_size, m);
  if (status) {
    status->assign(m.n_cases, 0);
    Handle d = make_dataset(H5Dopen2(f, "results/status", H5P_DEFAULT), "opening /results/status");
    check_status(H5Dread(d.id(), H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, status->data()),
                 "reading /results/status");
    d.close("closing /results/status");
    for (std::size_t i = 0; i < status->size(); ++i) // a value no study writes: damage
      if ((*status)[i] < -1 || (*status)[i] > 1)
        throw H5Error("/results/status of case " + std::to_string(i + 1) + " is " +
                      std::to_string((*status)[i]) + ", not 0 (pending), 1 (done) or -1 (failed)");
  }
  file.close("closing '" + path + "'");
  return m;
}

// ---- RowWriter ------------------------------------------------------------------

RowWriter::RowWriter(const std::string& path, MapLayout layout)
    : path_(path), layout_(std::move(layout)), rows_(layout_.segments, layout_.by_force) {
  // the file stores little-endian float64: raw rows are written as in memory
  const std::uint16_t probe = 1;
  unsigned char first_byte = 0;
  std::memcpy(&first_byte, &probe, 1);
  if (first_byte != 1) throw std::runtime_error("writing maps needs a little-endian host");
  if (layout_.fields.size() != rows_.fields().size() ||
      layout_.series.size() != (layout_.timeseries ? rows_.series().size() : 0))
    throw std::invalid_argument("RowWriter: layout does not match this program's fields");
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0)
    throw std::runtime_error("cannot open '" + path + "' for writing: " + std::strerror(errno));
}

RowWriter::~RowWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void RowWriter::pwrite_all(const void* data, std::size_t bytes, std::uint64_t offset,
                           const std::string& what) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pwrite(fd_, p, bytes, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error("writing " + what + ": " +
                               (n < 0 ? std::strerror(errno) : "nothing written"));
    p += n;
    bytes -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
}

void RowWriter::write_rows(std::size_t first, const std::vector<CaseRow>& rows) {
  const std::size_t count = rows.size();
  if (count == 0) return;
  if (fd_ < 0) throw std::logic_error("RowWriter::write_rows on a closed writer");
  if (first + count > layout_.n_cases)
    throw std::out_of_range("RowWriter::write_rows beyond the case count");
  const RowLayout& L = rows_;
  std::vector<double> block;
  for (std::size_t f = 0; f < L.fields().size(); ++f) {
    const std::size_t w = L.width(f), at = L.offset(f);
    block.resize(count * w);
    for (std::size_t i = 0; i < count; ++i)
      std::copy_n(rows[i].values.begin() + static_cast<long>(at), w,
                  block.begin() + static_cast<long>(i * w));
    pwrite_all(block.data(), block.size() * 8, layout_.fields[f] + 8 * w * first,
               "/" + L.fields()[f].info.path);
  }
  if (layout_.timeseries) {
    const auto S = layout_.segments * static_cast<std::size_t>(layout_.samples);
    block.resize(count * S);
    for (std::size_t q = 0; q < L.series().size(); ++q) {
      for (std::size_t i = 0; i < count; ++i) {
        const auto out = block.begin() + static_cast<long>(i * S);
        if (rows[i].series.size() == L.series().size() && rows[i].series[q].size() == S)
          std::copy(rows[i].series[q].begin(), rows[i].series[q].end(), out);
        else
          std::fill_n(out, S, 0.0); // failed case
      }
      pwrite_all(block.data(), block.size() * 8, layout_.series[q] + 8 * S * first,
                 "/" + L.series()[q].path);
    }
  }
  // status last: a case counts as done only once everything else is written
  std::vector<std::int8_t> st(count);
  for (std::size_t i = 0; i < count; ++i)
    st[i] = rows[i].status;
  pwrite_all(st.data(), count, layout_.status + first, "/results/status");
}

std::size_t RowWriter::write_failures(const std::vector<Failure>& failures) {
  if (fd_ < 0) throw std::logic_error("RowWriter::write_failures on a closed writer");
  const std::size_t slots = layout_.failure_slots, width = layout_.failure_width;
  if (slots == 0) return 0; // an earlier version's map: nowhere to record them
  const std::size_t n = std::min(failures.size(), slots);
  std::vector<char> text(n * width, '\0');
  std::vector<std::uint64_t> index(slots, kNoFailure);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& msg = failures[i].message;
    std::memcpy(&text[i * width], msg.data(), std::min(msg.size(), width - 1));
    index[i] = failures[i].index;
  }
  // every slot unused first, then the messages, then the case indices: a
  // slot counts once its index is written, so a write that fails part way
  // never pairs a case with another case's message (the status column stays
  // authoritative: an unrecorded failed case is retried on --resume)
  const std::vector<std::uint64_t> unused(slots, kNoFailure);
  pwrite_all(unused.data(), unused.size() * 8, layout_.failure_case, "/failures/case");
  pwrite_all(text.data(), text.size(), layout_.failure_message, "/failures/message");
  pwrite_all(index.data(), index.size() * 8, layout_.failure_case, "/failures/case");
  return n;
}

void RowWriter::close() {
  if (fd_ < 0) return;
  const int fd = std::exchange(fd_, -1);
  // errors of earlier writes may only show here (NFS, delayed allocation)
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    throw std::runtime_error("flushing '" + path_ + "' to disk: " + std::strerror(e));
  }
  if (::close(fd) != 0)
    throw std::runtime_error("closing '" + path_ + "': " + std::strerror(errno));
}

// ---- failures -------------------------------------------------------------------

namespace {

// Rows [i0, i0 + count) of the fixed-length string dataset m into text
// (count * len bytes).
void read_message_block(hid_t m, hid_t type, hsize_t i0, hsize_t count, char* text) {
  const std::string what = "reading /failures/message";
  Handle fspace = make_space(H5Dget_space(m), what);
  check_status(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, &i0, nullptr, &count, nullptr),
               what);
  Handle mspace = make_space(H5Screate_simple(1, &count, nullptr), what);
  check_status(H5Dread(m, type, mspace.id(), fspace.id(), H5P_DEFAULT, text), what);
}

} // namespace

std::vector<Failure> MapFile::read_failures(const std::string& path) {
  Handle file = make_file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                          "opening map file '" + path + "'");
  std::vector<Failure> out;
  if (!has_link(file.id(), "failures/case") || !has_link(file.id(), "failures/message")) return out;
  Handle c = make_dataset(H5Dopen2(file.id(), "failures/case", H5P_DEFAULT), "/failures/case");
  Handle m =
      make_dataset(H5Dopen2(file.id(), "failures/message", H5P_DEFAULT), "/failures/message");
  Handle space = make_space(H5Dget_space(c.id()), "/failures/case");
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id()));
  Handle type = make_type(H5Dget_type(m.id()), "/failures/message");
  const std::size_t len = H5Tget_size(type.id());
  if (H5Tget_class(type.id()) != H5T_STRING || H5Tis_variable_str(type.id()) != 0 || len == 0)
    throw H5Error("/failures/message is not a fixed-length string");
  std::vector<std::uint64_t> idx(n);
  if (n > 0)
    check_status(H5Dread(c.id(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, idx.data()),
                 "reading /failures/case");
  // the messages of the used slots only, by blocks: the table is reserved
  // for up to 100000 failures (25.6 MB) and is mostly unused
  constexpr std::size_t kBlock = 4096;
  std::vector<char> text(kBlock * len);
  for (std::size_t b = 0; b < n; b += kBlock) {
    const std::size_t count = std::min(kBlock, n - b);
    if (std::all_of(&idx[b], &idx[b] + count, [](std::uint64_t i) { return i == kNoFailure; }))
      continue;
    read_message_block(m.id(), type.id(), b, count, text.data());
    for (std::size_t i = 0; i < count; ++i) {
      if (idx[b + i] == kNoFailure) continue; // an unused slot
      const char* p = &text[i * len];
      out.push_back({idx[b + i], std::string(p, strnlen(p, len))});
    }
  }
  return out;
}

void MapFile::write_failures(const std::string& path, const std::vector<Failure>& failures) {
  RowWriter writer(path, read_layout(path, nullptr));
  writer.write_failures(failures);
  writer.close();
}

} // namespace mdrmap::io
