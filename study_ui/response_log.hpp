#pragma once
// ResponseLog: the crash-proof, append-only tidy CSV of one participant's answers.
//
// Durability: append_trial() writes all rows of one trial with a single write(2) and then fsync(2)s
// the file before returning, so a trial the engine moved past is on disk. create() also fsyncs the
// containing directory, so the new file's directory entry survives a power cut (POSIX fsync, see
// the Linux fsync(2) man page: "fsync() on the file does not necessarily ensure that the entry in
// the directory containing the file has also reached disk").
//
// Recovery (reopen()): after a crash or SIGKILL the file may end in a torn write: a last line without
// its newline, or only some rows of the last trial. A last line that holds every field (the last one
// non-empty) lacks only its newline: it is kept and the newline written. A torn line and the rows of
// an incomplete last trial are dropped (truncating the file to the end of the last complete trial and
// fsyncing), after the cut bytes have been appended to `<log>.recovered` beside it, so a resumed
// session re-asks exactly the trials that are not completely on disk (no duplicate and no missing
// rows) and no byte a participant produced is destroyed. Anything else that is inconsistent
// (another header, a malformed complete row, an incomplete trial before the last one) is an
// InputError: the file is then left untouched for a human to inspect.
#include <set>
#include <string>
#include <vector>

namespace crowdlab::study {

struct RecoveredLog {
  std::set<int> completed_trials;  ///< trial indices with all their rows on disk
  int max_session = 0;             ///< highest session number in the file
  long rows = 0;                   ///< complete rows kept
  long dropped_bytes = 0;          ///< bytes of torn or incomplete tail removed
  int dropped_rows = 0;            ///< complete rows of an incomplete last trial removed
};

class ResponseLog {
 public:
  ResponseLog(const ResponseLog&) = delete;
  ResponseLog& operator=(const ResponseLog&) = delete;
  ResponseLog(ResponseLog&& other) noexcept;
  ResponseLog& operator=(ResponseLog&&) = delete;
  ~ResponseLog();

  /// Creates `path` (which must not exist) holding the header line; fsyncs it and its directory.
  /// durable = false skips every fsync (synthetic data that can be regenerated: simulate-study).
  static ResponseLog create(const std::string& path, const std::vector<std::string>& header,
                            bool durable = true);

  /// Opens an existing log for appending after repairing its tail (see above). `trial_column` names
  /// the trial index column; a trial is complete when it has `rows_per_trial` rows.
  static ResponseLog reopen(const std::string& path, const std::vector<std::string>& header,
                            const std::string& trial_column, const std::string& session_column,
                            int rows_per_trial, RecoveredLog& recovered, bool durable = true);

  /// Appends rows (each header.size() fields) with one write and fsyncs. Throws RuntimeError on any
  /// I/O failure (disk full, ...), so the engine stops before showing the next trial.
  void append_trial(const std::vector<std::vector<std::string>>& rows);

  const std::string& path() const { return path_; }

 private:
  ResponseLog(std::string path, int fd, size_t columns, bool durable)
      : path_(std::move(path)), fd_(fd), columns_(columns), durable_(durable) {}
  std::string path_;
  int fd_ = -1;
  size_t columns_ = 0;
  bool durable_ = true;
};

/// fsync()s the directory containing `path` (best effort is not enough: throws RuntimeError).
void fsync_parent_directory(const std::string& path);

/// Writes `text` to `path` atomically: framework/core/write_file.hpp's write_file_atomic (temporary,
/// fsync, rename), then an fsync of the directory (the fsyncs are skipped when durable = false; the
/// rename keeps it atomic).
void write_file_atomically(const std::string& path, const std::string& text, bool durable = true);

}  // namespace crowdlab::study
