#include "material/card.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "material/pyvisco.hpp"
#include "material/small_file.hpp"
#include "material/text.hpp"

namespace mdrmap::material {
namespace {

const std::string kOption = "material";

std::string upper(std::string s) {
  for (char& ch : s)
    ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return s;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string item;
  while (std::getline(in, item, ','))
    out.push_back(trimmed(item));
  if (!out.empty() && out.back().empty()) out.pop_back(); // a trailing comma
  return out;
}

/// A keyword line: its name and its options KEY=VALUE (upper case, spaces kept).
struct Keyword {
  std::string name;
  std::vector<std::pair<std::string, std::string>> options;
};

Keyword keyword(const std::string& line) {
  const std::vector<std::string> parts = split(line.substr(1));
  Keyword k;
  k.name = upper(parts.empty() ? "" : parts[0]);
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::size_t eq = parts[i].find('=');
    k.options.emplace_back(upper(trimmed(parts[i].substr(0, eq))),
                           eq == std::string::npos ? "" : upper(trimmed(parts[i].substr(eq + 1))));
  }
  return k;
}

/// The data row's numbers, exactly `n` of them (a missing trailing one is 0 in
/// Abaqus; here it must be given).
std::vector<double> numbers(const std::string& at, const std::string& what, std::size_t n,
                            const std::string& line) {
  const std::vector<std::string> parts = split(line);
  if (parts.size() != n)
    throw InvalidInput(kOption, at + what + " takes " + std::to_string(n) +
                                    " values separated by commas, got " + shown(line));
  std::vector<double> x;
  for (std::size_t i = 0; i < n; ++i) {
    char* end = nullptr;
    const double v = std::strtod(parts[i].c_str(), &end);
    if (parts[i].empty() || *end != '\0' || !std::isfinite(v))
      throw InvalidInput(kOption, at + what + " value " + std::to_string(i + 1) +
                                      " must be a finite number, got " + shown(parts[i]));
    x.push_back(v);
  }
  return x;
}

/// What the block gives before the moduli are combined.
struct Block {
  double E = 0.0, nu = 0.0;
  bool elastic = false, instantaneous = false;
  std::vector<double> g, k, tau;
  std::optional<Wlf> wlf;
  std::string section; ///< the keyword whose data lines follow
  std::string at;      ///< "FILE:LINE: " of the *ELASTIC line
};

/// Checks a keyword's options and makes it the current section.
void open_section(Block& b, const std::string& at, const Keyword& k) {
  const auto refuse = [&](const std::string& what) {
    throw InvalidInput(kOption, at + "*" + k.name + ": " + what +
                                    "; supported: *ELASTIC [, MODULI=LONG TERM|INSTANTANEOUS], "
                                    "*VISCOELASTIC, TIME=PRONY and *TRS, DEFINITION=WLF");
  };
  b.section = k.name;
  for (const auto& [key, value] : k.options) {
    if (k.name == "MATERIAL" && key == "NAME") continue;
    if (k.name == "ELASTIC" && key == "TYPE" && value == "ISOTROPIC") continue;
    if (k.name == "ELASTIC" && key == "MODULI" &&
        (value == "LONG TERM" || value == "INSTANTANEOUS")) {
      b.instantaneous = value == "INSTANTANEOUS";
      continue;
    }
    if (k.name == "VISCOELASTIC" && key == "TIME" && value == "PRONY") continue;
    if (k.name == "TRS" && key == "DEFINITION" && value == "WLF") continue;
    refuse("the option " + key + (value.empty() ? "" : "=" + value) + " is not supported");
  }
  if (k.name == "MATERIAL") return;
  if (k.name == "ELASTIC") b.at = at;
  if (k.name == "VISCOELASTIC" && std::none_of(k.options.begin(), k.options.end(),
                                               [](const auto& o) { return o.first == "TIME"; }))
    refuse("needs TIME=PRONY (frequency data is not read)");
  if (k.name == "TRS" && k.options.empty()) refuse("needs DEFINITION=WLF");
  if (k.name != "ELASTIC" && k.name != "VISCOELASTIC" && k.name != "TRS")
    refuse("not a keyword of a material card mdrmap reads");
}

/// One data line of the current section.
void data_line(Block& b, const std::string& at, const std::string& line) {
  if (b.section == "ELASTIC") {
    if (b.elastic)
      throw InvalidInput(kOption, at + "*ELASTIC takes one line E, nu (no temperature table)");
    const auto x = numbers(at, "*ELASTIC E, nu", 2, line);
    if (!(x[0] > 0.0))
      throw InvalidInput(kOption, at + "E must be > 0, got " + format_number(x[0]));
    if (!(x[1] > -1.0 && x[1] <= 0.5))
      throw InvalidInput(kOption, at + "nu must be > -1 and <= 0.5, got " + format_number(x[1]));
    b.E = x[0], b.nu = x[1], b.elastic = true;
  } else if (b.section == "VISCOELASTIC") {
    const auto x = numbers(at, "*VISCOELASTIC g, k, tau", 3, line);
    if (!(x[0] > 0.0 && x[0] < 1.0))
      throw InvalidInput(kOption, at + "g" + std::to_string(b.g.size() + 1) +
                                      " must be > 0 and < 1, got " + format_number(x[0]));
    if (!branch_time_spec().contains(x[2]))
      throw InvalidInput(kOption, at + "tau" + std::to_string(b.g.size() + 1) + " must be " +
                                      branch_time_spec().allowed() + ", got " +
                                      format_number(x[2]));
    if (b.g.size() == kMaxBranches)
      throw InvalidInput(kOption,
                         at + "more than " + std::to_string(kMaxBranches) + " Prony terms");
    b.g.push_back(x[0]), b.k.push_back(x[1]), b.tau.push_back(x[2]);
  } else if (b.section == "TRS") {
    if (b.wlf) throw InvalidInput(kOption, at + "*TRS takes one line Tref, C1, C2");
    const auto x = numbers(at, "*TRS Tref, C1, C2", 3, line);
    if (!(x[1] > 0.0 && x[2] > 0.0))
      throw InvalidInput(kOption, at + "C1 and C2 must be > 0, got " + format_number(x[1]) + ", " +
                                      format_number(x[2]));
    b.wlf = Wlf{x[1], x[2], x[0]};
  } else
    throw InvalidInput(kOption, at + "a data line outside *ELASTIC, *VISCOELASTIC or *TRS");
}

Block read_block(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  Block b;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string at = path + ":" + std::to_string(n) + ": ";
    const std::string t = trimmed(line);
    if (t.empty() || t.compare(0, 2, "**") == 0) continue;
    if (t[0] == '*')
      open_section(b, at, keyword(t));
    else
      data_line(b, at, t);
  }
  if (!b.elastic)
    throw InvalidInput(kOption, path + ": no *ELASTIC line E, nu (the long-term or instantaneous "
                                       "modulus)");
  return b;
}

} // namespace

MaterialCard read_material(const std::string& path) {
  const std::string text = read_small_file(kOption, path, "a material card is a few lines");
  if (is_pyvisco_csv(text)) {
    MaterialCard m = read_pyvisco(path, text);
    m.text = text;
    return m;
  }
  const Block b = read_block(path, text);
  double sum_g = 0.0;
  for (double g : b.g)
    sum_g += g;
  if (!(sum_g < 1.0))
    throw InvalidInput(kOption, path + ": the Prony g_i sum to " + format_number(sum_g) +
                                    "; the sum must be < 1 (G = G0 (1 - sum g) > 0)");
  const double G_E = b.E / (4.0 * (1.0 - b.nu * b.nu)); // DESIGN section 9
  const double G0 = b.instantaneous ? G_E : G_E / (1.0 - sum_g);
  MaterialCard m;
  m.text = text;
  m.G = G0 * (1.0 - sum_g);
  for (std::size_t i = 0; i < b.g.size(); ++i)
    m.branches.push_back(Branch{b.g[i] * G0, b.tau[i]});
  if (b.wlf) m.wlf = UnitWlf{*b.wlf, TempUnit::None};
  std::size_t bulk = 0;
  for (double k : b.k)
    bulk += k != 0.0;
  if (bulk > 0)
    m.notes.push_back(path + ": " + std::to_string(bulk) +
                      " nonzero bulk Prony terms k_i are ignored (an incompressible foundation "
                      "has no bulk relaxation)");
  return m;
}

} // namespace mdrmap::material
