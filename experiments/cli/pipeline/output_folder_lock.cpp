#include "experiments/cli/pipeline/output_folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;
namespace {

/// The pid the current holder wrote into `path` ("unknown" when it is empty or unreadable).
std::string holder_pid(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string pid(buf, n > 0 ? static_cast<size_t>(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

/// Opens `path` and takes `operation` (LOCK_EX or LOCK_SH) without waiting; on success records our pid.
int lock_file(const fs::path& path, int operation, const std::string& what) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw RuntimeError(path.string() + ": cannot open the lock file: " + std::strerror(errno));
  if (::flock(fd, operation | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = holder_pid(fd);
    ::close(fd);
    if (error == EWOULDBLOCK)
      throw InputError(SourceLocation{path.parent_path().string(), 0, 0, "--out"},
                       what + " is in use by another crowdlab process (pid " + pid +
                           "); wait for it to finish or choose another --out");
    throw RuntimeError(path.string() + ": cannot lock: " + std::strerror(error));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  // The pid only serves the message of a refused run: the lock holds even if it cannot be written.
  [[maybe_unused]] const bool recorded =
      ::ftruncate(fd, 0) == 0 && ::pwrite(fd, pid.data(), pid.size(), 0) == static_cast<ssize_t>(pid.size());
  return fd;
}

}  // namespace

OutputFolderLock::OutputFolderLock(const fs::path& dir, int shard_index, int shard_count) {
  fs::create_directories(dir);
  const bool sharded = shard_count > 1;
  folder_fd_ = lock_file(dir / ".crowdlab.lock", sharded ? LOCK_SH : LOCK_EX, "the output folder");
  if (!sharded) return;
  try {
    shard_fd_ =
        lock_file(dir / (".crowdlab.shard-" + std::to_string(shard_index) + "-of-" +
                         std::to_string(shard_count) + ".lock"),
                  LOCK_EX, "shard " + std::to_string(shard_index) + "/" + std::to_string(shard_count));
  } catch (...) {
    ::close(folder_fd_);
    throw;
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (shard_fd_ >= 0) ::close(shard_fd_);
  if (folder_fd_ >= 0) ::close(folder_fd_);
}

}  // namespace crowdlab::cli
