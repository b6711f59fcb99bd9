#pragma once
// One job at a time on a map: an exclusive lock on the map file, held by the
// job's rank 0 from the map's creation (or the start of a --resume) to the
// job's end, and taken on the map an --overwrite replaces.
//
// An open-file-description lock (F_OFD_SETLK) on bytes [0, kPidOffset):
// unlike a POSIX record lock it is not dropped when the process closes
// another descriptor of the file (HDF5 opens and closes its own), and it
// follows the file through a rename. OFD locks do not tell their holder's
// PID, so the holder also takes a POSIX record lock on the byte at
// kPidOffset, which F_GETLK reports with its PID (closing any descriptor of
// the file in the process drops it: announce() again after such a read).
// Both lie far beyond the end of any map and do not overlap.
#include <string>

namespace mdrmap::io {

class MapLock {
public:
  MapLock() = default;
  MapLock(const MapLock&) = delete;
  MapLock& operator=(const MapLock&) = delete;
  MapLock(MapLock&& o) noexcept;
  MapLock& operator=(MapLock&& o) noexcept;
  ~MapLock();

  /// Locks the file at `path` (opened for writing, never created; a file
  /// this process may not write gets a shared read lock instead). False
  /// when another process holds the lock, with its PID in `holder` (0 when
  /// unknown); true also where the file system has no locks. Throws
  /// std::runtime_error when the file cannot be opened.
  bool acquire(const std::string& path, long* holder);
  bool held() const { return fd_ >= 0; }
  /// Does `path` name the locked file (the same device and inode)?
  bool names(const std::string& path) const;
  /// (Re)takes the POSIX lock that tells other processes this one's PID.
  void announce() const;
  /// Drops the lock (also on destruction).
  void release() noexcept;

private:
  int fd_ = -1;
};

/// rename(from, to) that never replaces `to`: 0, or the errno (EEXIST when
/// `to` exists). Where the file system has no such rename, link + unlink.
int rename_no_replace(const std::string& from, const std::string& to);

} // namespace mdrmap::io
