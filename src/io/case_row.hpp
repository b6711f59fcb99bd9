#pragma once
// One case's row of the friction map (schema mdrmap-map/2, docs/reference/map-schema.md),
// its datasets named by the output table (core/outputs/output_table.hpp),
// as computed (study/compute.hpp) and as written (io/map_file.hpp): which
// per-case datasets a study's map has, their units and meanings, and the row
// that holds one case's values. MPI- and HDF5-free.
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/model/state.hpp"
#include "core/outputs/output_table.hpp"

namespace mdrmap::io {

/// The netCDF default fill value of a double: undefined values (an event
/// metric across a hold, say) hold it, and their datasets say so in
/// `_FillValue`, so that xarray shows NaN while no file holds a NaN.
inline constexpr double kFillValue = 9.969209968386869e36;

/// What a dataset of the map holds, for the map's /schema group and the
/// datasets' `units` and `long_name` attributes.
struct FieldInfo {
  std::string path; ///< "group/name" in the map, e.g. "events/mu_peak"
  std::string
      unit; ///< a dimension name as core/model/params.hpp's dim_name: "force", "number", ...
  std::string meaning; ///< one line, lower case, no final period
};

/// One per-case float64 dataset: [N] or, per event, [N, K].
struct RowField {
  FieldInfo info;
  bool per_event = false;        ///< [N, K]
  bool may_be_undefined = false; ///< holds kFillValue where undefined (`_FillValue`)
};

/// Where the fields a solved case fills start in CaseRow::values, resolved
/// once from their names (RowLayout::slots()): the value of event k of a
/// per-event field is at its start + k. Per-quantity starts are in the
/// order of RowLayout::quantity().
struct RowSlots {
  static constexpr std::size_t kMaxQuantities = 6; ///< FN, Fx, mu, a2, d, a1
  using PerQuantity = std::array<std::size_t, kMaxQuantities>;
  /// The map's per-case results (the output table's Result entries in the map)
  /// but wall_seconds, which is measured last, at its own slot.
  std::vector<std::pair<const OutputSpec*, std::size_t>> results;
  std::size_t wall_seconds = 0;
  PerQuantity results_pre{}, analytic_pre{}, residuals_pre{};
  /// The map's event metrics (Event entries) and event states (EventState
  /// entries: each quantity's start), in table order.
  std::vector<std::pair<const OutputSpec*, std::size_t>> event_metrics;
  std::vector<std::pair<const OutputSpec*, PerQuantity>> event_states;
  PerQuantity analytic_ss{}, residuals_end{};
  PerQuantity analytic_jump{}, residuals_jump{};                 ///< at fixed depth only
  std::vector<std::pair<const OutputSpec*, std::size_t>> scales; ///< the case's Scales
};

/// The per-case datasets of a study's map: K segments, under load (the depth
/// and the leading edge move: d and a1 are quantities too) or at fixed depth
/// (where the seed's jump estimate exists).
class RowLayout {
public:
  RowLayout(std::size_t segments, bool by_force);
  std::size_t segments() const { return K_; }
  bool by_force() const { return by_force_; }
  /// float64 datasets, in the order of CaseRow::values.
  const std::vector<RowField>& fields() const { return fields_; }
  /// Values of field f in a row: 1 or K.
  std::size_t width(std::size_t f) const { return fields_[f].per_event ? K_ : 1; }
  /// Where field f starts in CaseRow::values.
  std::size_t offset(std::size_t f) const { return offsets_[f]; }
  std::size_t row_width() const { return offsets_.back(); }
  /// Index in values() of field `path` (event k for a per-event field); throws std::out_of_range.
  std::size_t at(const std::string& path, std::size_t k = 0) const;
  /// The fields a solved case fills, resolved by name once (at construction).
  const RowSlots& slots() const { return slots_; }
  /// The time series: t, FN, Fx, mu, a2 (and d, a1 under load), [N, K S].
  const std::vector<FieldInfo>& series() const { return series_; }
  /// The quantities of a state the map stores: FN, Fx, mu, a2 (and d, a1 under load).
  std::size_t quantities() const { return quantities_.size(); }
  /// Name of quantity q (< quantities()), as in the datasets' names: "FN", ...
  const char* quantity(std::size_t q) const;
  /// Quantity q of a state.
  double value(const State& s, std::size_t q) const;
  /// Series s (series() order: t, then the quantities) of a run's samples.
  const std::vector<double>& samples(const Series& x, std::size_t s) const;

private:
  void add(const std::string& path, const char* unit, const std::string& meaning,
           bool per_event = false, bool may_be_undefined = false);
  void add(const std::string& group, const OutputSpec& o); ///< an entry of the output table
  template <class F> void for_each_quantity(F f) const;    ///< FN, Fx, mu, a2 (d, a1 under load)
  std::string stationary() const;                          ///< "in stationary sliding at "
  void add_results();
  void add_events();
  void add_closed_forms();
  void add_scales();
  void add_residuals();
  void resolve_slots();
  RowSlots::PerQuantity per_quantity(const std::string& group, const char* suffix) const;
  std::size_t K_;
  bool by_force_;
  std::vector<RowField> fields_;
  std::vector<std::size_t> offsets_;                   ///< fields_.size() + 1
  std::unordered_map<std::string, std::size_t> index_; ///< path -> field
  std::vector<const OutputSpec*> quantities_;          ///< the state quantities of the table
  std::vector<FieldInfo> series_;
  RowSlots slots_;
};

/// results/status, /timeseries/segment, /failures/{case,message}.
const std::vector<FieldInfo>& other_result_info();
/// The entry of `path` in other_result_info(); throws std::out_of_range.
const FieldInfo& other_info(const std::string& path);

/// /cases/w and /cases/T [N, K]: each segment's velocity and duration as
/// run (name "w" or "T"; the case parameters' come with the study).
FieldInfo segment_case_info(const std::string& name);

/// An attribute of a map's root group.
struct RootAttribute {
  const char* name;
  const char* type;    ///< "string", "int64", ...
  const char* meaning; ///< one line, lower case, no final period
};
/// Every root attribute the map writer writes (io/map_file.cpp writes no other).
const std::vector<RootAttribute>& root_attributes();
/// The entry of `name` in root_attributes(); throws std::logic_error.
const char* root_attribute(const char* name);

/// /provenance/config_text and /provenance/config_canonical: uint8 text
/// datasets (path, "text", meaning; no `units` attribute or /schema entry).
const std::vector<FieldInfo>& provenance_info();

/// /provenance/material_card: in a map of a study with [run] material only.
const FieldInfo& material_card_info();

struct CaseRow {
  std::vector<double> values;              ///< RowLayout::row_width() values
  std::int8_t status = 0;                  ///< 1 done, -1 failed
  std::string message;                     ///< why it failed ("" otherwise)
  std::vector<std::vector<double>> series; ///< RowLayout::series() (when the map stores them)
};

} // namespace mdrmap::io
