// Every command that writes an output folder excludes a second process on the same folder (issue 21:
// `run` took a flock on DIR/.crowdlab.lock, `demo` and `reproduce` took none). The second invocation
// exits 2 with the message `run` gives, naming the folder and the pid of the process that holds it.
#include <signal.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <thread>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_output_locks {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// Waits until the process `pid` holds the lock of `dir` (it writes its pid into the lock file once it
/// has the lock); false when it ended first or 60 s passed.
bool holds_lock(pid_t pid, const fs::path& dir) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(dir / ".crowdlab.lock");
    std::string holder;
    if (in >> holder && holder == std::to_string(pid)) return true;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

void stop(pid_t pid) {
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

void check_refused(const CliResult& r, const fs::path& dir, pid_t holder) {
  INFO(r.out << r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(dir.string()) && Catch::Contains("in use by another crowdlab process") &&
                        Catch::Contains("pid " + std::to_string(holder)));
}

}  // namespace

TEST_CASE("demo and reproduce: a second invocation on the same folder exits 2 naming the first",
          "[pipeline][integrity]") {
  // Two real invocations at once: the first holds the folder while it works, the second is refused.
  const fs::path demo = scratch_dir("lock_demo");
  const pid_t first = spawn_cli({"-q", "demo", "--out", demo.string()});
  REQUIRE(first > 0);
  REQUIRE(holds_lock(first, demo));
  check_refused(run_cli({"-q", "demo", "--out", demo.string()}), demo, first);
  // The demo's stimuli folder is a `run --out` of its own: held as well.
  check_refused(run_cli({"-q", "run", tiny_spec(), "--out", (demo / "stimuli").string()}), demo / "stimuli",
                first);
  stop(first);

  const fs::path paper = scratch_dir("lock_reproduce");
  const pid_t reproducing = spawn_cli({"-q", "reproduce", "hoyet2016", "--quick", "--out", paper.string()});
  REQUIRE(reproducing > 0);
  REQUIRE(holds_lock(reproducing, paper));
  check_refused(run_cli({"-q", "reproduce", "hoyet2016", "--quick", "--out", paper.string()}), paper,
                reproducing);
  check_refused(run_cli({"-q", "reproduce", "gomez2024", "--quick", "--out", paper.string()}), paper,
                reproducing);
  stop(reproducing);
}

TEST_CASE("every other command that writes an output folder is refused while another holds it",
          "[pipeline][integrity]") {
  const fs::path dir = scratch_dir("lock_other_commands");
  // A long-running holder of the folder: a demo run into it.
  const pid_t holder = spawn_cli({"-q", "demo", "--out", dir.string()});
  REQUIRE(holder > 0);
  REQUIRE(holds_lock(holder, dir));
  const std::string spec = tiny_spec(), out = dir.string();
  const std::string demo_spec = (source_dir() / "experiments/demo.yaml").string();
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"run", spec, "--out", out},
           {"experiment", "damping", "--out", out},
           {"experiment", "overlap-vs-density", "--out", out},
           {"experiment", "manifold-compare", "--out", out},
           {"analyze", "report", out, "--spec", demo_spec, "--out", out},
           {"simulate-study", demo_spec, "--stimuli", out, "--out", out},
           {"plan", spec, "--emit", "make", "--out", out},
       }) {
    INFO(args[0] << " " << args[1]);
    check_refused(run_cli(args), dir, holder);
  }
  // import-web checks its inputs before it takes the folder (issue 29: a refused input writes nothing,
  // not even the lock file); these inputs are refused, so it exits 2 without touching the held folder.
  const CliResult r = run_cli({"import-web", out, "--spec", demo_spec, "--stimuli", out, "--out", out});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--stimuli"));
  stop(holder);
}

}  // namespace test_output_locks
