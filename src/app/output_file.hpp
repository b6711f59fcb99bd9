#pragma once
// Where `mdrmap simulate --output FILE` writes, by what FILE is (lstat, then
// stat through links), decided before the solver runs:
//
//   ""  or "-"                     standard output
//   a new name, a regular file     replaced at once: the text goes to
//                                  FILE.tmp.<pid> beside it, is fsync'ed and
//                                  renamed over FILE (the directory fsync'ed)
//                                  when the run succeeds; the temporary is
//                                  removed when it fails, FILE untouched. An
//                                  existing file's permissions are kept.
//   a symbolic link to a regular   the file it points to is replaced that way
//   file                           (FILE.tmp.<pid> beside the target); the
//                                  link stays
//   a link to this process's       standard output (/dev/stdout,
//   standard output                /proc/self/fd/1, ... whatever fd 1 is)
//   a character or block device,   written through: opened for writing, never
//   a FIFO, or a link to one       created, truncated or replaced. A FIFO
//                                  without a reader is refused (its open would
//                                  wait forever): start the reader first
//   a directory, a socket, a link  refused: InvalidInput("output"), one line
//   to nothing, a path that
//   cannot be written
#include <sys/stat.h>

#include <cstdio>
#include <string>

namespace mdrmap::app {

class OutputFile {
public:
  /// Opens the output for `path` as above. Throws InvalidInput("output").
  explicit OutputFile(const std::string& path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  /// Closes; a temporary that was never committed is removed.
  ~OutputFile();

  /// Where to write.
  std::FILE* get() const { return file_; }

  /// Flushes and checks for write errors; a replaced file is fsync'ed and
  /// renamed into place. Throws std::runtime_error naming the output.
  void commit();

private:
  enum class Mode { Stdout, Replace, Through };
  void open_replace(const std::string& target, const struct stat* existing);
  void open_through(const struct stat& st);

  std::string path_;   ///< as given
  std::string target_; ///< Replace: the regular file renamed over
  std::string tmp_;    ///< Replace: the temporary beside it
  Mode mode_ = Mode::Stdout;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

} // namespace mdrmap::app
