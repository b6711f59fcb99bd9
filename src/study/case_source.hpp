#pragma once
// The cases of a study by index, without holding them: a grid computes its
// case i from i (last axis fastest: the order of expand_cases); a case list
// reads its rows by range through a sparse index of its file (where every
// 4096th case's line starts). Memory: the axes for a grid, 16 bytes per 4096
// cases for a case list, whatever the number of cases. Pure C++: no MPI, no
// printing.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "study/config.hpp"

namespace mdrmap::study {

namespace detail {
class CaseListReader;
}

/// Where the cases of a case list are in its file, and what they hold.
struct CaseListIndex {
  static constexpr std::uint64_t kStride = 4096;
  std::uint64_t count = 0;            ///< cases in the file
  std::uint64_t file_bytes = 0;       ///< its size when scanned
  std::vector<std::uint64_t> offsets; ///< byte offset of the line of case k * kStride
  std::vector<std::uint64_t> lines;   ///< the number of the line before it
  std::string sha256;                 ///< of the cases' canonical rows (64 hex digits; canonical())

  /// Flat form, to broadcast.
  std::vector<std::uint64_t> pack() const;
  static CaseListIndex unpack(const std::vector<std::uint64_t>& v);
};

/// Reads a case list once, holding only its index: every row read and
/// checked, with the errors and in the order of read_cases_csv; with
/// check_cases also the time series' memory and each case's window and
/// samples, with the errors and in the order of expand_cases. Throws ConfigError.
CaseListIndex scan_case_list(const StudyConfig& c, bool check_cases);

/// Checks grid cases [i0, i1) in order as expand_cases does (the same
/// ConfigError for the first that fails), without storing them.
void check_grid_cases(const StudyConfig& c, std::size_t i0, std::size_t i1);

/// A study's cases by index. Holds a reference to the config, which must
/// outlive it. Not thread-safe (a case list's reader is shared).
class CaseSource {
public:
  /// A grid's cases (throws ConfigError for a grid of the wrong shape or
  /// size), or a case list's, scanned here (scan_case_list without check_cases).
  explicit CaseSource(const StudyConfig& c);
  /// A case list's cases, through its index (scan_case_list).
  CaseSource(const StudyConfig& c, CaseListIndex index);
  CaseSource(CaseSource&&) noexcept;
  CaseSource& operator=(CaseSource&&) noexcept;
  ~CaseSource();

  std::size_t size() const { return n_; }
  /// Case i (< size()), as expand_cases()[i].
  Row row(std::size_t i) const;
  /// Cases [i0, i1) into out, replacing its contents. A case list read back
  /// differently than scanned (the file changed) throws ConfigError("cases.file").
  void rows(std::size_t i0, std::size_t i1, std::vector<Row>& out) const;
  /// canonical(config), without reading a case list again.
  std::string canonical() const;

private:
  const StudyConfig* c_;
  std::size_t n_ = 0;
  std::vector<std::size_t> shape_; ///< grid: values per axis
  CaseListIndex index_;            ///< case list
  mutable std::unique_ptr<detail::CaseListReader> reader_;
  mutable std::size_t reader_next_ = 0; ///< the case the reader returns next
};

} // namespace mdrmap::study
