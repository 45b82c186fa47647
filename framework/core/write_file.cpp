#include "framework/core/write_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"

namespace crowdlab {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const char* what, int error) {
  throw RuntimeError(path.string() + ": " + what + ": " + std::strerror(error));
}

/// fsync(2) on an existing file, so that the rename that follows never publishes unwritten data.
void sync_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open to sync", errno);
  const int rc = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (rc != 0) fail(path, "fsync failed", error);
}

}  // namespace

namespace {

/// Opens `path` for writing (created or truncated), never through a link or into a device, FIFO or
/// folder (issue 32); O_NOFOLLOW closes the gap between the check and the open for the link itself.
int open_for_writing(const fs::path& path) {
  require_writable_destination(path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) fail(path, "cannot write", errno);
  return fd;
}

/// Writes all `n` bytes; returns 0 or the OS's error (write(2) returns 0 only when nothing more fits).
int write_all(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t written = ::write(fd, p, n);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return written < 0 ? errno : ENOSPC;
    p += written;
    n -= static_cast<size_t>(written);
  }
  return 0;
}

/// Closes the file (close(2) reports deferred write errors on some file systems: NFS, quotas); when
/// anything failed, removes it, so that a file that could not be written whole is not left behind
/// half-written under any name, and throws naming the file and the reason.
void close_or_fail(int fd, const fs::path& path, int error) {
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error == 0) return;
  ::unlink(path.c_str());
  fail(path, "write failed", error);
}

/// An output stream buffer that writes to a file descriptor in 1 MiB blocks and keeps the first error
/// (later writes are dropped): a stream cannot throw through every writer it is handed to.
class FileSink : public std::streambuf {
 public:
  explicit FileSink(int fd) : fd_(fd), block_(1 << 20) { setp(block_.data(), block_.data() + block_.size()); }
  int error() const { return error_; }
  void flush_block() {
    const std::ptrdiff_t n = pptr() - pbase();
    if (n > 0 && error_ == 0) error_ = write_all(fd_, pbase(), static_cast<size_t>(n));
    setp(block_.data(), block_.data() + block_.size());
  }

 protected:
  int_type overflow(int_type c) override {
    flush_block();
    if (!traits_type::eq_int_type(c, traits_type::eof())) sputc(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n < static_cast<std::streamsize>(block_.size())) return std::streambuf::xsputn(s, n);
    flush_block();  // a large write goes straight to the file, without a copy into the block
    if (error_ == 0) error_ = write_all(fd_, s, static_cast<size_t>(n));
    return n;
  }
  int sync() override {
    flush_block();
    return error_ == 0 ? 0 : -1;
  }

 private:
  int fd_;
  std::vector<char> block_;
  int error_ = 0;
};

}  // namespace

void write_text_file(const fs::path& path, std::string_view contents) {
  const int fd = open_for_writing(path);
  close_or_fail(fd, path, write_all(fd, contents.data(), contents.size()));
}

void write_streamed_file(const fs::path& path, const std::function<void(std::ostream&)>& fill) {
  const int fd = open_for_writing(path);
  FileSink sink(fd);
  std::ostream out(&sink);
  try {
    fill(out);
  } catch (...) {
    ::close(fd);
    ::unlink(path.c_str());
    throw;
  }
  sink.flush_block();
  close_or_fail(fd, path, sink.error());
}

void write_output_via_temporary(const fs::path& output, const std::function<void(const fs::path&)>& write,
                                bool durable) {
  // rename(2) replaces whatever the name holds: a device node, or a link that pointed elsewhere (issue 32).
  require_writable_destination(output);
  // Per-process temporary name: shards running at once may write the same file (e.g. spec.yaml).
  const fs::path tmp = output.parent_path() / (output.stem().string() + ".tmp." + std::to_string(::getpid()) +
                                               output.extension().string());
  try {
    write(tmp);
    if (durable) sync_file(tmp);
    std::error_code ec;
    fs::rename(tmp, output, ec);
    if (ec)
      throw RuntimeError(output.string() + ": cannot rename " + tmp.string() +
                         " into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void write_file_atomic(const fs::path& path, std::string_view contents, bool durable) {
  write_output_via_temporary(
      path, [&](const fs::path& tmp) { write_text_file(tmp, contents); }, durable);
}

namespace {

/// The pid in a temporary's name "<stem>.tmp.<pid>[<ext>][.partial]", or 0 when the name is not one.
pid_t temporary_owner(const std::string& name) {
  const size_t at = name.rfind(".tmp.");
  if (at == std::string::npos) return 0;
  size_t end = at + 5;
  pid_t pid = 0;
  while (end < name.size() && name[end] >= '0' && name[end] <= '9' && pid < 100000000)
    pid = pid * 10 + (name[end++] - '0');
  const bool ends_there = end == name.size() || name[end] == '.';
  return end > at + 5 && ends_there ? pid : 0;
}

}  // namespace

int remove_stale_temporaries(const fs::path& dir) {
  int removed = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const pid_t owner = temporary_owner(it->path().filename().string());
    // kill(pid, 0) fails with ESRCH only when no such process exists: a live writer keeps its file.
    if (owner <= 0 || owner == ::getpid() || ::kill(owner, 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    removed += fs::remove(it->path(), ignored) ? 1 : 0;
  }
  return removed;
}

}  // namespace crowdlab
