// glTF JSON nested deeper than any glTF needs (issue 21): a GLB whose `extras` nest 100,000 arrays deep
// crashed export-csv, metrics and correct inside the JSON parser (SIGSEGV). The depth is now measured
// before the file is handed to the parser, and such files are refused with exit 2.
#include <catch2/catch.hpp>
#include <cstdint>
#include <fstream>

#include "framework/io/json_nesting_depth.hpp"
#include "framework/io/load_gltf_model.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_gltf_nesting {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// A GLB holding only `json` (padded to 4 bytes) and no binary chunk.
void write_json_only_glb(const fs::path& path, std::string json) {
  while (json.size() % 4) json.push_back(' ');
  std::string out;
  const auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(static_cast<std::uint32_t>(12 + 8 + json.size()));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534A);  // "JSON"
  out += json;
  std::ofstream(path, std::ios::binary) << out;
}

std::string nested_arrays(int depth) {
  return std::string(static_cast<size_t>(depth), '[') + std::string(static_cast<size_t>(depth), ']');
}

}  // namespace

TEST_CASE("json_nesting_depth counts arrays and objects, not brackets inside strings") {
  CHECK(json_nesting_depth("1", 10) == 0);
  CHECK(json_nesting_depth(R"({"a":[1,{"b":[]}]})", 10) == 4);
  CHECK(json_nesting_depth(R"({"a":"[[[[\"[[{{"})", 10) == 1);
  CHECK(json_nesting_depth(nested_arrays(50), 10) == 11);  // stops once past the bound
  CHECK(json_nesting_depth(nested_arrays(50), 100) == 50);
}

TEST_CASE("a GLB whose JSON nests 100,000 arrays deep exits 2 with the file named, never a signal") {
  const fs::path dir = scratch_dir("gltf_nesting");
  const fs::path deep = dir / "deep.glb";
  write_json_only_glb(
      deep, R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[],"extras":)" + nested_arrays(100000) + "}]}");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"export-csv", deep.string(), "--out", (dir / "x.csv").string()},
        std::vector<std::string>{"metrics", deep.string()},
        std::vector<std::string>{"correct", deep.string(), "--out", (dir / "y.glb").string()}}) {
    INFO(args[0]);
    const CliResult r = run_cli(args);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains(deep.string()) && Catch::Contains("more than 256 levels deep"));
  }
  // At the bound the file gets past the depth check (and fails later for other reasons, or loads).
  const fs::path at_bound = dir / "at_bound.glb";
  write_json_only_glb(at_bound, R"({"asset":{"version":"2.0"},"extras":)" +
                                    nested_arrays(static_cast<int>(kMaxGltfJsonDepth) - 1) + "}");
  CHECK_NOTHROW(load_gltf_model(at_bound));
}

}  // namespace test_gltf_nesting
