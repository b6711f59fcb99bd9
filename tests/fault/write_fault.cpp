// write_fault: an LD_PRELOAD library for fault-injection tests. It makes
// writes to one file fail, as a full disk or a failing device would, below
// HDF5 and MPI-IO, so the real error path of the program is exercised.
//
//   MDRMAP_FAULT_PATH   absolute path of the file whose writes fail (required;
//                       compared with /proc/self/fd/N, so renames are seen)
//   MDRMAP_FAULT_SKIP   write calls to that file that still succeed first (0)
//   MDRMAP_FAULT_ERRNO  ENOSPC (default), EIO or EFBIG
//   MDRMAP_FAULT_RANK   fail only in the process with this OMPI_COMM_WORLD_RANK
//   MDRMAP_FAULT_FSYNC  1: writes succeed, fsync/fdatasync of the file fail (EIO)
//   MDRMAP_FAULT_BYTES  LO:HI: only positional writes touching bytes [LO, HI)
//                       of the file fail (e.g. one dataset's), the others pass
//
// Without MDRMAP_FAULT_PATH every call passes straight through.
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <dlfcn.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

std::atomic<long> g_matching_calls{0};

bool enabled_here() {
  static const int enabled = [] {
    const char* path = std::getenv("MDRMAP_FAULT_PATH");
    if (!path || !*path) return 0;
    const char* want = std::getenv("MDRMAP_FAULT_RANK");
    if (want && *want) {
      const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
      if (!rank || std::strcmp(rank, want) != 0) return 0;
    }
    return 1;
  }();
  return enabled != 0;
}

int fault_errno() {
  const char* e = std::getenv("MDRMAP_FAULT_ERRNO");
  if (e && std::strcmp(e, "EIO") == 0) return EIO;
  if (e && std::strcmp(e, "EFBIG") == 0) return EFBIG;
  return ENOSPC;
}

bool is_target(int fd) {
  if (!enabled_here()) return false;
  char link[64], target[PATH_MAX];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link, target, sizeof target - 1);
  if (n <= 0) return false;
  target[n] = '\0';
  return std::strcmp(target, std::getenv("MDRMAP_FAULT_PATH")) == 0;
}

bool fsync_mode() {
  const char* f = std::getenv("MDRMAP_FAULT_FSYNC");
  return f && std::strcmp(f, "1") == 0;
}

// Does a positional write of `count` bytes at `off` touch MDRMAP_FAULT_BYTES
// (always, when it is not set; never for a write without an offset)?
bool in_range(long long off, std::size_t count) {
  const char* r = std::getenv("MDRMAP_FAULT_BYTES");
  if (!r || !*r) return true;
  long long lo = 0, hi = 0;
  if (off < 0 || std::sscanf(r, "%lld:%lld", &lo, &hi) != 2) return false;
  return off < hi && off + static_cast<long long>(count) > lo;
}

// True when this write to fd must fail (sets errno); `off` -1 when the write
// has no offset.
bool must_fail(int fd, long long off = -1, std::size_t count = 0) {
  if (fsync_mode() || !is_target(fd) || !in_range(off, count)) return false;
  const char* skip_text = std::getenv("MDRMAP_FAULT_SKIP");
  const long skip = skip_text ? std::atol(skip_text) : 0;
  if (g_matching_calls.fetch_add(1) < skip) return false;
  errno = fault_errno();
  return true;
}

template <class F> F next(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

} // namespace

extern "C" {

ssize_t write(int fd, const void* buf, size_t count) {
  static auto real = next<ssize_t (*)(int, const void*, size_t)>("write");
  if (must_fail(fd)) return -1;
  return real(fd, buf, count);
}

ssize_t pwrite(int fd, const void* buf, size_t count, off_t off) {
  static auto real = next<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite");
  if (must_fail(fd, off, count)) return -1;
  return real(fd, buf, count, off);
}

ssize_t pwrite64(int fd, const void* buf, size_t count, off64_t off) {
  static auto real = next<ssize_t (*)(int, const void*, size_t, off64_t)>("pwrite64");
  if (must_fail(fd, off, count)) return -1;
  return real(fd, buf, count, off);
}

ssize_t writev(int fd, const struct iovec* iov, int n) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int)>("writev");
  if (must_fail(fd)) return -1;
  return real(fd, iov, n);
}

ssize_t pwritev(int fd, const struct iovec* iov, int n, off_t off) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int, off_t)>("pwritev");
  if (must_fail(fd)) return -1;
  return real(fd, iov, n, off);
}

ssize_t pwritev64(int fd, const struct iovec* iov, int n, off64_t off) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int, off64_t)>("pwritev64");
  if (must_fail(fd)) return -1;
  return real(fd, iov, n, off);
}

ssize_t pwritev2(int fd, const struct iovec* iov, int n, off_t off, int flags) {
  static auto real = next<ssize_t (*)(int, const struct iovec*, int, off_t, int)>("pwritev2");
  if (must_fail(fd)) return -1;
  return real(fd, iov, n, off, flags);
}

int fsync(int fd) {
  static auto real = next<int (*)(int)>("fsync");
  if (fsync_mode() && is_target(fd)) {
    errno = EIO;
    return -1;
  }
  return real(fd);
}

int fdatasync(int fd) {
  static auto real = next<int (*)(int)>("fdatasync");
  if (fsync_mode() && is_target(fd)) {
    errno = EIO;
    return -1;
  }
  return real(fd);
}

} // extern "C"
