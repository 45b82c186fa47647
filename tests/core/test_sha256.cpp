// core/sha256.hpp: FIPS 180-4's known answers (the empty message, "abc", the 448-bit message, a million
// 'a'), a file hashed in several reads equals its bytes hashed at once, and an unreadable file is an
// InputError naming it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_sha256 {

using namespace crowdlab;

TEST_CASE("sha256: FIPS 180-4 known answers, files equal their bytes, unreadable files named") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sha256_hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");

  const std::filesystem::path dir = test::scratch_dir("sha256");
  std::string bytes;
  for (int i = 0; bytes.size() < 2'600'000; ++i) bytes += std::to_string(i * 7919) + ",";  // > 2 reads
  std::ofstream(dir / "big.bin", std::ios::binary) << bytes;
  CHECK(sha256_file_hex((dir / "big.bin").string()) == sha256_hex(bytes));
  std::ofstream(dir / "empty.bin", std::ios::binary).flush();
  CHECK(sha256_file_hex((dir / "empty.bin").string()) == sha256_hex(""));
  const std::string missing = (dir / "missing.bin").string();
  CHECK_THROWS_AS(sha256_file_hex(missing), InputError);
  CHECK_THROWS_WITH(sha256_file_hex(missing), Catch::Contains("missing.bin"));
}

}  // namespace test_sha256
