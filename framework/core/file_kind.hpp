#pragma once
// Refusing special files before they are opened (issue 32). A FIFO that nobody writes blocks open(2) and
// read(2) for ever, /dev/zero and /dev/urandom never end, and a writer that renames a temporary over its
// target replaced a device node (`--csv /dev/full` run as root) or wrote through a symbolic link to a
// file outside the output folder. So every input is checked with stat(2) (it follows links: reading a
// linked regular file is fine) and every output with lstat(2) (it does not: a link is refused) before
// anything is opened.
//   require_regular_input        the path names a regular file (after links); else InputError (exit 2)
//   require_writable_destination the path is absent or a regular file that is not a link; else InputError
//   read_regular_file            require_regular_input, then the whole file, refused when its size (from
//                                stat, before reading) exceeds a limit; the message names the option or
//                                key that raises it
#include <cstdint>
#include <filesystem>
#include <string>

namespace crowdlab {

/// "a FIFO", "a character device", "a directory", "a symbolic link", ... (lstat semantics: `follow`
/// false describes a link itself). Empty for a regular file; "missing" when nothing is there.
std::string describe_file_kind(const std::filesystem::path& path, bool follow);

/// Throws InputError "<path>: cannot read <what>: it is a FIFO (only regular files are read)" when the
/// path (links followed) exists and is not a regular file, and "<path>: no such file" when absent.
void require_regular_input(const std::filesystem::path& path, const std::string& what);

/// Throws InputError "<path>: refusing to write: it is a symbolic link ..." when `path` exists and is not
/// a regular file (a link, device, FIFO, socket or folder). An absent path is fine.
void require_writable_destination(const std::filesystem::path& path);

/// The bytes of a regular file of at most `max_bytes` bytes (checked from its size before reading).
/// `raise_with` names how to raise the limit (e.g. "--max-input-mb"); it ends the refusal.
std::string read_regular_file(const std::filesystem::path& path, const std::string& what,
                              std::uintmax_t max_bytes, const std::string& raise_with);

}  // namespace crowdlab
