// canonical_bytes (framework/core/canonical_bytes.hpp): every field of a plain struct, however deep,
// is in the bytes without being named, and no two different values share their bytes.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "framework/core/canonical_bytes.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_canonical_bytes {

using namespace crowdlab;

namespace {

enum class Colour { red, green };

struct Inner {
  int count = 1;
  double size = 0.5;
};

struct Recipe {
  static constexpr int kNotAField = 3;  // static members are not fields
  bool on = false;
  int n = 2;
  std::uint64_t seed = 7;
  float f = 1.5f;
  double x = 0.25;
  Colour colour = Colour::red;
  std::string name = "a";
  std::optional<int> maybe;
  std::vector<std::string> list{"p", "q"};
  std::map<std::string, std::vector<double>> table{{"k", {1.0, 2.0}}};
  Inner inner;
};

}  // namespace

TEST_CASE("canonical bytes: the fields of a struct are found without being named") {
  CHECK(canonical_field_count<Inner>() == 2);
  CHECK(canonical_field_count<Recipe>() == 11);
}

TEST_CASE("canonical bytes: a change of any field, however deep, changes the bytes") {
  const Recipe base;
  const std::string bytes = canonical_bytes(base);
  CHECK(canonical_bytes(Recipe{}) == bytes);
  const std::vector<std::function<void(Recipe&)>> edits{
      [](Recipe& r) { r.on = true; },
      [](Recipe& r) { r.n = 3; },
      [](Recipe& r) { r.seed = 8; },
      [](Recipe& r) { r.f = 1.25f; },
      [](Recipe& r) { r.x = std::nextafter(0.25, 1.0); },  // bit for bit
      [](Recipe& r) { r.colour = Colour::green; },
      [](Recipe& r) { r.name = "b"; },
      [](Recipe& r) { r.maybe = 0; },
      [](Recipe& r) { r.list.push_back(""); },
      [](Recipe& r) { r.list = {"pq"}; },  // lengths are part of the bytes
      [](Recipe& r) { r.table["k"][1] = 3.0; },
      [](Recipe& r) { r.table["l"] = {}; },
      [](Recipe& r) { r.inner.count = 2; },
      [](Recipe& r) { r.inner.size = 0.75; },
  };
  std::set<std::string> seen{bytes};
  for (size_t i = 0; i < edits.size(); ++i) {
    INFO("edit " << i);
    Recipe r;
    edits[i](r);
    CHECK(seen.insert(canonical_bytes(r)).second);
  }
}

TEST_CASE("canonical bytes: string boundaries and empty values are unambiguous") {
  CHECK(canonical_bytes(std::vector<std::string>{"ab", "c"}) !=
        canonical_bytes(std::vector<std::string>{"a", "bc"}));
  CHECK(canonical_bytes(std::optional<int>{}) != canonical_bytes(std::optional<int>{0}));
  CHECK(canonical_bytes(std::string{}) != canonical_bytes(std::vector<std::string>{}));
  CHECK(canonical_bytes(0) != canonical_bytes(0.0));
}

}  // namespace test_canonical_bytes
