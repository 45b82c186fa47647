// Resumed and incremental runs reproduce an uninterrupted one (issue 21): a `crowdlab run` killed with
// SIGKILL at several points (during the animation, the correction, the clips) and resumed, and a
// finished run from which one crowd file was deleted and re-run, end with every file byte-identical to
// an uninterrupted run's (provenance sidecars compared without their creation time). Before the fix a
// resumed run corrected `ours` from the float32 baseline.glb read back from disk while an uninterrupted
// run corrected it from the in-memory baseline, and a recomputed crowd file left its metrics and clip
// stale.
#include <signal.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_run_resume {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// Every file of a run folder by relative path, with what must be equal between two runs: the bytes,
/// or for a provenance sidecar its JSON without `created_utc`. The lock file (it holds a pid) is left out.
std::map<std::string, std::string> run_contents(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file() || e.path().filename() == ".crowdlab.lock") continue;
    std::string bytes = slurp(e.path());
    if (e.path().string().ends_with(".prov.json")) {
      nlohmann::json j = nlohmann::json::parse(bytes);
      j.erase("created_utc");
      bytes = j.dump();
    }
    files[fs::relative(e.path(), root).generic_string()] = std::move(bytes);
  }
  return files;
}

/// Checks that `b` holds exactly the files of `a`, each equal; names the first files that differ.
void check_same_outputs(const fs::path& a, const fs::path& b) {
  const auto fa = run_contents(a), fb = run_contents(b);
  std::vector<std::string> differ;
  for (const auto& [name, bytes] : fa)
    if (!fb.count(name) || fb.at(name) != bytes) differ.push_back(name);
  for (const auto& [name, bytes] : fb)
    if (!fa.count(name)) differ.push_back(name + " (extra)");
  std::string list;
  for (const std::string& d : differ) list += "\n  " + d;
  INFO("files that differ from the uninterrupted run:" << list);
  CHECK(fa.size() > 20);
  CHECK(differ.empty());
}

/// Starts `crowdlab run SPEC --out DIR`, waits until `kill_when` exists and kills the run with SIGKILL
/// at once. Returns true when it killed the run, false when the run ended first (the point passed).
bool run_killed_at(const fs::path& out, const fs::path& kill_when) {
  const pid_t pid = spawn_cli({"-q", "run", tiny_spec(), "--out", out.string()});
  REQUIRE(pid > 0);
  int status = 0;
  for (;;) {
    if (fs::exists(kill_when)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return WIFSIGNALED(status);
    }
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void run_to_end(const fs::path& out) {
  const CliResult r = run_cli({"-q", "run", tiny_spec(), "--out", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
}

}  // namespace

TEST_CASE("run: killed at several stages and resumed, the outputs equal an uninterrupted run's",
          "[pipeline][integrity]") {
  const fs::path whole = scratch_dir("resume_whole"), resumed = scratch_dir("resume_killed");
  run_to_end(whole);
  // In run order: the first group's crowd is animated (the kill lands in its metrics or clip, before its
  // correction); the second group's crowd is corrected; the last group's first clip is rendered.
  const std::vector<fs::path> kill_points{
      resumed / "crowds/density-2.5_rep-1/baseline.glb",
      resumed / "crowds/density-3.0_rep-1/ours.glb",
      resumed / "conditions/density-3.5_viewpoint-V4_method-baseline_rep-1/clip.mp4",
  };
  int kills = 0;
  for (const fs::path& point : kill_points) {
    REQUIRE_FALSE(fs::exists(point));
    kills += run_killed_at(resumed, point) ? 1 : 0;
  }
  CHECK(kills >= 2);  // a point the run passed before the next poll is no kill
  run_to_end(resumed);
  check_same_outputs(whole, resumed);
}

TEST_CASE("run: a deleted crowd file is recomputed and everything downstream equals an uninterrupted run",
          "[pipeline][integrity]") {
  const fs::path whole = scratch_dir("recompute_whole"), partial = scratch_dir("recompute_partial");
  run_to_end(whole);
  run_to_end(partial);
  check_same_outputs(whole, partial);
  for (const char* file : {"crowds/density-3.0_rep-1/ours.glb", "crowds/density-2.5_rep-1/baseline.glb",
                           "crowds/density-3.5_rep-1/trajectories.csv"}) {
    INFO(file);
    fs::remove(partial / file);
    run_to_end(partial);
    check_same_outputs(whole, partial);
  }
}

}  // namespace test_run_resume
