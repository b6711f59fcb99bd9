// The help texts of `mdrmap study`: --help (a summary), --help-all and
// `mdrmap help study` (every option), `mdrmap help config` (the keys the
// options override). The override options come from app/study_options.hpp.
#include <string>
#include <vector>

#include "app/help_layout.hpp"
#include "app/reference_pages.hpp"
#include "app/study_cmd.hpp"
#include "app/study_options.hpp"
#include "core/model/params.hpp"

namespace mdrmap::app {
namespace {

constexpr const char* kCommand = "study";

/// Whether an override option is a spectrum's term (G1..G32, tau1..tau32).
bool spectrum_term(const std::string& name) {
  const std::size_t digits = name.find_first_of("0123456789");
  return digits != std::string::npos && digits > 0 &&
         (name.substr(0, digits) == "G" || name.substr(0, digits) == "tau");
}

/// The groups of the override options, each in the order of the help: the
/// key of the summary, the title of the full list, the options.
struct OverrideGroup {
  const char* key;
  const char* title;
  std::vector<std::string> options;
};

const std::vector<OverrideGroup>& override_groups() {
  static const std::vector<OverrideGroup> groups = {
      {"geometry",
       "Overrides: case geometry and loading",
       {"profile", "d", "F0", "R", "beta", "n", "A", "radius", "FN"}},
      {"material", "Overrides: material", {"tau", "G", "aT", "temperature", "wlf", "material"}},
      {"history", "Overrides: velocity history", {"v", "v1", "v1-over-v", "t-end-over-tau"}},
      {"output", "Overrides: sampling and stored output", {"samples", "timeseries"}},
      {"solver", "Overrides: solver", {"rtol", "solver"}}};
  return groups;
}

/// Whether `name` is in one of the override groups.
bool grouped(const std::string& name) {
  for (const auto& g : override_groups())
    for (const auto& o : g.options)
      if (o == name) return true;
  return false;
}

/// What an override sets: the key and, for a case parameter of the table,
/// its meaning and unit; a note where those do not say it all.
std::string override_text(const StudyOverride& ov) {
  std::string s = "sets " + ov.key;
  if (ov.option == "FN") return s + ", the old spelling of grid.F0 (the prescribed load)";
  if (const ParamSpec* p = find_parameter(ov.option))
    s += std::string(" (") + dim_name(p->dim) + "): " + p->meaning;
  if (ov.option == "G") return s + ", one number for every case";
  if (ov.option == "profile")
    return s + ": parabola (default, with R), cone (with beta), power (with n and A) or "
               "sphere (with radius); a cone, power law or sphere is solved by the spectrum "
               "solver (solver auto picks it)";
  if (ov.option == "wlf") return s + ", the WLF constants of the temperature";
  if (ov.option == "material")
    return s + ": an Abaqus card or pyvisco's CSV (relative to the working directory) that "
               "gives G, the spectrum's terms and the WLF constants of its *TRS";
  return s;
}

HelpEntry override_entry(const StudyOverride& ov) {
  HelpEntry e{"--" + ov.option + " " + ov.placeholder, override_text(ov)};
  e.summarized = canonical_parameter_name(ov.option) == ov.option; // not an old spelling
  return e;
}

/// The override options, in groups (a spectrum's terms as one entry; an
/// option of no group, if any, in a last group "other").
std::vector<HelpSection> override_sections() {
  std::vector<HelpSection> out;
  for (const auto& g : override_groups()) {
    HelpSection sec{g.key, g.title, {}};
    for (const auto& name : g.options)
      for (const auto& ov : study_overrides())
        if (ov.option == name) sec.entries.push_back(override_entry(ov));
    if (std::string(g.key) == "material")
      sec.entries.push_back({"--Gk SPEC --tauk SPEC",
                             "set grid.Gk and grid.tauk: a relaxation spectrum's term k = 1..32"});
    out.push_back(sec);
  }
  HelpSection other{"other", "Overrides: other", {}};
  for (const auto& ov : study_overrides())
    if (!spectrum_term(ov.option) && !grouped(ov.option))
      other.entries.push_back(override_entry(ov));
  if (!other.entries.empty()) out.push_back(other);
  return out;
}

HelpSection study_section() {
  return {"study",
          "The study and its map",
          {{"--config FILE.ini",
            "the study (INI: [grid] or [cases], [history], [run]; every key: mdrmap help config, "
            "docs/reference/config.md)"},
           {"--output MAP.h5",
            "the map file. Default: the config's name with .h5, in the current directory. An "
            "existing file is never touched without --resume or --overwrite; one that is not a "
            "regular file (a FIFO, a device) is refused"},
           {"--resume", "continue MAP.h5: run only the cases not yet done. Refused when the study "
                        "(config and overrides) differs from the one stored in the file"},
           {"--overwrite", "replace MAP.h5, only if it is an mdrmap map. The new map is built "
                           "under a temporary name and renamed when created"},
           {"--quiet", "no progress output (errors and the summary still print)"},
           {"--chunk-seconds S",
            "target compute time of one chunk of cases (default 0.2): larger means fewer "
            "dispatch messages, smaller means less work lost to a kill and a shorter tail"},
           {"--set SECTION.KEY=VALUE",
            "any key of the config, e.g. --set history.T1_over_tau=logspace:1:1000:4 or --set "
            "run.spacing=log (repeatable)"}}};
}

std::vector<HelpSection> sections() {
  std::vector<HelpSection> s = {study_section()};
  for (auto& sec : override_sections())
    s.push_back(sec);
  s.push_back({"help", "Help", {help_option_entry(kCommand), help_all_option_entry(kCommand)}});
  return s;
}

std::string usage() {
  return "Usage: mpirun -np P mdrmap study --config FILE.ini [--output MAP.h5]\n"
         "                 [--resume | --overwrite] [--quiet] [overrides...]\n";
}

std::string notes() {
  return R"(
Overrides win over the config file; values as in the INI (SPEC: a number, a
comma list, linspace:lo:hi:n or logspace:lo:hi:n). All are applied, then the
study is checked: a new history segment takes its two keys.

Progress goes to stderr on rank 0: a live bar on a terminal, a line every 10 s
in a batch log, then one summary line.

Signals: SIGTERM, SIGINT or SIGUSR1 (what batch systems send before the wall
time limit) make every rank stop taking work, write what it finished, and
exit with code 3; the message says how to resume.

Exit codes: 0 study complete (failed cases are recorded in the map: status
-1, with their message in /failures), 1 runtime failure, 2 bad input, 3
interrupted (resume with --resume).

A bad input is one line from rank 0, the first of the output. Open MPI's
mpirun follows any non-zero exit with a banner of about ten lines ("Primary
job terminated normally, but 1 process returned a non-zero exit code ...");
'mpirun -q' leaves the line alone (the exit code is the same).
)";
}

} // namespace

std::string study_help_all() {
  return usage() + R"(
Runs a parameter study: every case of the config (a grid over the case
parameters d or F0, R, tau, G, v, optionally a relaxation spectrum's terms
Gk, tauk and the shift aT or the temperature, and the history's segment
velocities and durations, or a CSV list of cases) is one velocity history
under a fixed depth d or a prescribed normal load F0, solved as by 'mdrmap
simulate' (a parabola, a cone or a power law). Rank 0 hands out cases in
chunks on request and computes too; every rank writes its results into one
HDF5 friction map (schema mdrmap-map/2, docs/reference/map-schema.md): the event
metrics of every velocity change (a, b, D_c, peaks), the closed-form
stationary states and the residuals between the two. Works with P = 1.

)" + full_options(sections()) +
         notes();
}

std::string study_help() {
  return usage() + R"(
Parameter maps over many cases in parallel: MPI ranks share the cases of the
config's grid or case list, the results go to one HDF5 friction map.

)" + options_summary(sections()) +
         R"(
Example:
  mpirun -q -np 2 mdrmap study --config jobs/examples/quick.ini --overwrite

A bad input is one line on stderr, exit 2 ('mpirun -q' keeps Open MPI's
banner away).

)" + full_list_pointer(kCommand);
}

std::string study_config_help() {
  std::string s = R"(Every key of a study config, section by section (docs/reference/config.md;
how to write a study: docs/studies.md). mdrmap study --set SECTION.KEY=VALUE
sets any key from the command line; these options set one each:

)";
  std::vector<HelpEntry> entries;
  for (const auto& ov : study_overrides())
    if (!spectrum_term(ov.option)) entries.push_back({ov.key, "--" + ov.option});
  entries.push_back({"grid.Gk, grid.tauk", "--Gk, --tauk (k = 1..32): a spectrum's term k"});
  return s + render_entries(entries) +
         "\nThe keys (SPEC: a number, a comma list, linspace:lo:hi:n or\n" +
         "logspace:lo:hi:n):\n" + config_keys_text();
}

} // namespace mdrmap::app
