#pragma once
// write_zip_archive: a ZIP file of stored (uncompressed) entries, byte-for-byte reproducible.
//
// Format: PKWARE APPNOTE.TXT 6.3 (https://pkware.cachefly.net/webdocs/casestudies/APPNOTE.TXT), §4.3:
// one local file header + data per entry, then the central directory and the end-of-central-directory
// record. Method 0 (stored: the clips are already compressed video), general-purpose flag bit 11 (names
// are UTF-8), CRC-32 from zlib, and a fixed DOS time (1980-01-01 00:00) so the same inputs give the same
// bytes. No ZIP64: every entry and the whole archive must stay under 4 GiB, at most 65535 entries.
// Used for JATOS study archives (.jzip), which are plain ZIP files.
#include <string>
#include <vector>

namespace crowdlab::study {

struct ZipEntry {
  std::string name;         ///< path inside the archive, '/'-separated, no leading '/'
  std::string source_path;  ///< file to store
};

/// Writes `entries` in the given order to `zip_path` (atomically: temp file + rename). Throws
/// InputError for an unreadable source or an invalid name, RuntimeError on write failure or when the
/// ZIP32 limits are exceeded.
void write_zip_archive(const std::string& zip_path, const std::vector<ZipEntry>& entries);

}  // namespace crowdlab::study
