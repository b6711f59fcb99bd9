#pragma once
// A lab record as the velocity history of `mdrmap simulate --history-file`
// (docs/design.md, "Lab records"; docs/velocity-steps.md): a CSV file whose
// header names its columns, `t` (time) and `v` (the load-point sliding
// velocity) required in any order, other columns (measured mu, Fx, ...)
// ignored. A row's velocity holds from its time to the next row's; before
// the first row the contact slides steadily at the first row's velocity.
//
// As a case: v0 = the first row's v and t = 0 at the first row's time; a
// segment starts at the first row and at every later row whose v differs
// from the previous row's (rows of equal v are one segment), and lasts to
// the next such row; the last row ends the record (its own v never acts).
// The output instants are the rows' times: Sampling::at gets, per segment,
// the times of its rows since its start and its end.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "core/model/case.hpp"

namespace mdrmap::cases {

/// The rows of a lab record, as read.
struct LabRecord {
  std::string path;
  std::vector<double> t;         ///< times, strictly increasing
  std::vector<double> v;         ///< load-point velocities, finite and >= 0
  std::vector<std::size_t> line; ///< the file's line of each row (1-based)
  /// The columns asked for as measured (read_lab_record's `measured`) that
  /// the header names: a number per row, NaN where the value is empty or
  /// nan (not measured).
  std::map<std::string, std::vector<double>> measured;
};

/// Reads a record: the first line that is not blank or a comment (first
/// non-blank character '#') is the header; then one row per line with as
/// many values as the header has names; at least two rows. Spaces around
/// a value and a final CR are allowed. Throws InvalidInput("history-file")
/// with "FILE:LINE: " where a line is at fault. The columns named in
/// `measured` (mdrmap fit's mu, Fx, FN, d, sd) are read too.
LabRecord read_lab_record(const std::string& path, const std::vector<std::string>& measured = {});

/// Sets c.history (v0 and the segments) and c.sampling.at from the record
/// as the header comment says. Throws InvalidInput("history-file") where
/// the first row's v is 0 or the record has more velocity changes than a
/// history may have segments.
void apply_lab_record(const LabRecord& r, Case& c);

/// The index in the series of c (a case that apply_lab_record made) of each
/// row of the record, in order: every sample but the end of each segment
/// before the last (the same instant as the next segment's start, which is
/// the row: the state once the row's velocity holds).
std::vector<std::size_t> record_rows(const Case& c);

/// The load-point slip since t = 0 at each row of the record.
std::vector<double> record_slip(const LabRecord& r);

} // namespace mdrmap::cases
