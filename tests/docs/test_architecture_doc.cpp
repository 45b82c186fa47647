// docs/architecture.md must not drift from the code (issue 30): its stage table lists the run's stages
// in the code's order (framework/pipeline/run_experiment.hpp: run_stage_names, with the stimuli
// module's presentation stages), and every test file it names exists.
#include <catch2/catch.hpp>
#include <filesystem>
#include <regex>
#include <sstream>

#include "framework/pipeline/run_experiment.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "stimuli/presentation_stages.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_architecture_doc {

using namespace crowdlab;
using namespace crowdlab::test;

TEST_CASE("docs/architecture.md's stage table is the run's stages, in run order", "[docs]") {
  const std::string doc = slurp(source_dir() / "docs/architecture.md");
  const size_t begin = doc.find("<!-- stage-table -->"), end = doc.find("<!-- /stage-table -->");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  std::vector<std::string> rows;
  std::istringstream table(doc.substr(begin, end - begin));
  std::string line;
  while (std::getline(table, line)) {
    if (!line.starts_with("| ") || line.starts_with("| stage ")) continue;
    rows.push_back(line.substr(2, line.find(" |", 2) - 2));
  }
  const ExperimentSpec spec = load_experiment_spec(tiny_spec());
  CHECK(rows == run_stage_names(stimuli::presentation_stages(spec)));
}

TEST_CASE("every test file docs/architecture.md names exists", "[docs]") {
  const std::string doc = slurp(source_dir() / "docs/architecture.md");
  const std::regex path(R"(`(tests/[A-Za-z0-9_/.]+\.(cpp|sh|yaml|py))`)");
  int named = 0;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), path); it != std::sregex_iterator(); ++it) {
    INFO((*it)[1].str());
    CHECK(std::filesystem::exists(source_dir() / (*it)[1].str()));
    ++named;
  }
  CHECK(named > 0);
}

}  // namespace test_architecture_doc
