#include "app/simulate_cmd.hpp"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <new>
#include <optional>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/program_options.hpp>

#include "app/csv_output.hpp"
#include "core/error_metric.hpp"
#include "core/exact.hpp"
#include "core/scene.hpp"
#include "core/solver.hpp"
#include "mdrmap/version.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
namespace {

constexpr const char* kPrefix = "mdrmap simulate: error: ";
constexpr double kDefaultRtol = 1e-4;
constexpr long kDefaultSamples = 201;
constexpr double kExactReferenceRtol = 1e-12;

/// Every option, in the order of the help text; `required` ones have no default.
struct OptionSpec {
  const char* name;
  bool required;
  const char* meaning; ///< used in "missing" messages
};

constexpr OptionSpec kOptions[] = {
    {"d", true, "the indentation depth, a finite number > 0"},
    {"R", true, "the radius of curvature of the indenter, a finite number > 0"},
    {"tau", true, "the relaxation time eta/G, a finite number >= 0"},
    {"v", true, "the sliding velocity before the step, a finite number > 0"},
    {"v1", true, "the sliding velocity after the step, a finite number >= 0"},
    {"G", false, ""},
    {"t-end", false, ""},
    {"samples", false, ""},
    {"rtol", false, ""},
    {"solver", false, ""},
    {"output", false, ""},
};

std::string all_option_names() {
  std::string s;
  for (const auto& o : kOptions) {
    s += "--";
    s += o.name;
    s += ", ";
  }
  return s + "--help";
}

/// Keeps a message on one line: control characters become visible escapes.
std::string one_line(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (c == '\t')
      out += "\\t";
    else if (static_cast<unsigned char>(c) < 0x20)
      out += '?';
    else
      out += c;
  }
  return out;
}

/// The value as typed, quoted only when it would otherwise be unreadable.
std::string shown(const std::string& text) {
  if (text.empty()) return "an empty string";
  if (text.find_first_of(" \t\n\r\f\v',") != std::string::npos) return "'" + text + "'";
  return text;
}

int report_bad_input(const std::string& option, const std::string& what) {
  std::fprintf(stderr, "%s--%s: %s\n", kPrefix, one_line(option).c_str(), one_line(what).c_str());
  return kExitBadInput;
}

int report_bad_input_raw(const std::string& what) {
  std::fprintf(stderr, "%s%s\n", kPrefix, one_line(what).c_str());
  return kExitBadInput;
}

int report_runtime(const std::string& what) {
  std::fprintf(stderr, "%s%s\n", kPrefix, one_line(what).c_str());
  return kExitRuntime;
}

/// Strict decimal (or hex) floating-point number, the whole text. "nan" and
/// "inf" parse; the core validation then rejects them with the allowed range.
double parse_double(const char* option, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const bool whole = !text.empty() && end != begin && *end == '\0' &&
                     std::strchr(" \t\n\r\f\v", text.front()) == nullptr;
  if (!whole) throw InvalidInput(option, "must be a number, got " + shown(text));
  if (errno == ERANGE && std::isinf(x))
    throw InvalidInput(option,
                       "must be a finite number, got " + text + " (too large for a double)");
  return x;
}

/// Strict integer: optional sign and decimal digits only.
long parse_samples(const std::string& text) {
  const std::string allowed =
      "must be an integer from 2 to " + std::to_string(kMaxSamples) + ", got " + shown(text);
  std::size_t i = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
  if (i >= text.size()) throw InvalidInput("samples", allowed);
  for (; i < text.size(); ++i)
    if (text[i] < '0' || text[i] > '9') throw InvalidInput("samples", allowed);
  errno = 0;
  const long n = std::strtol(text.c_str(), nullptr, 10);
  if (errno == ERANGE) throw InvalidInput("samples", allowed);
  return n;
}

struct SimulateArgs {
  Scene scene;
  Protocol protocol;
  SolverKind solver = SolverKind::Auto;
  double rtol = kDefaultRtol;
  std::string output; ///< empty or "-": stdout
};

/// Parses and validates the command line. Throws InvalidInput, or lets
/// boost::program_options errors through for the caller to translate.
SimulateArgs parse_args(const std::vector<std::string>& args) {
  po::options_description desc;
  for (const auto& o : kOptions)
    desc.add_options()(o.name, po::value<std::string>());
  desc.add_options()("help", "");

  const int style = po::command_line_style::unix_style & ~po::command_line_style::allow_guessing;
  const po::parsed_options parsed =
      po::command_line_parser(args).options(desc).style(style).allow_unregistered().run();

  // Unknown options and stray positional arguments.
  const std::vector<std::string> stray =
      po::collect_unrecognized(parsed.options, po::include_positional);
  if (!stray.empty()) {
    const std::string& tok = stray.front();
    if (tok.size() > 1 && tok[0] == '-') {
      std::string name = tok.substr(0, tok.find('='));
      name.erase(0, name.find_first_not_of('-'));
      throw InvalidInput(name, "not an option of mdrmap simulate (options are case-sensitive: " +
                                   all_option_names() + "), got " + tok);
    }
    throw InvalidInput("", "unexpected argument " + shown(tok) +
                               "; every value must follow its option, e.g. --d 0.1");
  }

  po::variables_map vm;
  po::store(parsed, vm);
  po::notify(vm);

  for (const auto& o : kOptions)
    if (o.required && !vm.count(o.name))
      throw InvalidInput(o.name, std::string("is required: ") + o.meaning + ", got nothing");

  auto text = [&](const char* name) { return vm[name].as<std::string>(); };

  SimulateArgs a;
  a.scene.d = parse_double("d", text("d"));
  a.scene.R = parse_double("R", text("R"));
  a.scene.tau = parse_double("tau", text("tau"));
  a.scene.v = parse_double("v", text("v"));
  a.scene.v1 = parse_double("v1", text("v1"));
  if (vm.count("G")) a.scene.G = parse_double("G", text("G"));
  std::optional<double> t_end;
  if (vm.count("t-end")) t_end = parse_double("t-end", text("t-end"));
  a.protocol.samples = vm.count("samples") ? parse_samples(text("samples")) : kDefaultSamples;
  if (vm.count("rtol")) a.rtol = parse_double("rtol", text("rtol"));
  if (vm.count("solver")) a.solver = parse_solver(text("solver"));
  if (vm.count("output")) a.output = text("output");

  validate(a.scene);
  a.protocol.t_end = t_end ? *t_end : default_t_end(a.scene);
  validate(a.protocol);
  validate_rtol(a.rtol);
  if (vm.count("output") && a.output.empty())
    throw InvalidInput("output", "must be a file path (or - for stdout), got an empty string");
  return a;
}

/// Output into FILE.tmp.<pid> next to FILE, renamed over FILE on commit();
/// the temporary is removed if commit() is never reached.
class AtomicFile {
public:
  /// Throws InvalidInput("output") if the file cannot be created.
  explicit AtomicFile(const std::string& path)
      : path_(path), tmp_(path + ".tmp." + std::to_string(static_cast<long>(::getpid()))) {
    const std::string fail = "must be a writable file in an existing directory";
    if (path.back() == '/')
      throw InvalidInput("output", fail + " (the path names a directory), got " + path);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      throw InvalidInput("output", fail + " (the path is a directory), got " + path);
    const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
      const int err = errno;
      throw InvalidInput("output", fail + " (" + std::strerror(err) + "), got " + path);
    }
    file_ = ::fdopen(fd, "w");
    if (!file_) {
      const int err = errno;
      ::close(fd);
      ::unlink(tmp_.c_str());
      throw std::runtime_error("cannot open " + tmp_ + ": " + std::strerror(err));
    }
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (file_) std::fclose(file_);
    if (!committed_) ::unlink(tmp_.c_str());
  }

  std::FILE* get() const { return file_; }

  /// Flushes, closes and renames over the target. Throws std::runtime_error.
  void commit() {
    const bool write_error = std::fflush(file_) != 0 || std::ferror(file_) != 0;
    const int err_write = errno;
    const int rc = std::fclose(file_);
    const int err_close = errno;
    file_ = nullptr;
    if (write_error || rc != 0)
      throw std::runtime_error("--output: writing " + tmp_ +
                               " failed: " + std::strerror(write_error ? err_write : err_close));
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
      const int err = errno;
      throw std::runtime_error("--output: renaming " + tmp_ + " to " + path_ +
                               " failed: " + std::strerror(err));
    }
    committed_ = true;
  }

private:
  std::string path_, tmp_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

int run(const SimulateArgs& a) {
  std::optional<AtomicFile> file; // created before the solver runs: a bad path fails fast
  const bool to_stdout = a.output.empty() || a.output == "-";
  if (!to_stdout) file.emplace(a.output);

  const auto start = std::chrono::steady_clock::now();
  const RunResult res = run_case(a.scene, a.protocol, a.solver, a.rtol);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  SimulateRecord rec;
  rec.version = kVersion;
  rec.commit = kGitCommit;
  rec.solver = res.info.solver.empty() ? solver_name(a.solver) : res.info.solver;
  rec.rtol = a.rtol;
  rec.info = res.info;
  rec.wall_seconds = wall;
  rec.scene = a.scene;
  rec.protocol = a.protocol;
  if (rec.solver != "exact") {
    const RunResult ref = run_exact(a.scene, a.protocol, kExactReferenceRtol);
    rec.error_vs_exact = case_error(res.series, ref.series, a.scene).max();
  }

  if (file) {
    write_simulate_csv(file->get(), rec, res.series);
    file->commit();
  } else {
    write_simulate_csv(stdout, rec, res.series);
    if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
      const int err = errno;
      return report_runtime(std::string("writing to stdout failed: ") + std::strerror(err));
    }
  }
  return kExitOk;
}

} // namespace

std::string simulate_help() {
  const std::string max_samples = std::to_string(kMaxSamples);
  return R"(Usage: mdrmap simulate --d D --R R --tau TAU --v V --v1 V1 [options]

Computes the response of a viscoelastic contact to a sudden change of the
sliding velocity, in the method of dimensionality reduction (MDR). A rigid
parabolic indenter (MDR profile x^2/R) is held at indentation depth d on a
Kelvin foundation (shear modulus G, relaxation time tau = eta/G). It slides
steadily at velocity v until t = 0, and at v1 from then on. The command prints
the stationary state before the step and, at N instants from t = 0 (just after
the step) to T, the normal force FN, the tangential (friction) force Fx,
positive when it resists the motion, the friction coefficient mu = Fx/FN, and
the trailing edge a2 of the contact. In the frame of the indenter the contact
occupies [-a1, a2]; the leading edge stays at -a1, a1 = sqrt(R d).

Any consistent units work (e.g. mm, s, MPa): d, R, a2 are lengths, tau and t
times, v and v1 length/time; forces come out in units of G * length^2.

Required options:
  --d D          indentation depth (length), > 0
  --R R          radius of curvature of the parabolic indenter (length), > 0
  --tau TAU      relaxation time eta/G of the foundation (time), >= 0;
                 0 is the purely elastic limit
  --v V          sliding velocity before the step (length/time), > 0
  --v1 V1        sliding velocity after the step (length/time), >= 0;
                 0 stops the indenter, v1 > v is a speed-up

Other options:
  --G G          shear modulus of the foundation (force/length^2), > 0.
                 Default: 1
  --t-end T      end of the sampled time window after the step (time), > 0.
                 Default: 6 tau; for tau = 0, 6 a1 / min(v, v1) (6 a1 / v if
                 v1 = 0)
  --samples N    number of output instants t_k = k T/(N-1), k = 0..N-1;
                 an integer from 2 to )" +
         max_samples + R"(. Default: 201
  --rtol E       target accuracy: bound on the case error (below), a number
                 in (0, 0.1]. Default: 1e-4
  --solver S     auto, exact, mdr or baseline. Default: auto
                   exact     continuum (dx -> 0) solution, semi-analytic
                   mdr       discrete MDR element simulation with error control
                   baseline  the paper's brute-force method, for reference
                   auto      the cheapest solver that meets rtol (exact here)
  --output FILE  write to FILE instead of stdout. FILE is replaced at once
                 when the run succeeds and left untouched when it fails;
                 "-" means stdout
  --help         print this text and exit

Output: comment lines starting with '#', then CSV with a header line.
  # mdrmap VERSION (COMMIT) simulate solver=NAME rtol=E error_estimate=...
      cells_per_a1=... elements=... steps=... element_updates=...
      root_solves=... wall_seconds=...            (all on one line)
  # scene d=... R=... tau=... v=... v1=... G=... t_end=T samples=N
      zeta=... zeta1=...                          (all on one line)
  # error_vs_exact=...     (solvers other than exact only: the case error
                            against the continuum solution)
  # pre FN=... Fx=... mu=... a2=...   (stationary state at v before the step)
  t,FN,Fx,mu,a2
  ... N rows, t = 0 to T ...
zeta = v tau / a1 and zeta1 = v1 tau / a1 are the dimensionless velocities.
The case error is the largest of max_k |q_k - q_ref,k| / max_k |q_ref,k| for
q = FN, Fx, mu and max_k |a2_k - a2_ref,k| / a1. error_estimate is the
solver's own bound on it. Numbers have 17 significant digits, so they read
back to the same double.

Example:
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 2 --v1 0.5 --output step.csv

Exit codes:
  0  success
  1  runtime failure (the solver or writing the output failed)
  2  bad input (one line on stderr names the option and what it allows)
)";
}

int simulate_main(const std::vector<std::string>& args) {
  for (const auto& arg : args) {
    if (arg == "--") break;
    if (arg == "--help" || arg == "-h") {
      std::fputs(simulate_help().c_str(), stdout);
      return std::fflush(stdout) == 0 ? kExitOk : kExitRuntime;
    }
  }

  SimulateArgs a;
  try {
    a = parse_args(args);
  } catch (const InvalidInput& e) {
    if (e.option().empty()) return report_bad_input_raw(e.what());
    return report_bad_input(e.option(), e.what());
  } catch (const po::multiple_occurrences& e) {
    return report_bad_input_raw(e.get_option_name() + ": may be given only once");
  } catch (const po::invalid_command_line_syntax& e) {
    std::string what;
    switch (e.kind()) {
    case po::invalid_syntax::missing_parameter:
      what = "needs a value, e.g. " + e.get_option_name() + " 1.5";
      break;
    case po::invalid_syntax::empty_adjacent_parameter:
      what = "needs a value after '=', e.g. " + e.get_option_name() + "=1.5";
      break;
    case po::invalid_syntax::extra_parameter:
      what = "takes no value";
      break;
    default:
      what = e.what();
      break;
    }
    return report_bad_input_raw(e.get_option_name() + ": " + what);
  } catch (const po::error_with_option_name& e) {
    const std::string name = e.get_option_name();
    if (name.empty()) return report_bad_input_raw(e.what());
    return report_bad_input_raw(name + ": " + e.what());
  } catch (const po::error& e) {
    return report_bad_input_raw(e.what());
  }

  try {
    return run(a);
  } catch (const InvalidInput& e) {
    if (e.option().empty()) return report_bad_input_raw(e.what());
    return report_bad_input(e.option(), e.what());
  } catch (const std::bad_alloc&) {
    return report_runtime("out of memory (try fewer --samples)");
  } catch (const std::exception& e) {
    return report_runtime(e.what());
  }
}

} // namespace mdrmap::app
