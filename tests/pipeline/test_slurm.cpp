// `crowdlab plan --emit slurm` checked by Slurm itself: when Debian's slurm-wlm and munge are installed
// (scripts/install-deps.sh --test), a private single-node cluster (scripts/slurm-single-node.sh) starts in
// the scratch folder, `sbatch --test-only` accepts the generated script, and real `sbatch --wait` runs its
// array tasks (one shard each), after which `run --collect` must find every condition exactly once.
// Without Slurm the test says so and skips (the plan test still checks the script with bash -n).
#include <catch2/catch.hpp>

#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_slurm {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

bool have(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1 || test -x /usr/sbin/" + tool).c_str()) == 0;
}

/// Runs `command` with SLURM_CONF set; returns its exit status.
int with_slurm(const fs::path& conf, const std::string& command) {
  const std::string full = "export SLURM_CONF=" + shell_quote(conf.string()) + "; " + command;
  const int status = std::system(full.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

struct Cluster {
  fs::path dir;
  bool up = false;
  explicit Cluster(fs::path d) : dir(std::move(d)) {
    fs::create_directories(dir);
    const std::string script = shell_quote((source_dir() / "scripts/slurm-single-node.sh").string());
    up = std::system((script + " start " + shell_quote(dir.string()) + " >" +
                      shell_quote((dir / "start.log").string()) + " 2>&1")
                         .c_str()) == 0;
  }
  ~Cluster() {
    const std::string script = shell_quote((source_dir() / "scripts/slurm-single-node.sh").string());
    [[maybe_unused]] const int rc = std::system((script + " stop " + shell_quote(dir.string())).c_str());
  }
  fs::path conf() const { return dir / "slurm.conf"; }
};

}  // namespace

TEST_CASE("plan --emit slurm: the script runs on a real single-node Slurm cluster", "[pipeline][slurm]") {
  if (!have("sbatch") || !have("slurmctld") || !have("slurmd") || !have("munged")) {
    WARN(
        "skipping: Slurm (slurm-wlm) or munge is not installed; scripts/install-deps.sh --test installs "
        "them");
    return;
  }
  const fs::path dir = scratch_dir("pipeline_slurm");
  const fs::path results = dir / "results";
  Cluster cluster(dir / "cluster");
  if (!cluster.up) {
    std::ifstream log(dir / "cluster" / "start.log");
    std::stringstream ss;
    ss << log.rdbuf();
    WARN("skipping: the single-node Slurm cluster did not start here:\n" << ss.str());
    return;
  }
  const std::string spec = (source_dir() / "tests/data/pipeline/tiny.yaml").string();
  REQUIRE(run_cli({"plan", spec, "--emit", "slurm", "--out", dir.string(), "--shards", "3", "--cpus", "1",
                   "--crowdlab", crowdlab_exe().string(), "--results", results.string()})
              .exit_code == 0);
  const std::string script = shell_quote((dir / "crowdlab.sbatch").string());
  CHECK(with_slurm(cluster.conf(), "sbatch --test-only " + script + " >/dev/null 2>&1") == 0);
  // --wait returns when every array task has finished, with a non-zero status if any failed.
  const int rc = with_slurm(cluster.conf(), "cd " + shell_quote(dir.string()) + " && sbatch --wait --quiet " +
                                                script + " >/dev/null 2>&1");
  INFO("array task logs are in " << dir.string());
  REQUIRE(rc == 0);
  for (int k = 1; k <= 3; ++k)
    CHECK(fs::exists(results / ("manifest.shard-" + std::to_string(k) + "-of-3.csv")));
  const CliResult collect = run_cli({"-q", "run", spec, "--out", results.string(), "--collect"});
  INFO(collect.err);
  REQUIRE(collect.exit_code == 0);
  CHECK(read_manifest((results / "manifest.csv").string()).entries.size() == 6);
}

}  // namespace test_slurm
