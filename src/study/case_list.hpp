#pragma once
// Private to the study config: CSV case lists ([cases] file = ...;
// read_cases_csv in study/config.hpp reads one), read line by line.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "study/config.hpp"

namespace mdrmap::study::detail {

/// Resolves a [cases] file against the INI's directory ("" for none) and
/// checks it can be read. Throws ConfigError("cases.file") without location.
std::string resolve_cases_file(const std::string& file, const std::string& base_dir);

/// The columns a case list's header names (split at commas), each listed
/// (its values in the file), in the file's order. Throws ConfigError("cases.file")
/// naming the file, line and column of an unknown or repeated name.
std::vector<Axis> read_list_columns(const std::string& path);

/// Refuses a case list without cases. Throws ConfigError("cases.file").
[[noreturn]] void no_cases_after_header(const std::string& path);

/// Reads a study's case list one case at a time: the constructor opens the
/// file and reads the header, next() each case line (blank and comment lines
/// skipped) as a row of the study (the listed columns' values from the line,
/// each checked against its column's range; the others the config's one value).
class CaseListReader {
public:
  explicit CaseListReader(const StudyConfig& c);
  /// The next case into r; false at the end of the file.
  bool next(Row& r);
  /// Passes over the next case without reading it; false at the end of the file.
  bool skip() {
    std::string line;
    return next_line(line);
  }
  /// Where the line of the case next() returned last starts: its byte
  /// offset, and the number of the line before it (for seek).
  std::uint64_t case_offset() const { return case_offset_; }
  std::uint64_t line_before_case() const { return case_line_ - 1; }
  /// Continues at a case line found by case_offset() / line_before_case().
  void seek(std::uint64_t offset, std::uint64_t line_before);

private:
  /// The next line that is neither blank nor a comment, trimmed; false at the end.
  bool next_line(std::string& line);
  const StudyConfig* c_;
  std::string path_;
  std::ifstream in_;
  std::vector<std::size_t> axis_of_column_; ///< CSV column -> index in c.axes
  Row fixed_;                               ///< the config's values, listed ones 0
  std::uint64_t offset_ = 0, line_ = 0;     ///< of the next line to read
  std::uint64_t case_offset_ = 0, case_line_ = 0;
};

/// SHA-256 (FIPS 180-4), for the digest of a case list's canonical rows.
class Sha256 {
public:
  Sha256();
  void add(const void* data, std::size_t n);
  void add(const std::string& s) { add(s.data(), s.size()); }
  /// The digest as 64 lowercase hex digits (ends the hashing).
  std::string hex();

private:
  void block(const unsigned char* p);
  std::uint32_t h_[8];
  unsigned char buf_[64];
  std::size_t used_ = 0;
  std::uint64_t bytes_ = 0;
};

} // namespace mdrmap::study::detail
