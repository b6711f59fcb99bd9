#include "io/map_lock.hpp"

#include <fcntl.h>
#include <stdio.h> // renameat2
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace mdrmap::io {
namespace {

constexpr off_t kPidOffset = off_t{1} << 62;

struct flock range(short type, off_t start, off_t len) {
  struct flock fl {};
  fl.l_type = type;
  fl.l_whence = SEEK_SET;
  fl.l_start = start;
  fl.l_len = len;
  return fl;
}

// The PID of the process announcing itself on fd's file, 0 if none.
long announced_holder(int fd) {
  struct flock probe = range(F_WRLCK, kPidOffset, 1);
  if (::fcntl(fd, F_GETLK, &probe) != 0 || probe.l_type == F_UNLCK) return 0;
  return probe.l_pid > 0 ? static_cast<long>(probe.l_pid) : 0;
}

} // namespace

MapLock::MapLock(MapLock&& o) noexcept : fd_(std::exchange(o.fd_, -1)) {}

MapLock& MapLock::operator=(MapLock&& o) noexcept {
  if (this != &o) {
    release();
    fd_ = std::exchange(o.fd_, -1);
  }
  return *this;
}

MapLock::~MapLock() {
  release();
}

void MapLock::release() noexcept {
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
}

bool MapLock::acquire(const std::string& path, long* holder) {
  release();
  constexpr int kFlags = O_CLOEXEC | O_NOCTTY | O_NONBLOCK;
  int fd = ::open(path.c_str(), O_RDWR | kFlags);
  short type = F_WRLCK;
  if (fd < 0 && (errno == EACCES || errno == EROFS)) { // a read-only map (to replace): a read
    fd = ::open(path.c_str(), O_RDONLY | kFlags);      // lock, refused while a job writes it
    type = F_RDLCK;
  }
  if (fd < 0) throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno));
  struct flock fl = range(type, 0, kPidOffset);
  if (::fcntl(fd, F_OFD_SETLK, &fl) != 0 && (errno == EACCES || errno == EAGAIN)) {
    if (holder) *holder = announced_holder(fd);
    ::close(fd);
    return false;
  }
  fd_ = fd; // locked, or no locks on this file system (ENOLCK, EINVAL, ...)
  return true;
}

bool MapLock::names(const std::string& path) const {
  struct stat a {
  }, b{};
  return fd_ >= 0 && ::fstat(fd_, &a) == 0 && ::stat(path.c_str(), &b) == 0 &&
         a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

void MapLock::announce() const {
  if (fd_ < 0) return;
  struct flock fl = range(F_WRLCK, kPidOffset, 1);
  (void)::fcntl(fd_, F_SETLK, &fl); // best effort: the PID is a courtesy
}

int rename_no_replace(const std::string& from, const std::string& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS) return errno;
  if (::link(from.c_str(), to.c_str()) != 0) return errno; // atomic: fails if `to` exists
  ::unlink(from.c_str());
  return 0;
}

} // namespace mdrmap::io
