#include "app/temp_cleanup.hpp"

#include <fcntl.h>
#include <limits.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

namespace mdrmap::app {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

char g_path[PATH_MAX + 1];
volatile std::sig_atomic_t g_armed = 0;

extern "C" void on_terminating_signal(int sig) {
  if (g_armed) ::unlink(g_path); // async-signal-safe
  g_armed = 0;
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig); // delivered when the handler returns: the default action
}

void install_once() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  for (int sig : kSignals) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = on_terminating_signal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

/// Blocks the terminating signals for its lifetime.
class BlockSignals {
public:
  BlockSignals() {
    sigset_t set;
    sigemptyset(&set);
    for (int sig : kSignals)
      sigaddset(&set, sig);
    ::sigprocmask(SIG_BLOCK, &set, &old_);
  }
  ~BlockSignals() { ::sigprocmask(SIG_SETMASK, &old_, nullptr); }
  BlockSignals(const BlockSignals&) = delete;
  BlockSignals& operator=(const BlockSignals&) = delete;

private:
  sigset_t old_;
};

} // namespace

int create_temporary(const std::string& path) {
  if (path.size() > PATH_MAX) {
    errno = ENAMETOOLONG;
    return -1;
  }
  const BlockSignals blocked;
  install_once();
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) return -1;
  std::memcpy(g_path, path.c_str(), path.size() + 1);
  g_armed = 1;
  return fd;
}

void release_temporary() {
  g_armed = 0;
}

} // namespace mdrmap::app
