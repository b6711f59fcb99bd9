#include "study/preflight.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include "study/case_columns.hpp"
#include "study/columns.hpp"

namespace mdrmap::study::detail {
namespace {

// First line where two texts differ, for the resume refusal message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::size_t i = 0, line = 1, start = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) {
    if (a[i] == '\n') ++line, start = i + 1;
    ++i;
  }
  auto line_of = [&](const std::string& s) {
    const std::size_t end = s.find('\n', start);
    return s.substr(start, end == std::string::npos ? std::string::npos : end - start);
  };
  return "stored '" + line_of(a) + "', now '" + line_of(b) + "'";
}

// Refuses to continue a map of an earlier schema (it is a map: is_map).
void check_schema(const std::string& out) {
  io::silence_hdf5_errors();
  const hid_t f = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return; // read_layout says why
  io::Handle file(f, H5Fclose);
  const std::string schema = io::read_string_attr(f, "mdrmap_schema");
  if (schema != io::kSchema)
    throw InvalidInput("resume", "'" + out + "' is an " + schema +
                                     " map, written by an earlier mdrmap; this version continues " +
                                     io::kSchema +
                                     " maps only: run the study again into a new map (or "
                                     "--overwrite it)");
}

// What a file that is not a regular file is, for a message.
const char* kind_of(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Refuses a map path that is not a regular file (or a new name), by stat
// alone: opening a FIFO would wait for a writer forever. A symbolic link to
// a regular file is taken (the map it names).
void check_regular(const std::string& out, const struct stat& st) {
  if (S_ISDIR(st.st_mode))
    throw InvalidInput("output", "'" + out + "' is a directory; give a file name");
  if (S_ISREG(st.st_mode)) return;
  struct stat lst {};
  const bool link = ::lstat(out.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode);
  throw InvalidInput("output", "'" + out + "' is " + (link ? "a symbolic link to " : "") +
                                   kind_of(st.st_mode) +
                                   ", not a regular file; a map must be a regular file (give a "
                                   "file name)");
}

// Rank 0's checks of the output path before anything is written or opened.
void check_output(const StudyRequest& req) {
  const std::string& out = req.output;
  if (out.empty()) throw InvalidInput("output", "must name the map file to write");
  struct stat st {};
  const bool exists = ::stat(out.c_str(), &st) == 0;
  if (exists) check_regular(out, st);
  const std::string dir = parent_dir(out);
  struct stat dst {};
  if (::stat(dir.c_str(), &dst) != 0)
    throw InvalidInput("output", "directory '" + dir + "' of '" + out + "' does not exist");
  if (!S_ISDIR(dst.st_mode))
    throw InvalidInput("output", "'" + dir + "' in '" + out + "' is not a directory");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InvalidInput("output", "no permission to write in directory '" + dir + "'");
  if (req.resume && req.overwrite)
    throw InvalidInput("resume", "--resume and --overwrite exclude each other");
  std::string why;
  if (req.resume) {
    if (!exists) throw InvalidInput("resume", "there is no map '" + out + "' to resume");
    if (!io::MapFile::is_map(out, &why))
      throw InvalidInput("resume", "'" + out + "' is " + why + "; refusing to touch it");
    check_schema(out);
    return;
  }
  if (!exists) return;
  if (!req.overwrite)
    throw InvalidInput("output", "'" + out +
                                     "' exists; pass --resume to continue it or --overwrite to "
                                     "replace it");
  if (!io::MapFile::is_map(out, &why))
    throw InvalidInput("overwrite", "'" + out + "' is " + why + "; refusing to replace it");
}

std::string format_bytes(double b) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (b >= 1024.0 && u < 5)
    b /= 1024.0, ++u;
  char buf[48];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", b, units[u]);
  return buf;
}

// Memory this machine can give without swapping (MemAvailable), 0 if unknown.
double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

// Memory a study needs per case, beyond what every rank needs anyway: rank 0
// holds the status of every case (1 byte) during the run; the map's /cases
// columns are written from the cases taken by range, the other ranks hold
// nothing per case. The sparse index of a case list (16 bytes per 4096
// cases) is negligible.
constexpr double kCreateBytesPerCase = 0.0;
constexpr double kRootBytesPerCase = 1.0;

// Refuses, before the map is created, a study whose cases would not fit in
// the memory of this node (ranks_here ranks).
void check_memory(std::size_t n_cases, int ranks_here) {
  const double need = static_cast<double>(n_cases) *
                      (kCreateBytesPerCase * static_cast<double>(ranks_here) + kRootBytesPerCase);
  const double have = available_memory_bytes();
  if (have > 0.0 && need > 0.5 * have)
    throw InvalidInput("config", "the study has " + std::to_string(n_cases) + " cases; its " +
                                     std::to_string(ranks_here) +
                                     " rank(s) on this node would need about " +
                                     format_bytes(need) + " of memory, more than half of the " +
                                     format_bytes(have) +
                                     " available; split the study or run fewer ranks per node");
}

// Refuses a new map that would not fit on its file system or under the
// file-size limit, before anything is written.
void check_space(const std::string& out, std::uint64_t bytes) {
  const std::string dir = parent_dir(out);
  const std::string need = format_bytes(static_cast<double>(bytes));
  struct rlimit lim {};
  if (::getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY &&
      bytes > static_cast<std::uint64_t>(lim.rlim_cur))
    throw InvalidInput("output", "the map '" + out + "' needs " + need +
                                     " but the file-size limit (ulimit -f) is " +
                                     format_bytes(static_cast<double>(lim.rlim_cur)));
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) == 0) {
    const double avail = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
    if (static_cast<double>(bytes) > avail)
      throw InvalidInput("output", "the map '" + out + "' needs " + need +
                                       " but the file system of '" + dir + "' has " +
                                       format_bytes(avail) +
                                       " free; free space, or write the map elsewhere");
  }
}

// A [run] line "solver = NAME" of an earlier mdrmap under today's name: the
// spectrum solver is row; a study of the retired mdr cannot resume (its cases
// would be finished by another solver).
std::string current_solver_line(const std::string& line, const std::string& map) {
  if (line.compare(0, 9, "solver = ") != 0) return line;
  const std::string name = line.substr(9, line.find_last_not_of("\r\n") - 8);
  if (name == "spectrum") return "solver = row" + line.substr(9 + name.size());
  if (name == "mdr")
    throw InvalidInput("resume", "'" + map +
                                     "' was written with solver mdr, which was retired; its "
                                     "cases cannot be finished by another solver: write a new "
                                     "map (solver = row or auto)");
  return line;
}

// The canonical text of a map of an earlier mdrmap under today's names: a
// [columns] line of an old spelling ("FN = ...", the prescribed load before
// it was named F0) as the table's name, and the [run] solver's old name, so
// that the map resumes as the same study (its /cases and /grid keep the names
// it was written with).
std::string with_current_names(const std::string& stored, const std::string& map) {
  std::string out;
  bool columns = false, run = false;
  std::size_t start = 0;
  while (start < stored.size()) {
    std::size_t end = stored.find('\n', start);
    end = end == std::string::npos ? stored.size() : end + 1;
    std::string line = stored.substr(start, end - start);
    start = end;
    if (!line.empty() && line[0] == '[') {
      columns = line.compare(0, 9, "[columns]") == 0;
      run = line.compare(0, 5, "[run]") == 0;
    } else if (run) {
      line = current_solver_line(line, map);
    } else if (columns) {
      const std::string key = line.substr(0, line.find(" ="));
      line = canonical_parameter_name(key) + line.substr(key.size());
    }
    out += line;
  }
  return out;
}

// Compares the study in an existing map with the requested one (rank 0,
// read-only, before the file is opened for writing).
void check_resume_matches(const StudyRequest& req, const std::string& canon) {
  io::silence_hdf5_errors();
  const hid_t f = H5Fopen(req.output.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw InvalidInput("resume", "cannot open '" + req.output + "' to resume it");
  io::Handle file(f, H5Fclose);
  std::string stored;
  try {
    stored = io::read_text_dataset(f, "provenance/config_canonical");
  } catch (const io::H5Error&) {
    throw InvalidInput("resume", "'" + req.output + "' has no readable study definition");
  }
  stored = with_current_names(stored, req.output);
  if (stored != canon)
    throw InvalidInput("config", "differs from the study stored in '" + req.output + "' (" +
                                     first_difference(stored, canon) +
                                     "); resume with the same config and options, or write a new "
                                     "map");
}

// Ranks of comm sharing this node's memory.
int ranks_on_this_node(MPI_Comm comm) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks_here = 1;
  MPI_Comm_size(node, &ranks_here);
  MPI_Comm_free(&node);
  return ranks_here;
}

} // namespace

// Unit and meaning of a grid axis: its column's range entry (the core's
// table, a segment's velocity or duration, or a ratio).
io::FieldInfo axis_info(const Axis& a) {
  return {"grid/" + stored_name(a), dim_name(column_spec(a.column).dim), column_meaning(a.column)};
}

// The map a study needs: its size, and the axes of a grid.
io::MapSpec map_spec(const StudyConfig& cfg, std::size_t n_cases) {
  io::MapSpec spec;
  spec.n_cases = n_cases;
  spec.segments = cfg.segments();
  spec.samples = cfg.run.samples;
  spec.by_force = cfg.by_force();
  spec.timeseries = cfg.run.timeseries;
  spec.case_params = case_parameter_info(cfg);
  if (cfg.kind == StudyConfig::Kind::Grid) {
    for (const auto& ax : cfg.axes) {
      spec.grid.names.push_back(stored_name(ax));
      spec.grid.values.push_back(ax.values);
      spec.grid.logarithmic.push_back(ax.logarithmic ? 1 : 0);
      spec.grid.info.push_back(axis_info(ax));
    }
  }
  return spec;
}

std::string bcast_from_root(MPI_Comm comm, std::string s) {
  int n = static_cast<int>(s.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  s.resize(static_cast<std::size_t>(n));
  MPI_Bcast(s.data(), n, MPI_CHAR, 0, comm);
  return s;
}

std::string parent_dir(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos) return ".";
  if (pos == 0) return "/";
  return path.substr(0, pos);
}

void bcast_from_root(MPI_Comm comm, std::vector<std::uint64_t>& v) {
  unsigned long long n = v.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  v.resize(static_cast<std::size_t>(n));
  MPI_Bcast(v.data(), static_cast<int>(n), MPI_UINT64_T, 0, comm);
}

StudyPlan preflight(MPI_Comm comm, const StudyRequest& req) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const StudyConfig& cfg = req.config;
  const int ranks_here = ranks_on_this_node(comm);
  StudyPlan plan;
  collectively(comm, [&] {
    plan.kind = parse_solver(cfg.run.solver);
    if (cfg.kind != StudyConfig::Kind::Grid) return;
    plan.cases.emplace(cfg);
    check_memory(plan.cases->size(), ranks_here); // (<= 1e9 cases: no overflow)
  });
  if (cfg.kind == StudyConfig::Kind::Cases) {
    std::vector<std::uint64_t> index;
    collectively(comm, [&] {
      if (rank == 0) index = scan_case_list(cfg, true).pack();
    });
    bcast_from_root(comm, index);
    plan.cases.emplace(cfg, CaseListIndex::unpack(index));
    collectively(comm, [&] { check_memory(plan.cases->size(), ranks_here); });
  }
  collectively(comm, [&] {
    plan.canon = plan.cases->canonical();
    plan.spec = map_spec(cfg, plan.cases->size());
    if (rank == 0) {
      check_output(req);
      if (req.resume)
        check_resume_matches(req, plan.canon);
      else
        check_space(req.output,
                    io::map_file_bytes(plan.spec, cfg.source_text.size() + plan.canon.size() +
                                                      cfg.run.material_text.size() +
                                                      req.command_line.size()));
    }
  });
  // every case of a grid checked (after the cheap size checks: 1e9 cases take
  // a while), each rank its share: the lowest failing rank's first failure is
  // the grid's first
  if (cfg.kind == StudyConfig::Kind::Grid)
    collectively(comm, [&] {
      const std::size_t n = plan.cases->size();
      const auto r = static_cast<std::size_t>(rank), p = static_cast<std::size_t>(size);
      check_grid_cases(cfg, n * r / p, n * (r + 1) / p);
    });
  return plan;
}

} // namespace mdrmap::study::detail
