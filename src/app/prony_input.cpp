#include "app/prony_input.hpp"
#include "app/text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "app/case_input.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"

namespace mdrmap::app {
namespace {

/// One value of term k (1-based): `spec` is the branch's modulus or time;
/// the key in a message is its name with k (G3, tau3). Throws
/// InvalidInput(option) with `where` before the message.
double term_value(const std::string& option, const std::string& where, const ParamSpec& spec,
                  std::size_t k, const std::string& text) {
  const std::string key = spec.name + std::to_string(k);
  const std::string t = trimmed(text);
  if (t.empty())
    throw InvalidInput(option, where + "no " + key +
                                   "; a term has its modulus and its relaxation "
                                   "time, both given");
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(t.c_str(), &end);
  if (*end != '\0') throw InvalidInput(option, where + key + " must be a number, got " + shown(t));
  if (!spec.contains(x))
    throw InvalidInput(option, where + key + " must be " + spec.allowed() + ", got " +
                                   (std::isfinite(x) ? format_number(x) : t));
  return x;
}

/// Term k from its two texts.
Branch term(const std::string& option, const std::string& where, std::size_t k,
            const std::string& G, const std::string& tau) {
  return Branch{term_value(option, where, branch_modulus_spec(), k, G),
                term_value(option, where, branch_time_spec(), k, tau)};
}

[[noreturn]] void too_many(const std::string& option, const std::string& where) {
  throw InvalidInput(option, where + "more than " + std::to_string(kMaxBranches) +
                                 " terms; a spectrum has at most " + std::to_string(kMaxBranches));
}

/// "G,tau" with spaces allowed around the names.
bool is_header(const std::string& line) {
  const std::size_t comma = line.find(',');
  return comma != std::string::npos && trimmed(line.substr(0, comma)) == "G" &&
         trimmed(line.substr(comma + 1)) == "tau";
}

constexpr std::size_t kMaxLine = 4096;     ///< characters of a line of a spectrum file
constexpr std::size_t kMaxFile = 1U << 20; ///< bytes of a spectrum file (1 MiB)

/// What kind of file `st` is, for a refusal.
const char* file_kind(const struct stat& st) {
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode)) return "a character device";
  if (S_ISBLK(st.st_mode)) return "a block device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

/// The whole text of the regular file `path`, at most kMaxFile bytes. A
/// FIFO, a device or a directory is refused before it is read (a FIFO's open
/// does not wait for a writer: O_NONBLOCK). Throws InvalidInput(option).
std::string read_small_file(const std::string& option, const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    throw InvalidInput(option, "cannot read '" + path + "': " + std::strerror(err));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw InvalidInput(option,
                       "must be a regular file, got '" + path + "' (" + file_kind(st) + ")");
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      throw InvalidInput(option, "cannot read '" + path + "': " + std::strerror(err));
    }
    if (n == 0) return text;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > kMaxFile)
      throw InvalidInput(option, "'" + path +
                                     "' is larger than 1 MiB; a spectrum file holds a "
                                     "header and at most " +
                                     std::to_string(kMaxBranches) + " terms G,tau");
  }
}

} // namespace

std::vector<Branch> parse_prony(const std::string& text) {
  const std::string form = "terms G:TAU separated by commas, e.g. 1:0.01,1:1,1:100";
  if (trimmed(text).empty())
    throw InvalidInput("prony", "must be " + form + "; got " + shown(text));
  std::vector<Branch> out;
  std::size_t start = 0;
  for (std::size_t k = 1;; ++k) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    const std::string quoted = item.size() > 60 ? shown(item) : "'" + item + "'"; // (cut)
    const std::string where = "term " + std::to_string(k) + " " + quoted + ": ";
    if (k > kMaxBranches) too_many("prony", "has ");
    const std::string tok = trimmed(item);
    if (tok.empty())
      throw InvalidInput("prony", "term " + std::to_string(k) + " is empty; give " + form);
    const std::size_t colon = tok.find(':');
    if (colon == std::string::npos || tok.find(':', colon + 1) != std::string::npos)
      throw InvalidInput("prony", where + "not G:TAU (one ':' between the modulus G" +
                                      std::to_string(k) + " and the time tau" + std::to_string(k) +
                                      ")");
    out.push_back(term("prony", where, k, tok.substr(0, colon), tok.substr(colon + 1)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

std::vector<Branch> read_prony_file(const std::string& path) {
  const std::string option = "prony-file";
  std::istringstream in(read_small_file(option, path));
  std::vector<Branch> out;
  bool header = false;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (n == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3); // UTF-8 BOM
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (line.size() > kMaxLine)
      throw InvalidInput(option, at + "the line is longer than " + std::to_string(kMaxLine) +
                                     " characters; a line holds one term G,tau");
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    if (!header) {
      if (!is_header(t))
        throw InvalidInput(option, at + "the first line must be the header G,tau, got " + shown(t));
      header = true;
      continue;
    }
    if (out.size() == kMaxBranches) too_many(option, at);
    const std::size_t comma = t.find(',');
    if (comma == std::string::npos || t.find(',', comma + 1) != std::string::npos)
      throw InvalidInput(option, at + "a term is G,tau (two values separated by one comma), got " +
                                     shown(t));
    const std::size_t k = out.size() + 1;
    out.push_back(term(option, at + "term " + std::to_string(k) + ": ", k, t.substr(0, comma),
                       t.substr(comma + 1)));
  }
  if (!header)
    throw InvalidInput(option, path + ": no header; the first line must be G,tau, then one term "
                                      "G,tau per line");
  if (out.empty())
    throw InvalidInput(option, path + ": no terms after the header G,tau; give one term G,tau "
                                      "per line");
  return out;
}

std::string format_prony(const std::vector<Branch>& branches) {
  std::string s;
  for (const Branch& b : branches)
    s += (s.empty() ? "" : ",") + format_number(b.G) + ":" + format_number(b.tau);
  return s;
}

} // namespace mdrmap::app
