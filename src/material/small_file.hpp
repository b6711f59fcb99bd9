#pragma once
// The whole text of a small input file (a spectrum, a material card): a
// regular file of at most 1 MiB, read without waiting on a FIFO or a device.
#include <string>

namespace mdrmap::material {

inline constexpr std::size_t kMaxInputFile = 1U << 20; ///< bytes of an input file (1 MiB)

/// The text of the regular file `path`, at most kMaxInputFile bytes. A FIFO,
/// a device or a directory is refused before it is read (a FIFO's open does
/// not wait for a writer: O_NONBLOCK). `holds` says what such a file holds,
/// for the refusal of a larger one. Throws InvalidInput(option).
std::string read_small_file(const std::string& option, const std::string& path,
                            const std::string& holds);

} // namespace mdrmap::material
