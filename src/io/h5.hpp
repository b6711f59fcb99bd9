#pragma once
// Thin RAII over the HDF5 C API. Every call goes through check(), which turns
// a negative return into an H5Error carrying the caller's description and
// the innermost message of the HDF5 error stack; HDF5's own printing of the
// stack is switched off (silence_hdf5_errors), so a failure is one line.
#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mdrmap::io {

class H5Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Turns off HDF5's automatic error-stack printing for this process.
void silence_hdf5_errors();

/// Throws H5Error("<what>: <HDF5 message>") when id < 0; returns id.
hid_t check(hid_t id, const std::string& what);
/// Throws H5Error when status < 0.
void check_status(herr_t status, const std::string& what);

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      closer_ = o.closer_;
    }
    return *this;
  }
  ~Handle() { reset(); }
  hid_t id() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  /// Closes now and reports failure (a destructor cannot).
  void close(const std::string& what);
  void reset() noexcept {
    if (id_ >= 0 && closer_) closer_(id_);
    id_ = -1;
  }

private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

Handle make_file(hid_t id, const std::string& what);
Handle make_group(hid_t id, const std::string& what);
Handle make_dataset(hid_t id, const std::string& what);
Handle make_space(hid_t id, const std::string& what);
Handle make_plist(hid_t id, const std::string& what);
Handle make_type(hid_t id, const std::string& what);
Handle make_attr(hid_t id, const std::string& what);

/// Fixed-length string attribute on an object (created; must not exist).
void write_string_attr(hid_t obj, const std::string& name, const std::string& value);
std::string read_string_attr(hid_t obj, const std::string& name);
bool has_attr(hid_t obj, const std::string& name);
void write_scalar_attr(hid_t obj, const std::string& name, long long value);
void write_double_attr(hid_t obj, const std::string& name, double value);
void write_int_array_attr(hid_t obj, const std::string& name, const std::vector<long long>& v);
bool has_link(hid_t loc, const std::string& path);
/// A 1-D uint8 dataset read as text (up to the first NUL).
std::string read_text_dataset(hid_t loc, const std::string& name);

} // namespace mdrmap::io
