#pragma once
// Private to the study config: the INI reader (sections, keys, comments, line
// numbers, unknown names answered with the nearest known one) and the string
// helpers its messages and the other config readers share.
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "study/config.hpp"

namespace mdrmap::study::detail {

// --- Strings -------------------------------------------------------------------

bool is_space(char c);
std::string trim(std::string_view s);
/// Every piece between separators, empty ones included ("a,,b" has three).
std::vector<std::string> split(const std::string& s, char sep);
bool starts_with(const std::string& s, const char* prefix);
char lower(char c);
std::string lower(std::string s);
bool contains(const std::vector<std::string>& v, const std::string& s);
std::string join(const std::vector<std::string>& v, const char* sep = ", ");

/// User text quoted for a one-line message: control bytes escaped, long text cut.
std::string shown(std::string_view s, std::size_t max_chars = 60);
/// An integer's digits (already checked) for a message: long ones cut.
std::string digits_shown(const std::string& digits);
/// A path quoted for a message (cut only when absurdly long).
std::string shown_path(const std::string& p);

/// The candidate nearest to word, or "" when none is plausibly meant.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

// --- Locations -------------------------------------------------------------------

/// Where a setting came from: "FILE:LINE: ", "FILE: " or "command line: ".
struct Where {
  std::string source;
  int line = 0;
  std::string prefix() const {
    return line > 0 ? source + ":" + std::to_string(line) + ": " : source + ": ";
  }
};

/// Adds the location to an error thrown without one.
[[noreturn]] void rethrow_at(const InvalidInput& e, const Where& w);

// --- The reader -------------------------------------------------------------------

/// The sections an INI file may have and the keys of each.
struct IniSchema {
  std::vector<std::string> sections;
  std::vector<std::vector<std::string>> keys; ///< keys[i]: those of sections[i]
  std::string any_section;  ///< where a key may go, e.g. "[grid], [cases] or [run]"
  std::string all_sections; ///< what a file has, e.g. "[grid] or [cases], and [run]"
  /// Keys a section takes besides its list (e.g. numbered ones); may be empty.
  std::function<bool(const std::string& section, const std::string& key)> also;
  /// What an unknown key of a section may have meant, said instead of the
  /// list of keys (e.g. a spectrum's term past the last); "" for none. May be empty.
  std::function<std::string(const std::string& section, const std::string& key)> hint;

  /// The keys of a known section.
  const std::vector<std::string>& keys_of(const std::string& section) const;
};

/// The lines each section header and key was read at.
struct IniLines {
  std::map<std::string, int> section_line; ///< section -> header line
  std::map<std::string, int> key_line;     ///< "section.key" -> line
};

/// What the reader calls for each section header and key, after its own
/// checks. A handler throws InvalidInput without a location; the reader adds it.
struct IniHandlers {
  std::function<void(const std::string& section, const IniLines& seen)> section;
  std::function<void(const std::string& section, const std::string& key, const std::string& value,
                     const IniLines& seen)>
      value;
};

/// Reads INI text line by line: unknown or repeated sections and keys, keys
/// outside a section or without a value are errors whose message starts with
/// "SOURCE:LINE: ". Returns where every section and key was read.
IniLines read_ini(const std::string& text, const std::string& source, const IniSchema& schema,
                  const IniHandlers& handlers);

/// A config file's text (at most 16 MiB). Throws ConfigError("config").
std::string read_config_file(const std::string& path);

} // namespace mdrmap::study::detail
