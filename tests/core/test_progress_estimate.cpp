// Progress prints, once a job has run a while, its estimated total time and the resident memory, and
// every plain progress line carries the time left (issue 33: `power --simulations 1000000000` and the other
// options with huge accepted maxima ran for hours without a word).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "framework/core/progress.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_progress_estimate {

using namespace crowdlab;

namespace {

/// What `body` writes to stderr (redirected to a file while it runs).
template <class F>
std::string stderr_of(F&& body) {
  const auto path = test::scratch_dir("progress-estimate") / "stderr.txt";
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  std::FILE* file = std::fopen(path.c_str(), "w");
  ::dup2(::fileno(file), STDERR_FILENO);
  body();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  std::fclose(file);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("progress: a long job's estimated total and memory are printed once, lines show the time left") {
  Progress::set_enabled(true);        // the default; --quiet turns it off
  Progress::set_estimate_after(0.0);  // at once: the threshold is a time, the test must not be
  const std::string out = stderr_of([] {
    Progress p("power n=20", 1000);
    for (int i = 0; i < 10; ++i) p.advance();
  });
  Progress::set_estimate_after(2.0);
  CHECK_THAT(out, Catch::Contains("power n=20: estimated ") &&
                      Catch::Contains(" in all for 1000 steps (1 done in") &&
                      Catch::Contains("MB resident now"));
  std::size_t count = 0;
  for (std::size_t at = out.find("estimated"); at != std::string::npos; at = out.find("estimated", at + 1))
    ++count;
  CHECK(count == 1);
}

TEST_CASE("progress: work found under way grows the total with a line that says why") {
  // Session 20 (issue 28): correct_crowd's extra lap was not counted, so the line sat at 100 % for a lap.
  Progress::set_enabled(true);
  std::vector<ProgressUpdate> seen;
  const std::string out = stderr_of([&] {
    Progress p("correcting x.glb", 10);
    p.set_observer([&](const ProgressUpdate& u) { seen.push_back(u); });
    for (int i = 0; i < 10; ++i) p.advance();
    p.grow(5, "an extra lap for 2 open characters");
    for (int i = 0; i < 5; ++i) p.advance();
    p.finish();
  });
  CHECK_THAT(out, Catch::Contains("correcting x.glb: an extra lap for 2 open characters: +5 steps, now 10/15 "
                                  "(66%)") &&
                      Catch::Contains("15/15 (100%)"));
  REQUIRE(seen.size() == 16);
  CHECK(seen[9].done == 10);
  CHECK(seen[9].total == 10);
  CHECK(seen[10].units == 0);  // the growth
  CHECK(seen[10].done == 10);
  CHECK(seen[10].total == 15);
  CHECK(seen.back().done == 15);
  CHECK(seen.back().total == 15);
}

}  // namespace test_progress_estimate
