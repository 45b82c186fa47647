#include "study_ui/response_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/write_file.hpp"

namespace crowdlab::study {
namespace {

std::string errno_text() {
  return std::strerror(errno);
}

void write_all(int fd, const std::string& bytes, const std::string& path) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw RuntimeError(path + ": write failed: " + errno_text());
    }
    done += static_cast<size_t>(n);
  }
}

void fsync_or_throw(int fd, const std::string& path) {
  if (::fsync(fd) != 0) throw RuntimeError(path + ": fsync failed: " + errno_text());
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the response log");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int parse_int(const std::string& cell, const std::string& path, int line, const std::string& column) {
  try {
    size_t used = 0;
    const int v = std::stoi(cell, &used);
    if (used == cell.size()) return v;
  } catch (const std::exception&) {
  }
  throw InputError(SourceLocation{path, line, 0, column}, "not an integer: '" + cell + "'");
}

/// True when `line` (no newline) holds every field of the header and a non-empty last one. The
/// session log's last column is a one-character flag, so a cut inside the row leaves either fewer
/// fields or an empty last field: such a line is complete but for its newline.
bool is_complete_row(const std::string& header_line, const std::string& line, size_t columns) {
  if (line.find('\n') != std::string::npos) return false;
  try {
    const CsvTable t = parse_csv(header_line + line + "\n", "");
    return t.rows.size() == 1 && t.rows[0].size() == columns && !t.rows[0].back().empty();
  } catch (const InputError&) {
    return false;  // ragged or an open quote: torn
  }
}

/// Appends `bytes` to `path` (created if missing), fsyncs when `durable`, and closes the descriptor
/// whatever fails.
void append_whole(const std::string& path, const std::string& bytes, bool durable) {
  require_writable_destination(path);  // never appends through a link (issue 32)
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) throw RuntimeError(path + ": cannot create: " + errno_text());
  try {
    write_all(fd, bytes, path);
    if (durable) fsync_or_throw(fd, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

/// Appends the bytes about to be cut from `path` to `path`.recovered (fsync'd) so that nothing a
/// participant answered is lost even if the recovery rule was wrong.
void save_cut_bytes(const std::string& path, const std::string& bytes, bool durable) {
  append_whole(path + ".recovered", bytes, durable);
}

}  // namespace

void fsync_parent_directory(const std::string& path) {
  std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) throw RuntimeError(dir.string() + ": cannot open directory to fsync: " + errno_text());
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw RuntimeError(dir.string() + ": directory fsync failed: " + errno_text());
}

void write_file_atomically(const std::string& path, const std::string& text, bool durable) {
  // The framework's atomic write (temporary, fsync, rename; no temporary left on failure, issue 21),
  // plus the folder's fsync so that a crash cannot undo the rename of a participant's file.
  write_file_atomic(path, text, durable);
  if (durable) fsync_parent_directory(path);
}

ResponseLog::ResponseLog(ResponseLog&& other) noexcept
    : path_(std::move(other.path_)), fd_(other.fd_), columns_(other.columns_), durable_(other.durable_) {
  other.fd_ = -1;
}

ResponseLog::~ResponseLog() {
  if (fd_ >= 0) ::close(fd_);
}

ResponseLog ResponseLog::create(const std::string& path, const std::vector<std::string>& header,
                                bool durable) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) throw InputError(path + ": already exists (use --resume to continue that session)");
    throw RuntimeError(path + ": cannot create the response log: " + errno_text());
  }
  ResponseLog log(path, fd, header.size(), durable);
  write_all(fd, csv_line(header), path);
  if (durable) {
    fsync_or_throw(fd, path);
    fsync_parent_directory(path);
  }
  return log;
}

ResponseLog ResponseLog::reopen(const std::string& path, const std::vector<std::string>& header,
                                const std::string& trial_column, const std::string& session_column,
                                int rows_per_trial, RecoveredLog& recovered, bool durable) {
  recovered = RecoveredLog{};
  // A log that is a link (to a file outside --out) or a FIFO is refused before it is read or appended to
  // (issue 32); O_NOFOLLOW below closes the gap for the link.
  require_writable_destination(path);
  std::string text = read_all(path);
  const size_t on_disk = text.size();
  const std::string header_line = csv_line(header);
  if (text.compare(0, header_line.size(), header_line) != 0)
    throw InputError(SourceLocation{path, 1, 0, ""},
                     "the response log's header differs from this spec and manifest (different study?)");
  // 1. A last line without its newline: complete rows get it back, torn ones are dropped.
  size_t keep = text.rfind('\n') + 1;  // header ends with '\n', so keep >= header size
  if (keep < on_disk && is_complete_row(header_line, text.substr(keep), header.size())) {
    text += '\n';
    keep = text.size();
  }
  // 2. Parse complete rows; the writer never emits embedded newlines, so row r is line r + 2.
  const CsvTable table = parse_csv(text.substr(0, keep), path);
  const size_t trial_col = table.column(trial_column);
  const size_t session_col = table.column(session_column);
  std::vector<size_t> line_end;  // byte offset just after each row's newline
  for (size_t pos = header_line.size(); pos < keep;) {
    const size_t nl = text.find('\n', pos);
    line_end.push_back(nl + 1);
    pos = nl + 1;
  }
  if (line_end.size() != table.rows.size())
    throw InputError(path + ": rows contain embedded newlines; not a crowdlab response log");
  std::map<int, int> rows_of_trial;
  std::map<int, int> first_line_of_trial;
  std::vector<int> trial_of_row, session_of_row;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const int line = table.line_numbers[r];
    const int trial = parse_int(table.cell(r, trial_col), path, line, trial_column);
    const int session = parse_int(table.cell(r, session_col), path, line, session_column);
    // A trial is written once, as one block of rows. Its rows appearing again (a copied block) were
    // reported as "trial 2 has 0 rows, expected 6" (issue 33).
    const auto [first, inserted] = first_line_of_trial.emplace(trial, line);
    if (!inserted && trial_of_row.back() != trial)
      throw InputError(SourceLocation{path, line, 0, trial_column},
                       "trial " + std::to_string(trial) + " appears again (its rows start at line " +
                           std::to_string(first->second) +
                           "); a trial is written once (the log was edited or is corrupted)");
    session_of_row.push_back(session);
    trial_of_row.push_back(trial);
    ++rows_of_trial[trial];
  }
  // 3. Only the last trial written may be incomplete (fewer rows than a trial has); drop its rows.
  size_t rows_kept = table.rows.size();
  if (!trial_of_row.empty() && rows_of_trial[trial_of_row.back()] < rows_per_trial) {
    const int last = trial_of_row.back();
    while (rows_kept > 0 && trial_of_row[rows_kept - 1] == last) --rows_kept;
    recovered.dropped_rows = static_cast<int>(table.rows.size() - rows_kept);
    rows_of_trial.erase(last);
  }
  for (size_t r = 0; r < rows_kept; ++r)
    if (rows_of_trial.at(trial_of_row[r]) != rows_per_trial)
      throw InputError(SourceLocation{path, table.line_numbers[r], 0, trial_column},
                       "trial " + std::to_string(trial_of_row[r]) + " has " +
                           std::to_string(rows_of_trial.at(trial_of_row[r])) + " rows, expected " +
                           std::to_string(rows_per_trial) + " (the log was edited or is corrupted)");
  for (const auto& [trial, n] : rows_of_trial) recovered.completed_trials.insert(trial);
  for (size_t r = 0; r < rows_kept; ++r)
    recovered.max_session = std::max(recovered.max_session, session_of_row[r]);
  recovered.rows = static_cast<long>(rows_kept);
  keep = rows_kept == 0 ? header_line.size() : line_end[rows_kept - 1];
  recovered.dropped_bytes = keep < on_disk ? static_cast<long>(on_disk - keep) : 0;

  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) throw RuntimeError(path + ": cannot open for appending: " + errno_text());
  ResponseLog log(path, fd, header.size(), durable);
  if (keep < on_disk) {
    save_cut_bytes(path, text.substr(keep, on_disk - keep), durable);  // before anything is cut
    if (::ftruncate(fd, static_cast<off_t>(keep)) != 0)
      throw RuntimeError(path + ": cannot truncate the torn tail: " + errno_text());
    fsync_or_throw(fd, path);
  } else if (keep > on_disk) {  // the restored newline of a complete last row
    write_all(fd, "\n", path);
    fsync_or_throw(fd, path);
  }
  return log;
}

void ResponseLog::append_trial(const std::vector<std::vector<std::string>>& rows) {
  std::string bytes;
  for (const auto& row : rows) {
    if (row.size() != columns_)
      throw RuntimeError(path_ + ": internal error: row has the wrong number of fields");
    std::vector<std::string> clean = row;
    for (std::string& f : clean)
      for (char& c : f)
        if (c == '\n' || c == '\r') c = ' ';  // one row per line keeps recovery line-based
    bytes += csv_line(clean);
  }
  write_all(fd_, bytes, path_);
  if (durable_) fsync_or_throw(fd_, path_);
}

}  // namespace crowdlab::study
