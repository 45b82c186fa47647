#pragma once
// Writing files so that a failure is never silent and never leaves a half-written file under its final
// name (issue 21: disk full gave "write failed" without the reason, or no file name, and left zero-byte
// temporaries behind).
//   write_text_file             writes every byte (any content, text or binary) with write(2); a failure
//                               (ENOSPC, EIO, EDQUOT, ...) throws RuntimeError "FILE: write failed: REASON"
//                               with the OS's reason (strerror), after closing the file
//   write_streamed_file         the same for a writer that fills an std::ostream (a 100 MB crowd file goes
//                               to the disk in 1 MiB blocks instead of being built in memory first)
//   write_output_via_temporary  makes a file atomically: a writer fills "<stem>.tmp.<pid><ext>" beside the
//                               target, it is fsync'd (when durable) and renamed over the target; on any
//                               failure the temporary is removed and the error passes on
//   write_file_atomic           both together: bytes to a file, atomically
//   remove_stale_temporaries    removes the temporaries of processes that no longer run (a run killed with
//                               SIGKILL cannot remove its own), so a resumed run ends with the same files
//                               as an uninterrupted one
// This is the one atomic writer of crowdlab (issue 30): crowd files (write_crowd_glb), every output of
// the run pipeline (StageRunner) and the study's files (study_ui, durable: fsync'd with their folder).
// Every message names the file and the OS's reason; the callers report them as runtime failures (exit 1).
// A destination that exists and is not a regular file (a symbolic link, a device such as /dev/full, a
// FIFO, a folder) is refused before anything is written, as an InputError (exit 2; file_kind.hpp): the
// rename would replace the device node or the link, and an in-place write would follow the link.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

namespace crowdlab {

/// Writes `contents` to `path` in place (created or truncated). Throws RuntimeError naming the file and
/// the OS's reason when it cannot be opened, written completely or closed.
void write_text_file(const std::filesystem::path& path, std::string_view contents);

/// Writes `path` in place with what `fill` writes to the stream (buffered; write(2) in 1 MiB blocks). The
/// same failures as write_text_file: a failed write or close throws RuntimeError naming the file and the
/// OS's reason, and the partial file is removed; so is it when `fill` throws (the exception passes on).
void write_streamed_file(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill);

/// Makes `output` atomically: `write(tmp)` writes the complete file at `tmp` (same folder, name
/// "<stem>.tmp.<pid><extension>", so writers that choose a format by extension still work); it is then
/// fsync'd and renamed over `output`. When anything throws, the temporary is removed and the exception
/// passes on; `output` is never seen half-written. `durable = false` skips the fsync (files a test or a
/// simulation can remake); the rename still keeps the write atomic.
void write_output_via_temporary(const std::filesystem::path& output,
                                const std::function<void(const std::filesystem::path& tmp)>& write,
                                bool durable = true);

/// Writes a file atomically (write_output_via_temporary + write_text_file).
void write_file_atomic(const std::filesystem::path& path, std::string_view contents, bool durable = true);

/// Removes, under `dir` (recursively), every temporary "<stem>.tmp.<pid>..." of write_output_via_temporary
/// whose process no longer runs. Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& dir);

}  // namespace crowdlab
