// Hand-mutated crowd files (issue 21): each broken GLB, through `correct`, `metrics` and `export-csv`,
// exits 2 with a message naming the file and what is wrong, where (before: "cannot read glTF: unknown
// error" or tinygltf's bare "Invalid glTF binary.").
#include <tiny_gltf.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "tests/support/glb_bytes.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_glb_mutations {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// The crowd file edited through tinygltf (which writes whatever it is given).
fs::path edited(const fs::path& good, const fs::path& out,
                const std::function<void(tinygltf::Model&)>& change) {
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  std::string err, warn;
  REQUIRE(gltf.LoadBinaryFromFile(&model, &err, &warn, good.string()));
  change(model);
  REQUIRE(gltf.WriteGltfSceneToFile(&model, out.string(), false, true, false, true));
  return out;
}

/// A valid crowd file of swaying characters, dir/good.glb, for the mutations to start from.
fs::path small_crowd_glb(const fs::path& dir, int characters, int frames) {
  SwayingCrowdOptions o;
  o.characters = characters;
  o.frames = frames;
  const fs::path good = dir / "good.glb";
  write_crowd_glb(make_swaying_crowd_fixture(o), good.string());
  return good;
}

void check_refused(const fs::path& file, const std::vector<std::string>& expected) {
  const fs::path dir = file.parent_path();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"correct", file.string(), "--out", (dir / "out.glb").string()},
        std::vector<std::string>{"metrics", file.string()},
        std::vector<std::string>{"export-csv", file.string(), "--out", (dir / "out.csv").string()}}) {
    const CliResult r = run_cli(args);
    INFO(args[0] << " " << file.filename().string() << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains(file.string() + ": "));
    for (const std::string& e : expected) CHECK_THAT(r.err, Catch::Contains(e));
    CHECK_THAT(r.err, !Catch::Contains("unknown error") && !Catch::Contains("gave no reason"));
  }
}

}  // namespace

TEST_CASE("hand-mutated GLBs exit 2 from correct, metrics and export-csv, saying what is wrong and where") {
  const fs::path dir = scratch_dir("glb_mutations");
  const fs::path good = small_crowd_glb(dir, 2, 3);
  const std::string bytes = slurp(good);
  const std::uint32_t json_length = glb_u32(bytes, 12);
  REQUIRE(bytes.size() > 20 + json_length + 8);

  std::string b = bytes;
  b[1] = 'L';
  write_bytes(dir / "magic.glb", b);
  check_refused(dir / "magic.glb",
                {"cannot read glTF: not a valid GLB file", "bytes 0-3 are 'gLTF', not the magic 'glTF'"});

  b = bytes;
  put_glb_u32(b, 4, 1);
  write_bytes(dir / "version.glb", b);
  check_refused(dir / "version.glb", {"container version 1, expected 2"});

  write_bytes(dir / "truncated.glb", bytes.substr(0, bytes.size() - 100));
  check_refused(dir / "truncated.glb",
                {"total length of " + std::to_string(bytes.size()) + " bytes",
                 "the file has " + std::to_string(bytes.size() - 100) + " (truncated?)"});

  b = bytes;
  put_glb_u32(b, 12, 0x7FFFFFF0u);
  write_bytes(dir / "json_length.glb", b);
  check_refused(dir / "json_length.glb",
                {"the JSON chunk (byte 12) gives a length of 2147483632 bytes", "past the total length"});

  b = bytes;
  std::memcpy(b.data() + 20 + json_length + 4, "BIM", 4);
  write_bytes(dir / "bin_type.glb", b);
  check_refused(dir / "bin_type.glb",
                {"the second chunk (byte " + std::to_string(20 + json_length) + ") has type 'BIM\\x00'",
                 "expected 'BIN'"});

  // A syntax error inside the JSON: the separator after the first key becomes ';'.
  b = bytes;
  const std::size_t colon = b.find("\":", 20) + 1;
  REQUIRE(colon < 20 + json_length);
  b[colon] = ';';
  write_bytes(dir / "json_syntax.glb", b);
  check_refused(dir / "json_syntax.glb",
                {"cannot read glTF",
                 "the JSON is not valid at byte " + std::to_string(colon) + " of the file (line 1, column " +
                     std::to_string(colon - 20 + 1) + " of the JSON)",
                 "syntax error", "expected ':'"});

  // Inside well-formed JSON: a bufferView beyond its buffer, and an accessor longer than its bufferView.
  const fs::path view = edited(good, dir / "view_range.glb",
                               [](tinygltf::Model& m) { m.bufferViews[0].byteOffset = 1u << 30; });
  check_refused(view, {"accessor", "bufferView 0 lies outside its buffer"});
  const fs::path count = edited(good, dir / "accessor_count.glb", [](tinygltf::Model& m) {
    for (tinygltf::Accessor& a : m.accessors)
      if (a.bufferView == 0) a.count = 100000000;
  });
  check_refused(count, {"accessor", "100000000 elements do not fit in bufferView 0"});
}

TEST_CASE("bodies no human has exit 2 from correct and metrics at once, not after minutes of voxelising") {
  // The second joint's (left_hip's) offset or the first capsule's radius is changed. Issue 21: joint offsets
  // of 65535 m or 1e300 m, or a capsule radius of 1e6 m, kept `correct` in union_fraction() (a 2.5 cm grid
  // over the body's box) for over 300 s; at 1e300 its x += 0.025 never advanced.
  const fs::path dir = scratch_dir("glb_implausible_bodies");
  const fs::path good = small_crowd_glb(dir, 2, 3);
  const std::string bytes = slurp(good), json = glb_json(bytes);
  // Replaces the first number after `key` (after `anchor`) in the JSON by `value`.
  const auto with_number = [&](const std::string& anchor, const std::string& key, const std::string& value) {
    std::string j = json;
    const std::size_t start = j.find_first_of("-0123456789", j.find(key, j.find(anchor)) + key.size());
    j.replace(start, j.find_first_of(",]}", start) - start, value);
    return glb_with_json(bytes, j);
  };
  const struct {
    const char* name;
    std::string bytes;
    const char* expected;
  } cases[] = {
      {"offset_65535", with_number("\"joint_offsets_m\"", "],[", "65535"), "more than the limit of 4 m"},
      {"offset_1e300", with_number("\"joint_offsets_m\"", "],[", "1e300"), "more than the limit of 4 m"},
      {"radius_1e6", with_number("\"capsules\"", "\"radius_m\":", "1e6"), "more than the limit of 1 m"}};
  for (const auto& c : cases) {
    const fs::path file = dir / (std::string(c.name) + ".glb");
    write_bytes(file, c.bytes);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"correct", file.string(), "--out", (dir / "out.glb").string()},
          std::vector<std::string>{"metrics", file.string()}}) {
      const auto start = std::chrono::steady_clock::now();
      const CliResult r = run_cli(args);
      INFO(args[0] << " " << c.name << ": " << r.err);
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.err, Catch::Contains(file.string()) && Catch::Contains(c.expected));
      CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(30));
    }
  }
}

TEST_CASE("a glTF parser message quoting a huge value is cut to a readable length") {
  const fs::path dir = scratch_dir("glb_long_reason");
  const fs::path good = small_crowd_glb(dir, 1, 2);
  const std::string bytes = slurp(good);
  std::string json = glb_json(bytes);
  const std::size_t type = json.find("\"type\":\"") + 8;
  json.insert(type,
              std::string(30000, '['));  // tinygltf: Unsupported `type` for accessor object. Got "[[[...
  write_bytes(dir / "long.glb", glb_with_json(bytes, json));
  const CliResult r = run_cli({"metrics", (dir / "long.glb").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("long.glb: cannot read glTF") && Catch::Contains("more characters)"));
  CHECK(r.err.size() < 1000);
}

TEST_CASE("accessors viewing one buffer many times over, and a buffer uri that is a folder, exit 2") {
  // Issue 32: a 40 MB GLB whose accessors all viewed one buffer asked 7.2 GB of export-csv, metrics
  // and correct; a buffer with `uri: "."` asked for exabytes. Small versions: each accessor fits its
  // view, so only the sum gives them away.
  const fs::path dir = scratch_dir("glb_amplification");
  const fs::path good = small_crowd_glb(dir, 2, 3);
  const fs::path amplified = edited(good, dir / "amplified.glb", [](tinygltf::Model& m) {
    std::size_t buffer = 0, largest = 0, largest_bytes = 0;
    for (const auto& b : m.buffers) buffer += b.data.size();
    for (std::size_t i = 0; i < m.accessors.size(); ++i) {
      const auto& a = m.accessors[i];
      const std::size_t bytes =
          a.count * static_cast<std::size_t>(
                        tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)) *
                        tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)));
      if (bytes > largest_bytes) largest = i, largest_bytes = bytes;
    }
    const tinygltf::Accessor copy = m.accessors[largest];
    // Enough copies to view 4 x the buffers + 1 MiB and a little more.
    const std::size_t copies = (4 * buffer + (1u << 20)) / largest_bytes + 2;
    for (std::size_t k = 0; k < copies; ++k) m.accessors.push_back(copy);
  });
  check_refused(amplified, {"cannot read glTF", "accessors view", "more than the limit of"});

  std::string json = glb_json(slurp(good));
  const std::size_t buffers = json.find("\"buffers\":[{");
  REQUIRE(buffers != std::string::npos);
  json.insert(buffers + 12, "\"uri\":\".\",");
  write_bytes(dir / "uri_folder.glb", glb_with_json(slurp(good), json));
  check_refused(dir / "uri_folder.glb", {"cannot read glTF", "directory"});
}

}  // namespace test_glb_mutations
