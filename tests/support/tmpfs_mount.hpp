#pragma once
// A small tmpfs mounted on a folder for a test's lifetime: a real "No space left on device" for the
// writers' full-disk paths (issue 21). Mounting needs root (CI runs as root); mounted() is false when
// it is not allowed, and the test then skips with a warning.
#include <sys/mount.h>

#include <filesystem>
#include <string>
#include <utility>

namespace crowdlab::test {

class TmpfsMount {
 public:
  TmpfsMount(std::filesystem::path dir, const std::string& size) : dir_(std::move(dir)) {
    std::filesystem::create_directories(dir_);
    mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
  }
  ~TmpfsMount() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  TmpfsMount(const TmpfsMount&) = delete;
  TmpfsMount& operator=(const TmpfsMount&) = delete;
  bool mounted() const { return mounted_; }

 private:
  std::filesystem::path dir_;
  bool mounted_ = false;
};

}  // namespace crowdlab::test
