#include "study/ini.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace mdrmap::study::detail {

// --- Strings -------------------------------------------------------------------

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && is_space(s[b]))
    ++b;
  while (e > b && is_space(s[e - 1]))
    --e;
  return std::string(s.substr(b, e - b));
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t p = s.find(sep, start);
    if (p == std::string::npos) {
      out.push_back(s.substr(start));
      return out;
    }
    out.push_back(s.substr(start, p - start));
    start = p + 1;
  }
}

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

std::string lower(std::string s) {
  for (char& c : s)
    c = lower(c);
  return s;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out += sep;
    out += v[i];
  }
  return out;
}

std::string shown(std::string_view s, std::size_t max_chars) {
  std::string out = "'";
  std::size_t n = 0;
  for (const char ch : s) {
    if (n == max_chars) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      static const char* const hex = "0123456789ABCDEF";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xf];
    } else {
      out += ch;
    }
    ++n;
  }
  return out + "'";
}

std::string digits_shown(const std::string& digits) {
  return digits.size() <= 30 ? digits : digits.substr(0, 30) + "...";
}

std::string shown_path(const std::string& p) {
  return shown(p, 4096);
}

// --- Suggestions -------------------------------------------------------------------

namespace {

/// Edit distance in half units: a change of case costs 1, any other
/// substitution, insertion or deletion 2.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = 2 * j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = 2 * i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const char x = a[i - 1], y = b[j - 1];
      const std::size_t sub = x == y ? 0 : (lower(x) == lower(y) ? 1 : 2);
      cur[j] = std::min({prev[j] + 2, cur[j - 1] + 2, prev[j - 1] + sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

} // namespace

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = static_cast<std::size_t>(-1);
  for (const auto& c : candidates) {
    const std::size_t dist = edit_distance(word, c);
    if (dist < best_d) {
      best_d = dist;
      best = c;
    }
  }
  if (best.empty()) return best;
  // Near enough: a few edits, and not a rewrite of the whole word ("G" is not "d").
  const std::size_t allowed = 2 * std::max<std::size_t>(2, best.size() / 3);
  if (best_d <= allowed && best_d < 2 * std::min(word.size(), best.size())) return best;
  // A known key that contains the word, or is contained in it ("end_over_tau", "run.samples").
  for (const auto& c : candidates)
    if (word.size() >= 2 &&
        (c.find(word) != std::string::npos || word.find(c) != std::string::npos) &&
        std::min(c.size(), word.size()) * 2 >= std::max(c.size(), word.size()))
      return c;
  return "";
}

// --- Locations -------------------------------------------------------------------

void rethrow_at(const InvalidInput& e, const Where& w) {
  throw ConfigError(e.option(), w.prefix() + e.what());
}

// --- The reader -------------------------------------------------------------------

const std::vector<std::string>& IniSchema::keys_of(const std::string& section) const {
  static const std::vector<std::string> none;
  for (std::size_t i = 0; i < sections.size(); ++i)
    if (sections[i] == section) return keys[i];
  return none;
}

namespace {

/// Strips a trailing comment: ';' or '#' at the start or after whitespace.
std::string strip_comment(const std::string& s) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if ((s[i] == ';' || s[i] == '#') && (i == 0 || is_space(s[i - 1]))) return s.substr(0, i);
  return s;
}

std::string unknown_key_message(const IniSchema& schema, const std::string& section,
                                const std::string& key) {
  for (const auto& other : schema.sections)
    if (other != section && contains(schema.keys_of(other), key))
      return "key " + shown(key) + " belongs in [" + other + "], not [" + section +
             "]; move it there";
  const std::string hint = schema.hint ? schema.hint(section, key) : "";
  if (!hint.empty()) return "unknown key " + shown(key) + " in [" + section + "]; " + hint;
  const std::vector<std::string>& keys = schema.keys_of(section);
  const std::string near = nearest(key, keys);
  if (!near.empty())
    return "unknown key " + shown(key) + " in [" + section + "]; did you mean '" + near + "'?";
  return "unknown key " + shown(key) + " in [" + section + "]; the keys of [" + section + "] are " +
         join(keys);
}

/// Reads the non-blank, non-comment lines of one INI text in order.
class IniReader {
public:
  IniReader(const IniSchema& schema, const IniHandlers& handlers)
      : schema_(schema), handlers_(handlers) {}

  /// One trimmed line: a section header or a key.
  void read(const std::string& line, const Where& here) {
    if (line[0] == '[')
      header(line, here);
    else
      key_value(line, here);
  }

  const IniLines& lines() const { return lines_; }

private:
  void header(const std::string& line, const Where& here);
  void key_value(const std::string& line, const Where& here);

  const IniSchema& schema_;
  const IniHandlers& handlers_;
  IniLines lines_;
  std::string section_; ///< the current section ("" before the first)
};

void IniReader::header(const std::string& line, const Where& here) {
  const std::size_t close = line.find(']');
  if (close == std::string::npos)
    throw ConfigError("config", here.prefix() + "malformed section header " + shown(line) +
                                    "; write " + schema_.any_section);
  const std::string rest = trim(line.substr(close + 1));
  if (!rest.empty() && rest[0] != ';' && rest[0] != '#')
    throw ConfigError("config", here.prefix() + "unexpected " + shown(rest) +
                                    " after the section header; only a comment may follow");
  const std::string name = trim(line.substr(1, close - 1));
  if (!contains(schema_.sections, name)) {
    const std::string near = nearest(name, schema_.sections);
    throw ConfigError("config",
                      here.prefix() + "unknown section " + shown("[" + name + "]") + "; " +
                          (near.empty() ? std::string("the sections are ")
                                        : "did you mean [" + near + "]? The sections are ") +
                          schema_.all_sections);
  }
  if (lines_.section_line.count(name))
    throw ConfigError("config", here.prefix() + "section [" + name +
                                    "] appears twice (first at line " +
                                    std::to_string(lines_.section_line.at(name)) + "); merge them");
  try {
    handlers_.section(name, lines_);
  } catch (const InvalidInput& e) {
    rethrow_at(e, here);
  }
  lines_.section_line[name] = here.line;
  section_ = name;
}

void IniReader::key_value(const std::string& line, const Where& here) {
  const std::size_t eq = line.find('=');
  if (eq == std::string::npos)
    throw ConfigError("config", here.prefix() + "cannot read " + shown(line) +
                                    "; expected 'key = value', a [section] header or a comment");
  const std::string key = trim(line.substr(0, eq));
  if (key.empty())
    throw ConfigError("config", here.prefix() + "no key before '=' in " + shown(line) +
                                    "; expected 'key = value'");
  if (section_.empty())
    throw ConfigError("config", here.prefix() + "key " + shown(key) +
                                    " is outside a section; put it under " + schema_.any_section);
  const std::string option = section_ + "." + key;
  if (!contains(schema_.keys_of(section_), key) && !(schema_.also && schema_.also(section_, key)))
    throw ConfigError(option, here.prefix() + unknown_key_message(schema_, section_, key));
  if (lines_.key_line.count(option))
    throw ConfigError(option, here.prefix() + "duplicate key '" + key + "' in [" + section_ +
                                  "] (first set at line " +
                                  std::to_string(lines_.key_line.at(option)) +
                                  "); give each key once");
  lines_.key_line[option] = here.line;
  const std::string value = trim(strip_comment(line.substr(eq + 1)));
  if (value.empty())
    throw ConfigError(option, here.prefix() + key + " has no value; write '" + key + " = value'");
  try {
    handlers_.value(section_, key, value, lines_);
  } catch (const InvalidInput& e) {
    rethrow_at(e, here);
  }
}

constexpr std::size_t kMaxConfigBytes = std::size_t{16} * 1024 * 1024;

[[noreturn]] void cannot_read(const std::string& path, const std::string& why) {
  throw ConfigError("config", "cannot read " + shown_path(path) + ": " + why);
}

} // namespace

IniLines read_ini(const std::string& text, const std::string& source, const IniSchema& schema,
                  const IniHandlers& handlers) {
  IniReader reader(schema, handlers);
  int line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    std::string raw = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (line_no == 1 && starts_with(raw, "\xEF\xBB\xBF")) raw.erase(0, 3); // UTF-8 BOM
    const std::string line = trim(raw);
    if (line.empty() || line[0] == ';' || line[0] == '#') continue;
    reader.read(line, Where{source, line_no});
  }
  return reader.lines();
}

std::string read_config_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) cannot_read(path, std::strerror(EISDIR));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    cannot_read(path, std::strerror(err));
  }
  std::string text;
  char buf[65536];
  for (;;) {
    const std::size_t n = std::fread(buf, 1, sizeof buf, f);
    text.append(buf, n);
    if (text.size() > kMaxConfigBytes) {
      std::fclose(f);
      cannot_read(path, "larger than 16 MiB; a study config is a short text file");
    }
    if (n < sizeof buf) {
      if (std::ferror(f)) {
        const int err = errno;
        std::fclose(f);
        cannot_read(path, std::strerror(err));
      }
      break;
    }
  }
  std::fclose(f);
  return text;
}

} // namespace mdrmap::study::detail
