// `crowdlab plan` with hostile names and paths (issue 21): nothing in a spec name, a spec path,
// --results or --crowdlab may run as code in the generated Slurm, GNU parallel or make script. Each
// script is executed for real in a scratch folder with a fake `crowdlab` that only records its arguments,
// and the test checks that no planted file appears and that the arguments arrive intact.
#include <catch2/catch.hpp>
#include <fstream>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_plan_injection {

using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// A copy of the tiny spec whose `name` is `name` (a YAML double-quoted scalar), at `path`.
void write_spec(const fs::path& path, const std::string& yaml_name) {
  std::string text = slurp(source_dir() / "tests/data/pipeline/tiny.yaml");
  const std::string from = "name: tiny\n";
  text.replace(text.find(from), from.size(), "name: " + yaml_name + "\n");
  std::ofstream(path) << text;
}

/// A stand-in for the crowdlab binary: appends its arguments, one per line, to args.txt beside it.
fs::path write_fake_crowdlab(const fs::path& dir) {
  const fs::path exe = dir / "fake crowdlab $HOME";
  std::ofstream(exe)
      << "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done >> \"$(dirname \"$0\")/args.txt\"\n";
  fs::permissions(exe, fs::perms::owner_all);
  return exe;
}

int sh(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

}  // namespace

TEST_CASE("plan: a spec name with a newline or shell code cannot inject into the Slurm script",
          "[pipeline][plan]") {
  const fs::path dir = scratch_dir("plan_injection_slurm");
  const fs::path spec = dir / "spec.yaml";
  // Even when the loader accepts the name (no control characters), quotes, `$()` and spaces stay inert.
  write_spec(spec, "\"demo $(touch PWN1) `touch PWN2` ; touch PWN3 'x\"");
  const fs::path exe = write_fake_crowdlab(dir);
  CliResult r = run_cli({"plan", spec.string(), "--emit", "slurm", "--out", dir.string(), "--shards", "2",
                         "--crowdlab", exe.string(), "--results", (dir / "res $(touch PWN4)").string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string sbatch = slurp(dir / "crowdlab.sbatch");
  // Slurm reads #SBATCH lines itself: the job name is reduced to characters Slurm and shells take as is.
  CHECK_THAT(sbatch, Catch::Contains("#SBATCH --job-name=crowdlab-demo_touch_PWN1"));
  // Run the array task body the way Slurm would, for task 1.
  REQUIRE(sh("cd " + shell_quote(dir.string()) + " && SLURM_ARRAY_TASK_ID=1 bash crowdlab.sbatch") == 0);
  for (const char* planted : {"PWN1", "PWN2", "PWN3", "PWN4"}) CHECK_FALSE(fs::exists(dir / planted));
  const std::string args = slurp(dir / "args.txt");
  CHECK_THAT(args, Catch::Contains((dir / "res $(touch PWN4)").string() + "\n--shard\n1/2\n"));

  // A newline in the name is refused at load (it would end the comment and the directive).
  write_spec(spec, "\"demo\\ntouch PWN5\"");
  r = run_cli({"plan", spec.string(), "--emit", "slurm", "--out", dir.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("spec.yaml:") && Catch::Contains("name") &&
                        Catch::Contains("control character"));
  // ANSI escape codes too: they would rewrite the terminal of whoever prints the name.
  write_spec(spec, "\"demo\\e[31mred\"");
  r = run_cli({"validate", spec.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("control character"));
}

TEST_CASE("plan: '$' and $(shell ...) in paths are not expanded by make, even under make -n",
          "[pipeline][plan]") {
  if (sh("command -v make >/dev/null 2>&1") != 0) {
    WARN("skipping: make is not installed");
    return;
  }
  const fs::path dir = scratch_dir("plan_injection_make");
  const fs::path sub = dir / "specs $(shell touch PWN1) $HOME $$x 'q' #c";
  fs::create_directories(sub);
  const fs::path spec = sub / "spec.yaml";
  write_spec(spec, "tiny");
  const fs::path exe = write_fake_crowdlab(dir);
  const fs::path results = dir / "res $(shell touch PWN2) %";
  CliResult r = run_cli({"plan", spec.string(), "--emit", "make", "--out", dir.string(), "--shards", "2",
                         "--crowdlab", exe.string(), "--results", results.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string make = "cd " + shell_quote(dir.string()) + " && make -s -f Makefile";
  REQUIRE(sh(make + " -n >/dev/null") == 0);
  CHECK_FALSE(fs::exists(dir / "PWN1"));
  CHECK_FALSE(fs::exists(dir / "PWN2"));
  REQUIRE(sh(make + " >/dev/null") == 0);
  CHECK_FALSE(fs::exists(dir / "PWN1"));
  CHECK_FALSE(fs::exists(dir / "PWN2"));
  // Every call got the paths byte for byte: two shards and the collect.
  const std::string args = slurp(dir / "args.txt");
  CHECK_THAT(args, Catch::Contains(fs::absolute(spec).string() + "\n--out\n" + results.string() +
                                   "\n--shard\n2/2\n"));
  CHECK_THAT(args, Catch::Contains(results.string() + "\n--collect\n"));
}

TEST_CASE("plan: GNU parallel lines keep hostile paths inert", "[pipeline][plan]") {
  const fs::path dir = scratch_dir("plan_injection_parallel");
  const fs::path spec = dir / "spec.yaml";
  write_spec(spec, "tiny");
  const fs::path exe = write_fake_crowdlab(dir);
  const fs::path results = dir / "r $(touch PWN1) `touch PWN2` ;touch PWN3";
  REQUIRE(run_cli({"plan", spec.string(), "--emit", "parallel", "--out", dir.string(), "--shards", "2",
                   "--crowdlab", exe.string(), "--results", results.string()})
              .exit_code == 0);
  // GNU parallel hands each line to the shell: run the lines the same way.
  REQUIRE(sh("cd " + shell_quote(dir.string()) + " && sh crowdlab.parallel") == 0);
  for (const char* planted : {"PWN1", "PWN2", "PWN3"}) CHECK_FALSE(fs::exists(dir / planted));
  CHECK_THAT(slurp(dir / "args.txt"), Catch::Contains(results.string() + "\n--shard\n1/2\n"));
}

TEST_CASE("plan: a newline in a path given to a job script is refused", "[pipeline][plan]") {
  const fs::path dir = scratch_dir("plan_injection_newline");
  const fs::path spec = dir / "spec.yaml";
  write_spec(spec, "tiny");
  for (const std::string emit : {"slurm", "parallel", "make"}) {
    INFO(emit);
    CliResult r = run_cli({"plan", spec.string(), "--emit", emit, "--out", dir.string(), "--results",
                           (dir / "res\ntouch PWN").string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--results") && Catch::Contains("control character"));
    r = run_cli({"plan", spec.string(), "--emit", emit, "--out", dir.string(), "--crowdlab", "crowdlab\rx"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("--crowdlab"));
  }
  CHECK_FALSE(fs::exists(dir / "PWN"));
}

}  // namespace test_plan_injection
