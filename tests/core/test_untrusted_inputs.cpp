// Issue 32: special files are refused as inputs and outputs before they are opened, writers never follow
// links or replace what is not a regular file, untrusted JSON is refused past its limits with the file
// and byte, and counts that multiply are refused from the counts, before the work.
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/write_file.hpp"
#include "framework/io/untrusted_json.hpp"
#include "framework/pipeline/provenance.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_untrusted_inputs {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

/// run_cli under `timeout`: a FIFO blocked the old code for ever; a hang fails the test instead.
test::CliResult run_cli_bounded(const std::vector<std::string>& args) {
  return test::run_cli(args, 60);
}

/// A FIFO in `dir` (nobody writes it: opening it to read blocks).
fs::path make_fifo(const fs::path& dir, const std::string& name) {
  const fs::path p = dir / name;
  REQUIRE(::mkfifo(p.c_str(), 0600) == 0);
  return p;
}

}  // namespace

TEST_CASE("the atomic writer refuses links, devices, FIFOs and folders as destinations", "[core]") {
  const auto dir = test::scratch_dir("untrusted-write");
  std::ofstream(dir / "target.csv") << "keep";
  fs::create_symlink(dir / "target.csv", dir / "link.csv");
  fs::create_symlink(dir / "absent.csv", dir / "dangling.csv");
  const fs::path fifo = make_fifo(dir, "fifo.csv");
  fs::create_directories(dir / "folder.csv");
  for (const fs::path& p : {dir / "link.csv", dir / "dangling.csv", fifo, dir / "folder.csv"}) {
    CAPTURE(p);
    CHECK_THROWS_WITH(write_file_atomic(p, "new"),
                      Catch::Contains(p.string()) && Catch::Contains("refusing to write"));
    CHECK_THROWS_AS(write_text_file(p, "new"), InputError);
  }
  CHECK(fs::is_symlink(dir / "link.csv"));
  CHECK(test::slurp(dir / "target.csv") == "keep");
  CHECK_FALSE(fs::exists(dir / "absent.csv"));
  CHECK(fs::is_fifo(fifo));
  if (::geteuid() == 0) {  // a device node of our own (the null device's numbers) in the scratch folder
    const fs::path dev = dir / "full.csv";
    REQUIRE(::mknod(dev.c_str(), S_IFCHR | 0600, makedev(1, 3)) == 0);
    CHECK_THROWS_WITH(write_file_atomic(dev, "new"), Catch::Contains("character device"));
    CHECK(fs::is_character_file(dev));
  }
  // A regular file is still replaced atomically.
  write_file_atomic(dir / "target.csv", "new");
  CHECK(test::slurp(dir / "target.csv") == "new");
}

TEST_CASE("read_regular_file refuses FIFOs, devices and files over the limit before reading", "[core]") {
  const auto dir = test::scratch_dir("untrusted-read");
  const fs::path fifo = make_fifo(dir, "spec.yaml");
  CHECK_THROWS_WITH(read_regular_file(fifo, "the spec", 100, ""),
                    Catch::Contains(fifo.string()) && Catch::Contains("FIFO"));
  CHECK_THROWS_WITH(read_regular_file("/dev/zero", "the spec", 100, ""), Catch::Contains("character device"));
  std::ofstream(dir / "big.txt") << std::string(101, 'x');
  CHECK_THROWS_WITH(
      read_regular_file(dir / "big.txt", "table", 100, "--max-x"),
      Catch::Contains("101 bytes") && Catch::Contains("limit of 100 bytes") && Catch::Contains("--max-x"));
  CHECK(read_regular_file(dir / "big.txt", "table", 101, "").size() == 101);
}

TEST_CASE("untrusted JSON: depth, size and syntax refused with the file and the byte", "[core]") {
  JsonLimits limits;
  limits.max_depth = 8;
  limits.max_bytes = 1000;
  CHECK(parse_untrusted_json("[[[[[[[[1]]]]]]]]", "f.json", limits).is_array());
  CHECK_THROWS_WITH(parse_untrusted_json("{\"a\": [[[[[[[[1]]]]]]]]}", "f.json", limits, 100),
                    Catch::Contains("f.json") && Catch::Contains("more than 8 levels deep at byte 113"));
  CHECK_THROWS_WITH(parse_untrusted_json("[" + std::string(2000, ' ') + "]", "f.json", limits),
                    Catch::Contains("larger than the limit of 1000 bytes"));
  CHECK_THROWS_WITH(parse_untrusted_json("{\"a\": tru}", "f.json", limits, 0, 7),
                    Catch::StartsWith("f.json:7: not valid JSON at byte"));
  // 1,000,000 levels (a stack overflow in the parse before): refused by the scan.
  const std::string deep(1000000, '[');
  CHECK_THROWS_AS(parse_untrusted_json(deep, "deep.json", JsonLimits{}), InputError);
}

TEST_CASE("cli: outputs that are links or devices are refused with exit 2, nothing replaced", "[core][cli]") {
  const auto dir = test::scratch_dir("untrusted-cli-out");
  const std::string spec = (test::source_dir() / "experiments" / "demo.yaml").string();
  const auto list = test::run_cli({"crowd", spec, "--list"});
  REQUIRE(list.exit_code == 0);
  const std::string first = list.out.substr(0, list.out.find('\n'));
  std::ofstream(dir / "elsewhere.csv") << "keep";
  fs::create_symlink(dir / "elsewhere.csv", dir / "t.csv");
  auto r = test::run_cli({"crowd", spec, "--condition", first, "--csv", (dir / "t.csv").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains((dir / "t.csv").string()) && Catch::Contains("symbolic link"));
  CHECK(fs::is_symlink(dir / "t.csv"));
  CHECK(test::slurp(dir / "elsewhere.csv") == "keep");
  if (::geteuid() == 0) {  // issue 32: `--csv /dev/full` as root replaced the device node
    const fs::path dev = dir / "full";
    REQUIRE(::mknod(dev.c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0);
    r = test::run_cli({"crowd", spec, "--condition", first, "--csv", dev.string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("character device"));
    CHECK(fs::is_character_file(dev));
  }
}

TEST_CASE("cli: FIFOs and devices are refused as inputs without blocking, exit 2", "[core][cli]") {
  const auto dir = test::scratch_dir("untrusted-cli-in");
  const fs::path fifo = make_fifo(dir, "spec.yaml");
  auto r = run_cli_bounded({"validate", fifo.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(fifo.string()) && Catch::Contains("FIFO"));
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    r = run_cli_bounded({"validate", device});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains(device) && Catch::Contains("character device"));
  }
  r = run_cli_bounded(
      {"analyze", "anova", "--csv", "/dev/zero", "--dv", "rt", "--subject", "id", "--within", "a"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("/dev/zero") && Catch::Contains("character device"));
}

TEST_CASE("cli: huge counts are refused from the count, before the work, exit 2", "[core][cli]") {
  const auto dir = test::scratch_dir("untrusted-cli-counts");
  auto r = test::run_cli({"plan", test::tiny_spec(), "--emit", "parallel", "--out", (dir / "plan").string(),
                          "--shards", "2147483647"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--shards") && Catch::Contains("6 conditions"));
  r = test::run_cli({"render", "--synthetic", "100000000", "--out", (dir / "x.mp4").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--synthetic") && Catch::Contains("10000"));
  r = test::run_cli({"render", "--synthetic", "-5", "--out", (dir / "x.mp4").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--synthetic"));
  r = test::run_cli({"bench", "correct", "--characters", "1000000", "--steps", "1"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--characters") && Catch::Contains("limit of 10000"));
  // Issue 33: 100 characters x a million steps passed the character limit and ended in a raw bad_alloc
  // (the fixture keeps every pose): the one crowd estimate counts character-frames too.
  r = test::run_cli({"bench", "correct", "--characters", "100", "--steps", "1000000"}, 60);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--characters 100") && Catch::Contains("100001000 character-frames") &&
                        Catch::Contains("lower --steps"));
}

TEST_CASE("a provenance sidecar nested deep or a FIFO is not up to date, never a crash or a hang", "[core]") {
  const auto dir = test::scratch_dir("untrusted-provenance");
  const fs::path out = dir / "out.csv";
  std::ofstream(out) << "x";
  std::ofstream(dir / "out.csv.prov.json") << "{\"input_hash\": " << std::string(400000, '[');
  CHECK_FALSE(output_up_to_date(out, "h"));
  CHECK_THROWS_WITH(read_provenance_record(dir / "out.csv.prov.json"),
                    Catch::Contains("out.csv.prov.json:1: JSON nests") && Catch::Contains("at byte 78"));
  fs::remove(dir / "out.csv.prov.json");
  make_fifo(dir, "out.csv.prov.json");
  CHECK_FALSE(output_up_to_date(out, "h"));
  CHECK(recorded_hash(out).empty());
}

TEST_CASE("a provenance sidecar with a number where a hash belongs is not up to date (issue 33)", "[core]") {
  // json's value() threw "[json.exception.type_error.302] type must be string, but is number" out of
  // `crowdlab run` (exit 1, no file named) before.
  const auto dir = test::scratch_dir("untrusted-provenance-types");
  const fs::path out = dir / "out.csv";
  std::ofstream(out) << "x";
  for (const char* record :
       {R"({"input_hash": 5, "output_sha256": "x"})", R"({"input_hash": "h", "output_sha256": [1]})"}) {
    INFO(record);
    std::ofstream(dir / "out.csv.prov.json", std::ios::trunc) << record;
    CHECK_FALSE(output_up_to_date(out, "h"));
  }
  std::ofstream(dir / "out.csv.prov.json", std::ios::trunc) << R"({"input_hash": 5})";
  CHECK(recorded_hash(out).empty());
}

TEST_CASE("cli: a misspelt command is named, not 'A subcommand is required' (issue 33)", "[core][cli]") {
  const auto r = test::run_cli({"nosuchcommand"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("unknown command 'nosuchcommand'"));
}

}  // namespace test_untrusted_inputs
