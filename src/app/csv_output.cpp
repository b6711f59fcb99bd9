#include "app/csv_output.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "case/lab_record.hpp"
#include "case/prony_input.hpp"
#include "core/model/params.hpp"
#include "core/model/scales.hpp"
#include "core/outputs/output_table.hpp"

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

const char* spacing_name(Spacing s) {
  return s == Spacing::Log ? "log" : "linear";
}

/// Whether the `# case` line shows parameter p of c: the indenter's of its
/// profile only; of a one_of group only the member given (non-zero); the shift aT (which the seed's
/// model has not) only where it shifts.
bool shown(const ParamSpec& p, const Case& c) {
  if (!p.applies_to(c.indenter.profile)) return false;
  if (p.one_of) return p.get(c) != 0.0;
  return std::strcmp(p.name, "aT") != 0 || p.get(c) != 1.0;
}

/// " name=value" for every table parameter of the sampling part (`sampling`)
/// or of the other parts that is shown.
std::string parameters(const Case& c, bool sampling) {
  std::string s;
  for (const auto& p : case_parameters())
    if ((p.part == Part::Sampling) == sampling && shown(p, c))
      s += std::string(" ") + p.name + "=" + format_double(p.get(c));
  return s;
}

void write_reference(std::FILE* out, const SimulateRecord& rec) {
  if (!rec.error_vs_exact) return;
  if (rec.reference == "exact")
    std::fprintf(out, "# error_vs_exact=%.17g\n", *rec.error_vs_exact);
  else
    std::fprintf(out, "# error_vs_reference=%.17g reference=%s reference_rtol=%.17g\n",
                 *rec.error_vs_exact, rec.reference.c_str(), rec.reference_rtol);
}

/// The Series entries of the table a run at this loading has.
std::vector<const OutputSpec*> columns(bool load) {
  std::vector<const OutputSpec*> c;
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Series && (load || !o.load_only)) c.push_back(&o);
  return c;
}

/// The room a line of n values needs: each value and its separator, and
/// the newline.
std::size_t line_room(std::size_t n) {
  return n * (kDoubleChars + 1) + 1;
}

/// format_double of the n values, comma-separated, at `p` (which has
/// line_room(n)); returns the end.
char* put_fields(char* p, const double* values, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) {
    if (j > 0) *p++ = ',';
    p = format_double_to(p, values[j]);
  }
  return p;
}

/// x as printf's "%.17g" prints it ("-0", "-nan" included), at `p` with room
/// for kDoubleChars; returns the end. (std::to_chars with a precision prints
/// what printf prints.)
char* put_g17(char* p, double x) {
  const auto r = std::to_chars(p, p + kDoubleChars, x, std::chars_format::general, 17);
  return r.ec == std::errc() ? r.ptr : p;
}

/// Row k of the series: its columns, comma-separated (no newline), at `p`
/// with line_room(cols.size()); `values` has cols.size() elements.
char* put_row(char* p, const std::vector<const OutputSpec*>& cols, const Series& s, std::size_t k,
              std::vector<double>& values) {
  for (std::size_t j = 0; j < cols.size(); ++j)
    values[j] = sample(*cols[j], s, k);
  return put_fields(p, values.data(), values.size());
}

void write_line(std::FILE* out, const std::vector<char>& line, const char* end) {
  std::fwrite(line.data(), 1, static_cast<std::size_t>(end - line.data()), out);
}

void write_rows(std::FILE* out, const Series& s, bool load) {
  const std::vector<const OutputSpec*> cols = columns(load);
  std::vector<double> values(cols.size());
  std::vector<char> line(line_room(cols.size()));
  for (std::size_t k = 0; k < s.size(); ++k) {
    char* p = put_row(line.data(), cols, s, k, values);
    *p++ = '\n';
    write_line(out, line, p);
  }
}

/// The rows of a lab record (--history-file): its rows only, each with its
/// load-point velocity v and the slip since t = 0.
void write_record_rows(std::FILE* out, const Case& c, const Series& s, const LabRecord& r) {
  const std::vector<std::size_t> rows = record_rows(c);
  const std::vector<double> slip = record_slip(r);
  const std::vector<const OutputSpec*> cols = columns(c.loading.by_force());
  std::vector<double> values(cols.size());
  std::vector<char> line(line_room(cols.size() + 2));
  for (std::size_t n = 0; n < rows.size() && n < r.v.size(); ++n) {
    char* p = put_row(line.data(), cols, s, rows[n], values);
    *p++ = ',';
    p = put_g17(p, r.v[n]);
    *p++ = ',';
    p = put_g17(p, slip[n]);
    *p++ = '\n';
    write_line(out, line, p);
  }
}

void write_event(std::FILE* out, std::size_t k, const EventMetrics& e) {
  std::string line = "# event k=" + std::to_string(k);
  for (const auto& [name, value] : event_fields(e))
    line += std::string(" ") + name + "=" + format_double(value);
  if (e.d_c_undefined != nullptr) line += " " + d_c_undefined_key() + "=" + e.d_c_undefined;
  std::fprintf(out, "%s\n", line.c_str());
}

} // namespace

std::string case_line(const Case& c, const std::optional<TemperatureInput>& temperature) {
  const bool load = c.loading.by_force();
  std::string s = "# case";
  if (!c.indenter.parabolic()) s += std::string(" profile=") + profile_name(c.indenter.profile);
  s += parameters(c, false);
  if (!c.rheology.branches.empty()) s += " prony=" + format_prony(c.rheology.branches);
  if (temperature)
    s += " T=" + format_double(temperature->T) + unit_suffix(temperature->unit) +
         " wlf=" + format_wlf(temperature->wlf) + unit_suffix(temperature->unit);
  s += " history=" + format_history(c.history);
  if (c.sampling.at.empty())
    s += " spacing=" + std::string(spacing_name(c.sampling.spacing)) + parameters(c, true);
  else
    s += " sampling=record"; // (--history-file: the rows at the record's times)
  if (load) s += " a0=" + format_double(c.a0());
  return s + " zeta0=" + format_double(c.history.v0 * c.rheology.tau / c.edge_scale());
}

std::string scales_line(const Case& c) {
  const Scales sc = scales(c);
  std::string s = "# scales";
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Scale)
      s += std::string(" ") + o.name + "=" + format_double(sc.*(o.scale));
  return s;
}

std::string csv_header(bool load) {
  std::string h;
  for (const OutputSpec* o : columns(load))
    h += (h.empty() ? "" : ",") + std::string(o->name);
  return h;
}

std::string format_double(double x) {
  char buf[kDoubleChars];
  return std::string(buf, format_double_to(buf, x));
}

char* format_double_to(char* p, double x) {
  if (std::isnan(x)) {
    std::memcpy(p, "nan", 3);
    return p + 3;
  }
  if (x == 0.0) x = 0.0; // never "-0"
  // (std::to_chars with a precision prints what printf's %.17g prints, in
  // about a fifth of its time)
  return put_g17(p, x);
}

void write_csv_line(std::FILE* out, const double* values, std::size_t n) {
  constexpr std::size_t kOnStack = 16; // (the tables' rows have at most 10 values)
  char stack[kOnStack * (kDoubleChars + 1) + 1];
  std::vector<char> heap;
  if (n > kOnStack) heap.resize(line_room(n));
  char* const line = n > kOnStack ? heap.data() : stack;
  char* p = put_fields(line, values, n);
  *p++ = '\n';
  std::fwrite(line, 1, static_cast<std::size_t>(p - line), out);
}

std::string format_history(const History& h) {
  std::string s;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (k > 0) s += ',';
    s += format_double(h.segments[k].w) + ":" + format_double(h.segments[k].T);
  }
  return s;
}

void write_simulate_csv(std::FILE* out, const SimulateRecord& rec, const Series& series,
                        const std::optional<TemperatureInput>& temperature,
                        const LabRecord* record) {
  std::string first = "# mdrmap " + rec.version + " (" + rec.commit +
                      ") simulate solver=" + rec.solver + " rtol=" + format_double(rec.rtol);
  for (const auto& [name, value] : result_fields(rec.info, rec.wall_seconds))
    first += " " + name + "=" + format_double(value);
  std::fprintf(out, "%s\n", first.c_str());

  const Case& c = rec.c;
  const bool load = c.loading.by_force();
  std::fprintf(out, "%s\n", case_line(c, temperature).c_str());
  std::fprintf(out, "%s\n", scales_line(c).c_str());
  write_reference(out, rec);
  for (std::size_t k = 0; k < rec.events.size(); ++k)
    write_event(out, k, rec.events[k]);

  std::fputs("# pre", out);
  for (const auto& [name, value] : state_fields(series.pre, load))
    std::fprintf(out, " %s=%s", name.c_str(), format_double(value).c_str());
  std::fprintf(out, "\n%s%s\n", csv_header(load).c_str(), record ? ",v,slip" : "");
  if (record)
    write_record_rows(out, c, series, *record);
  else
    write_rows(out, series, load);
}

} // namespace mdrmap::app
