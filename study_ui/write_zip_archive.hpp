#pragma once
// write_zip_archive: a ZIP file of stored (uncompressed) entries, byte-for-byte reproducible, written
// with libzip (https://libzip.org/, Debian's libzip-dev).
//
// Stored (method 0): the clips are already compressed video, and JATOS only unpacks the archive.
// Reproducible: every entry gets the same DOS time (1980-01-01 00:00, zip_file_set_dostime, so the
// time zone does not matter) and the same Unix attributes (a regular file, mode 0644,
// zip_file_set_external_attributes), whatever the source files' times and modes; entries are
// written in the given order. libzip writes to a temporary file beside zip_path and renames it on
// success, so a failed write leaves no partial archive. Used for JATOS study archives (.jzip), which
// are plain ZIP files.
#include <string>
#include <vector>

namespace crowdlab::study {

struct ZipEntry {
  std::string name;         ///< path inside the archive, '/'-separated, no leading '/'
  std::string source_path;  ///< file to store; "" stores `contents` instead
  std::string contents;     ///< the entry's bytes when source_path is ""
};

/// Writes `entries` in the given order to `zip_path` (replacing it). Throws InputError for an
/// unreadable source or an invalid or repeated name, RuntimeError when libzip cannot write the archive.
void write_zip_archive(const std::string& zip_path, const std::vector<ZipEntry>& entries);

}  // namespace crowdlab::study
