#pragma once
// A temporary file removed when the process is ended by SIGINT, SIGTERM or
// SIGHUP (Ctrl-C, kill, a closed terminal) before it is renamed into place:
// the handler unlinks it and ends the process by the same signal, with that
// signal's default action. A signal the process ignores (nohup) stays ignored.
// One temporary at a time (the process's --output).
#include <string>

namespace mdrmap::app {

/// Creates `path` (O_EXCL, mode 0666 before the umask) and names it as the
/// temporary to remove on a terminating signal, with those signals blocked in
/// between; installs the handlers (once). Returns the descriptor, or -1 with
/// errno set (nothing created, nothing watched).
int create_temporary(const std::string& path);

/// The temporary is renamed or removed: a signal no longer touches it.
void release_temporary();

} // namespace mdrmap::app
