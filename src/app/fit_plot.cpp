#include "app/fit_plot.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/model/case.hpp"

extern char** environ;

#ifndef MDRMAP_PYTHON_EXE
#define MDRMAP_PYTHON_EXE ""
#endif
#ifndef MDRMAP_PYTHON_REL_DIR
#define MDRMAP_PYTHON_REL_DIR ""
#endif

namespace mdrmap::app {
namespace {

namespace fs = std::filesystem;

/// Where the package may be, next to this program: <dir>/../python (the
/// build tree) and <dir>/../<the install's python dir>.
std::string package_path() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "";
  const fs::path up = exe.parent_path().parent_path();
  std::string path = (up / "python").string();
  if (*MDRMAP_PYTHON_REL_DIR) path += ":" + (up / MDRMAP_PYTHON_REL_DIR).string();
  return path;
}

} // namespace

void check_plot(const std::string& png) {
  if (!*MDRMAP_PYTHON_EXE)
    throw InvalidInput("plot", "this mdrmap was built without Python; write --output FILE.json "
                               "and draw it with python3 -m mdrmap plot_fit");
  if (png.empty()) throw InvalidInput("plot", "must name a file, e.g. fit.png");
  const fs::path dir = fs::path(png).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw InvalidInput("plot", "no directory " + dir.string() + " for " + png);
}

void draw_plot(const std::string& json, const std::string& png) {
  std::string pythonpath = "PYTHONPATH=" + package_path();
  if (const char* old = std::getenv("PYTHONPATH"); old && *old)
    pythonpath += ":" + std::string(old);
  std::vector<std::string> env_text{pythonpath};
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "PYTHONPATH=", 11) != 0) env_text.emplace_back(*e);
  std::vector<char*> env;
  for (auto& s : env_text)
    env.push_back(s.data());
  env.push_back(nullptr);
  std::vector<std::string> arg_text{MDRMAP_PYTHON_EXE, "-m", "mdrmap", "plot_fit", json, "-o", png};
  std::vector<char*> argv;
  for (auto& s : arg_text)
    argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int err = ::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), env.data());
  if (err != 0)
    throw std::runtime_error(std::string("--plot: cannot run ") + argv[0] + ": " +
                             std::strerror(err));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("--plot: lost the plot tool");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("--plot: python3 -m mdrmap plot_fit failed (exit " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                             "); the fit's JSON was written");
}

} // namespace mdrmap::app
