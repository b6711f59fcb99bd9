#include "app/help_layout.hpp"

#include "case/case_input.hpp"
#include "case/option_help.hpp"

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

constexpr std::size_t kWidth = 79;

/// `text` (split at spaces) after `head`, wrapped at kWidth columns, every
/// line after the first indented to `indent` columns.
std::string wrapped(std::string head, const std::string& text, std::size_t indent) {
  const std::size_t line_start = head.rfind('\n');
  std::size_t col = line_start == std::string::npos ? head.size() : head.size() - line_start - 1;
  bool first = true;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find(' ', pos);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(pos, end - pos);
    if (!first && col + 1 + word.size() > kWidth) {
      head += "\n" + std::string(indent, ' ');
      col = indent;
      first = true;
    }
    if (!first) head += ' ', ++col;
    head += word;
    col += word.size();
    first = false;
    pos = end + 1;
  }
  return head + "\n";
}

} // namespace

std::string help_entry(const std::string& option, const std::string& text) {
  constexpr std::size_t kColumn = 17;
  std::string out = "  " + option;
  if (out.size() + 1 > kColumn)
    out += "\n" + std::string(kColumn, ' ');
  else
    out += std::string(kColumn - out.size(), ' ');
  return wrapped(out, text, kColumn);
}

HelpEntry parameter_entry(const ParamSpec& p) {
  return {std::string("--") + p.name + " " + p.symbol, parameter_help_text(p)};
}

std::vector<HelpEntry> parameter_entries(Part part) {
  std::vector<HelpEntry> entries;
  for (const auto& p : case_parameters())
    if (p.part == part) entries.push_back(parameter_entry(p));
  return entries;
}

HelpEntry help_option_entry(const std::string& command) {
  return {"--help", "print a short summary of the options of mdrmap " + command + " and exit"};
}

HelpEntry help_all_option_entry(const std::string& command) {
  return {"--help-all", "print every option of mdrmap " + command +
                            ", its output and exit codes (this text; also mdrmap help " + command +
                            ") and exit"};
}

std::string render_entries(const std::vector<HelpEntry>& entries) {
  std::string s;
  for (const auto& e : entries)
    s += help_entry(e.label, e.text) + e.tail;
  return s;
}

std::string full_options(const std::vector<HelpSection>& sections) {
  std::string s;
  for (const auto& sec : sections) {
    if (!s.empty()) s += "\n";
    s += sec.title + ":\n" + render_entries(sec.entries) + sec.note;
  }
  return s;
}

std::string options_summary(const std::vector<HelpSection>& sections) {
  constexpr std::size_t kColumn = 13;
  std::string s = "Options:\n";
  for (const auto& sec : sections) {
    std::string head = "  " + sec.key;
    head += std::string(head.size() + 1 > kColumn ? 1 : kColumn - head.size(), ' ');
    std::string labels;
    for (const auto& e : sec.entries) {
      if (!e.summarized) continue;
      std::string label = e.label;
      // a label is never broken: its spaces become no-break for the wrapping
      for (auto& c : label)
        if (c == ' ') c = '\x01';
      labels += (labels.empty() ? "" : " ") + label + ",";
    }
    if (!labels.empty()) labels.pop_back();
    std::string line = wrapped(head, labels, kColumn);
    for (auto& c : line)
      if (c == '\x01') c = ' ';
    s += line;
  }
  return s;
}

std::string paragraph(const std::string& text) {
  return wrapped("", text, 0);
}

std::string full_list_pointer(const std::string& command) {
  return paragraph("Every option with its unit, range and default, the output and the exit "
                   "codes: mdrmap " +
                   command + " --help-all (or mdrmap help " + command +
                   "; mdrmap help lists the topics).");
}

std::string case_usage(bool history) {
  std::string s;
  for (const auto& p : case_parameters()) {
    if (p.required && p.profile == nullptr && (history || p.part != Part::History))
      s += std::string(" --") + p.name + " " + p.symbol;
    if (!p.one_of) continue;
    const auto members = group_members(p.one_of);
    if (members.front() == &p) s += " (" + group_usage(members, " | ", " | ") + ")";
  }
  const std::string indent = "\n           ";
  std::string alternatives, line; // (lines of at most 80 columns)
  for (const Profile kind : all_profiles()) {
    std::string alt =
        kind == Profile::of<Parabola>() ? "" : std::string("--profile ") + profile_name(kind);
    for (const auto& p : case_parameters())
      if (p.required && p.profile && std::string(p.profile) == profile_name(kind))
        alt += (alt.empty() ? "--" : " --") + std::string(p.name) + " " + p.symbol;
    const std::string piece = (line.empty() && alternatives.empty() ? "(" : " | ") + alt;
    if (!line.empty() && indent.size() + line.size() + piece.size() > 79) {
      alternatives += indent + line;
      line.clear();
    }
    line += piece;
  }
  return s + alternatives + indent + line + ")";
}

HelpEntry option_entry(const std::string& name, const std::string& extra) {
  const OptionHelp& h = option_help(name);
  const std::string label = "--" + h.name + (h.placeholder.empty() ? "" : " " + h.placeholder);
  return {label, h.full(extra), h.tail};
}

HelpEntry profile_entry(bool solvers) {
  return option_entry("profile", solvers ? "The cone and power profiles are solved by the "
                                           "spectrum solver (auto picks it); the other solvers "
                                           "take the parabola only. Their stationary states: "
                                           "mdrmap stationary."
                                         : "");
}

HelpEntry output_entry() {
  return {"--output FILE",
          "write to FILE instead of stdout. A regular file (or the file a symbolic link points "
          "to) is replaced at once when the run succeeds and left untouched when it fails; a "
          "device or a FIFO is written to, never replaced (a FIFO needs its reader running); "
          "\"-\" means stdout"};
}

std::vector<HelpEntry> rheology_entries() {
  std::vector<HelpEntry> e;
  for (const char* name :
       {"material", "prony", "prony-file", "nu", "T", "wlf", "allow-large-shift"})
    e.push_back(option_entry(name));
  return e;
}

std::vector<HelpEntry> geometry_entries(bool solvers) {
  std::vector<HelpEntry> e = {profile_entry(solvers)};
  for (const Part part : {Part::Loading, Part::Indenter})
    for (auto& p : parameter_entries(part))
      e.push_back(p);
  return e;
}

std::vector<HelpEntry> material_entries() {
  std::vector<HelpEntry> e = parameter_entries(Part::Material);
  for (auto& r : rheology_entries())
    e.push_back(r);
  return e;
}

} // namespace mdrmap::app
