#pragma once
// Where a text stops being well-formed UTF-8 (Unicode 15, Table 3-7: shortest forms only, no
// surrogates, nothing above U+10FFFF). Used where text files enter (specs), so that UTF-16 or Latin-1
// files get an error naming the line instead of being misread silently.
#include <cstddef>
#include <string_view>

namespace crowdlab {

/// Byte offset of the first byte that is not part of a well-formed UTF-8 sequence, or
/// std::string_view::npos when `text` is entirely well-formed.
std::size_t first_invalid_utf8_byte(std::string_view text);

}  // namespace crowdlab
