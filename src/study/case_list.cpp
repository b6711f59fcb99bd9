#include "study/case_list.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study::detail {
namespace {

namespace fs = std::filesystem;

/// Columns of a case list, in StepRow field order.
constexpr const char* kColumns[5] = {"d", "R", "tau", "v", "v1"};
const char* const kAllColumns = "d, R, tau, v, v1";

[[noreturn]] void cannot_read(const std::string& path, const std::string& why) {
  throw ConfigError("cases.file", "cannot read " + shown_path(path) + ": " + why);
}

/// The StepRow field (index into kColumns) a column name or option names, or -1.
int field_index(const std::string& name) {
  int f = -1;
  for (int j = 0; j < 5; ++j)
    if (name == kColumns[j]) f = j;
  return f;
}

/// Where each field is in a case list's lines, from its header.
struct Columns {
  int column_of_field[5] = {-1, -1, -1, -1, -1}; ///< StepRow field -> CSV column index
  std::vector<int> field_of_column;              ///< CSV column -> StepRow field
};

/// Reads the header line (split at commas); `at` is "FILE:LINE".
Columns read_header(const std::vector<std::string>& fields, const std::string& at) {
  Columns cols;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const std::string name = trim(fields[k]);
    const std::string here = at + ":" + std::to_string(k + 1) + ": ";
    const int f = field_index(name);
    if (f < 0) {
      const std::string near = nearest(name, {"d", "R", "tau", "v", "v1"});
      throw ConfigError("cases.file", here + "unknown column " + shown(name) + "; " +
                                          (near.empty() ? "" : "did you mean '" + near + "'? ") +
                                          "the header must name the columns " + kAllColumns +
                                          ", each once, in any order");
    }
    if (cols.column_of_field[f] >= 0)
      throw ConfigError("cases.file", here + "column '" + name + "' appears twice (also column " +
                                          std::to_string(cols.column_of_field[f] + 1) +
                                          "); give each of " + kAllColumns + " once");
    cols.column_of_field[f] = static_cast<int>(k);
    cols.field_of_column.push_back(f);
  }
  for (int j = 0; j < 5; ++j)
    if (cols.column_of_field[j] < 0)
      throw ConfigError("cases.file", at + ": missing column '" + kColumns[j] +
                                          "'; the header must name the columns " + kAllColumns +
                                          " (in any order)");
  return cols;
}

/// Reads one case line (split at commas), validated; `at` is "FILE:LINE".
StepRow read_row(const std::vector<std::string>& fields, const std::string& at, const Columns& cols,
                 double G) {
  if (fields.size() != 5)
    throw ConfigError("cases.file", at + ": " + std::to_string(fields.size()) +
                                        " fields, the header has 5; give one value per column");
  double x[5] = {0, 0, 0, 0, 0};
  for (std::size_t k = 0; k < 5; ++k) {
    const int f = cols.field_of_column[k];
    const std::string cell = trim(fields[k]);
    const Num n = to_number(cell);
    if (n.err != NumError::None)
      throw ConfigError(std::string("cases.") + kColumns[f],
                        at + ":" + std::to_string(k + 1) + ": " + kColumns[f] +
                            (n.err == NumError::Empty ? std::string(" is empty")
                                                      : " value " + number_problem(cell, n.err)) +
                            "; " + kColumns[f] + " must be " + range_text(kColumns[f]));
    x[f] = n.x;
  }
  StepRow s;
  s.d = x[0];
  s.R = x[1];
  s.tau = x[2];
  s.v = x[3];
  s.v1 = x[4];
  s.G = G;
  try {
    validate_row(s);
  } catch (const InvalidInput& e) {
    const int f = field_index(e.option());
    if (f < 0) throw ConfigError("run.G", at + ": G " + e.what());
    throw ConfigError(std::string("cases.") + kColumns[f],
                      at + ":" + std::to_string(cols.column_of_field[f] + 1) + ": " + kColumns[f] +
                          " " + e.what());
  }
  return s;
}

std::ifstream open_cases(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) cannot_read(path, std::strerror(EISDIR));
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno != 0 ? errno : ENOENT;
    cannot_read(path, std::strerror(err));
  }
  return in;
}

} // namespace

std::string resolve_cases_file(const std::string& file, const std::string& base_dir) {
  const fs::path p(file);
  const std::string resolved =
      (p.is_absolute() || base_dir.empty()) ? p.string() : (fs::path(base_dir) / p).string();
  const std::string rule = "; file must name a CSV case list";
  std::error_code ec;
  if (fs::is_directory(resolved, ec)) cannot_read(resolved, std::strerror(EISDIR) + rule);
  std::FILE* f = std::fopen(resolved.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    cannot_read(resolved, std::strerror(err) + rule);
  }
  std::fclose(f);
  return resolved;
}

} // namespace mdrmap::study::detail

namespace mdrmap::study {

using namespace detail;

std::vector<StepRow> read_cases_csv(const std::string& path, double G) {
  if (!std::isfinite(G) || !(G > 0.0))
    throw ConfigError("run.G", "G must be a finite number > 0, got " + format_number(G));
  std::ifstream in = open_cases(path);
  Columns cols;
  std::vector<StepRow> cases;
  bool have_header = false;
  int line_no = 0;
  std::string raw;
  while (std::getline(in, raw)) {
    ++line_no;
    if (line_no == 1 && starts_with(raw, "\xEF\xBB\xBF")) raw.erase(0, 3); // UTF-8 BOM
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::string at = path + ":" + std::to_string(line_no);
    const auto fields = split(line, ',');
    if (have_header) {
      cases.push_back(read_row(fields, at, cols, G));
    } else {
      cols = read_header(fields, at);
      have_header = true;
    }
  }
  if (in.bad()) cannot_read(path, "read error");
  if (!have_header)
    throw ConfigError("cases.file", path + ": no header; the first line must name the columns " +
                                        kAllColumns + " (in any order)");
  if (cases.empty())
    throw ConfigError("cases.file",
                      path + ": no cases after the header; add one line of values per case");
  return cases;
}

} // namespace mdrmap::study
