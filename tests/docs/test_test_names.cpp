// ctest registers each Catch2 test case by name (catch_discover_tests), and CMake cuts a name at every ';'
// (its list separator): a test case whose name holds one is registered as two tests that match nothing,
// and both "pass" without running. This guards every test source.
#include <catch2/catch.hpp>
#include <filesystem>
#include <regex>

#include "tests/support/test_paths.hpp"

TEST_CASE("no test case name holds a semicolon, which ctest would split into tests that never run", "[docs]") {
  namespace fs = std::filesystem;
  const std::regex test_case(R"re(TEST_CASE\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+))re");
  const std::regex literal(R"re("((?:[^"\\]|\\.)*)")re");
  int cases = 0;
  for (const auto& entry : fs::recursive_directory_iterator(crowdlab::test::source_dir() / "tests")) {
    if (entry.path().extension() != ".cpp") continue;
    const std::string text = crowdlab::test::slurp(entry.path());
    for (auto m = std::sregex_iterator(text.begin(), text.end(), test_case); m != std::sregex_iterator();
         ++m) {
      std::string name;
      const std::string literals = (*m)[1];
      for (auto l = std::sregex_iterator(literals.begin(), literals.end(), literal);
           l != std::sregex_iterator(); ++l)
        name += (*l)[1];
      ++cases;
      CAPTURE(entry.path().string(), name);
      CHECK(name.find(';') == std::string::npos);
    }
  }
  CHECK(cases > 300);  // the scan found the suite
}
