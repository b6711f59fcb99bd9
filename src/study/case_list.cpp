#include "study/case_list.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "study/columns.hpp"
#include "study/config_detail.hpp"
#include "study/ini.hpp"
#include "study/temperature_column.hpp"

namespace mdrmap::study::detail {
namespace {

namespace fs = std::filesystem;

const char* const kAllColumns =
    "d or F0 (or its old spelling FN), R, tau, v, optionally G, a spectrum's G1, tau1, G2, "
    "tau2, ... and aT or temperature, and the history: w1, T1, w2, T2, ... or the seed's v1";

[[noreturn]] void cannot_read(const std::string& path, const std::string& why) {
  throw ConfigError("cases.file", "cannot read " + shown_path(path) + ": " + why);
}

/// Reads one case line (split at commas) into the row's listed columns; `at` is "FILE:LINE".
void read_row(const std::vector<std::string>& fields, const std::string& at,
              const std::vector<std::size_t>& axis_of_column, const StudyConfig& c, Row& r) {
  if (fields.size() != axis_of_column.size())
    throw ConfigError("cases.file",
                      at + ": " + std::to_string(fields.size()) + " fields, the header has " +
                          std::to_string(axis_of_column.size()) + "; give one value per column");
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const Axis& a = c.axes[axis_of_column[k]];
    const ParamSpec& spec = column_spec(a.column);
    std::string cell = trim(fields[k]);
    const std::string here = at + ":" + std::to_string(k + 1) + ": ";
    const TempUnit unit = a.column.kind == Column::Kind::Temperature // 35C: in TREF's unit
                              ? listed_temperature_unit(c, a.option(), here, cell)
                              : TempUnit::None;
    const Num n = to_number(cell);
    if (n.err != NumError::None)
      throw ConfigError(a.option(),
                        here + a.name +
                            (n.err == NumError::Empty ? std::string(" is empty")
                                                      : " value " + number_problem(cell, n.err)) +
                            "; " + a.name + " must be " + spec.allowed());
    const double x = unit == TempUnit::None ? n.x : listed_in_wlf_unit(c, n.x, unit);
    try {
      spec.check(x);
    } catch (const InvalidInput& e) {
      throw ConfigError(a.option(), here + a.name + " " + e.what());
    }
    r[axis_of_column[k]] = x;
  }
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

void no_cases_after_header(const std::string& path) {
  throw ConfigError("cases.file",
                    path + ": no cases after the header; add one line of values per case");
}

namespace {

/// The next line of a case list that is neither blank nor a comment, trimmed
/// (a UTF-8 BOM on line 1 dropped), into `out`, and where it starts into
/// `start`; false at the end of the file. `offset` and `line` are those of
/// the next line to read.
bool content_line(std::istream& in, const std::string& path, std::uint64_t& offset,
                  std::uint64_t& line, std::string& out, std::uint64_t& start) {
  std::string raw;
  while (true) {
    const std::uint64_t here = offset;
    if (!std::getline(in, raw)) break;
    offset += raw.size() + (in.eof() ? 0 : 1);
    ++line;
    if (line == 1 && starts_with(raw, "\xEF\xBB\xBF")) raw.erase(0, 3); // UTF-8 BOM
    out = trim(raw);
    if (out.empty() || out[0] == '#') continue;
    start = here;
    return true;
  }
  if (in.bad()) cannot_read(path, "read error");
  return false;
}

/// The header line of a case list (its first content line). Throws ConfigError("cases.file").
std::string header_line(std::istream& in, const std::string& path, std::uint64_t& offset,
                        std::uint64_t& line) {
  std::string header;
  std::uint64_t start = 0;
  if (!content_line(in, path, offset, line, header, start))
    throw ConfigError("cases.file", path + ": no header; the first line must name the columns " +
                                        kAllColumns + " (in any order)");
  return header;
}

} // namespace

std::vector<Axis> read_list_columns(const std::string& path) {
  std::ifstream in = open_cases(path);
  std::uint64_t offset = 0, line = 0;
  const std::string text = header_line(in, path, offset, line);
  std::vector<Axis> out;
  const std::vector<std::string> names = split(text, ',');
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string here = path + ":" + std::to_string(line) + ":" + std::to_string(k + 1) + ": ";
    Axis a;
    a.name = trim(names[k]);
    a.section = "cases";
    a.listed = true;
    if (!parse_column(a.name, a.column))
      throw ConfigError("cases.file", here + "unknown column " + shown(a.name) +
                                          "; the header names the columns " + kAllColumns);
    for (const Axis& b : out)
      if (column_rank(b.column) == column_rank(a.column))
        throw ConfigError(
            "cases.file",
            here + "column '" + a.name + "' " +
                (a.name == b.name ? "appears twice" : "sets what column '" + b.name + "' sets") +
                "; give each once");
    out.push_back(a);
  }
  return out;
}

CaseListReader::CaseListReader(const StudyConfig& c) : c_(&c), path_(c.cases_file) {
  in_ = open_cases(path_);
  const std::string line = header_line(in_, path_, offset_, line_);
  for (const std::string& name : split(line, ','))
    for (std::size_t i = 0; i < c.axes.size(); ++i)
      if (c.axes[i].listed && c.axes[i].name == trim(name)) axis_of_column_.push_back(i);
  std::size_t listed = 0;
  fixed_.assign(c.axes.size(), 0.0);
  for (std::size_t i = 0; i < c.axes.size(); ++i) {
    if (c.axes[i].listed)
      ++listed;
    else
      fixed_[i] = c.axes[i].values.front();
  }
  if (axis_of_column_.size() != listed || listed != split(line, ',').size())
    throw ConfigError("cases.file", shown_path(path_) + " has another header than when the "
                                                        "study was read; run it again");
}

bool CaseListReader::next_line(std::string& line) {
  if (!content_line(in_, path_, offset_, line_, line, case_offset_)) return false;
  case_line_ = line_;
  return true;
}

bool CaseListReader::next(Row& r) {
  std::string line;
  if (!next_line(line)) return false;
  r = fixed_;
  read_row(split(line, ','), path_ + ":" + std::to_string(line_), axis_of_column_, *c_, r);
  return true;
}

void CaseListReader::seek(std::uint64_t offset, std::uint64_t line_before) {
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  if (!in_) cannot_read(path_, "cannot seek to byte " + std::to_string(offset));
  offset_ = offset;
  line_ = line_before;
}

// ---- SHA-256 ------------------------------------------------------------------

namespace {

constexpr std::uint32_t kSha256K[64] = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

std::uint32_t rotr(std::uint32_t x, int n) {
  return (x >> n) | (x << (32 - n));
}

} // namespace

Sha256::Sha256()
    : h_{0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
         0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19},
      buf_{} {}

void Sha256::block(const unsigned char* p) {
  std::uint32_t w[64];
  for (int i = 0; i < 16; ++i)
    w[i] = static_cast<std::uint32_t>(p[4 * i]) << 24 |
           static_cast<std::uint32_t>(p[4 * i + 1]) << 16 |
           static_cast<std::uint32_t>(p[4 * i + 2]) << 8 | static_cast<std::uint32_t>(p[4 * i + 3]);
  for (int i = 16; i < 64; ++i) {
    const std::uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
    const std::uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
    w[i] = w[i - 16] + s0 + w[i - 7] + s1;
  }
  std::uint32_t a = h_[0], b = h_[1], c = h_[2], d = h_[3], e = h_[4], f = h_[5], g = h_[6],
                h = h_[7];
  for (int i = 0; i < 64; ++i) {
    const std::uint32_t t1 =
        h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + kSha256K[i] + w[i];
    const std::uint32_t t2 =
        (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
    h = g, g = f, f = e, e = d + t1, d = c, c = b, b = a, a = t1 + t2;
  }
  const std::uint32_t out[8] = {a, b, c, d, e, f, g, h};
  for (int i = 0; i < 8; ++i)
    h_[i] += out[i];
}

void Sha256::add(const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  bytes_ += n;
  while (n > 0) {
    const std::size_t k = std::min(n, sizeof buf_ - used_);
    std::memcpy(buf_ + used_, p, k);
    used_ += k, p += k, n -= k;
    if (used_ == sizeof buf_) {
      block(buf_);
      used_ = 0;
    }
  }
}

std::string Sha256::hex() {
  const std::uint64_t bits = bytes_ * 8;
  const unsigned char pad = 0x80, zero = 0;
  add(&pad, 1);
  while (used_ != 56)
    add(&zero, 1);
  unsigned char len[8];
  for (int i = 0; i < 8; ++i)
    len[i] = static_cast<unsigned char>(bits >> (56 - 8 * i));
  add(len, 8);
  std::string out;
  char two[3];
  for (const std::uint32_t x : h_)
    for (int i = 3; i >= 0; --i) {
      std::snprintf(two, sizeof two, "%02x", static_cast<unsigned>((x >> (8 * i)) & 0xff));
      out += two;
    }
  return out;
}

} // namespace mdrmap::study::detail
