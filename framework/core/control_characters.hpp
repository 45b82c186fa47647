#pragma once
// Control characters in text that ends up in terminals, job scripts or file headers: a newline ends a
// comment or a directive, an ESC (0x1b) starts an ANSI escape sequence that rewrites a terminal. ASCII
// control characters are the bytes 0x00-0x1f and 0x7f (ECMA-6 / ISO 646).
#include <string>

namespace crowdlab {

/// True for the ASCII control bytes 0x00-0x1f and 0x7f.
bool is_control_character(char c);

/// "a control character (0x0a at byte 4)" for the first control byte of `s`, or "" when it has none.
std::string describe_control_character(const std::string& s);

}  // namespace crowdlab
