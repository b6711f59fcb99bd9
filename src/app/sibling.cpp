#include "app/sibling.hpp"

#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "app/exit_codes.hpp"

namespace mdrmap::app {
namespace {

/// The directory of this executable (/proc/self/exe; argv[0]'s where that
/// cannot be read).
std::filesystem::path own_directory(const char* argv0) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) return self.parent_path();
  return std::filesystem::absolute(argv0 != nullptr ? argv0 : "", ec).parent_path();
}

} // namespace

int run_sibling(const char* name, char** argv) {
  const std::string path = (own_directory(argv[0]) / name).string();
  argv[0] = const_cast<char*>(path.c_str());
  ::execv(path.c_str(), argv);
  std::fprintf(stderr,
               "mdrmap: error: cannot run %s: %s (it is built and installed beside mdrmap; "
               "rebuild or reinstall mdrmap)\n",
               path.c_str(), std::strerror(errno));
  return kExitRuntime;
}

int sibling_main(const char* subcommand, int argc, char** argv,
                 int (*command)(const std::vector<std::string>&, int, char**)) {
  // A write past the file-size limit (ulimit -f) must fail with EFBIG and be
  // reported, not kill the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args.front() == subcommand) args.erase(args.begin());
  try {
    return command(args, argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mdrmap: error: %s\n", e.what());
    return kExitRuntime;
  }
}

} // namespace mdrmap::app
