#include "framework/io/glb_container.hpp"

#include <cstdint>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

std::uint32_t u32_at(std::string_view bytes, std::size_t offset) {
  std::uint32_t v = 0;
  for (int k = 3; k >= 0; --k)
    v = v << 8 | static_cast<unsigned char>(bytes[offset + static_cast<std::size_t>(k)]);
  return v;  // little-endian, as glTF 2.0 §4.4.1 requires
}

/// Four bytes quoted, the unprintable ones as \xNN: 'glTF', 'BIN\x00', '\x00\x01\x02\x03'.
std::string four_bytes(std::string_view bytes, std::size_t offset) {
  static const char* const kHex = "0123456789ABCDEF";
  std::string s = "'";
  for (const char c : bytes.substr(offset, 4)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F)
      s += c;
    else
      s += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
  }
  return s + "'";
}

}  // namespace

std::string_view glb_json_chunk(std::string_view bytes, const std::string& file) {
  const auto fail = [&](const std::string& what) {
    throw InputError(file + ": cannot read glTF: not a valid GLB file: " + what);
  };
  const auto n = std::to_string(bytes.size());
  if (bytes.size() < kGlbJsonOffset)
    fail("the file has " + n + " bytes, fewer than the 20 of a GLB header and its first chunk header");
  if (bytes.substr(0, 4) != "glTF")
    fail("bytes 0-3 are " + four_bytes(bytes, 0) + ", not the magic 'glTF' (is it a .gltf text file?)");
  if (const std::uint32_t version = u32_at(bytes, 4); version != 2)
    fail("the header (byte 4) gives container version " + std::to_string(version) + ", expected 2");
  const std::uint32_t length = u32_at(bytes, 8);
  if (length > bytes.size())
    fail("the header (byte 8) gives a total length of " + std::to_string(length) +
         " bytes, but the file has " + n + " (truncated?)");
  const std::uint32_t json_length = u32_at(bytes, 12);
  if (u32_at(bytes, 16) != 0x4E4F534Au)
    fail("the first chunk (byte 12) has type " + four_bytes(bytes, 16) + ", expected 'JSON'");
  if (json_length == 0) fail("the JSON chunk (byte 12) is empty");
  const std::uint64_t json_end = kGlbJsonOffset + std::uint64_t{json_length};
  if (json_end > length)
    fail("the JSON chunk (byte 12) gives a length of " + std::to_string(json_length) +
         " bytes, which runs to byte " + std::to_string(json_end) + ", past the total length of " +
         std::to_string(length));
  if (json_end < length) {  // a BIN chunk follows (§4.4.3.2), padded to 4 bytes like every chunk
    const std::string at = "the second chunk (byte " + std::to_string(json_end) + ")";
    if (json_end + 8 > length) fail(at + " has no room for its 8-byte header before the total length");
    const std::uint32_t bin_length = u32_at(bytes, static_cast<std::size_t>(json_end));
    if (u32_at(bytes, static_cast<std::size_t>(json_end) + 4) != 0x004E4942u)
      fail(at + " has type " + four_bytes(bytes, static_cast<std::size_t>(json_end) + 4) +
           ", expected 'BIN'");
    if (json_end + 8 + bin_length > length)
      fail(at + " gives a length of " + std::to_string(bin_length) + " bytes, past the total length of " +
           std::to_string(length));
    if (bin_length == 0 || bin_length % 4 != 0)
      fail(at + " gives a length of " + std::to_string(bin_length) +
           " bytes; a BIN chunk holds a positive "
           "multiple of 4");
  }
  return bytes.substr(kGlbJsonOffset, json_length);
}

}  // namespace crowdlab
