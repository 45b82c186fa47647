#include "framework/core/control_characters.hpp"

#include <cstdio>

namespace crowdlab {

bool is_control_character(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

std::string describe_control_character(const std::string& s) {
  for (size_t i = 0; i < s.size(); ++i) {
    if (!is_control_character(s[i])) continue;
    char code[8];
    std::snprintf(code, sizeof code, "0x%02x", static_cast<unsigned>(static_cast<unsigned char>(s[i])));
    return std::string("a control character (") + code + " at byte " + std::to_string(i) + ")";
  }
  return "";
}

}  // namespace crowdlab
