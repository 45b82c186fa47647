#pragma once
// SHA-256 (FIPS 180-4) of bytes or a file, as lowercase hex. Used for provenance and manifests.
// Computed by OpenSSL's libcrypto (Debian's libssl-dev), which uses the CPU's SHA extensions where it
// has them: the stage cache hashes every crowd file it writes and reads (up to ~100 MB each), where the
// hand-written version this replaced ran at ~115 MB/s (issue 31).
#include <string>
#include <string_view>

namespace crowdlab {
std::string sha256_hex(std::string_view bytes);
/// Throws InputError when the file cannot be read.
std::string sha256_file_hex(const std::string& path);
}  // namespace crowdlab
