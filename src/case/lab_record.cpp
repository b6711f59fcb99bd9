#include "case/lab_record.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "case/case_input.hpp"
#include "case/text.hpp"

namespace mdrmap::cases {
namespace {

const char* const kOption = "history-file";

/// The comma-separated fields of a line, each trimmed.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string f;
  while (std::getline(in, f, ','))
    out.push_back(trimmed(f));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// The columns of `t` and `v` in the header `names`.
struct Columns {
  std::size_t t = 0, v = 0, count = 0;
  std::map<std::string, std::size_t> measured; ///< name -> column
};

Columns header_columns(const std::vector<std::string>& names, const std::string& at,
                       const std::vector<std::string>& measured) {
  Columns c;
  c.count = names.size();
  for (std::size_t i = 0; i < names.size(); ++i)
    for (const auto& m : measured)
      if (names[i] == m && !c.measured.emplace(m, i).second)
        throw InvalidInput(kOption, at + "the header names column " + m + " twice");
  bool has_t = false, has_v = false;
  for (std::size_t i = 0; i < names.size(); ++i) {
    bool* seen = names[i] == "t" ? &has_t : names[i] == "v" ? &has_v : nullptr;
    if (seen == nullptr) continue;
    if (*seen) throw InvalidInput(kOption, at + "the header names column " + names[i] + " twice");
    *seen = true;
    (names[i] == "t" ? c.t : c.v) = i;
  }
  if (!has_t || !has_v)
    throw InvalidInput(kOption, at + "the header has no column " + (has_t ? "v" : "t") +
                                    "; it must name the columns t (time) and v (load-point "
                                    "velocity), in any order");
  return c;
}

/// The number in `text`, finite; `what` names it in a refusal.
double number(const std::string& text, const std::string& what, const std::string& at) {
  char* end = nullptr;
  errno = 0;
  const double x = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x) || errno == ERANGE)
    throw InvalidInput(kOption, at + what + " must be a finite number, got " + shown(text));
  return x;
}

/// Appends the row `line` to r, checked against the previous row.
void add_row(LabRecord& r, const Columns& cols, const std::string& line, const std::string& at) {
  const std::vector<std::string> f = fields(line);
  if (f.size() != cols.count)
    throw InvalidInput(kOption, at + "the row has " + std::to_string(f.size()) +
                                    " values; the header names " + std::to_string(cols.count) +
                                    " columns");
  const double t = number(f[cols.t], "t", at), v = number(f[cols.v], "v", at);
  if (!r.t.empty() && !(t > r.t.back()))
    throw InvalidInput(kOption, at + "t = " + format_number(t) +
                                    " does not follow the previous row's t = " +
                                    format_number(r.t.back()) + "; times must increase strictly");
  if (!(v >= 0.0))
    throw InvalidInput(kOption, at + "v = " + format_number(v) +
                                    " is negative; the load-point "
                                    "velocity is >= 0 (0 is a hold)");
  r.t.push_back(t);
  r.v.push_back(v);
  for (const auto& [name, col] : cols.measured) {
    const std::string& x = f[col];
    const bool missing = x.empty() || x == "nan" || x == "NaN" || x == "NAN";
    r.measured[name].push_back(missing ? NAN : number(x, name, at));
  }
}

/// Refuses what is not a regular file (a FIFO would block the read).
void require_regular_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    throw InvalidInput(kOption, "cannot read '" + path + "': " + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode))
    throw InvalidInput(kOption, "must be a regular file, got '" + path + "'");
}

} // namespace

LabRecord read_lab_record(const std::string& path, const std::vector<std::string>& measured) {
  require_regular_file(path);
  std::ifstream in(path);
  if (!in) throw InvalidInput(kOption, "cannot read '" + path + "'");
  LabRecord r;
  r.path = path;
  Columns cols;
  bool header = false;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (n == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3); // UTF-8 BOM
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string t = trimmed(line), at = path + ":" + std::to_string(n) + ": ";
    if (t.empty() || t[0] == '#') continue;
    if (header) {
      add_row(r, cols, t, at);
      r.line.push_back(n);
    } else {
      cols = header_columns(fields(t), at, measured);
      for (const auto& [name, col] : cols.measured)
        r.measured[name]; // named by the header: present, if with no rows
      header = true;
    }
  }
  if (in.bad()) throw InvalidInput(kOption, "cannot read '" + path + "'");
  if (!header)
    throw InvalidInput(kOption, path + ": no header; the first line must name the columns, t "
                                       "and v among them");
  if (r.t.size() < 2)
    throw InvalidInput(kOption, path + ": " + std::to_string(r.t.size()) +
                                    " row(s); a record needs at least two (the first row's time "
                                    "is t = 0, the last ends the record)");
  return r;
}

void apply_lab_record(const LabRecord& r, Case& c) {
  const std::size_t n = r.t.size();
  if (!(r.v.front() > 0.0))
    throw InvalidInput(kOption, r.path + ": the first row's v is 0; it is the steady sliding "
                                         "before the record, > 0 (start the record while sliding)");
  c.history.v0 = r.v.front();
  c.history.segments.clear();
  c.sampling.at.clear();
  for (std::size_t a = 0; a + 1 < n;) {
    std::size_t b = a + 1; // the next segment's first row, or the last row
    while (b + 1 < n && r.v[b] == r.v[a])
      ++b;
    std::vector<double> at;
    for (std::size_t i = a; i <= b; ++i)
      at.push_back(r.t[i] - r.t[a]);
    c.history.segments.push_back(Segment{r.v[a], at.back()});
    c.sampling.at.push_back(std::move(at));
    if (c.history.size() > kMaxSegments)
      throw InvalidInput(kOption, r.path + ": more than " + std::to_string(kMaxSegments) +
                                      " velocity changes; a history has at most " +
                                      std::to_string(kMaxSegments) + " segments");
    a = b;
  }
}

std::vector<std::size_t> record_rows(const Case& c) {
  std::vector<std::size_t> rows;
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const auto n = static_cast<std::size_t>(c.sampling.count(k));
    const std::size_t used = k + 1 == c.history.size() ? n : n - 1;
    for (std::size_t j = 0; j < used; ++j)
      rows.push_back(i + j);
    i += n;
  }
  return rows;
}

std::vector<double> record_slip(const LabRecord& r) {
  std::vector<double> slip(r.t.size(), 0.0);
  for (std::size_t i = 1; i < r.t.size(); ++i)
    slip[i] = slip[i - 1] + r.v[i - 1] * (r.t[i] - r.t[i - 1]);
  return slip;
}

} // namespace mdrmap::cases
