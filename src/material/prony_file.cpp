#include "material/prony_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "material/small_file.hpp"
#include "material/text.hpp"

namespace mdrmap::material {
namespace {

const std::string kOption = "prony-file";
constexpr std::size_t kMaxLine = 4096; ///< characters of a line of a spectrum file

enum class Col { G, E, g, tau };

const char* col_name(Col c) {
  switch (c) {
  case Col::G:
    return "G";
  case Col::E:
    return "E";
  case Col::g:
    return "g";
  case Col::tau:
    return "tau";
  }
  return "?";
}

const std::string kColumns = "the columns are tau and one of G (shear moduli), E (Young's moduli, "
                             "G = E / (4 (1 - nu^2))) or g (normalised by '# G0 = VALUE')";

/// The header's columns, in the file's order: each known, none twice, tau and
/// exactly one modulus column.
std::vector<Col> read_header(const std::string& at, const std::string& line) {
  std::vector<Col> cols;
  std::size_t start = 0, moduli = 0;
  for (std::size_t i = 1;; ++i) {
    const std::size_t comma = line.find(',', start);
    const std::string name =
        trimmed(line.substr(start, comma == std::string::npos ? comma : comma - start));
    const std::string where = at + "header column " + std::to_string(i) + " " + shown(name) + ": ";
    Col c = Col::G;
    if (name == "G")
      c = Col::G;
    else if (name == "E")
      c = Col::E;
    else if (name == "g")
      c = Col::g;
    else if (name == "tau")
      c = Col::tau;
    else
      throw InvalidInput(kOption, where + "not a column of a spectrum file; " + kColumns);
    for (Col seen : cols)
      if (seen == c || (c != Col::tau && seen != Col::tau))
        throw InvalidInput(kOption, where + "a second " + (c == Col::tau ? "tau" : "modulus") +
                                        " column; " + kColumns);
    moduli += c != Col::tau;
    cols.push_back(c);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (moduli == 0 || cols.size() != 2)
    throw InvalidInput(kOption, at + "the header " + shown(line) + " has no " +
                                    (moduli == 0 ? "modulus" : "tau") + " column; " + kColumns);
  return cols;
}

/// The instantaneous modulus of a comment `# G0 = VALUE` or `# E0 = VALUE`.
struct Scale {
  double value = 0.0;
  bool young = false;   ///< E0: a Young's modulus
  std::size_t line = 0; ///< 0: not given
};

/// Reads a comment's G0 or E0 into `s`; any other comment is skipped.
void read_comment(const std::string& at, std::size_t n, const std::string& comment, Scale& s) {
  const std::string t = trimmed(comment.substr(1));
  const std::size_t eq = t.find('=');
  const std::string key = eq == std::string::npos ? "" : trimmed(t.substr(0, eq));
  if (key != "G0" && key != "E0") return;
  if (s.line != 0)
    throw InvalidInput(kOption, at +
                                    "a second instantaneous modulus (G0 or E0; the first is on "
                                    "line " +
                                    std::to_string(s.line) + ")");
  const std::string text = trimmed(t.substr(eq + 1));
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x) || x <= 0.0)
    throw InvalidInput(kOption, at + key + " must be a finite number > 0, got " + shown(text));
  s = Scale{x, key == "E0", n};
}

/// The value of column `c` (the `i`-th) of term k.
double cell(const std::string& at, Col c, std::size_t i, std::size_t k, const std::string& text) {
  const std::string key = col_name(c) + std::to_string(k);
  const std::string where = at + "column " + std::to_string(i) + " (" + col_name(c) + "): ";
  const std::string t = trimmed(text);
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0')
    throw InvalidInput(kOption, where + key + " must be a number, got " + shown(t));
  const std::string got = std::isfinite(x) ? format_number(x) : t;
  if (c == Col::g) {
    if (!(x > 0.0 && x < 1.0))
      throw InvalidInput(kOption, where + key +
                                      " must be a finite number > 0 and < 1 (a modulus "
                                      "normalised by G0), got " +
                                      got);
    return x;
  }
  const ParamSpec& spec = c == Col::tau ? branch_time_spec() : branch_modulus_spec();
  if (!spec.contains(x))
    throw InvalidInput(kOption, where + key + " must be " + spec.allowed() + ", got " + got);
  return x;
}

/// One term from a row of the header's columns.
Branch row(const std::string& at, const std::vector<Col>& cols, std::size_t k,
           const std::string& line) {
  Branch b{};
  std::size_t start = 0;
  for (std::size_t i = 0; i < cols.size(); ++i) {
    const std::size_t comma = line.find(',', start);
    if ((comma == std::string::npos) != (i + 1 == cols.size()))
      throw InvalidInput(
          kOption, at + "term " + std::to_string(k) + " must have " + std::to_string(cols.size()) +
                       " values separated by commas, one per header column, got " + shown(line));
    const double x = cell(at, cols[i], i + 1, k,
                          line.substr(start, comma == std::string::npos ? comma : comma - start));
    (cols[i] == Col::tau ? b.tau : b.G) = x;
    start = comma + 1;
  }
  return b;
}

/// The file's terms and columns, before any modulus is converted.
struct Raw {
  std::vector<Col> cols;
  std::vector<Branch> terms;
  Scale scale;
};

Raw read_lines(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  Raw r;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (n == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3); // UTF-8 BOM
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (line.size() > kMaxLine)
      throw InvalidInput(kOption, at + "the line is longer than " + std::to_string(kMaxLine) +
                                      " characters; a line holds one term");
    const std::string t = trimmed(line);
    if (t.empty()) continue;
    if (t[0] == '#')
      read_comment(at, n, t, r.scale);
    else if (r.cols.empty())
      r.cols = read_header(at, t);
    else if (r.terms.size() == kMaxBranches)
      throw InvalidInput(kOption, at + "more than " + std::to_string(kMaxBranches) +
                                      " terms; a spectrum has at most " +
                                      std::to_string(kMaxBranches));
    else
      r.terms.push_back(row(at, r.cols, r.terms.size() + 1, t));
  }
  if (r.cols.empty())
    throw InvalidInput(kOption, path +
                                    ": no header; the first line that is not a comment names "
                                    "the columns, e.g. G,tau; " +
                                    kColumns);
  if (r.terms.empty())
    throw InvalidInput(kOption, path + ": no terms after the header; give one term per line");
  return r;
}

} // namespace

SpectrumFile read_prony_file(const std::string& path, double nu) {
  const Raw r = read_lines(path, read_small_file(kOption, path,
                                                 "a spectrum file holds a header and at most " +
                                                     std::to_string(kMaxBranches) + " terms"));
  const Col modulus = r.cols[0] == Col::tau ? r.cols[1] : r.cols[0];
  const double young = 1.0 / (4.0 * (1.0 - nu * nu)); // G = E / (4 (1 - nu^2))
  const std::string at = path + ":" + std::to_string(r.scale.line) + ": ";
  if (r.scale.line != 0 && modulus != Col::g)
    throw InvalidInput(kOption, at + (r.scale.young ? "E0" : "G0") +
                                    " applies to normalised moduli (a column g) only");
  if (modulus == Col::g && r.scale.line == 0)
    throw InvalidInput(kOption, path + ": the column g (moduli normalised by the instantaneous "
                                       "modulus) needs a line '# G0 = VALUE' (or '# E0 = VALUE')");
  SpectrumFile out;
  out.uses_nu = modulus == Col::E || r.scale.young;
  const double scale = modulus == Col::G   ? 1.0
                       : modulus == Col::E ? young
                                           : r.scale.value * (r.scale.young ? young : 1.0);
  double sum_g = 0.0;
  for (const Branch& b : r.terms) {
    out.branches.push_back(Branch{b.G * scale, b.tau});
    sum_g += b.G;
  }
  if (modulus == Col::g) {
    if (!(sum_g < 1.0))
      throw InvalidInput(kOption, path + ": the normalised moduli g sum to " +
                                      format_number(sum_g) +
                                      "; the sum must be < 1 (G = G0 (1 - sum g) > 0)");
    out.G = scale * (1.0 - sum_g);
  }
  for (std::size_t k = 0; k < out.branches.size(); ++k)
    if (!branch_modulus_spec().contains(out.branches[k].G))
      throw InvalidInput(kOption, path + ": term " + std::to_string(k + 1) + " gives G" +
                                      std::to_string(k + 1) + " = " +
                                      format_number(out.branches[k].G) + ", which must be " +
                                      branch_modulus_spec().allowed());
  return out;
}

} // namespace mdrmap::material
