// Walkable meshes from glTF (load_gltf_surface.hpp), on small files written here: triangles, strips,
// node transforms, binary .glb, and every kind of bad input giving a clear error.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>

#include "framework/core/error.hpp"
#include "framework/surface/load_gltf_surface.hpp"
#include "framework/surface/surface_scenes.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_gltf_surface {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

/// One scratch folder for the whole binary (scratch_dir empties it, so it is made once).
const fs::path& gltf_dir() {
  static const fs::path dir = test::scratch_dir("gltf_surface");
  return dir;
}

std::string bytes_of(const std::vector<float>& floats, const std::vector<std::uint16_t>& indices) {
  std::string b(floats.size() * 4 + indices.size() * 2, '\0');
  // memcpy from an empty vector's data() (which may be null) is undefined even for 0 bytes.
  if (!floats.empty()) std::memcpy(b.data(), floats.data(), floats.size() * 4);
  if (!indices.empty()) std::memcpy(b.data() + floats.size() * 4, indices.data(), indices.size() * 2);
  while (b.size() % 4) b.push_back('\0');
  return b;
}

/// glTF JSON for one mesh with one primitive; POSITION at offset 0, u16 indices after it.
std::string gltf_json(size_t vertex_count, size_t index_count, size_t buffer_bytes, const std::string& uri,
                      int mode, const std::string& node_extra = "", const std::string& type = "VEC3") {
  const size_t pos_bytes = vertex_count * 12;
  std::string j = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)";
  j += R"("nodes":[{"mesh":0)" + node_extra + "}],";
  j += R"("meshes":[{"name":"m","primitives":[{"attributes":{"POSITION":0})";
  if (index_count) j += R"(,"indices":1)";
  j += R"(,"mode":)" + std::to_string(mode) + "}]}],";
  j += R"("buffers":[{)" + (uri.empty() ? std::string() : R"("uri":")" + uri + R"(",)") + R"("byteLength":)" +
       std::to_string(buffer_bytes) + "}],";
  j += R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" + std::to_string(pos_bytes) + "}";
  if (index_count)
    j += R"(,{"buffer":0,"byteOffset":)" + std::to_string(pos_bytes) + R"(,"byteLength":)" +
         std::to_string(index_count * 2) + "}";
  j += "],";
  j += R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" + std::to_string(vertex_count) +
       R"(,"type":")" + type + R"("})";
  if (index_count)
    j += R"(,{"bufferView":1,"componentType":5123,"count":)" + std::to_string(index_count) +
         R"(,"type":"SCALAR"})";
  j += "]}";
  return j;
}

fs::path write_gltf(const std::string& name, const std::vector<float>& pos,
                    const std::vector<std::uint16_t>& idx, int mode = 4, const std::string& node_extra = "",
                    const std::string& type = "VEC3") {
  const fs::path& dir = gltf_dir();
  const std::string bin = bytes_of(pos, idx);
  std::ofstream(dir / (name + ".bin"), std::ios::binary) << bin;
  std::ofstream(dir / (name + ".gltf"))
      << gltf_json(pos.size() / 3, idx.size(), bin.size(), name + ".bin", mode, node_extra, type);
  return dir / (name + ".gltf");
}

fs::path write_glb(const std::string& name, const std::vector<float>& pos,
                   const std::vector<std::uint16_t>& idx) {
  const fs::path& dir = gltf_dir();
  const std::string bin = bytes_of(pos, idx);
  std::string json = gltf_json(pos.size() / 3, idx.size(), bin.size(), "", 4);
  while (json.size() % 4) json.push_back(' ');
  std::string out;
  const auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534A);  // "JSON"
  out += json;
  u32(static_cast<std::uint32_t>(bin.size()));
  u32(0x004E4942);  // "BIN\0"
  out += bin;
  std::ofstream(dir / (name + ".glb"), std::ios::binary) << out;
  return dir / (name + ".glb");
}

// A unit square in the y = 0 plane, wound so its normal is +Y, as two triangles.
const std::vector<float> kSquare = {0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0};
const std::vector<std::uint16_t> kSquareTris = {0, 1, 2, 0, 2, 3};

void check_square(const SurfaceMesh& m, const Vec3& offset, double scale) {
  REQUIRE(m.face_count() == 2);
  REQUIRE(m.vertices_m.size() == 4);
  CHECK(m.total_area_m2 == Approx(scale * scale));
  for (const Vec3& n : m.face_normals) CHECK(n.isApprox(Vec3::UnitY()));
  for (const Vec3& n : m.vertex_normals) CHECK(n.isApprox(Vec3::UnitY()));
  // The diagonal is shared: each face has exactly one neighbour, the other one.
  for (int f = 0; f < 2; ++f) {
    int shared = 0;
    for (int e = 0; e < 3; ++e)
      if (m.neighbors[size_t(f)][size_t(e)] >= 0) {
        ++shared;
        CHECK(m.neighbors[size_t(f)][size_t(e)] == 1 - f);
        CHECK_FALSE(m.flips_orientation[size_t(f)][size_t(e)]);
      }
    CHECK(shared == 1);
  }
  Vec3 lo = Vec3::Constant(1e9);
  for (const Vec3& v : m.vertices_m) lo = lo.cwiseMin(v);
  CHECK((lo - offset).norm() < 1e-6);
}

}  // namespace

TEST_CASE("glTF triangles load with adjacency and normals, through node transforms and as .glb") {
  check_square(load_gltf_surface(write_gltf("square", kSquare, kSquareTris).string()), Vec3::Zero(), 1);
  check_square(load_gltf_surface(write_glb("square_bin", kSquare, kSquareTris).string()), Vec3::Zero(), 1);
  // Through make_surface_scene too.
  check_square(make_surface_scene(write_gltf("square2", kSquare, kSquareTris).string()), Vec3::Zero(), 1);
  // translation (1, 2, 3) and uniform scale 2.
  check_square(
      load_gltf_surface(
          write_gltf("moved", kSquare, kSquareTris, 4, R"(,"translation":[1,2,3],"scale":[2,2,2])").string()),
      Vec3(1, 2, 3), 2);
  // A rotation of 180 degrees about X turns the floor into a ceiling: normals point down.
  const SurfaceMesh ceiling =
      load_gltf_surface(write_gltf("flipped", kSquare, kSquareTris, 4, R"(,"rotation":[1,0,0,0])").string());
  for (const Vec3& n : ceiling.face_normals) CHECK(n.isApprox(-Vec3::UnitY()));
  // A mirroring scale keeps the normals on the same (outward) side.
  const SurfaceMesh mirrored =
      load_gltf_surface(write_gltf("mirror", kSquare, kSquareTris, 4, R"(,"scale":[-1,1,1])").string());
  for (const Vec3& n : mirrored.face_normals) CHECK(n.isApprox(Vec3::UnitY()));
}

TEST_CASE("glTF triangle strips and non-indexed triangles give the same square") {
  check_square(load_gltf_surface(write_gltf("strip", kSquare, {1, 2, 0, 3}, 5).string()), Vec3::Zero(), 1);
  const std::vector<float> soup = {0, 0, 0, 0, 0, 1, 1, 0, 1,
                                   0, 0, 0, 1, 0, 1, 1, 0, 0};  // duplicated corners
  check_square(load_gltf_surface(write_gltf("soup", soup, {}).string()), Vec3::Zero(), 1);  // welded
}

TEST_CASE("bad glTF meshes give clear errors naming the file") {
  const auto fails_with = [](const fs::path& path, const std::string& needle) {
    INFO(path.string() << " should fail with '" << needle << "'");
    try {
      load_gltf_surface(path.string());
      FAIL("no error");
    } catch (const InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find(path.filename().string()) != std::string::npos);
      CHECK(what.find(needle) != std::string::npos);
    }
  };
  // Three triangles on one edge (0-2): non-manifold.
  const std::vector<float> fan = {0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0, -1, 0, 0};
  fails_with(write_gltf("nonmanifold", fan, {0, 1, 2, 0, 2, 3, 0, 4, 2}), "non-manifold");
  fails_with(write_gltf("points", kSquare, kSquareTris, 0), "not a triangle mode");
  fails_with(write_gltf("lines", kSquare, kSquareTris, 1), "not a triangle mode");
  fails_with(write_gltf("badindex", kSquare, {0, 1, 2, 0, 2, 9}), "out of range");
  fails_with(write_gltf("vec2", kSquare, kSquareTris, 4, "", "VEC2"), "POSITION");
  fails_with(write_gltf("notmultiple", kSquare, {0, 1, 2, 0}), "multiple of 3");
  // Every triangle degenerate (collinear points).
  fails_with(write_gltf("degenerate", {0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2}), "degenerate");
  const std::vector<float> nan_square = {0, 0, 0, 0, 0, 1, 1, 0, 1, 1, std::nanf(""), 0};
  fails_with(write_gltf("nan", nan_square, kSquareTris), "not a finite number");
  // Truncated JSON, and a missing .bin.
  const fs::path& dir = gltf_dir();
  std::ofstream(dir / "truncated.gltf") << R"({"asset":{"version":"2.0"},"meshes":[{"primi)";
  fails_with(dir / "truncated.gltf", "cannot read glTF");
  const fs::path orphan = write_gltf("orphan", kSquare, kSquareTris);
  fs::remove(dir / "orphan.bin");
  fails_with(orphan, "cannot read glTF");
  fails_with(dir / "does_not_exist.gltf", "no such file");
}

TEST_CASE("glTF surface: a 100,000-node parent->child chain loads without recursing (issue 21)") {
  // The fuzzer's file: every node the only child of the one before, the mesh on the last. A recursive
  // node visit overflowed the stack (SIGSEGV); the visit now keeps its own stack.
  const fs::path file = write_gltf("chain", kSquare, kSquareTris);
  std::string json = test::slurp(file);
  constexpr int kNodes = 100000;
  std::string nodes = R"("nodes":[)";
  for (int i = 0; i + 1 < kNodes; ++i) nodes += R"({"children":[)" + std::to_string(i + 1) + "]},";
  nodes += R"({"mesh":0,"translation":[2,0,3]}],)";
  const std::string from = R"("nodes":[{"mesh":0}],)";
  REQUIRE(json.find(from) != std::string::npos);
  json.replace(json.find(from), from.size(), nodes);
  std::ofstream(file) << json;
  check_square(load_gltf_surface(file.string()), Vec3(2, 0, 3), 1);
}

}  // namespace test_gltf_surface
