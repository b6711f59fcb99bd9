#include "app/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "app/temp_cleanup.hpp"
#include "core/model/case.hpp"

namespace mdrmap::app {
namespace {

/// Refuses the output: "must be a writable file ... (why), got PATH".
[[noreturn]] void refuse(const std::string& why, const std::string& path) {
  throw InvalidInput("output",
                     "must be a writable file in an existing directory (" + why + "), got " + path);
}

[[noreturn]] void refuse_errno(int err, const std::string& path) {
  refuse(std::strerror(err), path);
}

std::string dir_of(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos) return ".";
  return pos == 0 ? "/" : path.substr(0, pos);
}

bool same_file(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/// The regular file a symbolic link `path` leads to (st: stat of path), by a
/// name that leads to the same file, so that a temporary beside it can be
/// renamed over it. Throws InvalidInput("output") when there is none (a
/// /proc link to a deleted file).
std::string link_target(const std::string& path, const struct stat& st) {
  char* real = ::realpath(path.c_str(), nullptr);
  if (real == nullptr) refuse_errno(errno, path);
  const std::string target(real);
  std::free(real);
  struct stat rs {};
  if (::stat(target.c_str(), &rs) != 0 || !same_file(rs, st))
    throw InvalidInput("output", "'" + path +
                                     "' is a link to a file that has no name to replace it by ('" +
                                     target + "'); give the file itself");
  return target;
}

/// Makes a rename in `dir` durable. A file system that cannot sync a
/// directory (EINVAL) is left as it is.
void sync_dir(const std::string& dir, const std::string& target) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return; // (a directory we may write but not read: nothing to sync with)
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0 && err != EINVAL)
    throw std::runtime_error("--output: " + target + " is written, but syncing its directory " +
                             dir + " failed: " + std::strerror(err));
}

} // namespace

OutputFile::OutputFile(const std::string& path) : path_(path), file_(stdout) {
  if (path.empty() || path == "-") return;
  if (path.back() == '/') refuse("the path names a directory", path);
  struct stat lst {};
  if (::lstat(path.c_str(), &lst) != 0) {
    if (errno != ENOENT) refuse_errno(errno, path);
    open_replace(path, nullptr); // a new file (or a missing directory, said by its open)
    return;
  }
  const bool link = S_ISLNK(lst.st_mode);
  struct stat st = lst;
  if (link && ::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    throw InvalidInput("output", "'" + path + "' is a symbolic link to nothing (" +
                                     std::strerror(err) + "); give an existing file or a new name");
  }
  if (S_ISDIR(st.st_mode)) refuse("the path is a directory", path);
  struct stat out {};
  if (link && ::fstat(STDOUT_FILENO, &out) == 0 && same_file(out, st)) return; // /dev/stdout
  if (S_ISREG(st.st_mode))
    open_replace(link ? link_target(path, st) : path, &st);
  else
    open_through(st);
}

void OutputFile::open_replace(const std::string& target, const struct stat* existing) {
  file_ = nullptr;
  target_ = target;
  tmp_ = target + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  const int fd = create_temporary(tmp_); // removed on SIGINT, SIGTERM, SIGHUP
  if (fd < 0) refuse_errno(errno, path_);
  mode_ = Mode::Replace;
  // the replaced file keeps its permissions (best effort: a failure leaves
  // those of a new file)
  if (existing != nullptr) (void)::fchmod(fd, existing->st_mode & 0777);
  file_ = ::fdopen(fd, "w");
  if (file_ == nullptr) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp_.c_str());
    release_temporary();
    throw std::runtime_error("cannot open " + tmp_ + ": " + std::strerror(err));
  }
}

void OutputFile::open_through(const struct stat& st) {
  file_ = nullptr;
  if (S_ISSOCK(st.st_mode))
    throw InvalidInput("output", "'" + path_ + "' is a socket; give a file, a FIFO or a device");
  // O_NONBLOCK: a FIFO without a reader fails at once (ENXIO) instead of
  // waiting for one; no O_CREAT or O_TRUNC: the file is written, not replaced
  const int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == ENXIO && S_ISFIFO(st.st_mode))
      throw InvalidInput("output", "'" + path_ +
                                       "' is a FIFO without a reader; start its reader first "
                                       "(writing would wait for one forever)");
    refuse_errno(err, path_);
  }
  struct stat now {};
  const int flags = ::fcntl(fd, F_GETFL);
  if (::fstat(fd, &now) != 0 || !same_file(now, st) || flags < 0 ||
      ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
    ::close(fd);
    throw InvalidInput("output", "'" + path_ + "' changed while it was opened; run again");
  }
  mode_ = Mode::Through;
  file_ = ::fdopen(fd, "w");
  if (file_ == nullptr) {
    const int err = errno;
    ::close(fd);
    throw std::runtime_error("cannot open " + path_ + ": " + std::strerror(err));
  }
}

OutputFile::~OutputFile() {
  if (file_ != nullptr && mode_ != Mode::Stdout) std::fclose(file_);
  if (mode_ == Mode::Replace && !committed_) ::unlink(tmp_.c_str());
  if (mode_ == Mode::Replace) release_temporary();
}

void OutputFile::commit() {
  const bool write_error = std::fflush(file_) != 0 || std::ferror(file_) != 0;
  int err = errno;
  if (mode_ == Mode::Stdout) {
    if (write_error)
      throw std::runtime_error(std::string("writing to stdout failed: ") + std::strerror(err));
    committed_ = true;
    return;
  }
  bool sync_error = false;
  if (!write_error && mode_ == Mode::Replace && ::fsync(::fileno(file_)) != 0)
    sync_error = true, err = errno;
  const int rc = std::fclose(file_);
  const int err_close = errno;
  file_ = nullptr;
  const std::string written = mode_ == Mode::Replace ? tmp_ : path_;
  if (write_error || sync_error || rc != 0)
    throw std::runtime_error("--output: writing " + written + " failed: " +
                             std::strerror(write_error || sync_error ? err : err_close));
  if (mode_ == Mode::Through) {
    committed_ = true;
    return;
  }
  if (std::rename(tmp_.c_str(), target_.c_str()) != 0) {
    const int e = errno;
    throw std::runtime_error("--output: renaming " + tmp_ + " to " + target_ +
                             " failed: " + std::strerror(e));
  }
  committed_ = true;
  release_temporary(); // renamed: the name no longer holds the temporary
  sync_dir(dir_of(target_), target_);
}

} // namespace mdrmap::app
