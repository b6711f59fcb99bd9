#pragma once
// Text output of `mdrmap simulate`: provenance comment lines, then CSV.
//
//   # mdrmap <version> (<commit>) simulate solver=... rtol=... error_estimate=...
//     cells_per_a1=... elements=... steps=... element_updates=... root_solves=...
//     wall_seconds=...                                        (one line)
//   # case d=... R=... tau=... G=... [aT=...] v=... [prony=G1:TAU1,...]
//     [T=... wlf=C1:C2:TREF] history=W1:T1,W2:T2,... spacing=linear|log
//     samples=... log-decades=... zeta0=...                   (one line; under load
//     F0=... (the prescribed load) in place of d=..., and a0=... before zeta0)
//   # scales length=... depth=... force=... friction=... time=...
//                                         (the case's Scales, core/model/scales.hpp)
//   # error_vs_exact=...                  (fixed depth, a solver other than exact)
//   # error_vs_reference=... reference=NAME reference_rtol=...
//                                         (under load, a solver other than the default)
//   # event k=... t=... w_before=... w_after=... mu_before=... mu_after=... mu_peak=...
//     t_peak=... slip_peak=... mu_end=... mu_ss_before=... mu_ss_after=... D_c=... a=...
//     a_minus_b=... b=...                 (one line per segment k = 0, 1, ...)
//   # pre FN=... Fx=... mu=... a2=...     (always the last comment line; FN the
//                                          measured normal force; under load
//                                          d=... a1=... follow)
//   t,segment,FN,Fx,mu,a2                 (under load t,segment,FN,Fx,mu,a2,d,a1)
//   <samples rows per segment, segment after segment>
//
// With a lab record (--history-file, case/lab_record.hpp) the rows are the
// record's, one per row at its time, and two columns follow: v (the row's
// load-point velocity) and slip (the load-point slip since t = 0); the
// `# case` line then says sampling=record in place of the spacing and the
// sampling parameters.
//
// The `# case` line gives every parameter of the table (core/model/params.hpp) as
// name=value in the table's order, the parameters of the sampling after the
// history; of a one_of group (the loading: d or F0) only the member given;
// the shift aT only where it is not 1. The spectrum's terms (prony=) follow
// the table's parameters where there are terms, then the temperature and
// its WLF constants where --T gave aT: a Kelvin case prints what it always has.
// `v` is the velocity v0 before t = 0 and zeta0 = v tau / a1 at fixed depth;
// under load zeta0 = v tau / a0, a0 the Hertz radius of F0 (Case::a0). The
// event fields are core/metrics/events.hpp's EventMetrics of the change at the start
// of segment k: its time t (since the first change), the velocities before
// and after it, mu just before and just after it, the extremum of mu in the
// segment (mu_peak, at t_peak after the change, after a slip slip_peak), mu at
// the segment's end, the stationary mu at both velocities, the slip D_c over
// which |mu - mu_ss_after| falls to 1/e of its value just after the change,
// and the apparent rate-and-state parameters a, a - b and b. A value that is
// undefined (a log of 0 or of 1, a hold, no 1/e decay within the segment) is
// printed as nan.
//
// Every name on these lines is the output table's (core/outputs/output_table.hpp).
//
// Every floating-point number is printed with 17 significant digits, which
// reads back to the same double.
#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>

#include "case/lab_record.hpp"
#include "case/simulation.hpp"
#include "core/model/case.hpp"

namespace mdrmap::app {

/// `%.17g`: round-trips every finite double; NaN prints as "nan" (never
/// "-nan"), -0 as "0".
std::string format_double(double x);

/// The room format_double_to needs: its longest text is 24 characters
/// ("-2.2250738585072014e-308").
inline constexpr std::size_t kDoubleChars = 32;

/// Writes format_double(x) at `p`, which has room for kDoubleChars
/// characters, and returns the end of what it wrote (no terminating NUL):
/// format_double without a std::string, for the rows of a table.
char* format_double_to(char* p, double x);

/// Writes one CSV line to `out`: format_double of each of the n values,
/// comma-separated, then '\n', in one fwrite.
void write_csv_line(std::FILE* out, const double* values, std::size_t n);

/// A history as "W1:T1,W2:T2,...", each number with 17 significant digits.
std::string format_history(const History& h);

/// The CSV column header line (without newline): the output table's Series
/// entries (core/outputs/output_table.hpp), "t,segment,FN,Fx,mu,a2" at
/// depth control, with ",d,a1" under load.
std::string csv_header(bool load);

/// The `# case` line of a case (without newline); `temperature` as the
/// input gave it (CaseInput::temperature).
std::string case_line(const Case& c, const std::optional<cases::TemperatureInput>& temperature);

/// The `# scales` line of a case (without newline): its Scales, which the
/// tools measure by (as the map's /scales).
std::string scales_line(const Case& c);

/// Writes the comment lines, the header and one row per sample to `out`
/// (with `record`, the case's lab record: one row per row of the record,
/// with v and slip). Does not flush or check for I/O errors; the caller does
/// (ferror / fclose).
void write_simulate_csv(std::FILE* out, const cases::SimulateRecord& rec, const Series& series,
                        const std::optional<cases::TemperatureInput>& temperature = std::nullopt,
                        const cases::LabRecord* record = nullptr);

} // namespace mdrmap::app
