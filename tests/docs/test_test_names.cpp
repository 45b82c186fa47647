// ctest registers each Catch2 test case by name (catch_discover_tests), and CMake cuts a name at every ';'
// (its list separator): a test case whose name holds one is registered as two tests that match nothing,
// and both "pass" without running. This guards every test source.
#include <catch2/catch.hpp>
#include <cctype>
#include <filesystem>

#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_test_names {

namespace {

/// The names of the TEST_CASEs in a source text: the adjacent string literals after a line that starts
/// with the macro, joined.
/// (A hand scan: std::regex trips GCC 12's -Wmaybe-uninitialized in the sanitizer build.)
std::vector<std::string> test_case_names(const std::string& text) {
  std::vector<std::string> names;
  const std::string marker = "TEST_CASE(";
  for (std::size_t at = text.find(marker); at != std::string::npos; at = text.find(marker, at + 1)) {
    if (at > 0 && text[at - 1] != '\n') continue;  // a use of the macro starts a line
    std::size_t i = at + marker.size();
    std::string name;
    while (true) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i >= text.size() || text[i] != '"') break;
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\' && i + 1 < text.size()) ++i;
        name += text[i];
      }
      ++i;  // the closing quote
    }
    names.push_back(name);
  }
  return names;
}

}  // namespace

TEST_CASE("no test case name holds a semicolon, which ctest would split into tests that never run",
          "[docs]") {
  namespace fs = std::filesystem;
  CHECK(test_case_names("TEST_CASE(\"a, b\"\n    \"c\\\"d\", \"[x]\")") ==
        std::vector<std::string>{"a, bc\"d"});
  std::size_t cases = 0;
  for (const auto& entry : fs::recursive_directory_iterator(crowdlab::test::source_dir() / "tests")) {
    if (entry.path().extension() != ".cpp") continue;
    for (const std::string& name : test_case_names(crowdlab::test::slurp(entry.path()))) {
      ++cases;
      CAPTURE(entry.path().string(), name);
      CHECK(name.find(';') == std::string::npos);
    }
  }
  CHECK(cases > 300);  // the scan found the suite
}

TEST_CASE("every test that tests/test_costs*.cmake give a ctest COST is a test case of its area", "[docs]") {
  // ctest silently ignores set_tests_properties on a name that matches no test, so a renamed slow test
  // would lose its cost, start late again on a clean clone, and nothing would say so (issue 31). The
  // sanitizer build has a second list of its own measured costs.
  namespace fs = std::filesystem;
  const fs::path tests = crowdlab::test::source_dir() / "tests";
  for (const auto& [file, at_least] :
       {std::pair<std::string, std::size_t>{"test_costs.cmake", 20},
        std::pair<std::string, std::size_t>{"test_costs_sanitized.cmake", 5}}) {
    CAPTURE(file);
    const std::string costs = crowdlab::test::slurp(tests / file);
    std::size_t named = 0;
    for (std::size_t at = costs.find("[=["); at != std::string::npos; at = costs.find("[=[", at + 1)) {
      const std::size_t end = costs.find("]=]", at);
      REQUIRE(end != std::string::npos);
      const std::string ctest_name = costs.substr(at + 3, end - at - 3);
      ++named;
      CAPTURE(ctest_name);
      // catch_discover_tests registers "<area>:<test case>" (it drops the TEST_PREFIX's trailing space).
      const std::size_t colon = ctest_name.find(':');
      REQUIRE(colon != std::string::npos);
      const fs::path area = tests / ctest_name.substr(0, colon);
      REQUIRE(fs::is_directory(area));
      bool found = false;
      for (const auto& entry : fs::directory_iterator(area))
        if (entry.path().extension() == ".cpp")
          for (const std::string& name : test_case_names(crowdlab::test::slurp(entry.path())))
            found = found || name == ctest_name.substr(colon + 1);
      CHECK(found);
    }
    CHECK(named >= at_least);  // the scan found the list
  }
}

}  // namespace test_test_names
