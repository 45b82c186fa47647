// `crowdlab run`, `plan` and `run --collect` driven as a user would, on a tiny spec.
#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <sstream>

#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_run_pipeline {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

std::map<std::string, std::string> hashes(const fs::path& manifest) {
  std::map<std::string, std::string> out;
  for (const auto& e : read_manifest(manifest.string()).entries) out[e.id] = e.sha256;
  return out;
}
using crowdlab::test::slurp;
}  // namespace

TEST_CASE("run makes every condition's crowd, metrics and clip, then reuses them") {
  const fs::path out = scratch_dir("pipeline_run");
  CliResult r = run_cli({"-q", "run", tiny_spec(), "--out", out.string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const StimulusManifest m = read_manifest((out / "manifest.csv").string());
  REQUIRE(m.entries.size() == 6);
  for (const auto& e : m.entries) {
    CHECK(fs::exists(out / "conditions" / e.id / "crowd.glb"));
    CHECK(fs::exists(out / "conditions" / e.id / "clip.mp4"));
    CHECK(fs::exists(out / e.file));
    CHECK(fs::exists(out / (e.file + ".prov.json")));
    CHECK(e.frames == 15);
    CHECK(e.width == 160);
    CHECK(e.sha256.size() == 64);
    CHECK(e.mean_overlap_l >= 0.0);
  }
  // Both methods of one density show the same crowd: the corrected one never overlaps more.
  std::map<std::string, std::map<std::string, double>> overlap;  // density -> method -> litres
  for (const auto& e : m.entries) overlap[e.factors.at("density")][e.factors.at("method")] = e.mean_overlap_l;
  for (const auto& [density, by_method] : overlap) {
    INFO("density " << density);
    CHECK(by_method.at("ours") <= by_method.at("baseline") + 1e-9);
  }
  // Every clip carries the correction-quality measures of its crowd against the input (issue 18): the
  // baseline against itself (no pops, no floating), ours against the baseline of the same crowd.
  std::map<std::string, std::map<std::string, ClipQuality>> quality;  // density -> method -> measures
  for (const auto& e : m.entries) {
    INFO(e.id);
    const ClipQuality& q = e.quality;
    CHECK(q.depth_p99_m >= 0.0);
    CHECK(q.depth_max_m >= q.depth_p99_m);
    CHECK(q.stance_foot_drift_max_m >= q.stance_foot_drift_p99_m);
    CHECK(q.stance_foot_drift_p99_m >= 0.0);
    CHECK(q.foot_pops >= 0);
    CHECK(q.foot_ground_penetration_max_m >= 0.0);
    CHECK(q.foot_float_p99_m >= 0.0);
    CHECK(q.free_limb_dev_max_deg >= q.free_limb_dev_p99_deg);  // issue 27
    CHECK(q.free_limb_dev_p99_deg >= 0.0);
    CHECK(q.joint_flips >= 0);
    CHECK(q.env_penetration_max_m >= q.env_penetration_p99_m);
    CHECK(q.env_penetration_p99_m >= 0.0);
    quality[e.factors.at("density")][e.factors.at("method")] = q;
  }
  for (const auto& [density, by_method] : quality) {
    INFO("density " << density);
    const ClipQuality& base = by_method.at("baseline");
    // The contact rule lets an input foot creep by up to 1 mm per frame, so the input's own drift is
    // small but not zero (docs/correction.md: 0.2-0.8 mm on gomez2024).
    CHECK(base.stance_foot_drift_max_m < 0.002);
    CHECK(base.foot_pops == 0);
    CHECK(base.foot_float_p99_m == 0.0);
    CHECK(base.joint_flips == 0);
    CHECK(base.free_limb_dev_max_deg < 1e-3);
    // The corrected crowd is measured against the baseline, not against itself: it moved somebody.
    const ClipQuality& ours = by_method.at("ours");
    CHECK(ours.depth_max_m <= base.depth_max_m + 1e-9);
  }
  const std::string metrics_json = slurp(out / "conditions" / m.entries.front().id / "metrics.json");
  CHECK_THAT(metrics_json, Catch::Contains("\"correction_quality\"") && Catch::Contains("foot_pop_frames"));
  // Second run: everything is up to date.
  r = run_cli({"-q", "run", tiny_spec(), "--out", out.string()});
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("0 stage outputs made"));
  CHECK(hashes(out / "manifest.csv") == hashes(out / "manifest.csv"));
}

TEST_CASE("shards are disjoint, collect merges them, and the result equals an unsharded run") {
  const fs::path whole = scratch_dir("pipeline_whole"), sharded = scratch_dir("pipeline_sharded");
  REQUIRE(run_cli({"-q", "run", tiny_spec(), "--out", whole.string()}).exit_code == 0);
  REQUIRE(run_cli({"-q", "run", tiny_spec(), "--out", sharded.string(), "--shard", "1/3"}).exit_code == 0);
  REQUIRE(run_cli({"-q", "run", tiny_spec(), "--out", sharded.string(), "--shard", "3/3"}).exit_code == 0);
  // Shard 2 is missing: collect must refuse and name what is missing.
  CliResult r = run_cli({"-q", "run", tiny_spec(), "--out", sharded.string(), "--collect"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("missing conditions"));
  REQUIRE(run_cli({"-q", "run", tiny_spec(), "--out", sharded.string(), "--shard", "2/3"}).exit_code == 0);
  r = run_cli({"-q", "run", tiny_spec(), "--out", sharded.string(), "--collect"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(fs::exists(sharded / "provenance.json"));
  // Same spec and seed: bit-identical clips whether sharded or not.
  CHECK(hashes(sharded / "manifest.csv") == hashes(whole / "manifest.csv"));
}

TEST_CASE("plan writes Slurm, GNU parallel and make job files") {
  const fs::path dir = scratch_dir("pipeline_plan");
  CliResult r = run_cli({"plan", tiny_spec(), "--emit", "slurm", "--out", dir.string(), "--shards", "2",
                         "--crowdlab", crowdlab_exe().string(), "--results", (dir / "res").string()});
  REQUIRE(r.exit_code == 0);
  const std::string sbatch = slurp(dir / "crowdlab.sbatch");
  CHECK_THAT(sbatch, Catch::Contains("#SBATCH --array=1-2") &&
                         Catch::Contains("--shard \"${SLURM_ARRAY_TASK_ID}/2\""));
  CHECK(std::system(("bash -n " + shell_quote((dir / "crowdlab.sbatch").string())).c_str()) == 0);

  REQUIRE(run_cli({"plan", tiny_spec(), "--emit", "parallel", "--out", dir.string(), "--shards", "2",
                   "--crowdlab", crowdlab_exe().string(), "--results", (dir / "res").string()})
              .exit_code == 0);
  const std::string jobs = slurp(dir / "crowdlab.parallel");
  CHECK(std::count(jobs.begin(), jobs.end(), '\n') == 2);
  if (std::system("command -v parallel >/dev/null 2>&1") == 0) {
    // Run the shards as separate local processes through GNU parallel, then collect.
    const std::string cmd = "parallel --will-cite -j 2 < " +
                            shell_quote((dir / "crowdlab.parallel").string()) + " >/dev/null 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    REQUIRE(run_cli({"-q", "run", tiny_spec(), "--out", (dir / "res").string(), "--collect"}).exit_code == 0);
    CHECK(read_manifest((dir / "res" / "manifest.csv").string()).entries.size() == 6);
  } else {
    WARN("skipping the GNU parallel run: `parallel` is not installed");
  }
  REQUIRE(
      run_cli({"plan", tiny_spec(), "--emit", "make", "--out", dir.string(), "--shards", "2"}).exit_code ==
      0);
  CHECK_THAT(slurp(dir / "Makefile"), Catch::Contains("shard-2:"));
  CHECK(run_cli({"plan", tiny_spec(), "--emit", "cron", "--out", dir.string()}).exit_code == 2);
}

TEST_CASE("bad run arguments exit with code 2") {
  const fs::path out = scratch_dir("pipeline_bad");
  CHECK(run_cli({"run", tiny_spec(), "--out", out.string(), "--shard", "3/2"}).exit_code == 2);
  CHECK(run_cli({"run", tiny_spec(), "--out", out.string(), "--shard", "x"}).exit_code == 2);
  CHECK(run_cli({"run", tiny_spec(), "--out", out.string(), "--condition", "nope"}).exit_code == 2);
  CHECK(run_cli({"run", "/no/such/spec.yaml", "--out", out.string()}).exit_code == 2);
}

}  // namespace test_run_pipeline
