// docs/architecture.md must not drift from the code (issue 30): its stage table lists the run's stages
// in the code's order (framework/pipeline/run_experiment.hpp: run_stage_names, with the stimuli
// module's presentation stages), every test file it names exists, and each framework module includes only
// the modules its row of the module table lists (the stage order: correction before metrics, session 16).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
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

/// docs/architecture.md's module table: framework module (core, spec, ...) -> the framework modules its
/// "depends on" column names ("every framework module above" for the pipeline: all of them).
std::map<std::string, std::set<std::string>> documented_framework_deps(const std::string& doc) {
  std::map<std::string, std::set<std::string>> deps;
  const std::regex row(R"(\| `framework/([a-z_]+)` \| [^|]+ \| [^|]+ \| ([^|]+) \|)");
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), row); it != std::sregex_iterator(); ++it) {
    std::set<std::string>& of = deps[(*it)[1].str()];
    const std::string column = (*it)[2].str();
    const std::regex word(R"([a-z_]+)");
    for (auto w = std::sregex_iterator(column.begin(), column.end(), word); w != std::sregex_iterator(); ++w)
      of.insert((*w)[0].str());
    if (column.find("every framework module") != std::string::npos)
      for (const auto& [module, unused] : deps) of.insert(module);
  }
  return deps;
}

TEST_CASE("each framework module includes only the modules docs/architecture.md lists for it", "[docs]") {
  const auto deps = documented_framework_deps(slurp(source_dir() / "docs/architecture.md"));
  REQUIRE(deps.count("core") == 1);
  REQUIRE(deps.count("correction") == 1);
  const std::regex include(R"re(#include "(framework|stimuli|study_ui|analysis|experiments)/([a-z_]+)/?)re");
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_dir() / "framework")) {
    if (!entry.is_regular_file()) continue;
    const auto rel = std::filesystem::relative(entry.path(), source_dir() / "framework");
    const std::string module = rel.begin()->string();
    if (!deps.contains(module)) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!line.starts_with("#include \"") || !std::regex_search(line, m, include)) continue;
      INFO(entry.path().string() << ": " << line);
      CHECK(m[1].str() == "framework");
      CHECK((m[2].str() == module || deps.at(module).contains(m[2].str())));
    }
  }
  CHECK(files > 100);
}

}  // namespace test_architecture_doc
