#include "material/text.hpp"

namespace mdrmap::material {

std::string shown(const std::string& text) {
  if (text.empty()) return "an empty string";
  constexpr std::size_t kShown = 60; // a longer text is cut: the message stays one short line
  if (text.size() > kShown) {
    std::size_t cut = kShown; // not inside a UTF-8 character
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U)
      --cut;
    return "'" + text.substr(0, cut) + "...' (" + std::to_string(text.size()) + " characters)";
  }
  if (text.find_first_of(" \t\n\r\f\v',") != std::string::npos) return "'" + text + "'";
  return text;
}

} // namespace mdrmap::material
