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

#include "core/params.hpp"

namespace mdrmap::io {
namespace {

const char* const kSeriesNames[] = {"t", "FN", "Fx", "mu", "a2"};
const char* const kCaseColumns[] = {"d", "R", "tau", "v", "v1", "G"};

Handle create_group(hid_t loc, const char* name) {
  return make_group(H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    std::string("creating group ") + name);
}

// Contiguous, allocated at creation, zero-filled, no timestamps: later
// writes touch raw data only, never metadata.
Handle dataset_plist(const std::string& what) {
  Handle dcpl = make_plist(H5Pcreate(H5P_DATASET_CREATE), what);
  check_status(H5Pset_layout(dcpl.id(), H5D_CONTIGUOUS), what);
  check_status(H5Pset_alloc_time(dcpl.id(), H5D_ALLOC_TIME_EARLY), what);
  check_status(H5Pset_fill_time(dcpl.id(), H5D_FILL_TIME_ALLOC), what);
  check_status(H5Pset_obj_track_times(dcpl.id(), 0), what);
  return dcpl;
}

Handle create_dataset(hid_t loc, const std::string& name, hid_t type, std::vector<hsize_t> dims) {
  const std::string what = "creating dataset /" + name;
  Handle space =
      make_space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), what);
  Handle dcpl = dataset_plist(what);
  return make_dataset(
      H5Dcreate2(loc, name.c_str(), type, space.id(), H5P_DEFAULT, dcpl.id(), H5P_DEFAULT), what);
}

// ---- self-description: /schema, CF attributes, dimension scales ----------------

// Unit and meaning of a /cases column or a grid axis: the core's parameter
// table, plus the step's v1 (its one history segment) and the axis v1_over_v.
FieldInfo case_column_info(const std::string& group, const std::string& name) {
  if (const ParamSpec* p = find_parameter(name))
    return {group + "/" + name, dim_name(p->dim), p->meaning};
  if (name == "v1") {
    const ParamSpec& w = segment_velocity_spec();
    return {group + "/v1", dim_name(w.dim),
            std::string("after the step at t = 0, the history's one segment: ") + w.meaning};
  }
  if (name == "v1_over_v")
    return {group + "/v1_over_v", "number", "velocity ratio v1 / v of the step"};
  throw std::logic_error("map: no unit and meaning for the case column " + name);
}

// A group whose links iterate in creation order (h5py and xarray list them so).
Handle create_ordered_group(hid_t loc, const std::string& name) {
  const std::string what = "creating group /" + name;
  Handle gcpl = make_plist(H5Pcreate(H5P_GROUP_CREATE), what);
  check_status(H5Pset_link_creation_order(gcpl.id(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
               what);
  return make_group(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl.id(), H5P_DEFAULT), what);
}

// Describes dataset `dset` (at info.path): CF attributes `units` and
// `long_name` on it (what xarray shows), and /schema/<path> with string
// attributes `unit` and `meaning` (the map's table of contents).
void describe(hid_t file, hid_t dset, const FieldInfo& info) {
  write_string_attr(dset, "units", info.unit);
  write_string_attr(dset, "long_name", info.meaning);
  Handle g = create_ordered_group(file, "schema/" + info.path);
  write_string_attr(g.id(), "unit", info.unit);
  write_string_attr(g.id(), "meaning", info.meaning);
  g.close("closing /schema/" + info.path);
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

Handle message_type() {
  Handle t = make_type(H5Tcopy(H5T_C_S1), "string type");
  check_status(H5Tset_size(t.id(), kMessageLen), "string type");
  check_status(H5Tset_strpad(t.id(), H5T_STR_NULLPAD), "string type");
  return t;
}

// Writes a whole float64 dataset (independent I/O: rank 0 alone).
void write_doubles(hid_t dset, hid_t dxpl, const double* data, const std::string& what) {
  check_status(H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, dxpl, data), what);
}

// /cases/<column> from the cases, taken by range in blocks of 65536 rows
// (memory independent of the number of cases).
void write_case_columns(const std::vector<Handle>& sets, hid_t dxpl, std::size_t n,
                        const MapFile::CaseRange& cases) {
  constexpr std::size_t kBlock = 65536;
  std::vector<study::StepRow> rows;
  std::vector<double> col;
  for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
    const std::size_t i1 = std::min(n, i0 + kBlock);
    cases(i0, i1, rows);
    if (rows.size() != i1 - i0) throw std::invalid_argument("MapFile::create: case count");
    const hsize_t start = i0, count = i1 - i0;
    col.resize(rows.size());
    for (std::size_t c = 0; c < sets.size(); ++c) {
      const std::string what = std::string("writing /cases/") + kCaseColumns[c];
      for (std::size_t i = 0; i < rows.size(); ++i) {
        const study::StepRow& s = rows[i];
        const double vals[6] = {s.d, s.R, s.tau, s.v, s.v1, s.G};
        col[i] = vals[c];
      }
      Handle fspace = make_space(H5Dget_space(sets[c].id()), what);
      check_status(
          H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, &start, nullptr, &count, nullptr), what);
      Handle mspace = make_space(H5Screate_simple(1, &count, nullptr), what);
      check_status(
          H5Dwrite(sets[c].id(), H5T_NATIVE_DOUBLE, mspace.id(), fspace.id(), dxpl, col.data()),
          what);
    }
  }
}

void write_text_dataset(hid_t loc, const std::string& name, const std::string& text) {
  Handle d = create_dataset(loc, name, H5T_STD_U8LE, {std::max<std::size_t>(text.size(), 1)});
  std::string buf = text.empty() ? std::string(1, '\0') : text;
  check_status(H5Dwrite(d.id(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()),
               "writing /" + name);
  d.close("closing /" + name);
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
  const std::uint64_t n = spec.n_cases;
  std::uint64_t per_case = sizeof(kCaseColumns) / sizeof(kCaseColumns[0]) * 8 +
                           row_fields().size() * 8 + 1 /* status */ + kMessageLen;
  if (spec.timeseries)
    per_case += sizeof(kSeriesNames) / sizeof(kSeriesNames[0]) * 8 *
                static_cast<std::uint64_t>(spec.samples);
  std::uint64_t grid = 0;
  for (const auto& v : spec.grid.values)
    grid += 8 * v.size();
  // superblock, object headers, attributes and B-trees: about 32 KiB measured,
  // plus about 40 KiB for /schema, the datasets' units and dimension scales
  return n * per_case + grid + 2 * static_cast<std::uint64_t>(text_bytes) + 128 * 1024;
}

void MapFile::create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const std::vector<study::StepRow>& cases) {
  if (cases.size() != spec.n_cases) throw std::invalid_argument("MapFile::create: case count");
  create(comm, path, spec, prov,
         [&cases](std::size_t i0, std::size_t i1, std::vector<study::StepRow>& out) {
           out.assign(cases.begin() + static_cast<std::ptrdiff_t>(i0),
                      cases.begin() + static_cast<std::ptrdiff_t>(i1));
         });
}

void MapFile::create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                     const Provenance& prov, const CaseRange& cases) {
  if (spec.n_cases == 0) throw std::invalid_argument("MapFile::create: no cases");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  Handle fapl = mpio_fapl(comm, "creating " + path);
  Handle file = make_file(H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.id()),
                          "creating map file '" + path + "'");
  const hid_t f = file.id();
  const hsize_t n = spec.n_cases;

  // Metadata (collective: identical calls on every rank).
  write_string_attr(f, "mdrmap_schema", kSchema);
  write_string_attr(f, "program_version", prov.program_version);
  write_string_attr(f, "git_commit", prov.git_commit);
  write_string_attr(f, "created_utc", prov.created_utc);
  write_string_attr(f, "command_line", prov.command_line);
  write_string_attr(f, "units", prov.units);
  write_scalar_attr(f, "mpi_size", prov.mpi_size);
  write_scalar_attr(f, "n_cases", static_cast<long long>(spec.n_cases));
  write_scalar_attr(f, "samples", spec.samples);
  write_scalar_attr(f, "timeseries", spec.timeseries ? 1 : 0);
  // an attribute must fit in the object header (64 KiB): long configs live in /provenance only
  write_string_attr(f, "config_text",
                    prov.config_text.size() < 48 * 1024 ? prov.config_text
                                                        : "(long: see /provenance/config_text)");
  {
    Handle g = create_group(f, "provenance");
    write_text_dataset(f, "provenance/config_text", prov.config_text);
    write_text_dataset(f, "provenance/config_canonical", prov.config_canonical);
    g.close("closing /provenance");
  }
  // every object is closed before the file: a map is closed complete
  for (const char* group : {"cases", "results", "analytic", "residuals"})
    create_ordered_group(f, group).close(std::string("closing /") + group);
  // /schema/<group>/<name>: unit and meaning of every per-case dataset
  {
    Handle schema = create_ordered_group(f, "schema");
    for (const char* group : {"cases", "results", "analytic", "residuals", "timeseries", "grid"})
      if ((std::strcmp(group, "timeseries") != 0 || spec.timeseries) &&
          (std::strcmp(group, "grid") != 0 || !spec.grid.names.empty()))
        create_ordered_group(f, std::string("schema/") + group)
            .close(std::string("closing /schema/") + group);
    schema.close("closing /schema");
  }
  // named dimensions (xarray): /case for every per-case dataset, /sample for
  // the time series' second axis
  Handle case_dim = create_dimension(f, "case", n);
  std::vector<Handle> case_sets;
  for (const char* c : kCaseColumns) {
    const std::string dpath = std::string("cases/") + c;
    case_sets.push_back(create_dataset(f, dpath, H5T_IEEE_F64LE, {n}));
    describe(f, case_sets.back().id(), case_column_info("cases", c));
    attach(case_sets.back().id(), case_dim.id(), 0, dpath);
  }
  const auto per_case = [&](const std::string& dpath, hid_t type) {
    Handle d = create_dataset(f, dpath, type, {n});
    describe(f, d.id(), result_info(dpath));
    attach(d.id(), case_dim.id(), 0, dpath);
    d.close("closing /" + dpath);
  };
  for (const auto& name : row_fields())
    per_case(name, H5T_IEEE_F64LE);
  per_case("results/status", H5T_STD_I8LE);
  {
    Handle t = message_type();
    per_case("results/message", t.id());
  }
  if (spec.timeseries) {
    Handle g = create_ordered_group(f, "timeseries");
    Handle sample_dim = create_dimension(f, "sample", static_cast<hsize_t>(spec.samples));
    for (const char* s : kSeriesNames) {
      const std::string dpath = std::string("timeseries/") + s;
      Handle d = create_dataset(f, dpath, H5T_IEEE_F64LE, {n, static_cast<hsize_t>(spec.samples)});
      describe(f, d.id(), result_info(dpath));
      attach(d.id(), case_dim.id(), 0, dpath);
      attach(d.id(), sample_dim.id(), 1, dpath);
      d.close("closing /" + dpath);
    }
    sample_dim.close("closing /sample");
    g.close("closing /timeseries");
  }
  case_dim.close("closing /case");
  std::vector<Handle> grid_sets;
  if (!spec.grid.names.empty()) {
    Handle g = create_ordered_group(f, "grid");
    std::string axes;
    std::vector<long long> shape, logs;
    for (std::size_t i = 0; i < spec.grid.names.size(); ++i) {
      const std::string& a = spec.grid.names[i];
      axes += (i ? "," : "") + a;
      shape.push_back(static_cast<long long>(spec.grid.values[i].size()));
      logs.push_back(spec.grid.logarithmic[i]);
      grid_sets.push_back(
          create_dataset(f, "grid/" + a, H5T_IEEE_F64LE, {spec.grid.values[i].size()}));
      // a coordinate variable: the dimension `a` of group /grid, with its values
      describe(f, grid_sets.back().id(), case_column_info("grid", a));
      check_status(H5DSset_scale(grid_sets.back().id(), a.c_str()),
                   "making /grid/" + a + " a dimension scale");
    }
    write_string_attr(g.id(), "axes", axes);
    write_int_array_attr(g.id(), "shape", shape);
    write_int_array_attr(g.id(), "log", logs);
    g.close("closing /grid");
  }
  // Raw data known up front: rank 0 writes it (independent I/O).
  Handle dxpl = make_plist(H5Pcreate(H5P_DATASET_XFER), "transfer property list");
  check_status(H5Pset_dxpl_mpio(dxpl.id(), H5FD_MPIO_INDEPENDENT), "independent transfer");
  if (rank == 0) {
    write_case_columns(case_sets, dxpl.id(), spec.n_cases, cases);
    for (std::size_t i = 0; i < grid_sets.size(); ++i)
      write_doubles(grid_sets[i].id(), dxpl.id(), spec.grid.values[i].data(), "writing /grid");
  }
  for (auto& h : case_sets)
    h.close("closing /cases");
  for (auto& h : grid_sets)
    h.close("closing /grid");
  file.close("closing " + path);
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
      if (schema == kSchema) return true;
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
                               static_cast<std::uint64_t>(samples),
                               timeseries ? 1u : 0u,
                               status,
                               message,
                               fields.size(),
                               series.size()};
  v.insert(v.end(), fields.begin(), fields.end());
  v.insert(v.end(), series.begin(), series.end());
  return v;
}

MapLayout MapLayout::unpack(const std::vector<std::uint64_t>& v) {
  if (v.size() < 7 || v.size() != 7 + v[5] + v[6])
    throw std::invalid_argument("MapLayout::unpack: bad size");
  MapLayout m;
  m.n_cases = v[0];
  m.samples = static_cast<long>(v[1]);
  m.timeseries = v[2] != 0;
  m.status = v[3];
  m.message = v[4];
  const auto nf = static_cast<long>(v[5]);
  m.fields.assign(v.begin() + 7, v.begin() + 7 + nf);
  m.series.assign(v.begin() + 7 + nf, v.end());
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

} // namespace

MapLayout MapFile::read_layout(const std::string& path, std::vector<std::int8_t>* status) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw H5Error("cannot stat '" + path + "': " + std::strerror(errno));
  const auto file_size = static_cast<std::uint64_t>(st.st_size);
  Handle file = make_file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                          "opening map file '" + path + "'");
  const hid_t f = file.id();
  if (!has_attr(f, "mdrmap_schema") || read_string_attr(f, "mdrmap_schema") != kSchema)
    throw H5Error("'" + path + "' is not an mdrmap map of schema " + kSchema);
  {
    Handle fcpl = make_plist(H5Fget_create_plist(f), "file creation properties");
    hsize_t userblock = 0;
    check_status(H5Pget_userblock(fcpl.id(), &userblock), "file creation properties");
    if (userblock != 0) throw H5Error("'" + path + "' has a user block");
  }
  MapLayout m;
  const long long n = read_ll_attr(f, "n_cases"), samples = read_ll_attr(f, "samples");
  if (n < 1 || samples < 2) throw H5Error("attributes n_cases or samples out of range");
  m.n_cases = static_cast<std::uint64_t>(n);
  m.samples = static_cast<long>(samples);
  m.timeseries = read_ll_attr(f, "timeseries") != 0;
  const hsize_t N = m.n_cases;
  for (const auto& name : row_fields())
    m.fields.push_back(raw_offset(f, name, H5T_IEEE_F64LE, {N}, file_size));
  m.status = raw_offset(f, "results/status", H5T_STD_I8LE, {N}, file_size);
  {
    Handle t = message_type();
    m.message = raw_offset(f, "results/message", t.id(), {N}, file_size);
  }
  if (m.timeseries)
    for (const char* s : kSeriesNames)
      m.series.push_back(raw_offset(f, std::string("timeseries/") + s, H5T_IEEE_F64LE,
                                    {N, static_cast<hsize_t>(m.samples)}, file_size));
  if (status) {
    status->assign(m.n_cases, 0);
    Handle d = make_dataset(H5Dopen2(f, "results/status", H5P_DEFAULT), "opening /results/status");
    check_status(H5Dread(d.id(), H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, status->data()),
                 "reading /results/status");
    d.close("closing /results/status");
  }
  file.close("closing '" + path + "'");
  return m;
}

// ---- RowWriter ------------------------------------------------------------------

RowWriter::RowWriter(const std::string& path, MapLayout layout)
    : path_(path), layout_(std::move(layout)) {
  // the file stores little-endian float64: raw rows are written as in memory
  const std::uint16_t probe = 1;
  unsigned char first_byte = 0;
  std::memcpy(&first_byte, &probe, 1);
  if (first_byte != 1) throw std::runtime_error("writing maps needs a little-endian host");
  if (layout_.fields.size() != row_fields().size() ||
      layout_.series.size() != (layout_.timeseries ? std::size(kSeriesNames) : 0))
    throw std::invalid_argument("RowWriter: layout does not match this program's fields");
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0)
    throw std::runtime_error("cannot open '" + path + "' for writing: " + std::strerror(errno));
}

bool RowWriter::lock(long* holder) {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET; // l_start = l_len = 0: the whole file
  if (::fcntl(fd_, F_SETLK, &fl) == 0) return true;
  if (errno != EACCES && errno != EAGAIN) return true; // no locking here (ENOLCK, ...)
  struct flock probe {};
  probe.l_type = F_WRLCK;
  probe.l_whence = SEEK_SET;
  if (holder) *holder = ::fcntl(fd_, F_GETLK, &probe) == 0 ? static_cast<long>(probe.l_pid) : 0;
  return false;
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
  std::vector<double> col(count);
  const auto& names = row_fields();
  for (std::size_t k = 0; k < names.size(); ++k) {
    for (std::size_t i = 0; i < count; ++i)
      col[i] = rows[i].values.at(k);
    pwrite_all(col.data(), count * 8, layout_.fields[k] + 8 * first, "/" + names[k]);
  }
  if (layout_.timeseries) {
    const auto S = static_cast<std::size_t>(layout_.samples);
    std::vector<double> block(count * S);
    for (std::size_t q = 0; q < std::size(kSeriesNames); ++q) {
      for (std::size_t i = 0; i < count; ++i) {
        const std::vector<double>* src[] = {&rows[i].t, &rows[i].FN, &rows[i].Fx, &rows[i].mu,
                                            &rows[i].a2};
        const auto& v = *src[q];
        if (v.size() == S)
          std::copy(v.begin(), v.end(), block.begin() + static_cast<long>(i * S));
        else
          std::fill_n(block.begin() + static_cast<long>(i * S), S, 0.0); // failed case
      }
      pwrite_all(block.data(), block.size() * 8, layout_.series[q] + 8 * S * first,
                 std::string("/timeseries/") + kSeriesNames[q]);
    }
  }
  std::vector<char> msgs(count * kMessageLen, '\0');
  for (std::size_t i = 0; i < count; ++i)
    std::memcpy(&msgs[i * kMessageLen], rows[i].message.data(),
                std::min(rows[i].message.size(), kMessageLen - 1));
  pwrite_all(msgs.data(), msgs.size(), layout_.message + kMessageLen * first, "/results/message");
  // status last: a case counts as done only once everything else is written
  std::vector<std::int8_t> st(count);
  for (std::size_t i = 0; i < count; ++i)
    st[i] = rows[i].status;
  pwrite_all(st.data(), count, layout_.status + first, "/results/status");
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

} // namespace mdrmap::io
