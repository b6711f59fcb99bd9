// mdrmap study: the MPI parameter study (app layer: options, signals,
// progress printing, exit codes). The work is in study/runner.
#include "app/study_cmd.hpp"

#include <mpi.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "app/cli_common.hpp"
#include "app/exit_codes.hpp"
#include "app/study_options.hpp"
#include "core/model/params.hpp"
#include "mdrmap/version.hpp"
#include "study/runner.hpp"

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

namespace po = boost::program_options;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop_signal(int) {
  g_stop = 1;
}

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGTERM, SIGINT, SIGUSR1})
    sigaction(sig, &sa, nullptr);
}

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                        "0123456789-_./=:,+@%") == std::string::npos)
    return s;
  std::string out = "'";
  for (char c : s)
    out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long t = std::lround(s);
  char buf[32];
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", t / 60, t % 60);
  return buf;
}

// Collective: the peak resident memory (getrusage's ru_maxrss) of rank 0
// and the largest of the other ranks', for rank 0's summary.
std::string peak_memory(MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  struct rusage ru {};
  ::getrusage(RUSAGE_SELF, &ru);
  const long long mine = ru.ru_maxrss; // KiB on Linux
  std::vector<long long> all(rank == 0 ? static_cast<std::size_t>(size) : 1);
  MPI_Gather(&mine, 1, MPI_LONG_LONG, all.data(), 1, MPI_LONG_LONG, 0, comm);
  if (rank != 0) return "";
  char buf[160];
  long long others = 0;
  for (int r = 1; r < size; ++r)
    others = std::max(others, all[static_cast<std::size_t>(r)]);
  int n = std::snprintf(buf, sizeof buf, "peak memory (max RSS): rank 0 %.1f MiB",
                        static_cast<double>(all[0]) / 1024.0);
  const double others_mib = static_cast<double>(others) / 1024.0;
  if (size == 2)
    std::snprintf(buf + n, sizeof buf - static_cast<std::size_t>(n), ", rank 1 %.1f MiB",
                  others_mib);
  else if (size > 2)
    std::snprintf(buf + n, sizeof buf - static_cast<std::size_t>(n),
                  ", ranks 1-%d at most %.1f MiB", size - 1, others_mib);
  return buf;
}

// Rank 0's progress printer: a live bar on a terminal, plain lines in a log.
class StderrProgress : public study::ProgressSink {
public:
  explicit StderrProgress(bool quiet) : quiet_(quiet), tty_(::isatty(2) != 0) {
    interval = tty_ ? 0.25 : 10.0;
  }
  void report(const study::Progress& p) override {
    if (quiet_) return;
    const std::size_t n = p.done + p.failed;
    const double rate = p.elapsed > 0 ? static_cast<double>(n) / p.elapsed : 0.0;
    const double eta = rate > 0 ? static_cast<double>(p.todo - n) / rate : NAN;
    const double frac = p.todo ? static_cast<double>(n) / static_cast<double>(p.todo) : 1.0;
    if (tty_) {
      char bar[31];
      const int filled = static_cast<int>(frac * 30.0);
      for (int i = 0; i < 30; ++i)
        bar[i] = i < filled ? '#' : '.';
      bar[30] = '\0';
      std::fprintf(stderr, "\r[%s] %zu/%zu cases %5.1f%%  %zu failed  %.0f cases/s  ETA %s   ", bar,
                   n, p.todo, 100.0 * frac, p.failed, rate, format_duration(eta).c_str());
      if (p.final) std::fputc('\n', stderr);
    } else if (!p.final) {
      std::fprintf(stderr, "progress: %zu/%zu cases (%.1f%%), %zu failed, %.0f cases/s, ETA %s\n",
                   n, p.todo, 100.0 * frac, p.failed, rate, format_duration(eta).c_str());
    }
    std::fflush(stderr);
  }

private:
  bool quiet_, tty_;
};

struct StudyArgs {
  double chunk_seconds = 0.2;
  std::string config, output;
  bool resume = false, overwrite = false, quiet = false;
  std::vector<std::pair<std::string, std::string>> overrides;
  std::vector<std::string> args; // as given, for the resume command
};

/// Two options of one group of the table (--d and --F0: the loading), or
/// both spellings of one parameter (--F0 and --FN), set the same thing:
/// refused, as simulate refuses them.
void refuse_two_of_a_group(const po::variables_map& vm) {
  for (const ParamAlias& a : parameter_aliases())
    if (vm.count(a.name) && vm.count(a.alias)) throw InvalidInput(a.alias, two_spellings(a, "--"));
  // the option a parameter was given as (its name or its old spelling), or ""
  const auto given = [&vm](const ParamSpec& p) -> std::string {
    if (vm.count(p.name)) return p.name;
    const ParamAlias* a = alias_of(p.name);
    return a && vm.count(a->alias) ? a->alias : "";
  };
  for (const ParamSpec& p : case_parameters()) {
    if (p.one_of == nullptr || given(p).empty()) continue;
    for (const ParamSpec& q : case_parameters())
      if (&q != &p && q.one_of != nullptr && std::string(q.one_of) == p.one_of && !given(q).empty())
        throw InvalidInput(given(p), "--" + given(p) + " and --" + given(q) +
                                         " set the same thing (the " + p.one_of +
                                         "); give only one");
  }
}

po::options_description options() {
  po::options_description o;
  o.add_options()("config", po::value<std::string>(), "")("output", po::value<std::string>(), "")(
      "resume", po::bool_switch(), "")("overwrite", po::bool_switch(), "")(
      "quiet", po::bool_switch(), "")("help", po::bool_switch(), "")("chunk-seconds",
                                                                     po::value<std::string>(), "")(
      "set", po::value<std::vector<std::string>>()->composing(), "");
  for (const auto& ov : study_overrides())
    o.add_options()(ov.option.c_str(), po::value<std::string>(), "");
  return o;
}

std::string default_output(const std::string& config) {
  std::string base = config.substr(config.find_last_of('/') + 1);
  const auto dot = base.find_last_of('.');
  if (dot != std::string::npos && dot > 0) base = base.substr(0, dot);
  return base + ".h5";
}

// Throws InvalidInput for bad options.
StudyArgs parse(const std::vector<std::string>& args, bool& help) {
  po::variables_map vm;
  try {
    const po::options_description desc = options(); // parsed refers to it
    const po::parsed_options parsed =
        po::command_line_parser(args)
            .options(desc)
            .style(po::command_line_style::unix_style ^ po::command_line_style::allow_guessing)
            .run();
    // a stray word (e.g. "--overwrite no") must not be dropped silently
    const std::vector<std::string> stray =
        po::collect_unrecognized(parsed.options, po::include_positional);
    if (!stray.empty())
      throw InvalidInput("config", "unexpected argument '" + stray.front() +
                                       "'; switches take no value and every value follows its "
                                       "option (see --help)");
    po::store(parsed, vm);
  } catch (const po::error_with_option_name& e) {
    std::string opt = e.get_option_name();
    while (!opt.empty() && opt[0] == '-')
      opt.erase(0, 1);
    if (const std::string why = beyond_last_term(opt); !why.empty()) throw InvalidInput(opt, why);
    throw InvalidInput(opt.empty() ? "config" : opt, e.what());
  } catch (const po::error& e) {
    throw InvalidInput("config", e.what());
  }
  StudyArgs a;
  a.args = args;
  help = vm["help"].as<bool>();
  if (help) return a;
  if (!vm.count("config"))
    throw InvalidInput("config", "is required: the INI file of the study (see --help)");
  a.config = vm["config"].as<std::string>();
  a.output = vm.count("output") ? vm["output"].as<std::string>() : default_output(a.config);
  a.resume = vm["resume"].as<bool>();
  a.overwrite = vm["overwrite"].as<bool>();
  a.quiet = vm["quiet"].as<bool>();
  if (vm.count("chunk-seconds")) {
    const std::string& txt = vm["chunk-seconds"].as<std::string>();
    char* end = nullptr;
    const double x = std::strtod(txt.c_str(), &end);
    if (txt.empty() || *end != '\0' || !std::isfinite(x) || !(x > 0.0) || x > 3600.0)
      throw InvalidInput("chunk-seconds",
                         "must be a number of seconds in (0, 3600], got '" + txt + "'");
    a.chunk_seconds = x;
  }
  refuse_two_of_a_group(vm);
  for (const auto& ov : study_overrides())
    if (vm.count(ov.option)) a.overrides.emplace_back(ov.key, vm[ov.option].as<std::string>());
  if (vm.count("set"))
    for (const std::string& kv : vm["set"].as<std::vector<std::string>>()) {
      const std::size_t eq = kv.find('=');
      if (eq == std::string::npos || eq == 0)
        throw InvalidInput(
            "set", "expects SECTION.KEY=VALUE (e.g. history.T1_over_tau=1,10), got '" + kv + "'");
      a.overrides.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    }
  return a;
}

void print_error(const InvalidInput& e) {
  const std::string& opt = e.option();
  // "section.key" names a setting of the INI file; anything else is an option
  // (whole-file problems are reported against --config)
  const bool config_key = opt.find('.') != std::string::npos;
  std::fprintf(stderr, "mdrmap study: error: %s%s: %s\n", config_key ? "" : "--", opt.c_str(),
               e.what());
}

} // namespace

namespace {

// A bad option, found before MPI starts: every rank sees the same arguments,
// so only the first process (where the launcher says which it is) prints.
int refuse_options(const InvalidInput& e, const char* env_rank, bool first, int argc, char** argv) {
  if (!env_rank) { // no launcher: no MPI needed to say so
    print_error(e);
    return kExitBadInput;
  }
  // Under a launcher, end the job together after rank 0 has printed: a rank
  // that exits early with an error may make the launcher kill rank 0 before
  // its message is out.
  MPI_Init(&argc, &argv);
  if (first) {
    print_error(e);
    std::fflush(stderr);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return kExitBadInput;
}

study::StudyRequest make_request(const StudyArgs& a, int argc, char** argv) {
  study::StudyRequest req;
  req.config = study::load_config(a.config, a.overrides); // overrides applied, then checked
  req.output = a.output;
  req.resume = a.resume;
  req.overwrite = a.overwrite;
  req.stop = &g_stop;
  req.chunk_seconds = a.chunk_seconds;
  std::string cl = "mdrmap";
  for (int i = 1; i < argc; ++i)
    cl += " " + shell_quote(argv[i]);
  req.command_line = cl;
  return req;
}

// The command that resumes the run: its options as given (every override,
// in order), without --resume, --overwrite and --output, then the map and
// --resume; so the study it defines is the one stored in the map.
std::string resume_command(const StudyArgs& a, int size) {
  std::string cmd = "mpirun -np " + std::to_string(size) + " mdrmap study";
  const auto is_switch = [](const std::string& name) {
    return name == "resume" || name == "overwrite" || name == "quiet" || name == "help";
  };
  for (std::size_t i = 0; i < a.args.size(); ++i) {
    const std::string& arg = a.args[i];
    const bool option = arg.size() > 2 && arg.compare(0, 2, "--") == 0;
    const std::string name = option ? arg.substr(2, arg.find('=') - 2) : "";
    // an option that takes a value and has none after '=' takes the next word
    const bool takes_next = option && !is_switch(name) && arg.find('=') == std::string::npos;
    const bool dropped = name == "resume" || name == "overwrite" || name == "output";
    if (!dropped) cmd += " " + shell_quote(arg);
    if (takes_next && i + 1 < a.args.size()) {
      ++i;
      if (!dropped) cmd += " " + shell_quote(a.args[i]);
    }
  }
  return cmd + " --output " + shell_quote(a.output) + " --resume";
}

// Rank 0's last lines: a write failure, an interruption (and how the map
// resumes) or the summary, then the ranks' peak memory.
void print_outcome(const study::StudySummary& sum, const StudyArgs& a, int size,
                   const std::string& memory) {
  const std::size_t ran = sum.done + sum.failed;
  const std::string resume_hint = resume_command(a, size);
  if (!sum.write_failure.empty()) {
    // a failed case is not done: --resume runs it again unless /failures
    // holds its message
    const std::size_t done = sum.already_done - sum.already_failed + sum.done;
    std::fprintf(stderr,
                 "mdrmap study: error: %s; %zu of %zu cases are done in the map, %zu failed and "
                 "recorded, %zu left for --resume; fix the cause, then resume with: %s\n",
                 sum.write_failure.c_str(), done, sum.total, sum.recorded,
                 sum.total - done - sum.recorded, resume_hint.c_str());
    return;
  }
  if (sum.interrupted) {
    // Inside a batch job the job script resumes the map (it requeues or
    // resubmits itself): say so rather than suggest an mpirun of its own.
    const char* slurm = std::getenv("SLURM_JOB_ID");
    const char* pbs = std::getenv("PBS_JOBID");
    std::string next = "resume with: " + resume_hint;
    if (pbs != nullptr && *pbs != '\0') // (also under Slurm's PBS wrappers)
      next = std::string("PBS job ") + pbs + ": the job resumes the map when it runs again";
    else if (slurm != nullptr && *slurm != '\0')
      next = std::string("Slurm job ") + slurm + ": the job resumes the map when it runs again";
    std::fprintf(stderr,
                 "mdrmap study: interrupted: %zu of %zu cases done (%zu this run), %zu "
                 "pending; %s\n",
                 sum.already_done + ran, sum.total, ran, sum.pending, next.c_str());
  } else {
    std::fprintf(stderr,
                 "mdrmap study: %zu cases in %s: %zu done, %zu failed this run (%zu done "
                 "before), wall %.2f s, %.0f cases/s, %d ranks, %zu chunks, %zu requests served\n",
                 sum.total, a.output.c_str(), sum.done, sum.failed, sum.already_done,
                 sum.wall_seconds,
                 sum.wall_seconds > 0 ? static_cast<double>(ran) / sum.wall_seconds : 0.0, size,
                 sum.chunks, sum.messages);
  }
  std::fprintf(stderr, "mdrmap study: %s\n", memory.c_str());
}

} // namespace

int study_main(const std::vector<std::string>& args, int argc, char** argv) {
  bool help = false;
  const bool help_all = asks_for_help_all(args);
  StudyArgs a;
  const char* env_rank = std::getenv("OMPI_COMM_WORLD_RANK");
  if (!env_rank) env_rank = std::getenv("PMI_RANK");
  const bool first = !env_rank || std::string(env_rank) == "0";
  try {
    if (!help_all) a = parse(args, help);
  } catch (const InvalidInput& e) {
    return refuse_options(e, env_rank, first, argc, argv);
  }
  if (help || help_all) {
    if (first) std::fputs((help_all ? study_help_all() : study_help()).c_str(), stdout);
    return kExitOk;
  }

  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  install_signal_handlers();
  int code = kExitOk;
  try {
    const study::StudyRequest req = make_request(a, argc, argv);
    StderrProgress progress(a.quiet);
    const auto sum = study::run_study(MPI_COMM_WORLD, req, rank == 0 ? &progress : nullptr);
    const std::string memory = peak_memory(MPI_COMM_WORLD);
    if (rank == 0) print_outcome(sum, a, size, memory);
    code = !sum.write_failure.empty() ? kExitRuntime : sum.interrupted ? kExitInterrupted : kExitOk;
  } catch (const InvalidInput& e) {
    // decided collectively (or identically on every rank): clean shutdown
    if (rank == 0) print_error(e);
    code = kExitBadInput;
  } catch (const study::CollectiveFailure& e) {
    if (rank == 0) std::fprintf(stderr, "mdrmap study: error: %s\n", e.what());
    code = kExitRuntime;
  } catch (const std::exception& e) {
    // one rank alone: the others may be waiting on it; end the job
    std::fprintf(stderr, "mdrmap study: error (rank %d): %s\n", rank, e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, kExitRuntime);
  }
  MPI_Finalize();
  return code;
}

} // namespace mdrmap::app
