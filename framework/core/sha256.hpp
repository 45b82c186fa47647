#pragma once
// SHA-256 (FIPS 180-4) of bytes or a file, as lowercase hex. Used for provenance and manifests.
#include <string>
#include <string_view>

namespace crowdlab {
std::string sha256_hex(std::string_view bytes);
/// Throws InputError when the file cannot be read.
std::string sha256_file_hex(const std::string& path);
}  // namespace crowdlab
