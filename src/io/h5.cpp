#include "io/h5.hpp"

#include <cstring>

namespace mdrmap::io {
namespace {

herr_t innermost(unsigned n, const H5E_error2_t* err, void* data) {
  auto* out = static_cast<std::string*>(data);
  if (n == 0 && err && err->desc)
    *out = std::string(err->func_name ? err->func_name : "") + ": " + err->desc;
  return 0;
}

std::string stack_message() {
  std::string msg;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, &msg);
  H5Eclear2(H5E_DEFAULT);
  return msg.empty() ? std::string("HDF5 call failed") : msg;
}

} // namespace

void silence_hdf5_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) throw H5Error(what + ": " + stack_message());
  return id;
}

void check_status(herr_t status, const std::string& what) {
  if (status < 0) throw H5Error(what + ": " + stack_message());
}

void Handle::close(const std::string& what) {
  if (id_ < 0) return;
  const hid_t id = std::exchange(id_, -1);
  check_status(closer_(id), what);
}

Handle make_file(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Fclose);
}
Handle make_group(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Gclose);
}
Handle make_dataset(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Dclose);
}
Handle make_space(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Sclose);
}
Handle make_plist(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Pclose);
}
Handle make_type(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Tclose);
}
Handle make_attr(hid_t id, const std::string& what) {
  return Handle(check(id, what), H5Aclose);
}

void write_string_attr(hid_t obj, const std::string& name, const std::string& value) {
  const std::string what = "attribute '" + name + "'";
  Handle type = make_type(H5Tcopy(H5T_C_S1), what);
  check_status(H5Tset_size(type.id(), value.empty() ? 1 : value.size()), what);
  check_status(H5Tset_strpad(type.id(), H5T_STR_NULLPAD), what);
  Handle space = make_space(H5Screate(H5S_SCALAR), what);
  Handle attr = make_attr(
      H5Acreate2(obj, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT), what);
  const std::string buf = value.empty() ? std::string(1, '\0') : value;
  check_status(H5Awrite(attr.id(), type.id(), buf.data()), what);
  attr.close(what);
}

std::string read_string_attr(hid_t obj, const std::string& name) {
  const std::string what = "attribute '" + name + "'";
  Handle attr = make_attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), what);
  Handle ftype = make_type(H5Aget_type(attr.id()), what);
  if (H5Tget_class(ftype.id()) != H5T_STRING || H5Tis_variable_str(ftype.id()) != 0)
    throw H5Error(what + ": not a fixed-length string");
  const std::size_t n = H5Tget_size(ftype.id());
  Handle mtype = make_type(H5Tcopy(H5T_C_S1), what);
  check_status(H5Tset_size(mtype.id(), n), what);
  // NULLPAD like the file type: the default NULLTERM would drop the last character
  check_status(H5Tset_strpad(mtype.id(), H5T_STR_NULLPAD), what);
  std::string buf(n + 1, '\0');
  check_status(H5Aread(attr.id(), mtype.id(), buf.data()), what);
  buf.resize(std::strlen(buf.c_str()));
  return buf;
}

bool has_attr(hid_t obj, const std::string& name) {
  const htri_t r = H5Aexists(obj, name.c_str());
  check_status(static_cast<herr_t>(r < 0 ? -1 : 0), "checking attribute '" + name + "'");
  return r > 0;
}

namespace {

// A scalar attribute of type `file_type` from the value at `value` (`mem_type`).
void write_scalar(hid_t obj, const std::string& name, hid_t file_type, hid_t mem_type,
                  const void* value) {
  const std::string what = "attribute '" + name + "'";
  Handle space = make_space(H5Screate(H5S_SCALAR), what);
  Handle attr = make_attr(
      H5Acreate2(obj, name.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT), what);
  check_status(H5Awrite(attr.id(), mem_type, value), what);
  attr.close(what);
}

} // namespace

void write_scalar_attr(hid_t obj, const std::string& name, long long value) {
  write_scalar(obj, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, &value);
}

void write_double_attr(hid_t obj, const std::string& name, double value) {
  write_scalar(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void write_int_array_attr(hid_t obj, const std::string& name, const std::vector<long long>& v) {
  const std::string what = "attribute '" + name + "'";
  const hsize_t n = v.size();
  Handle space = make_space(H5Screate_simple(1, &n, nullptr), what);
  Handle attr = make_attr(
      H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT), what);
  check_status(H5Awrite(attr.id(), H5T_NATIVE_LLONG, v.data()), what);
  attr.close(what);
}

std::string read_text_dataset(hid_t loc, const std::string& name) {
  const std::string what = "reading /" + name;
  Handle d = make_dataset(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), what);
  Handle sp = make_space(H5Dget_space(d.id()), what);
  const hssize_t n = H5Sget_simple_extent_npoints(sp.id());
  if (n < 0) throw H5Error(what + ": bad extent");
  std::string buf(static_cast<std::size_t>(n), '\0');
  check_status(H5Dread(d.id(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()), what);
  buf.resize(std::strlen(buf.c_str()));
  return buf;
}

bool has_link(hid_t loc, const std::string& path) {
  // check each component: H5Lexists fails on a missing intermediate group
  std::size_t pos = 0;
  while (true) {
    const std::size_t next = path.find('/', pos + 1);
    const std::string part = path.substr(0, next);
    const htri_t r = H5Lexists(loc, part.c_str(), H5P_DEFAULT);
    if (r <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    if (next == std::string::npos) return true;
    pos = next;
  }
}

} // namespace mdrmap::io
