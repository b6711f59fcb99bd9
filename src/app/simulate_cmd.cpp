#include "app/simulate_cmd.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <iterator>
#include <new>
#include <optional>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/program_options.hpp>

#include "app/csv_output.hpp"
#include "core/case.hpp"
#include "core/error_metric.hpp"
#include "core/events.hpp"
#include "core/exact.hpp"
#include "core/params.hpp"
#include "core/solver.hpp"
#include "mdrmap/version.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
namespace {

constexpr const char* kPrefix = "mdrmap simulate: error: ";
constexpr double kDefaultRtol = 1e-4;
constexpr double kExactReferenceRtol = 1e-12;
/// Under load the reference is the load solver at rtol * factor, not below the floor.
constexpr double kLoadReferenceFactor = 1e-3;
constexpr double kLoadReferenceFloor = 1e-9;

/// Options that are not case parameters of the table (core/params.hpp): the
/// history's two forms, the sampling's spacing and how to run.
constexpr const char* kHistoryOptions[] = {"v1", "t-end", "history"};
constexpr const char* kRunOptions[] = {"spacing", "rtol", "solver", "output"};

/// Every option, in the order of the help text: the table's case parameters,
/// the history, the table's sampling parameters, then the rest.
std::vector<std::string> option_names() {
  std::vector<std::string> names;
  for (const auto& p : case_parameters())
    if (p.part != Part::Sampling) names.emplace_back(p.name);
  names.insert(names.end(), std::begin(kHistoryOptions), std::end(kHistoryOptions));
  for (const auto& p : case_parameters())
    if (p.part == Part::Sampling) names.emplace_back(p.name);
  names.insert(names.end(), std::begin(kRunOptions), std::end(kRunOptions));
  return names;
}

std::string all_option_names() {
  std::string s;
  for (const auto& o : option_names())
    s += "--" + o + ", ";
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

// --- Numbers -------------------------------------------------------------------

/// Strict decimal (or hex) floating-point number, the whole text. "nan" and
/// "inf" parse; the range checks then reject them with the allowed range.
double parse_double(const std::string& option, const std::string& text) {
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

/// Strict integer for a count parameter: optional sign and decimal digits.
double parse_integer(const ParamSpec& spec, const std::string& text) {
  const std::string allowed = "must be " + spec.allowed() + ", got " + shown(text);
  std::size_t i = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
  if (i >= text.size()) throw InvalidInput(spec.name, allowed);
  for (; i < text.size(); ++i)
    if (text[i] < '0' || text[i] > '9') throw InvalidInput(spec.name, allowed);
  errno = 0;
  const long long n = std::strtoll(text.c_str(), nullptr, 10);
  if (errno == ERANGE) throw InvalidInput(spec.name, allowed);
  return static_cast<double>(n);
}

/// A table parameter's value from its text: parsed, checked against its range.
double parse_parameter(const ParamSpec& spec, const std::string& text) {
  const double x = spec.integer() ? parse_integer(spec, text) : parse_double(spec.name, text);
  spec.check(x);
  return x;
}

/// Checks x against a spec, blaming `option` (e.g. the segment spec "w" is
/// given as --v1 in the one-step shorthand).
void check_as(const std::string& option, const ParamSpec& spec, double x) {
  try {
    spec.check(x);
  } catch (const InvalidInput& e) {
    throw InvalidInput(option, e.what());
  }
}

// --- History -------------------------------------------------------------------

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? comma : comma - start));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

/// W or T of one segment: a number in its spec's range. `where` names the segment.
double segment_number(const std::string& where, const ParamSpec& spec, const std::string& text) {
  try {
    const double x = parse_double(spec.symbol, trimmed(text));
    spec.check(x);
    return x;
  } catch (const InvalidInput& e) {
    throw InvalidInput("history", where + ": " + spec.symbol + " " + e.what());
  }
}

/// One segment "W:T"; k is 1-based.
Segment parse_segment(std::size_t k, const std::string& item) {
  const std::string where = "segment " + std::to_string(k) + " '" + item + "'";
  const std::string form = "a segment is W:T, its velocity W then its duration T";
  const std::string tok = trimmed(item);
  if (tok.empty())
    throw InvalidInput("history", "segment " + std::to_string(k) +
                                      " is empty; segments W:T are separated by single commas, "
                                      "e.g. 0.1:10,0:100,1:10");
  const std::size_t colon = tok.find(':');
  if (colon == std::string::npos) throw InvalidInput("history", where + " has no ':'; " + form);
  if (tok.find(':', colon + 1) != std::string::npos)
    throw InvalidInput("history", where + " has more than one ':'; " + form);
  Segment s;
  s.w = segment_number(where, segment_velocity_spec(), tok.substr(0, colon));
  s.T = segment_number(where, segment_duration_spec(), tok.substr(colon + 1));
  return s;
}

/// "W1:T1,W2:T2,...": every token checked; throws InvalidInput("history").
std::vector<Segment> parse_history(const std::string& text) {
  if (trimmed(text).empty())
    throw InvalidInput("history", "must be one or more segments W:T separated by commas, e.g. "
                                  "0.1:10,0:100,1:10; got " +
                                      shown(text));
  const std::size_t n = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
  if (n > kMaxSegments)
    throw InvalidInput("history", "has " + std::to_string(n) + " segments; at most " +
                                      std::to_string(kMaxSegments) + " are allowed");
  std::vector<Segment> segments;
  const auto items = split_commas(text);
  for (std::size_t k = 0; k < items.size(); ++k)
    segments.push_back(parse_segment(k + 1, items[k]));
  return segments;
}

// --- Command line --------------------------------------------------------------

struct SimulateArgs {
  Case c;
  SolverKind solver = SolverKind::Auto;
  double rtol = kDefaultRtol;
  std::string output; ///< empty or "-": stdout
};

/// Parses the command line into option texts. Throws InvalidInput for stray
/// arguments, or lets boost::program_options errors through.
po::variables_map option_texts(const std::vector<std::string>& args) {
  po::options_description desc;
  for (const auto& name : option_names())
    desc.add_options()(name.c_str(), po::value<std::string>());
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
  return vm;
}

/// What the table says about a parameter, for help and "required" messages.
std::string describe(const ParamSpec& p) {
  return std::string(p.meaning) + " (" + dim_name(p.dim) + "), " + p.allowed();
}

void require_options(const po::variables_map& vm) {
  for (const auto& p : case_parameters())
    if (p.required && !vm.count(p.name))
      throw InvalidInput(p.name, "is required: " + describe(p) + ", got nothing");
  if (vm.count("v1") && vm.count("history"))
    throw InvalidInput("history", "cannot be combined with --v1: give either --history "
                                  "W1:T1,W2:T2,... or its one-segment shorthand --v1 V1 "
                                  "[--t-end T]");
  if (!vm.count("v1") && !vm.count("history"))
    throw InvalidInput("v1", "is required: the sliding velocity after t = 0 (length/time), " +
                                 segment_velocity_spec().allowed() +
                                 "; or give a whole history with --history W1:T1,W2:T2,...; "
                                 "got nothing");
  if (vm.count("t-end") && vm.count("history"))
    throw InvalidInput("t-end", "belongs to the shorthand --v1 V1 [--t-end T]; with --history "
                                "each segment W:T has its own duration");
}

/// Sets every table parameter from its option, or from the table's default
/// (0 for the members of a one_of group that are not given). An explicitly
/// given value is checked against its own range here, before the groups.
void read_case_parameters(const po::variables_map& vm, Case& c) {
  for (const auto& p : case_parameters()) {
    const double x =
        vm.count(p.name) ? parse_parameter(p, vm[p.name].as<std::string>()) : p.fallback;
    p.set(c, x);
  }
}

/// The members of the table's one_of group `group`, in the table's order.
std::vector<const ParamSpec*> group_members(const std::string& group) {
  std::vector<const ParamSpec*> members;
  for (const auto& q : case_parameters())
    if (q.one_of && group == q.one_of) members.push_back(&q);
  return members;
}

/// "--d D or --FN F0": the members with their symbols, `sep` between all
/// but the last two, `last_sep` between those.
std::string group_usage(const std::vector<const ParamSpec*>& members, const char* sep,
                        const char* last_sep) {
  std::string s;
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (i > 0) s += i + 1 == members.size() ? last_sep : sep;
    s += std::string("--") + members[i]->name + " " + members[i]->symbol;
  }
  return s;
}

/// Exactly one option of each one_of group (e.g. --d or --FN, the loading)
/// is given; otherwise one line naming the whole group. Raw message: no single
/// option is at fault.
void require_one_of_each_group(const po::variables_map& vm) {
  for (const auto& p : case_parameters()) {
    if (!p.one_of || group_members(p.one_of).front() != &p) continue; // each group once
    const auto members = group_members(p.one_of);
    std::string given;
    int n = 0;
    for (const ParamSpec* q : members) {
      if (!vm.count(q->name)) continue;
      given += (n++ ? " and --" : "--") + std::string(q->name);
    }
    if (n == 1) continue;
    std::string what;
    for (const ParamSpec* q : members)
      what += std::string(what.empty() ? "" : ", ") + "--" + q->name + " " + q->meaning;
    throw InvalidInput("", "give exactly one of " + group_usage(members, ", ", " or ") + " (the " +
                               p.one_of + ": " + what + "); got " +
                               (n == 0 ? std::string("none") : given));
  }
}

/// The history from --history, or the one segment of --v1 V1 [--t-end T];
/// every value is checked with the segment specs, the shorthand's reported as
/// --v1 / --t-end. Needs the case parameters set (the default window).
void read_history(const po::variables_map& vm, Case& c) {
  auto text = [&](const char* name) { return vm[name].as<std::string>(); };
  if (vm.count("history")) {
    c.history.segments = parse_history(text("history"));
    return;
  }
  const double v1 = parse_double("v1", text("v1"));
  check_as("v1", segment_velocity_spec(), v1);
  std::optional<double> t_end;
  if (vm.count("t-end")) {
    t_end = parse_double("t-end", text("t-end"));
    check_as("t-end", segment_duration_spec(), *t_end);
  }
  // the scales first (as for any case), then the window they give
  c.history.segments = {Segment{v1, 1.0}};
  validate(c);
  // the window's length scale: a1 = sqrt(R d) at fixed depth, the Hertz
  // radius a0 = sqrt(R d0) of F0 under load (tau = 0: Hertz at once, a1 = a0)
  const double a = c.edge_scale(), R = c.indenter.R, tau = c.material.tau, v = c.history.v0;
  const double d = c.loading.by_force() ? a * a / R : c.loading.d;
  const double T = t_end ? *t_end : default_step_duration(d, R, tau, v, v1);
  if (!t_end) {
    try {
      segment_duration_spec().check(T);
    } catch (const InvalidInput& e) {
      throw InvalidInput("t-end", std::string("the default window ") + e.what() +
                                      "; give --t-end or rescale the units");
    }
  }
  c.history.segments = {Segment{v1, T}};
}

Spacing parse_spacing(const std::string& text) {
  if (text == "linear") return Spacing::Linear;
  if (text == "log") return Spacing::Log;
  throw InvalidInput("spacing", "must be linear or log, got " + shown(text));
}

/// Refuses outputs beyond kMaxSamples rows in all.
void check_total_samples(const Case& c) {
  const double rows =
      static_cast<double>(c.sampling.samples) * static_cast<double>(c.history.size());
  if (rows > static_cast<double>(kMaxSamples))
    throw InvalidInput("samples", std::to_string(c.sampling.samples) + " per segment x " +
                                      std::to_string(c.history.size()) +
                                      " segments = " + format_number(rows) + " rows, more than " +
                                      std::to_string(kMaxSamples) + "; lower --samples");
}

/// Parses and validates the command line. Throws InvalidInput, or lets
/// boost::program_options errors through for the caller to translate.
SimulateArgs parse_args(const std::vector<std::string>& args) {
  const po::variables_map vm = option_texts(args);
  require_options(vm);
  auto text = [&](const char* name) { return vm[name].as<std::string>(); };

  SimulateArgs a;
  read_case_parameters(vm, a.c);
  require_one_of_each_group(vm);
  if (vm.count("spacing")) a.c.sampling.spacing = parse_spacing(text("spacing"));
  if (vm.count("log-decades") && a.c.sampling.spacing != Spacing::Log)
    throw InvalidInput("log-decades", "applies to --spacing log only; add --spacing log or "
                                      "drop --log-decades");
  read_history(vm, a.c);
  validate(a.c);
  check_total_samples(a.c);
  if (vm.count("rtol")) a.rtol = parse_double("rtol", text("rtol"));
  if (vm.count("solver")) a.solver = parse_solver(text("solver"));
  if (vm.count("output")) a.output = text("output");
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

/// For a solver other than the default: the case error against a reference.
/// At fixed depth the continuum solver at 1e-12; under load the default (load)
/// solver at a much tighter rtol (docs/design.md, "Error metric").
void add_reference_error(const SimulateArgs& a, const RunResult& res, SimulateRecord& rec) {
  if (!a.c.loading.by_force()) {
    if (rec.solver == "exact") return;
    const RunResult ref = run_exact(a.c, kExactReferenceRtol);
    rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
    return;
  }
  if (a.solver == SolverKind::Auto) return;
  rec.reference_rtol = std::max(a.rtol * kLoadReferenceFactor, kLoadReferenceFloor);
  const RunResult ref = run_case(a.c, SolverKind::Auto, rec.reference_rtol);
  rec.reference = ref.info.solver.empty() ? "auto" : ref.info.solver;
  rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
}

int run(const SimulateArgs& a) {
  std::optional<AtomicFile> file; // created before the solver runs: a bad path fails fast
  const bool to_stdout = a.output.empty() || a.output == "-";
  if (!to_stdout) file.emplace(a.output);

  const auto start = std::chrono::steady_clock::now();
  const RunResult res = run_case(a.c, a.solver, a.rtol);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  SimulateRecord rec;
  rec.version = kVersion;
  rec.commit = kGitCommit;
  rec.solver = res.info.solver.empty() ? solver_name(a.solver) : res.info.solver;
  rec.rtol = a.rtol;
  rec.info = res.info;
  rec.wall_seconds = wall;
  rec.c = a.c;
  rec.events = event_metrics(a.c, res.series);
  add_reference_error(a, res, rec);

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

// --- Help ----------------------------------------------------------------------

/// "  --name ARG" padded to the text column, then `text` wrapped to 79 columns.
std::string help_entry(const std::string& option, const std::string& text) {
  constexpr std::size_t kColumn = 17, kWidth = 79;
  std::string out = "  " + option;
  if (out.size() + 1 > kColumn)
    out += "\n" + std::string(kColumn, ' ');
  else
    out += std::string(kColumn - out.size(), ' ');
  std::size_t col = kColumn;
  std::size_t pos = 0;
  bool first = true;
  while (pos < text.size()) {
    std::size_t end = text.find(' ', pos);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(pos, end - pos);
    if (!first && col + 1 + word.size() > kWidth) {
      out += "\n" + std::string(kColumn, ' ');
      col = kColumn;
      first = true;
    }
    if (!first) out += ' ', ++col;
    out += word;
    col += word.size();
    first = false;
    pos = end + 1;
  }
  return out + "\n";
}

/// One help entry per table parameter of the sampling part or of the others.
std::string parameter_help(bool sampling) {
  std::string s;
  for (const auto& p : case_parameters()) {
    if ((p.part == Part::Sampling) != sampling) continue;
    std::string allowed = p.allowed();
    allowed[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(allowed[0])));
    std::string text = "(" + std::string(dim_name(p.dim)) + ") " + p.meaning + ". " + allowed;
    if (p.one_of)
      text += ". The " + std::string(p.one_of) + ": give exactly one of " +
              group_usage(group_members(p.one_of), ", ", " or ");
    else
      text += p.required ? ", required" : ". Default: " + format_number(p.fallback);
    s += help_entry(std::string("--") + p.name + " " + p.symbol, text);
  }
  return s;
}

/// The required options of the table, as the usage line gives them: each
/// one_of group as "(--d D | --FN F0)" where its first member stands.
std::string required_usage() {
  std::string s;
  for (const auto& p : case_parameters()) {
    if (p.required) s += std::string(" --") + p.name + " " + p.symbol;
    if (!p.one_of) continue;
    const auto members = group_members(p.one_of);
    if (members.front() == &p) s += " (" + group_usage(members, " | ", " | ") + ")";
  }
  return s;
}

std::string history_help() {
  const ParamSpec &w = segment_velocity_spec(), &T = segment_duration_spec();
  return help_entry("--v1 V1", "one step: the sliding velocity from t = 0 on (" +
                                   std::string(dim_name(w.dim)) + "), " + w.allowed() +
                                   "; 0 stops the indenter, V1 > V0 is a speed-up") +
         help_entry("--t-end T", "with --v1: how long the step is followed (" +
                                     std::string(dim_name(T.dim)) + "), " + T.allowed() +
                                     ". Default: 6 tau; for tau = 0, 6 a1/min(V0,V1) "
                                     "(6 a1/V0 if V1 = 0), a0 in place of a1 under --FN") +
         help_entry("--history W1:T1,W2:T2,...",
                    "segments one after another from t = 0: sliding velocity Wk (" +
                        std::string(dim_name(w.dim)) + "), " + w.allowed() + ", 0 is a hold; " +
                        "duration Tk (" + dim_name(T.dim) + "), " + T.allowed() + "; at most " +
                        std::to_string(kMaxSegments) +
                        " segments. --v1 V1 --t-end T is --history V1:T; give one of the two "
                        "forms, not both");
}

std::string sampling_help() {
  return parameter_help(true) +
         help_entry("--spacing S",
                    "linear or log: where the N instants of a segment k (start t_k, duration "
                    "T_k) lie. Default: linear") +
         "                   linear  t_k + j T_k/(N-1), j = 0..N-1\n"
         "                   log     t_k, then t_k + T_k 10^(-D (N-1-j)/(N-2)),\n"
         "                           j = 1..N-1 (D = --log-decades): a long hold and\n"
         "                           the transient at its start both resolved\n";
}

std::string output_help() {
  return R"(Output: comment lines starting with '#', then CSV with a header line.
  # mdrmap VERSION (COMMIT) simulate solver=NAME rtol=E error_estimate=...
      cells_per_a1=... elements=... steps=... element_updates=...
      root_solves=... wall_seconds=...            (all on one line)
  # case d=... R=... tau=... G=... v=... history=W1:T1,... spacing=linear
      samples=N log-decades=D zeta0=...           (all on one line: every
                                                   case parameter given, the
                                                   history; under --FN: FN=...
                                                   in place of d=..., and
                                                   a0=... before zeta0)
  # error_vs_exact=...     (solvers other than exact only: the case error
                            against the continuum solution)
  # error_vs_reference=... reference=NAME reference_rtol=...
                           (under --FN, solvers other than auto only: the
                            case error against the load solver at a 1000x
                            tighter rtol, at least 1e-9)
  # event k=K t=... w_before=... w_after=... mu_before=... mu_after=...
      mu_peak=... t_peak=... slip_peak=... mu_end=... mu_ss_before=...
      mu_ss_after=... D_c=... a=... a_minus_b=... b=...
                           (one line per segment K = 0, 1, ...: the change at
                            its start, see below)
  # pre FN=... Fx=... mu=... a2=...   (stationary state at V0 before t = 0;
                                       under --FN also d=... a1=...)
  t,segment,FN,Fx,mu,a2               (under --FN: t,segment,FN,Fx,mu,a2,d,a1)
  ... N rows per segment, segment after segment; segment is 0-based, t is
      measured from the first change (t = 0 is the instant just after it) ...
zeta0 = V0 tau / a1 is the dimensionless velocity before t = 0; under --FN
zeta0 = V0 tau / a0, a0 the Hertz contact radius of F0 (F0 = 16/3 G a0^3/R),
and the columns d and a1 give the depth and the leading edge, a1 = sqrt(R d).
The stationary states of the events are then those under the load F0.
Events: the change at time t from w_before to w_after; mu just before it
(mu_before) and just after it (mu_after); the extremum of mu in the segment,
the sample farthest from the stationary mu_ss_after (mu_peak), its time since
the change (t_peak) and the slip w_after t_peak (slip_peak); mu at the
segment's end (mu_end); the stationary mu at both velocities; D_c, the slip
over which |mu - mu_ss_after| falls to 1/e of its value just after the change;
the apparent rate-and-state parameters a = (mu_after - mu_before) /
ln(w_after/w_before), a_minus_b = (mu_ss_after - mu_ss_before) /
ln(w_after/w_before) and b = a - a_minus_b. Where a value is undefined (a
velocity of 0 or equal velocities in the log, no 1/e decay within the segment,
a hold) it is printed as nan.
The case error is the largest of max_k |q_k - q_ref,k| / max_k |q_ref,k| for
q = FN, Fx, mu and max_k |a2_k - a2_ref,k| / a1. Under --FN: max_k |FN_k - F0|
/ F0, d, Fx and mu by their largest magnitude, a1 and a2 by a0.
error_estimate is the solver's own bound on it. Numbers have 17 significant
digits, so they read back to the same double.
)";
}

} // namespace

std::string simulate_help() {
  return "Usage: mdrmap simulate" + required_usage() +
         R"(
           (--v1 V1 [--t-end T] | --history W1:T1,W2:T2,...) [options]

Computes the response of a viscoelastic contact to changes of the sliding
velocity, in the method of dimensionality reduction (MDR). A rigid parabolic
indenter (MDR profile x^2/R) is held at indentation depth d (--d, depth
control) or pressed with the normal force F0 (--FN, load control: the depth
follows) on a Kelvin foundation (shear modulus G, relaxation time tau =
eta/G). It slides steadily at velocity V0 until t = 0, then follows a
velocity history: one step to V1 (--v1), or segments of constant velocity,
holds included (--history). The command prints the stationary state before
t = 0, event metrics of every velocity change and, at N instants per segment,
the normal force FN, the tangential (friction) force Fx, positive when it
resists the motion, the friction coefficient mu = Fx/FN, and the trailing
edge a2 of the contact. In the frame of the indenter the contact occupies
[-a1, a2], a1 = sqrt(R d); at fixed depth the leading edge stays at -a1,
under load the depth d and a1 are printed too.

Any consistent units work (e.g. mm, s, MPa): d, R, a2 are lengths, tau and t
times, velocities length/time; forces come out in units of G * length^2.

Case parameters:
)" + parameter_help(false) +
         "\nVelocity history after t = 0 (--v1 or --history):\n" + history_help() +
         "\nSampling, per segment:\n" + sampling_help() + R"(
Other options:
  --rtol E       target accuracy: bound on the case error (below), a number
                 in (0, 0.1]. Default: 1e-4
  --solver S     auto, exact, mdr or baseline. Default: auto
                   exact     continuum (dx -> 0) solution, semi-analytic
                   mdr       discrete MDR element simulation with error control
                   baseline  the paper's brute-force method, for reference
                   auto      the cheapest solver that meets rtol (exact at
                             fixed depth, the load solver under --FN)
  --output FILE  write to FILE instead of stdout. FILE is replaced at once
                 when the run succeeds and left untouched when it fails;
                 "-" means stdout
  --help         print this text and exit

)" + output_help() +
         R"(
Examples:
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 2 --v1 0.5 --output step.csv
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 1 --history 1:2,0:1000,1:5 \
      --samples 101 --spacing log       (slide-hold-slide: a hold of 1000 tau)
  mdrmap simulate --FN 0.1 --R 10 --tau 1 --v 1 --history 0.1:20,1:20
                                        (load control: a step down and up)

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
