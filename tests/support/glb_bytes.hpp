#pragma once
// Byte-level access to a GLB file's container (glTF 2.0 §4.4: 12-byte header, JSON chunk at byte 12,
// its text from byte 20, then the BIN chunk), for tests that mutate crowd files by hand or by fuzzing.
#include <cstdint>
#include <cstring>
#include <string>

namespace crowdlab::test {

inline std::uint32_t glb_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

inline void put_glb_u32(std::string& bytes, std::size_t at, std::uint32_t v) {
  std::memcpy(bytes.data() + at, &v, 4);
}

/// The JSON chunk's text.
inline std::string glb_json(const std::string& glb) {
  return glb.substr(20, glb_u32(glb, 12));
}

/// The GLB rebuilt around a new JSON text (padded with spaces), keeping the binary chunk and making the
/// lengths agree: mutations of the JSON then reach the glTF reader instead of the container's checks.
inline std::string glb_with_json(const std::string& glb, std::string json) {
  while (json.size() % 4) json.push_back(' ');
  const std::string bin = glb.substr(20 + glb_u32(glb, 12));
  std::string out = glb.substr(0, 20);
  put_glb_u32(out, 8, static_cast<std::uint32_t>(20 + json.size() + bin.size()));
  put_glb_u32(out, 12, static_cast<std::uint32_t>(json.size()));
  return out + json + bin;
}

}  // namespace crowdlab::test
