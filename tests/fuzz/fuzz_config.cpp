// libFuzzer harness of the study config and case-list readers: the same
// properties as the StudyFuzz tests in tests/test_config.cpp, with coverage
// guidance. Built with -DMDRMAP_LIBFUZZER=ON and clang (tests/fuzz/CMakeLists.txt
// shows how to build and run it).
//
// An input is an INI text, optionally followed by a line "%%" and a CSV text.
// The CSV is written as cases.csv and failing.csv (the names the shipped
// [cases] configs use) next to the INI, then:
//   - the CSV read as a case list (a [cases] config of it alone) gives valid,
//     finite cases or throws InvalidInput;
//   - parse_config returns or throws InvalidInput; a config that parses
//     expands (grids always; case lists or InvalidInput) to valid, finite cases.
// InvalidInput messages must be non-empty and one line without control bytes.
// Anything else aborts: another exception type, a broken property, or a
// sanitizer report.
#include <stdlib.h> // mkdtemp

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/model/case.hpp"
#include "study/config.hpp"

namespace {

namespace fs = std::filesystem;
using mdrmap::InvalidInput;
using namespace mdrmap::study;

/// Expanding more cases than this is skipped (case_count() tells first).
constexpr std::size_t kExpandLimit = 5000;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_config: %s\n", what.c_str());
  std::abort();
}

void check_message(const InvalidInput& e) {
  const std::string m = e.what();
  if (m.empty()) fail("InvalidInput with an empty message");
  if (e.option().empty()) fail("InvalidInput without an option: " + m);
  for (const char ch : m) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t') || c == 0x7f) fail("control byte in the message: " + m);
  }
}

/// Runs f: true when it returns, false on InvalidInput; aborts on anything else.
template <class F> bool returns_or_refuses(const char* step, F&& f) {
  try {
    f();
    return true;
  } catch (const InvalidInput& e) {
    check_message(e);
    return false;
  } catch (const std::exception& e) {
    fail(std::string(step) + " threw something other than InvalidInput: " + e.what());
  } catch (...) {
    fail(std::string(step) + " threw a non-std exception");
  }
}

/// A row of a parsed study: finite values, one per column, and a valid Case.
void check_row(const StudyConfig& c, const Row& s) {
  if (s.size() != c.axes.size()) fail("a case has the wrong number of values");
  for (const double x : s)
    if (!std::isfinite(x)) fail("a case has a value that is not finite");
  try {
    const mdrmap::Case k = case_for(c, s);
    mdrmap::validate(k);
    if (k.history.size() != c.segments()) fail("a case has the wrong number of segments");
  } catch (const std::exception& e) {
    fail(std::string("a case is invalid: ") + e.what());
  }
}

void check_config(const StudyConfig& c) {
  const bool grid = c.kind == StudyConfig::Kind::Grid;
  std::size_t count = 0;
  if (!returns_or_refuses("case_count", [&] { count = case_count(c); })) {
    if (grid) fail("case_count of a parsed grid threw");
    return;
  }
  if (count > kExpandLimit) return;
  std::vector<Row> cases;
  if (!returns_or_refuses("expand_cases", [&] { cases = expand_cases(c); })) {
    if (grid) fail("a parsed grid refused to expand (a case the parse-time check missed)");
    return;
  }
  if (cases.size() != count) fail("expand_cases and case_count disagree");
  for (const Row& s : cases)
    check_row(c, s);
  std::string text;
  if (returns_or_refuses("canonical", [&] { text = canonical(c); }) && text.empty())
    fail("canonical() is empty");
}

/// A private directory for the case lists, removed at exit.
class WorkDir {
public:
  WorkDir() {
    std::string templ = (fs::temp_directory_path() / "mdrmap_fuzz_config_XXXXXX").string();
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (mkdtemp(buf.data()) == nullptr) fail("mkdtemp failed");
    path_ = buf.data();
  }
  ~WorkDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  const std::string& path() const { return path_; }

private:
  std::string path_;
};

/// Writes in place and cuts to size (faster than truncating to 0 on ext4).
void write_fast(const std::string& path, const std::string& content) {
  {
    std::fstream out(path, std::ios::in | std::ios::out | std::ios::binary);
    if (!out.is_open()) out.open(path, std::ios::out | std::ios::binary);
    out << content;
    if (!out) fail("cannot write " + path);
  }
  fs::resize_file(path, content.size());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t sep = input.find("\n%%\n");
  const std::string ini = input.substr(0, sep);
  const std::string csv = sep == std::string::npos ? std::string() : input.substr(sep + 4);

  static const WorkDir work;
  const std::string& dir = work.path();
  const std::string csv_path = (fs::path(dir) / "cases.csv").string();
  write_fast(csv_path, csv);
  write_fast((fs::path(dir) / "failing.csv").string(), csv);

  StudyConfig list;
  if (returns_or_refuses("case list",
                         [&] { list = parse_config("[cases]\nfile = cases.csv\n", dir, "l.ini"); }))
    check_config(list);

  StudyConfig c;
  if (returns_or_refuses("parse_config", [&] { c = parse_config(ini, dir, "fuzz.ini"); }))
    check_config(c);
  return 0;
}
