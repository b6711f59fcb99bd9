// The extension module mdrmap._core: the C++ half of the Python package
// `mdrmap` (src/python/mdrmap/__init__.py is the other). It takes the
// options' values as Python gives them, numbers as doubles (never as texts;
// case/option_value.hpp), and builds and checks the case with the command
// line's checks and messages (case/case_input.hpp) and runs it as `mdrmap simulate` does
// (case/simulation.hpp), without the GIL, looking at Ctrl-C and reporting progress now and then
// (python/call.hpp); the time series are handed over as
// numpy arrays that own the result's vectors (no copy). InvalidInput becomes
// mdrmap.InvalidInput.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "case/case_input.hpp"
#include "case/fit_problem.hpp"
#include "case/option_help.hpp"
#include "case/simulation.hpp"
#include "case/stationary_input.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/params.hpp"
#include "core/model/scales.hpp"
#include "core/model/temperature.hpp"
#include "core/outputs/output_table.hpp"
#include "fit/least_squares.hpp"
#include "mdrmap/version.hpp"
#include "python/call.hpp"

namespace py = pybind11;

namespace mdrmap::python {
namespace {

/// The Python class of bad input; created once at import, kept for the
/// process's lifetime (a module's globals are never torn down before it).
py::handle invalid_input_class;

constexpr const char* kInvalidInputSource = R"(
class InvalidInput(ValueError):
    """Bad input to mdrmap.simulate / mdrmap.stationary: the same refusal, with
    the same message, as `mdrmap simulate` gives on the command line.

    option   the option as the CLI spells it ("d", "t-end", "log-decades"),
             "" where no single option is at fault (e.g. neither d nor F0)
    keyword  the keyword argument ("d", "t_end", "log_decades")
    message  the CLI's message after "--OPTION: "
    """

    def __init__(self, message, option=""):
        self.option = option
        self.keyword = option.replace("-", "_")
        self.message = message
        super().__init__(f"{self.keyword}: {message}" if option else message)
)";

void make_invalid_input_class(py::module_& m) {
  py::dict ns;
  ns["__builtins__"] = py::module_::import("builtins");
  ns["__name__"] = "mdrmap";
  py::exec(kInvalidInputSource, ns);
  py::object cls = ns["InvalidInput"];
  m.attr("InvalidInput") = cls;
  invalid_input_class = cls.release();
}

/// A value the package (mdrmap/__init__.py) hands over: a str (a text: a
/// name, a path, or a number as the command line writes it), a float (a
/// number: that double), a bool (a flag), a tuple of floats (wlf, v-list) or
/// a list of pairs of floats (history, prony). The package has checked the
/// types against the keyword; anything else here is its error.
cases::OptionValue to_value(const std::string& option, const py::handle& value) {
  if (py::isinstance<py::str>(value))
    return cases::OptionValue::of_text(py::cast<std::string>(value));
  if (py::isinstance<py::bool_>(value)) return cases::OptionValue::of_flag(py::cast<bool>(value));
  if (py::isinstance<py::float_>(value))
    return cases::OptionValue::of_number(py::cast<double>(value));
  if (py::isinstance<py::list>(value)) {
    std::vector<std::pair<double, double>> pairs;
    for (const py::handle item : value)
      pairs.push_back(py::cast<std::pair<double, double>>(item));
    return cases::OptionValue::of_pairs(std::move(pairs));
  }
  if (py::isinstance<py::tuple>(value))
    return cases::OptionValue::of_numbers(py::cast<std::vector<double>>(value));
  throw std::logic_error("mdrmap._core: the value of " + option + " is a " +
                         py::cast<std::string>(py::str(value.get_type())));
}

cases::OptionValues to_values(const py::dict& options) {
  cases::OptionValues values;
  for (const auto& [key, value] : options) {
    const std::string option = py::cast<std::string>(key);
    values.emplace(option, to_value(option, value));
  }
  return values;
}

/// A numpy array over `v`, kept alive by `owner` (no copy).
template <class T> py::array_t<T> view(const std::vector<T>& v, const py::capsule& owner) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data(), owner);
}

py::dict fields(const std::vector<cases::Field>& f) {
  py::dict d;
  for (const auto& [name, value] : f)
    d[py::str(name)] = value;
  return d;
}

py::list events(const cases::SimulateRecord& rec) {
  py::list out;
  for (std::size_t k = 0; k < rec.events.size(); ++k) {
    py::dict e;
    e["k"] = k;
    for (const auto& [name, value] : cases::event_fields(rec.events[k]))
      e[py::str(name)] = value;
    if (const char* why = rec.events[k].d_c_undefined)
      e[py::str(cases::d_c_undefined_key())] = why; // (as the CSV)
    out.append(std::move(e));
  }
  return out;
}

/// The `# mdrmap ...` line and the reference line of the CSV, as a dict.
py::dict info(const cases::SimulateRecord& rec) {
  const RunInfo& in = rec.info;
  py::dict d;
  d["version"] = rec.version;
  d["commit"] = rec.commit;
  d["solver"] = rec.solver;
  d["rtol"] = rec.rtol;
  for (const auto& [name, value] : cases::result_fields(in, rec.wall_seconds)) // (as the CSV)
    if (output(OutputGroup::Result, name.c_str()).dim == Dim::Count)
      d[py::str(name)] = static_cast<long>(value);
    else
      d[py::str(name)] = value;
  if (rec.error_vs_exact && rec.reference == "exact") d["error_vs_exact"] = *rec.error_vs_exact;
  if (rec.error_vs_exact && rec.reference != "exact") {
    d["error_vs_reference"] = *rec.error_vs_exact;
    d["reference"] = rec.reference;
    d["reference_rtol"] = rec.reference_rtol;
  }
  return d;
}

/// The `# case` line as a dict: the profile (other than the parabola), the
/// table's parameters of the case's profile (of a one_of group the member given), the history as
/// (w, T) pairs, the spectrum as (G, tau) pairs where it has terms, the spacing (a lab record's:
/// sampling "record" in place of it and the sampling parameters); a0 under load; zeta0.
py::dict case_dict(const Case& c) {
  py::dict d;
  if (!c.indenter.parabolic()) d["profile"] = profile_name(c.indenter.profile);
  const bool record = !c.sampling.at.empty(); // (history_file: no spacing, no samples)
  for (const auto& p : case_parameters())
    if (p.applies_to(c.indenter.profile) && (!p.one_of || p.get(c) != 0.0) &&
        !(record && p.part == Part::Sampling)) {
      if (p.integer())
        d[p.name] = static_cast<long long>(p.get(c));
      else
        d[p.name] = p.get(c);
    }
  py::list history;
  for (const Segment& s : c.history.segments)
    history.append(py::make_tuple(s.w, s.T));
  d["history"] = history;
  if (!c.rheology.branches.empty()) {
    py::list prony;
    for (const Branch& b : c.rheology.branches)
      prony.append(py::make_tuple(b.G, b.tau));
    d["prony"] = prony;
  }
  if (record)
    d["sampling"] = "record";
  else
    d["spacing"] = c.sampling.spacing == Spacing::Log ? "log" : "linear";
  if (c.loading.by_force()) d["a0"] = c.a0();
  d["zeta0"] = c.history.v0 * c.rheology.tau / c.edge_scale();
  return d;
}

/// The series as numpy arrays (t, segment, FN, Fx, mu, a2; d, a1 under
/// load) that are views of its vectors: the capsule takes `sim` over.
void series_views(py::dict& out, std::unique_ptr<cases::Simulation> sim) {
  const Series& s = sim->series;
  const bool load = sim->record.c.loading.by_force();
  py::capsule owner(sim.get(), [](void* p) { delete static_cast<cases::Simulation*>(p); });
  sim.release();
  for (const OutputSpec& o : output_table()) // the CSV's columns (core/outputs/output_table.hpp)
    if (o.group == OutputGroup::Series && (load || !o.load_only))
      out[o.name] = o.column != nullptr ? py::object(view(s.*(o.column), owner))
                                        : py::object(view(s.segment, owner));
}

/// The elements `rows` of v, as a new array.
template <class T>
py::array_t<T> picked(const std::vector<T>& v, const std::vector<std::size_t>& rows) {
  py::array_t<T> a(static_cast<py::ssize_t>(rows.size()));
  auto x = a.template mutable_unchecked<1>();
  for (std::size_t n = 0; n < rows.size(); ++n)
    x(static_cast<py::ssize_t>(n)) = v[rows[n]];
  return a;
}

/// A lab record's run as the CLI's CSV gives it (csv_output.cpp): one row
/// per record row, the series' columns at the row and the row's load-point
/// velocity v and slip since t = 0.
void record_rows(py::dict& out, const cases::Simulation& sim, const cases::LabRecord& r) {
  std::vector<std::size_t> rows = cases::record_rows(sim.record.c);
  rows.resize(std::min(rows.size(), r.v.size()));
  const Series& s = sim.series;
  const bool load = sim.record.c.loading.by_force();
  for (const OutputSpec& o : output_table()) // the CSV's columns
    if (o.group == OutputGroup::Series && (load || !o.load_only))
      out[o.name] = o.column != nullptr ? py::object(picked(s.*(o.column), rows))
                                        : py::object(picked(s.segment, rows));
  std::vector<double> v(r.v.begin(), r.v.begin() + static_cast<std::ptrdiff_t>(rows.size()));
  std::vector<double> slip = cases::record_slip(r);
  slip.resize(rows.size());
  out["v"] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
  out["slip"] = py::array_t<double>(static_cast<py::ssize_t>(slip.size()), slip.data());
}

/// Runs one case from its options' values; the result as a dict of numpy
/// arrays and the records. A lab record's run (history-file) has one row
/// per record row (and its v and slip), as the CLI's CSV.
py::dict simulate(const py::dict& options, const py::object& progress) {
  const cases::OptionValues values = to_values(options);
  auto sim = std::make_unique<cases::Simulation>();
  std::optional<cases::LabRecord> record;
  run_call( // (the input reads a spectrum file)
      [&](const RunControl& control) {
        const cases::CaseInput in = cases::read_case_input(values);
        record = in.record;
        *sim = cases::simulate(in, control);
      },
      progress);
  py::dict out;
  out["events"] = events(sim->record);
  const bool load = sim->record.c.loading.by_force();
  out["pre"] = fields(cases::state_fields(sim->series.pre, load));
  out["info"] = info(sim->record);
  out["case"] = case_dict(sim->record.c);
  const Scales sc = scales(sim->record.c);
  py::dict scale_dict; // the CSV's `# scales` line
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Scale) scale_dict[o.name] = sc.*(o.scale);
  out["scales"] = scale_dict;
  if (record)
    record_rows(out, *sim, *record);
  else
    series_views(out, std::move(sim));
  return out;
}

/// mdrmap fit: the case's option texts, the records, the free names, the
/// bounds texts; the points of a batch over `threads` threads without the
/// GIL. The result as the CLI's JSON has it (parameters, correlation, ...).
py::dict fit(const py::dict& options, const std::vector<std::string>& data,
             const std::vector<std::string>& free, const std::vector<std::string>& bounds,
             const std::string& starts, unsigned threads) {
  cases::FitSpec spec;
  spec.texts = cases::as_texts(to_values(options)); // (each number's text reads back to it)
  spec.data = data;
  spec.free = free;
  spec.bounds = bounds;
  spec.starts = starts;
  std::unique_ptr<cases::FitProblem> p;
  fit::Result r;
  run_call(
      [&](const RunControl&) {
        p = std::make_unique<cases::FitProblem>(spec);
        cases::ThreadEvaluator ev(*p, threads);
        r = fit::fit(p->parameters(), ev, p->options());
      },
      py::none());
  py::dict params;
  std::vector<std::string> names;
  for (const auto& q : r.parameters) {
    params[q.name.c_str()] =
        py::dict(py::arg("value") = q.value, py::arg("stderr") = q.stderr_,
                 py::arg("ci95") = py::make_tuple(q.ci95_lo, q.ci95_hi),
                 py::arg("ci95_method") = q.ci95_method,
                 py::arg("ci95_covariance") = py::make_tuple(q.cov_lo, q.cov_hi),
                 py::arg("at_bound") = q.at_bound);
    names.push_back(q.name);
  }
  py::dict out;
  out["parameters"] = params;
  out["undetermined"] = r.undetermined;
  out["correlation"] = py::dict(py::arg("names") = names, py::arg("matrix") = r.correlation);
  out["rms"] = r.rms;
  out["sigma"] = r.sigma;
  out["residuals"] = r.m;
  out["evaluations"] = r.evaluations;
  out["batches"] = r.batches;
  out["iterations"] = r.iterations;
  out["converged"] = r.converged;
  out["rtol"] = p->rtol();
  out["step"] = p->options().step;
  return out;
}

/// The stationary states of the case's loading as `mdrmap stationary` gives
/// them: `options` its options (the case's, and v or v-list), the result
/// {"v": velocities, FN, Fx, mu, a2 (d, a1 under load): arrays}.
py::dict stationary(const py::dict& options, const py::object& progress) {
  const cases::OptionValues values = to_values(options);
  cases::StationaryInput in;
  std::vector<State> states;
  run_call( // a spectrum file, quadratures
      [&](const RunControl& control) {
        in = cases::read_stationary_input(values);
        states = cases::stationary_states(in, control);
      },
      progress);
  const bool load = in.in.c.loading.by_force();
  py::dict out;
  out["v"] =
      py::array_t<double>(static_cast<py::ssize_t>(in.velocities.size()), in.velocities.data());
  const std::size_t n = cases::state_fields(State{}, load).size();
  for (std::size_t j = 0; j < n; ++j) {
    py::array_t<double> a(static_cast<py::ssize_t>(states.size()));
    auto x = a.mutable_unchecked<1>();
    for (std::size_t k = 0; k < states.size(); ++k)
      x(static_cast<py::ssize_t>(k)) = cases::state_fields(states[k], load)[j].second;
    out[py::str(cases::state_fields(State{}, load)[j].first)] = a;
  }
  return out;
}

/// One part of a case as read_case_part reads it: its options as the case
/// holds them (the indenter: profile and its parameters; the material: G,
/// tau, aT, the spectrum's (G, tau) pairs, the temperature and the WLF
/// constants that gave aT, notes; the history: its (w, T) pairs, and v and
/// the record's path and rows where a lab record gave it).
py::dict read_part(const py::dict& options, const std::string& part) {
  const Part which = part == "indenter"   ? Part::Indenter
                     : part == "material" ? Part::Material
                     : part == "history"  ? Part::History
                                          : throw std::logic_error("read_part: " + part);
  const cases::OptionValues values = to_values(options);
  cases::CaseInput in;
  run_call([&](const RunControl&) { in = cases::read_case_part(values, which); }, // (files)
           py::none());
  const Case& c = in.c;
  py::dict d;
  if (which == Part::Indenter) d["profile"] = profile_name(c.indenter.profile);
  for (const auto& p : case_parameters())
    if (p.part == which && which != Part::History && p.applies_to(c.indenter.profile))
      d[p.name] = p.get(c);
  if (which == Part::Material) {
    py::list prony;
    for (const Branch& b : c.rheology.branches)
      prony.append(py::make_tuple(b.G, b.tau));
    d["prony"] = prony;
    if (in.temperature) {
      const cases::TemperatureInput& t = *in.temperature;
      d["temperature"] = t.T;
      d["wlf"] = py::make_tuple(t.wlf.C1, t.wlf.C2, t.wlf.Tref);
      d["unit"] = unit_suffix(t.unit);
    }
    d["notes"] = in.notes;
  }
  if (which == Part::History) {
    py::list history;
    for (const Segment& seg : c.history.segments)
      history.append(py::make_tuple(seg.w, seg.T));
    d["history"] = history;
    if (in.record) {
      d["v"] = c.history.v0;
      d["record"] = in.record->path;
      d["rows"] = in.record->t.size();
    }
  }
  return d;
}

/// The old spellings the options take: {alias: the table's name}.
py::dict alias_table() {
  py::dict d;
  for (const ParamAlias& a : mdrmap::parameter_aliases())
    d[a.alias] = a.name;
  return d;
}

py::list parameter_table() {
  py::list out;
  for (const auto& p : case_parameters()) {
    py::dict d;
    d["name"] = p.name;
    d["symbol"] = p.symbol;
    d["unit"] = dim_name(p.dim);
    d["range"] = p.allowed();
    d["meaning"] = p.meaning;
    d["required"] = p.required;
    d["one_of"] = p.one_of ? py::object(py::str(p.one_of)) : py::object(py::none());
    d["profile"] = p.profile ? py::object(py::str(p.profile)) : py::object(py::none());
    d["default"] =
        p.required || p.one_of ? py::object(py::none()) : py::object(py::float_(p.fallback));
    d["sampling"] = p.part == Part::Sampling;
    d["help"] = cases::parameter_help_text(p);
    out.append(std::move(d));
  }
  return out;
}

/// The output table (core/outputs/output_table.hpp) as a list of dicts:
/// name, unit, group, csv, map, meaning, may_be_undefined, old_map_name, load_only.
py::list output_table_list() {
  py::list out;
  for (const OutputSpec& o : output_table()) {
    py::dict d;
    d["name"] = o.name;
    d["unit"] = dim_name(o.dim);
    d["group"] = output_group_name(o.group);
    d["csv"] = (o.where & kInCsv) != 0;
    d["map"] = (o.where & kInMap) != 0;
    d["meaning"] = o.meaning;
    d["may_be_undefined"] = o.may_be_undefined;
    d["old_map_name"] =
        o.old_map_name ? py::object(py::str(o.old_map_name)) : py::object(py::none());
    d["load_only"] = o.load_only;
    out.append(std::move(d));
  }
  return out;
}

/// The help of the case options outside the table (case/option_help.hpp),
/// {name: {placeholder, text, default}} in the command line's words.
py::dict option_help_table() {
  py::dict out;
  for (const cases::OptionHelp& h : cases::case_option_help()) {
    py::dict d;
    d["placeholder"] = h.placeholder;
    d["text"] = h.text;
    d["default"] = h.fallback.empty() ? py::object(py::none()) : py::object(py::str(h.fallback));
    out[py::str(h.name)] = std::move(d);
  }
  return out;
}

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const InvalidInput& e) {
    const py::object exc = invalid_input_class(e.what(), e.option());
    PyErr_SetObject(invalid_input_class.ptr(), exc.ptr());
  } catch (const CaseAbandoned& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
  } catch (const Interrupted&) { // (run_call raises the signal's exception before)
    PyErr_SetNone(PyExc_KeyboardInterrupt);
  }
}

} // namespace
} // namespace mdrmap::python

PYBIND11_MODULE(_core, m) {
  using namespace mdrmap::python;
  m.doc() = "mdrmap's solvers (the C++ half of the package mdrmap; use mdrmap, not _core)";
  make_invalid_input_class(m);
  init_call();
  py::register_exception_translator(&translate);
  m.attr("__version__") = mdrmap::kVersion;
  m.attr("commit") = mdrmap::kGitCommit;
  m.def("option_names", &mdrmap::cases::case_option_names,
        "The options of a case, as the CLI spells them, in the order of its help.");
  m.def("simulate", &simulate, py::arg("options"), py::arg("progress") = py::none(),
        "Runs one case from {option: value}; a dict of numpy arrays and records.");
  m.def("fit", &fit, py::arg("options"), py::arg("data"), py::arg("free"), py::arg("bounds"),
        py::arg("starts"), py::arg("threads"), "mdrmap fit: case parameters from lab records.");
  m.def("stationary", &stationary, py::arg("options"), py::arg("progress") = py::none(),
        "The stationary states at v or v-list of a case given as {option: value}.");
  m.def("read_part", &read_part, py::arg("options"), py::arg("part"),
        "One part (indenter, material, history) of a case from {option: value}, checked.");
  m.def("material_file_option", &mdrmap::cases::material_file_option, py::arg("path"),
        "The option a material file goes under: material (a card) or prony-file.");
  m.def("parameter_table", &parameter_table, "The parameter table as a list of dicts.");
  m.def("output_table", &output_table_list,
        "The output table as a list of dicts: name, unit, group (series, event, event_state, "
        "result), csv, map, meaning, may_be_undefined, old_map_name, load_only.");
  m.def("option_help", &option_help_table,
        "The help of the case options outside the table, {name: {placeholder, text, default}}.");
  m.def("parameter_aliases", &alias_table,
        "The old spellings of the table's parameters, {alias: name} (FN: F0).");
}
