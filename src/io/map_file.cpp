#include "io/map_file.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace mdrmap::io {
namespace {

const char* const kSeriesNames[] = {"t", "FN", "Fx", "mu", "a2"};
const char* const kCaseColumns[] = {"d", "R", "tau", "v", "v1", "G"};

std::vector<std::string> make_fields() {
  std::vector<std::string> f;
  const char* q[] = {"FN", "Fx", "mu", "a2"};
  const char* when[] = {"pre", "jump", "post"};
  for (const char* group : {"results", "analytic", "residuals"}) {
    for (const char* w : when)
      for (const char* x : q)
        f.push_back(std::string(group) + "/" + x + "_" + w);
  }
  f.push_back("results/error_estimate");
  f.push_back("results/wall_seconds");
  for (const char* lim : {"FN_inf", "Fx_inf", "mu_inf", "mu_post_drop"}) {
    f.push_back(std::string("analytic/") + lim);
    f.push_back(std::string("residuals/") + lim);
  }
  return f;
}

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

Handle message_type() {
  Handle t = make_type(H5Tcopy(H5T_C_S1), "string type");
  check_status(H5Tset_size(t.id(), kMessageLen), "string type");
  check_status(H5Tset_strpad(t.id(), H5T_STR_NULLPAD), "string type");
  return t;
}

// Writes rows [first, first+count) x [0, width) of a 1-D or 2-D dataset.
void write_block(hid_t dset, hid_t mem_type, hid_t dxpl, std::size_t first, std::size_t count,
                 std::size_t width, const void* data, const std::string& what) {
  if (count == 0) return;
  Handle fspace = make_space(H5Dget_space(dset), what);
  const int rank = H5Sget_simple_extent_ndims(fspace.id());
  hsize_t start[2] = {first, 0}, cnt[2] = {count, width};
  check_status(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start, nullptr, cnt, nullptr),
               what);
  Handle mspace = make_space(H5Screate_simple(rank, cnt, nullptr), what);
  check_status(H5Dwrite(dset, mem_type, mspace.id(), fspace.id(), dxpl, data), what);
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

const std::vector<std::string>& row_fields() {
  static const std::vector<std::string> f = make_fields();
  return f;
}

std::size_t field_index(const std::string& name) {
  const auto& f = row_fields();
  const auto it = std::find(f.begin(), f.end(), name);
  if (it == f.end()) throw std::out_of_range("no map field " + name);
  return static_cast<std::size_t>(it - f.begin());
}

MapFile::~MapFile() = default;

void MapFile::open_datasets() {
  const hid_t f = file_.id();
  fields_.clear();
  for (const auto& name : row_fields())
    fields_.push_back(make_dataset(H5Dopen2(f, name.c_str(), H5P_DEFAULT), "opening /" + name));
  status_ = make_dataset(H5Dopen2(f, "results/status", H5P_DEFAULT), "opening /results/status");
  message_ = make_dataset(H5Dopen2(f, "results/message", H5P_DEFAULT), "opening /results/message");
  msg_type_ = message_type();
  series_.clear();
  if (timeseries_) {
    for (const char* s : kSeriesNames) {
      const std::string name = std::string("timeseries/") + s;
      series_.push_back(make_dataset(H5Dopen2(f, name.c_str(), H5P_DEFAULT), "opening /" + name));
    }
  }
  dxpl_ = make_plist(H5Pcreate(H5P_DATASET_XFER), "transfer property list");
  check_status(H5Pset_dxpl_mpio(dxpl_.id(), H5FD_MPIO_INDEPENDENT), "independent transfer");
}

MapFile MapFile::create(MPI_Comm comm, const std::string& path, const MapSpec& spec,
                        const Provenance& prov, const std::vector<Scene>& cases) {
  if (cases.size() != spec.n_cases) throw std::invalid_argument("MapFile::create: case count");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MapFile m;
  m.comm_ = comm;
  m.path_ = path;
  m.n_ = spec.n_cases;
  m.samples_ = spec.samples;
  m.timeseries_ = spec.timeseries;
  Handle fapl = mpio_fapl(comm, "creating " + path);
  m.file_ = make_file(H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.id()),
                      "creating map file '" + path + "'");
  const hid_t f = m.file_.id();
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
  }
  Handle gcases = create_group(f, "cases");
  std::vector<Handle> case_sets;
  for (const char* c : kCaseColumns)
    case_sets.push_back(create_dataset(f, std::string("cases/") + c, H5T_IEEE_F64LE, {n}));
  Handle gres = create_group(f, "results"), gan = create_group(f, "analytic"),
         gresid = create_group(f, "residuals");
  for (const auto& name : row_fields())
    create_dataset(f, name, H5T_IEEE_F64LE, {n});
  create_dataset(f, "results/status", H5T_STD_I8LE, {n});
  {
    Handle t = message_type();
    create_dataset(f, "results/message", t.id(), {n});
  }
  if (spec.timeseries) {
    Handle g = create_group(f, "timeseries");
    for (const char* s : kSeriesNames)
      create_dataset(f, std::string("timeseries/") + s, H5T_IEEE_F64LE,
                     {n, static_cast<hsize_t>(spec.samples)});
  }
  std::vector<Handle> grid_sets;
  if (!spec.grid.names.empty()) {
    Handle g = create_group(f, "grid");
    std::string axes;
    std::vector<long long> shape, logs;
    for (std::size_t i = 0; i < spec.grid.names.size(); ++i) {
      axes += (i ? "," : "") + spec.grid.names[i];
      shape.push_back(static_cast<long long>(spec.grid.values[i].size()));
      logs.push_back(spec.grid.logarithmic[i]);
      grid_sets.push_back(create_dataset(f, "grid/" + spec.grid.names[i], H5T_IEEE_F64LE,
                                         {spec.grid.values[i].size()}));
    }
    write_string_attr(g.id(), "axes", axes);
    write_int_array_attr(g.id(), "shape", shape);
    write_int_array_attr(g.id(), "log", logs);
  }
  m.open_datasets();

  // Raw data known up front: rank 0 writes it (independent I/O).
  if (rank == 0) {
    std::vector<double> col(cases.size());
    for (std::size_t c = 0; c < 6; ++c) {
      for (std::size_t i = 0; i < cases.size(); ++i) {
        const Scene& s = cases[i];
        const double vals[6] = {s.d, s.R, s.tau, s.v, s.v1, s.G};
        col[i] = vals[c];
      }
      write_block(case_sets[c].id(), H5T_NATIVE_DOUBLE, m.dxpl_.id(), 0, cases.size(), 1,
                  col.data(), std::string("writing /cases/") + kCaseColumns[c]);
    }
    for (std::size_t i = 0; i < grid_sets.size(); ++i)
      write_block(grid_sets[i].id(), H5T_NATIVE_DOUBLE, m.dxpl_.id(), 0, spec.grid.values[i].size(),
                  1, spec.grid.values[i].data(), "writing /grid");
  }
  for (auto& h : case_sets)
    h.close("closing /cases");
  for (auto& h : grid_sets)
    h.close("closing /grid");
  check_status(H5Fflush(f, H5F_SCOPE_GLOBAL), "flushing " + path);
  return m;
}

MapFile MapFile::open(MPI_Comm comm, const std::string& path) {
  MapFile m;
  m.comm_ = comm;
  m.path_ = path;
  Handle fapl = mpio_fapl(comm, "opening " + path);
  m.file_ =
      make_file(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id()), "opening map file '" + path + "'");
  const hid_t f = m.file_.id();
  if (!has_attr(f, "mdrmap_schema") || read_string_attr(f, "mdrmap_schema") != kSchema)
    throw H5Error("'" + path + "' is not an mdrmap map of schema " + kSchema);
  m.n_ = static_cast<std::size_t>(read_ll_attr(f, "n_cases"));
  m.samples_ = static_cast<long>(read_ll_attr(f, "samples"));
  m.timeseries_ = read_ll_attr(f, "timeseries") != 0;
  m.open_datasets();
  return m;
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

std::string MapFile::config_canonical() const {
  return read_text_dataset(file_.id(), "provenance/config_canonical");
}

std::vector<std::int8_t> MapFile::read_status() const {
  std::vector<std::int8_t> st(n_);
  if (n_ > 0)
    check_status(H5Dread(status_.id(), H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, dxpl_.id(), st.data()),
                 "reading /results/status");
  return st;
}

void MapFile::write_rows(std::size_t first, const std::vector<CaseRow>& rows) {
  const std::size_t count = rows.size();
  if (count == 0) return;
  if (first + count > n_) throw std::out_of_range("MapFile::write_rows beyond the case count");
  std::vector<double> col(count);
  const auto& names = row_fields();
  for (std::size_t k = 0; k < names.size(); ++k) {
    for (std::size_t i = 0; i < count; ++i)
      col[i] = rows[i].values.at(k);
    write_block(fields_[k].id(), H5T_NATIVE_DOUBLE, dxpl_.id(), first, count, 1, col.data(),
                "writing /" + names[k]);
  }
  if (timeseries_) {
    const auto S = static_cast<std::size_t>(samples_);
    std::vector<double> block(count * S);
    for (std::size_t q = 0; q < 5; ++q) {
      for (std::size_t i = 0; i < count; ++i) {
        const std::vector<double>* src[] = {&rows[i].t, &rows[i].FN, &rows[i].Fx, &rows[i].mu,
                                            &rows[i].a2};
        const auto& v = *src[q];
        if (v.size() == S)
          std::copy(v.begin(), v.end(), block.begin() + static_cast<long>(i * S));
        else
          std::fill_n(block.begin() + static_cast<long>(i * S), S, 0.0); // failed case
      }
      write_block(series_[q].id(), H5T_NATIVE_DOUBLE, dxpl_.id(), first, count, S, block.data(),
                  std::string("writing /timeseries/") + kSeriesNames[q]);
    }
  }
  std::vector<char> msgs(count * kMessageLen, '\0');
  for (std::size_t i = 0; i < count; ++i)
    std::memcpy(&msgs[i * kMessageLen], rows[i].message.data(),
                std::min(rows[i].message.size(), kMessageLen - 1));
  write_block(message_.id(), msg_type_.id(), dxpl_.id(), first, count, 1, msgs.data(),
              "writing /results/message");
  // status last: a case counts as done only once everything else is on disk
  std::vector<std::int8_t> st(count);
  for (std::size_t i = 0; i < count; ++i)
    st[i] = rows[i].status;
  write_block(status_.id(), H5T_NATIVE_INT8, dxpl_.id(), first, count, 1, st.data(),
              "writing /results/status");
}

void MapFile::close() {
  if (!file_) return;
  fields_.clear();
  series_.clear();
  status_.close("closing /results/status");
  message_.close("closing /results/message");
  msg_type_.reset();
  dxpl_.reset();
  check_status(H5Fflush(file_.id(), H5F_SCOPE_GLOBAL), "flushing " + path_);
  file_.close("closing " + path_);
}

} // namespace mdrmap::io
