// Documentation that must not drift: docs/cli.md is exactly `crowdlab help --markdown`, it covers every
// command, and the README links the references a new user needs.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_docs {

using namespace crowdlab::test;

namespace {
using crowdlab::test::slurp;
}  // namespace

TEST_CASE("docs/cli.md is the binary's own --help text", "[docs][cli]") {
  const CliResult r = run_cli({"help", "--markdown"});
  REQUIRE(r.exit_code == 0);
  const std::string doc = slurp(source_dir() / "docs/cli.md");
  INFO("regenerate with: build/crowdlab help --markdown > docs/cli.md");
  CHECK(doc == r.out);
  // Every top-level command and the reproductions have a section.
  for (const char* cmd : {"run", "plan", "demo", "reproduce gomez2024", "reproduce hoyet2016", "validate",
                          "correct", "render", "analyze report", "experiment damping", "bench correct"}) {
    INFO(cmd);
    CHECK(doc.find(std::string("## `crowdlab ") + cmd + "`") != std::string::npos);
  }
}

TEST_CASE("every subcommand's --help works and matches its reference section", "[docs][cli]") {
  const std::string doc = slurp(source_dir() / "docs/cli.md");
  for (const std::vector<std::string>& cmd :
       {std::vector<std::string>{"reproduce", "gomez2024"}, {"reproduce", "hoyet2016"}, {"plan"}, {"run"}}) {
    std::vector<std::string> args = cmd;
    args.push_back("--help");
    const CliResult r = run_cli(args);
    REQUIRE(r.exit_code == 0);
    // The usage line names the binary as it was invoked; the reference calls it `crowdlab`.
    std::string text = r.out;
    const std::string exe = crowdlab_exe().string();
    const size_t at = text.find(exe);
    REQUIRE(at != std::string::npos);
    text.replace(at, exe.size(), "crowdlab");
    INFO(text);
    CHECK(doc.find("```text\n" + text) != std::string::npos);
  }
}

TEST_CASE("the README links the references", "[docs]") {
  const std::string readme = slurp(source_dir() / "README.md");
  for (const char* link : {"docs/cli.md", "docs/spec-reference.md", "docs/embedding.md",
                           "docs/reproductions.md", "docs/architecture.md"}) {
    INFO(link);
    CHECK(readme.find(std::string("(") + link + ")") != std::string::npos);
    CHECK(std::filesystem::exists(source_dir() / link));
  }
}

}  // namespace test_docs
