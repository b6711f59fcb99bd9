#include "study/case_source.hpp"

#include <optional>
#include <sys/stat.h>
#include <utility>

#include "study/axes.hpp"
#include "study/case_list.hpp"
#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

std::uint64_t file_size(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
}

} // namespace

std::vector<std::uint64_t> CaseListIndex::pack() const {
  std::vector<std::uint64_t> v{count, file_bytes, offsets.size()};
  v.insert(v.end(), offsets.begin(), offsets.end());
  v.insert(v.end(), lines.begin(), lines.end());
  v.push_back(sha256.size());
  for (const char ch : sha256)
    v.push_back(static_cast<unsigned char>(ch));
  return v;
}

CaseListIndex CaseListIndex::unpack(const std::vector<std::uint64_t>& v) {
  CaseListIndex x;
  x.count = v.at(0);
  x.file_bytes = v.at(1);
  const auto k = static_cast<std::ptrdiff_t>(v.at(2));
  x.offsets.assign(v.begin() + 3, v.begin() + 3 + k);
  x.lines.assign(v.begin() + 3 + k, v.begin() + 3 + 2 * k);
  const std::size_t at = 3 + 2 * static_cast<std::size_t>(k);
  for (std::size_t i = 0; i < v.at(at); ++i)
    x.sha256 += static_cast<char>(v.at(at + 1 + i));
  return x;
}

CaseListIndex scan_case_list(const StudyConfig& c, bool check_cases) {
  CaseListReader reader(c);
  CaseListIndex index;
  Sha256 hash;
  std::optional<InvalidInput> first_bad; // expand_cases checks the windows after reading all
  Row s;
  while (reader.next(s)) {
    if (index.count % CaseListIndex::kStride == 0) {
      index.offsets.push_back(reader.case_offset());
      index.lines.push_back(reader.line_before_case());
    }
    hash.add(canonical_row(c, s));
    if (check_cases && !first_bad) {
      try {
        check_listed_case(c, index.count, s);
      } catch (const InvalidInput& e) {
        first_bad = e;
      }
    }
    ++index.count;
  }
  if (index.count == 0) no_cases_after_header(c.cases_file);
  if (check_cases) {
    check_case_list_size(c, index.count);
    if (first_bad) throw *first_bad;
  }
  index.file_bytes = file_size(c.cases_file);
  index.sha256 = hash.hex();
  return index;
}

void check_grid_cases(const StudyConfig& c, std::size_t i0, std::size_t i1) {
  const CaseSource source(c);
  for (std::size_t i = i0; i < i1; ++i)
    check_grid_case(c, i, source.row(i));
}

CaseSource::CaseSource(const StudyConfig& c) : c_(&c) {
  if (c.kind == StudyConfig::Kind::Cases) {
    index_ = scan_case_list(c, false);
    n_ = index_.count;
    return;
  }
  n_ = case_count(c);
  for (const Axis& a : c.axes)
    shape_.push_back(a.values.size());
}

CaseSource::CaseSource(const StudyConfig& c, CaseListIndex index)
    : c_(&c), n_(index.count), index_(std::move(index)) {}

CaseSource::CaseSource(CaseSource&&) noexcept = default;
CaseSource& CaseSource::operator=(CaseSource&&) noexcept = default;
CaseSource::~CaseSource() = default;

Row CaseSource::row(std::size_t i) const {
  if (c_->kind == StudyConfig::Kind::Cases) {
    std::vector<Row> one;
    rows(i, i + 1, one);
    return one.front();
  }
  Row r(shape_.size());
  for (std::size_t j = shape_.size(); j-- > 0;) { // C order: the last axis fastest
    r[j] = c_->axes[j].values[i % shape_[j]];
    i /= shape_[j];
  }
  return r;
}

void CaseSource::rows(std::size_t i0, std::size_t i1, std::vector<Row>& out) const {
  out.clear();
  if (i1 <= i0) return;
  out.reserve(i1 - i0);
  if (c_->kind != StudyConfig::Kind::Cases) {
    for (std::size_t i = i0; i < i1; ++i)
      out.push_back(row(i));
    return;
  }
  const auto changed = [&](const std::string& how) {
    return ConfigError("cases.file", shown_path(c_->cases_file) + " " + how +
                                         " since the study began; run it again from an "
                                         "unchanged case list");
  };
  if (!reader_) {
    if (file_size(c_->cases_file) != index_.file_bytes) throw changed("changed size");
    reader_ = std::make_unique<CaseListReader>(*c_);
    reader_next_ = 0;
  }
  if (i1 > n_) throw changed("has fewer cases"); // a caller's bug, or a truncated file
  if (i0 != reader_next_) {
    const std::size_t block = i0 / CaseListIndex::kStride;
    reader_->seek(index_.offsets[block], index_.lines[block]);
    reader_next_ = block * CaseListIndex::kStride;
    for (; reader_next_ < i0; ++reader_next_)
      if (!reader_->skip()) throw changed("has fewer cases");
  }
  Row s;
  for (; reader_next_ < i1; ++reader_next_) {
    if (!reader_->next(s)) throw changed("has fewer cases");
    out.push_back(s);
  }
}

std::string CaseSource::canonical() const {
  if (c_->kind == StudyConfig::Kind::Cases)
    return canonical_case_list(*c_, index_.count, index_.sha256);
  return study::canonical(*c_);
}

} // namespace mdrmap::study
