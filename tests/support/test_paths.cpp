// The configured paths of tests/support/test_paths.hpp (CMake passes them to this file alone).
// It does not include the header, which needs CROWDLAB_SANITIZED (only the test executables get it).
#include <filesystem>

namespace crowdlab::test {

std::filesystem::path source_dir() {
  return CROWDLAB_SOURCE_DIR;
}
std::filesystem::path binary_dir() {
  return CROWDLAB_BINARY_DIR;
}
std::filesystem::path crowdlab_exe() {
  return CROWDLAB_EXE;
}

}  // namespace crowdlab::test
