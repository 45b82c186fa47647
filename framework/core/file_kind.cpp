#include "framework/core/file_kind.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

std::string kind_of_mode(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string describe_file_kind(const std::filesystem::path& path, bool follow) {
  struct stat st {};
  const int rc = follow ? ::stat(path.c_str(), &st) : ::lstat(path.c_str(), &st);
  if (rc != 0)
    return errno == ENOENT ? "missing" : std::string("not accessible (") + std::strerror(errno) + ")";
  return kind_of_mode(st.st_mode);
}

void require_regular_input(const std::filesystem::path& path, const std::string& what) {
  const std::string kind = describe_file_kind(path, true);
  if (kind.empty()) return;
  if (kind == "missing") throw InputError(path.string() + ": no such file");
  throw InputError(path.string() + ": cannot read " + what + ": it is " + kind +
                   " (only regular files are read)");
}

void require_writable_destination(const std::filesystem::path& path) {
  const std::string kind = describe_file_kind(path, false);
  if (kind.empty() || kind == "missing") return;
  throw InputError(path.string() + ": refusing to write: it is " + kind +
                   "; outputs replace only regular files (give the path of a regular file or of none)");
}

std::string read_regular_file(const std::filesystem::path& path, const std::string& what,
                              std::uintmax_t max_bytes, const std::string& raise_with) {
  require_regular_input(path, what);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(path.string() + ": cannot read " + what + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {  // replaced between the checks
    ::close(fd);
    throw InputError(path.string() + ": cannot read " + what + ": not a regular file");
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes) {
    ::close(fd);
    throw InputError(path.string() + ": " + what + " of " + std::to_string(size) +
                     " bytes is larger than the limit of " + std::to_string(max_bytes) + " bytes" +
                     (raise_with.empty() ? std::string() : "; raise it with " + raise_with));
  }
  std::string bytes(static_cast<size_t>(size), '\0');
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // shrank while reading: what was there
    got += static_cast<size_t>(n);
  }
  ::close(fd);
  bytes.resize(got);
  return bytes;
}

}  // namespace crowdlab
