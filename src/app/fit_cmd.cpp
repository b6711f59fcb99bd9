#include "app/fit_cmd.hpp"

#include <mpi.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "app/cli_common.hpp"
#include "app/exit_codes.hpp"
#include "app/fit_mpi.hpp"
#include "app/fit_plot.hpp"
#include "app/help_layout.hpp"
#include "app/output_file.hpp"
#include "case/case_input.hpp"
#include "case/fit_problem.hpp"
#include "core/model/params.hpp"
#include "fit/least_squares.hpp"

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

constexpr const char* kCommand = "fit";

/// The case options of simulate that a fit takes: all but the history and
/// the sampling, which the records give.
std::vector<std::string> case_names() {
  std::vector<std::string> out;
  for (const auto& name : case_option_spellings()) {
    const ParamSpec* p = find_parameter(name);
    if (p && (p->part == Part::History || p->part == Part::Sampling)) continue;
    if (name == "v1" || name == "t-end" || name == "history" || name == "history-file" ||
        name == "spacing")
      continue;
    out.push_back(name);
  }
  return out;
}

std::vector<std::string> option_names() {
  std::vector<std::string> names = case_names();
  names.insert(names.end(), {"free", "starts", "output", "plot"});
  return names;
}

/// Takes every `--NAME VALUE` and `--NAME=VALUE` of a repeatable option out of args.
std::vector<std::string> take_repeated(std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> values, rest;
  const std::string flag = "--" + name;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--") {
      rest.insert(rest.end(), args.begin() + static_cast<long>(i), args.end());
      break;
    }
    if (args[i] == flag) {
      if (i + 1 >= args.size()) throw InvalidInput(name, "needs a value");
      values.push_back(args[++i]);
    } else if (args[i].compare(0, flag.size() + 1, flag + "=") == 0) {
      values.push_back(args[i].substr(flag.size() + 1));
    } else {
      rest.push_back(args[i]);
    }
  }
  args = rest;
  return values;
}

struct FitArgs {
  FitSpec spec;
  std::string output;
  std::string plot; ///< empty: none
  std::string command_line;
};

FitArgs parse_args(const std::vector<std::string>& given) {
  std::vector<std::string> args = given;
  FitArgs a;
  a.spec.data = take_repeated(args, "data");
  a.spec.bounds = take_repeated(args, "bounds");
  const auto vm = option_texts(args, kCommand, option_names(), "--free R");
  a.spec.texts = given_texts(vm, case_names());
  if (vm.count("free")) a.spec.free = {vm["free"].as<std::string>()};
  if (vm.count("starts")) a.spec.starts = vm["starts"].as<std::string>();
  a.output = output_option(vm);
  if (vm.count("plot")) {
    a.plot = vm["plot"].as<std::string>();
    check_plot(a.plot);
  }
  a.command_line = "mdrmap fit";
  for (const auto& s : given)
    a.command_line += " " + s;
  return a;
}

// --- JSON ----------------------------------------------------------------------

std::string num(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string str(const std::string& s) {
  std::string o = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
      continue;
    }
    o += c;
  }
  return o + "\"";
}

/// `mdrmap simulate` of record k at the fitted values.
std::string reproduce(const FitProblem& p, const std::vector<double>& x, std::size_t k) {
  std::string s = "mdrmap simulate";
  for (const auto& [name, text] : p.texts_at(x, k))
    s += " --" + name + " " + text;
  return s;
}

std::string array(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + num(v[i]);
  return s + "]";
}

/// Per record: its file, t and v, and per fitted column the data and the
/// model at x (null where not measured), as python -m mdrmap plot_fit draws them.
std::string records_json(const FitProblem& p, const std::vector<double>& x) {
  const auto model = p.model_values(x);
  std::string s;
  for (std::size_t k = 0; k < p.scenes().size(); ++k) {
    const FitScene& sc = p.scenes()[k];
    s += std::string(k ? "," : "") + "\n    {\"file\": " + str(sc.record.path) +
         ", \"t\": " + array(sc.record.t) + ", \"v\": " + array(sc.record.v) + ", \"columns\": {";
    for (std::size_t c = 0; c < sc.columns.size(); ++c) {
      const std::string& q = sc.columns[c];
      const std::vector<double> none(sc.record.t.size(), NAN);
      s += std::string(c ? ", " : "") + str(q) + ": {\"data\": " + array(sc.record.measured.at(q)) +
           ", \"model\": " + array(model.empty() ? none : model[k].at(q)) + "}";
    }
    s += "}}";
  }
  return s;
}

std::string json(const FitProblem& p, const fit::Result& r, const FitArgs& a, double wall,
                 int ranks) {
  std::vector<double> x;
  for (const auto& q : r.parameters)
    x.push_back(q.value);
  std::string s = "{\n  \"parameters\": {";
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const auto& q = r.parameters[i];
    const auto& f = p.parameters()[i];
    s += std::string(i ? "," : "") + "\n    " + str(q.name) + ": {\"value\": " + num(q.value) +
         ", \"stderr\": " + num(q.stderr_) + ", \"ci95\": [" + num(q.ci95_lo) + ", " +
         num(q.ci95_hi) + "], \"ci95_method\": " + str(q.ci95_method) + ", \"ci95_covariance\": [" +
         num(q.cov_lo) + ", " + num(q.cov_hi) + "], \"start\": " + num(f.start) +
         ", \"log\": " + (f.log ? "true" : "false") +
         ", \"at_bound\": " + (q.at_bound ? "true" : "false") + "}";
  }
  s += "\n  },\n  \"correlation\": {\"names\": [";
  for (std::size_t i = 0; i < r.parameters.size(); ++i)
    s += (i ? ", " : "") + str(r.parameters[i].name);
  s += "], \"matrix\": [";
  for (std::size_t i = 0; i < r.correlation.size(); ++i) {
    s += i ? ", [" : "[";
    for (std::size_t j = 0; j < r.correlation[i].size(); ++j)
      s += (j ? ", " : "") + num(r.correlation[i][j]);
    s += "]";
  }
  s += "]},\n  \"rms\": " + num(r.rms) + ",\n  \"sigma\": " + num(r.sigma) +
       ",\n  \"residuals\": " + std::to_string(r.m) +
       ",\n  \"weighted_by_sd\": " + (p.options().known_sd ? "true" : "false") +
       ",\n  \"evaluations\": " + std::to_string(r.evaluations) +
       ",\n  \"batches\": " + std::to_string(r.batches) +
       ",\n  \"iterations\": " + std::to_string(r.iterations) +
       ",\n  \"converged\": " + (r.converged ? "true" : "false") +
       ",\n  \"termination\": " + str(r.termination) + ",\n  \"rtol\": " + num(p.rtol()) +
       ",\n  \"step\": " + num(p.options().step) + ",\n  \"t_quantile\": " + num(r.t_quantile) +
       ",\n  \"wall_seconds\": " + num(wall) + ",\n  \"ranks\": " + std::to_string(ranks) +
       ",\n  \"command\": " + str(a.command_line) + ",\n  \"best_fit\": [";
  for (std::size_t k = 0; k < p.scenes().size(); ++k)
    s += std::string(k ? ",\n    " : "\n    ") + str(reproduce(p, x, k));
  return s + "\n  ],\n  \"records\": [" + records_json(p, x) + "\n  ]\n}\n";
}

/// The figure of the JSON `text` (the --output file where it is a regular
/// file, else a temporary copy).
void plot(const std::string& text, const FitArgs& a) {
  std::error_code ec;
  if (!a.output.empty() && a.output != "-" && std::filesystem::is_regular_file(a.output, ec))
    return draw_plot(a.output, a.plot);
  std::string tmp = (std::filesystem::temp_directory_path() / "mdrmap_fit_XXXXXX").string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw std::runtime_error("--plot: cannot make a temporary file for the JSON");
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  try {
    if (!ok) throw std::runtime_error("--plot: cannot write a temporary file for the JSON");
    draw_plot(tmp, a.plot);
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    throw;
  }
  std::filesystem::remove(tmp, ec);
}

/// Rank 0: fits and writes. Throws InvalidInput("free") for a direction
/// the records do not determine.
int drive(const FitProblem& p, const FitArgs& a, fit::Evaluator& ev, int ranks) {
  OutputFile out(a.output); // opened first: a bad path fails before the fit
  const auto start = std::chrono::steady_clock::now();
  const fit::Result r = fit::fit(p.parameters(), ev, p.options());
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!r.undetermined.empty()) {
    std::string names;
    for (const auto& n : r.undetermined)
      names += (names.empty() ? "" : ", ") + n;
    throw InvalidInput("free", "the records do not determine " + names +
                                   " (their 95% interval would span more than a factor 10); "
                                   "fix it, bound it, or add records that it changes");
  }
  const std::string text = json(p, r, a, wall, ranks);
  if (std::fputs(text.c_str(), out.get()) < 0) throw std::runtime_error("cannot write the output");
  out.commit();
  if (!a.plot.empty()) plot(text, a);
  return kExitOk;
}

int run_ranks(const FitArgs& a) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const FitProblem p(a.spec); // every rank checks the same input the same way
  MpiEvaluator ev(p, MPI_COMM_WORLD);
  if (rank != 0) {
    ev.serve();
    return kExitOk;
  }
  struct Stop {
    MpiEvaluator& ev;
    ~Stop() { ev.stop(); }
  } stop{ev};
  return drive(p, a, ev, size);
}

} // namespace

int fit_main(const std::vector<std::string>& args, int argc, char** argv) {
  if (asks_for_help_all(args)) return print_help(fit_help_all());
  if (asks_for_help(args)) return print_help(fit_help());
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int code = kExitOk;
  try {
    const FitArgs a = parse_args(args);
    try {
      code = run_ranks(a);
    } catch (...) {
      code = rank == 0 ? report_run_error(kCommand, "try fewer records") : kExitBadInput;
    }
  } catch (...) {
    code = rank == 0 ? report_parse_error(kCommand) : kExitBadInput;
  }
  MPI_Finalize();
  return code;
}

} // namespace mdrmap::app
