#pragma once
// Paths the tests need, fixed at configure time, plus access to ../shared test data (which a user's
// machine does not have: tests that need it call shared_data_or_skip()). The configured paths live in one
// small translation unit (test_paths.cpp), so the test sources compile to the same objects in every
// checkout and a compiler cache can share them between worktrees.
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace crowdlab::test {

std::filesystem::path source_dir();
std::filesystem::path binary_dir();
std::filesystem::path crowdlab_exe();

/// The small pipeline spec most `run` tests use (tests/data/pipeline/tiny.yaml).
inline std::string tiny_spec() {
  return (source_dir() / "tests/data/pipeline/tiny.yaml").string();
}
inline constexpr bool kSanitized = CROWDLAB_SANITIZED;

/// `../shared/data/<sub>` beside the checkout, or empty when absent (a message is printed).
inline std::filesystem::path shared_data(const std::string& sub) {
  const auto p = source_dir().parent_path() / "shared" / "data" / sub;
  if (!std::filesystem::exists(p)) WARN("skipping: shared test data not found at " << p.string());
  return std::filesystem::exists(p) ? p : std::filesystem::path{};
}

/// A short, stable name for the running test case (FNV-1a of its name, in hex).
inline std::string current_test_tag() {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : Catch::getResultCapture().getCurrentTestName()) h = (h ^ c) * 1099511628211ull;
  std::ostringstream tag;
  tag << std::hex << h;
  return tag.str();
}

/// A fresh, empty scratch directory under the build tree for one test case. ctest runs the test cases
/// of one executable as parallel processes, and two cases may ask for the same name (a helper shared by
/// a file's cases): each case gets its own folder under the name, so one case's remove_all never empties
/// a folder another case is writing (the CI failure of stop 40).
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto p = binary_dir() / "test-scratch" / name / current_test_tag();
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

/// The whole content of a file, byte for byte (empty when it cannot be opened).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace crowdlab::test
