// Integrity of `crowdlab run` outputs (issue 21): a truncated clip beside its old, still-matching
// sidecar is redone, not reported up to date; outputs appear only complete; and two runs on one --out
// exclude each other with a message naming the other process.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <map>

#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_run_integrity {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// Holds flock(2) `operation` on `path` for its lifetime and writes our pid into it, the way a running
/// `crowdlab run` does.
struct HeldLock {
  int fd;
  HeldLock(const fs::path& path, int operation) : fd(::open(path.c_str(), O_RDWR | O_CREAT, 0644)) {
    REQUIRE(fd >= 0);
    REQUIRE(::flock(fd, operation | LOCK_NB) == 0);
    const std::string pid = std::to_string(::getpid()) + "\n";
    REQUIRE(::pwrite(fd, pid.data(), pid.size(), 0) == static_cast<ssize_t>(pid.size()));
  }
  ~HeldLock() { ::close(fd); }
};

}  // namespace

TEST_CASE("run: a truncated clip beside its old sidecar is re-rendered, and no temporary is left",
          "[pipeline][integrity]") {
  const fs::path out = scratch_dir("pipeline_integrity");
  CliResult r = run_cli({"-q", "run", tiny_spec(), "--out", out.string(), "--condition",
                         "density-2.5_viewpoint-V4_method-baseline_rep-1"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const fs::path clip = out / "conditions/density-2.5_viewpoint-V4_method-baseline_rep-1/clip.mp4";
  REQUIRE(fs::exists(clip));
  const auto full_size = fs::file_size(clip);
  const std::string whole_hash = sha256_file_hex(clip.string());
  // What a `run --force` killed mid-encode used to leave: half a clip under the final name, with the
  // previous run's sidecar still claiming it.
  fs::resize_file(clip, full_size / 2);
  r = run_cli({"-q", "run", tiny_spec(), "--out", out.string(), "--condition",
               "density-2.5_viewpoint-V4_method-baseline_rep-1"});
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("1 stage outputs made"));
  // The same clip again, vouched for by its sidecar and the manifest (a resumed run renders from the
  // crowd file on disk, and so does a fresh one: issue 21).
  const std::string hash = sha256_file_hex(clip.string());
  CHECK(hash == whole_hash);
  const StimulusManifest m = read_manifest((out / "manifest.csv").string());
  REQUIRE(m.entries.size() == 1);
  CHECK(m.entries[0].sha256 == hash);
  CHECK_THAT(slurp(clip.string() + ".prov.json"), Catch::Contains(hash));
  for (const auto& entry : fs::recursive_directory_iterator(out))
    CHECK(entry.path().filename().string().find(".tmp.") == std::string::npos);
  // An altered crowd file is redone as well; the clip made from it stays up to date.
  const fs::path baseline = out / "crowds/density-2.5_rep-1/baseline.glb";
  REQUIRE(fs::exists(baseline));
  fs::resize_file(baseline, fs::file_size(baseline) - 4);
  r = run_cli({"-q", "run", tiny_spec(), "--out", out.string(), "--condition",
               "density-2.5_viewpoint-V4_method-baseline_rep-1"});
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("1 stage outputs made"));
  CHECK(sha256_file_hex(clip.string()) == hash);
  // Nothing changed: nothing is redone.
  r = run_cli({"-q", "run", tiny_spec(), "--out", out.string(), "--condition",
               "density-2.5_viewpoint-V4_method-baseline_rep-1"});
  CHECK_THAT(r.out, Catch::Contains("0 stage outputs made"));
}

TEST_CASE("run: a second run on the same --out exits 2 naming the other process", "[pipeline][integrity]") {
  const fs::path out = scratch_dir("pipeline_lock");
  {
    const HeldLock other(out / ".crowdlab.lock", LOCK_EX);
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{}, std::vector<std::string>{"--shard", "1/2"},
          std::vector<std::string>{"--collect"}}) {
      std::vector<std::string> args{"run", tiny_spec(), "--out", out.string()};
      args.insert(args.end(), extra.begin(), extra.end());
      const CliResult r = run_cli(args);
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.err, Catch::Contains(out.string()) &&
                            Catch::Contains("in use by another crowdlab process") &&
                            Catch::Contains("pid " + std::to_string(::getpid())));
    }
    CHECK_FALSE(fs::exists(out / "manifest.csv"));
  }
  {
    // Shards of one array share the folder, but one shard never runs twice at once.
    const HeldLock folder(out / ".crowdlab.lock", LOCK_SH);
    const HeldLock shard(out / ".crowdlab.shard-1-of-2.lock", LOCK_EX);
    CliResult r = run_cli({"run", tiny_spec(), "--out", out.string(), "--shard", "1/2"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("shard 1/2 is in use"));
    r = run_cli({"run", tiny_spec(), "--out", out.string()});
    CHECK(r.exit_code == 2);
    r = run_cli({"-q", "run", tiny_spec(), "--out", out.string(), "--shard", "2/2", "--condition",
                 "density-3.0_viewpoint-V4_method-baseline_rep-1"});
    INFO(r.err);
    CHECK(r.exit_code == 0);
  }
}

}  // namespace test_run_integrity
