// core/write_file.hpp's write_streamed_file: what the stream receives lands in the file byte for byte
// (small writes, single characters and writes larger than its 1 MiB block, mixed); a full disk throws
// naming the file and the OS's reason and removes the partial file; a writer that throws leaves no file.
#include <catch2/catch.hpp>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/write_file.hpp"
#include "tests/support/test_paths.hpp"
#include "tests/support/tmpfs_mount.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_write_streamed_file {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

/// About 3.5 MB written as a writer would: many small writes, single characters, and two large blocks.
std::string write_mixed(std::ostream& out) {
  std::string expected;
  for (int i = 0; i < 20000; ++i) {
    const std::string piece = std::to_string(i * 31) + ";";
    out << piece;
    expected += piece;
    if (i % 97 == 0) {
      out.put('\n');
      expected += '\n';
    }
    if (i == 5000 || i == 15000) {
      const std::string block(1536 * 1024 + i, static_cast<char>('a' + i % 26));
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
      expected += block;
    }
  }
  return expected;
}

}  // namespace

TEST_CASE(
    "write_streamed_file: the bytes written, a full disk named with no partial file, a throwing writer") {
  const fs::path dir = test::scratch_dir("write_streamed_file");
  std::string expected;
  write_streamed_file(dir / "mixed.bin", [&](std::ostream& out) { expected = write_mixed(out); });
  CHECK(expected.size() > 3'000'000);
  CHECK(test::slurp(dir / "mixed.bin") == expected);

  CHECK_THROWS_AS(write_streamed_file(dir / "thrown.bin",
                                      [](std::ostream& out) {
                                        out << std::string(3 << 20, 'x');
                                        throw std::runtime_error("the writer gave up");
                                      }),
                  std::runtime_error);
  CHECK_FALSE(fs::exists(dir / "thrown.bin"));

  const test::TmpfsMount disk(dir / "small_disk", "1m");
  if (!disk.mounted()) {
    WARN("full-disk half skipped: cannot mount a tmpfs here (needs root); CI runs as root");
    return;
  }
  const fs::path full = dir / "small_disk" / "too_big.bin";
  try {
    write_streamed_file(full, [](std::ostream& out) { write_mixed(out); });
    FAIL("a 3.5 MB file fitted on a 1 MB disk");
  } catch (const RuntimeError& e) {
    CHECK_THAT(e.what(), Catch::Contains(full.string()) && Catch::Contains("No space left on device"));
  }
  CHECK_FALSE(fs::exists(full));
}

}  // namespace test_write_streamed_file
