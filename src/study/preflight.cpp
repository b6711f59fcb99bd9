#include "study/preflight.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <utility>

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

// Rank 0's checks of the output path before anything is written.
void check_output(const StudyRequest& req) {
  const std::string& out = req.output;
  if (out.empty()) throw InvalidInput("output", "must name the map file to write");
  struct stat st {};
  const bool exists = ::stat(out.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode))
    throw InvalidInput("output", "'" + out + "' is a directory; give a file name");
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

// Cases of the study and the memory one rank needs for them, without
// building them: per case the row (6 doubles), its place in the to-do list,
// its status and rank 0's column buffer at creation; a case list's canonical
// text besides. Counting a case list streams its file.
std::pair<std::size_t, double> study_memory(const StudyConfig& cfg) {
  if (cfg.kind == StudyConfig::Kind::Grid) {
    const std::size_t n = case_count(cfg);
    return {n, 72.0 * static_cast<double>(n)};
  }
  std::ifstream in(cfg.cases_file, std::ios::binary);
  std::size_t lines = 0;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    lines += static_cast<std::size_t>(
        std::count(buf.begin(), buf.begin() + static_cast<long>(in.gcount()), '\n'));
  }
  return {lines, 200.0 * static_cast<double>(lines)}; // unreadable: 0, expand_cases says why
}

// Refuses, before anything is built or written, a study whose cases would
// not fit in the memory of this node (ranks_here ranks each hold them all).
void check_memory(const StudyConfig& cfg, int ranks_here) {
  const auto [n_cases, per_rank] = study_memory(cfg);
  const double need = per_rank * ranks_here;
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

// The map a study needs: its size, and the axes of a grid.
io::MapSpec map_spec(const StudyConfig& cfg, std::size_t n_cases) {
  io::MapSpec spec;
  spec.n_cases = n_cases;
  spec.samples = cfg.run.samples;
  spec.timeseries = cfg.run.timeseries;
  if (cfg.kind == StudyConfig::Kind::Grid) {
    for (const auto& ax : cfg.axes) {
      spec.grid.names.push_back(ax.name);
      spec.grid.values.push_back(ax.values);
      spec.grid.logarithmic.push_back(ax.logarithmic ? 1 : 0);
    }
  }
  return spec;
}

} // namespace

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

StudyPlan preflight(MPI_Comm comm, const StudyRequest& req) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const StudyConfig& cfg = req.config;
  const int ranks_here = ranks_on_this_node(comm);
  StudyPlan plan;
  collectively(comm, [&] {
    plan.kind = parse_solver(cfg.run.solver);
    check_memory(cfg, ranks_here);
    plan.cases = expand_cases(cfg);
    plan.canon = canonical(cfg);
    plan.spec = map_spec(cfg, plan.cases.size());
    if (rank == 0) {
      check_output(req);
      if (req.resume)
        check_resume_matches(req, plan.canon);
      else
        check_space(req.output,
                    io::map_file_bytes(plan.spec, cfg.source_text.size() + plan.canon.size() +
                                                      req.command_line.size()));
    }
  });
  return plan;
}

} // namespace mdrmap::study::detail
