// Crowd files (.glb): exact round trip, Khronos validation, and clear errors for broken files.
#include <tiny_gltf.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_crowd_glb {

using namespace crowdlab;

namespace {

Quat random_rotation(Rng& rng) {
  Quat q(standard_normal(rng), standard_normal(rng), standard_normal(rng), standard_normal(rng));
  return q.normalized();
}

// A crowd with random bodies, random joint rotations and root positions spread over +-20 m.
CrowdAnimation random_crowd(std::uint64_t seed, int characters, int frames) {
  Rng rng(seed);
  CrowdAnimation crowd;
  crowd.meta.fps = 25.0 + 10.0 * uniform01(rng);
  crowd.meta.seed = 0xfedcba9876543210ULL ^ seed;  // needs all 64 bits
  crowd.meta.condition_id = "density-2.22_viewpoint-V1_method-ours_rep-" + std::to_string(seed);
  crowd.meta.scenario = "stationary";
  for (int c = 0; c < characters; ++c) {
    CharacterAnimation ch;
    ch.name = "c" + std::to_string(100 + c);
    ch.palette = c;
    ch.shape = make_procedural_body(
        {c % 2 ? Sex::kFemale : Sex::kMale, 1.5 + 0.4 * uniform01(rng), 0.8 + 0.5 * uniform01(rng)});
    for (int f = 0; f < frames; ++f) {
      Pose p;
      p.root_position_m =
          Vec3(40.0 * uniform01(rng) - 20.0, 0.8 + 0.3 * uniform01(rng), 40.0 * uniform01(rng) - 20.0);
      for (auto& q : p.local_rotations) q = random_rotation(rng);
      ch.frames.push_back(p);
    }
    crowd.characters.push_back(std::move(ch));
  }
  Box b;
  b.center_m = Vec3(1.0, 0.5, -2.0);
  b.half_extents_m = Vec3(2.0, 0.5, 0.1);
  b.rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
  crowd.environment.boxes.push_back(b);
  TriangleMesh m;
  m.name = "ramp";
  m.vertices_m = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.25, 1), Vec3(0, 0.25, 1)};
  m.triangles = {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 3, 2)};
  crowd.environment.meshes.push_back(m);
  return crowd;
}

// Largest |a - b| over quaternion coefficients, with b's sign chosen to match a (q and -q are equal).
double quat_distance(const Quat& a, const Quat& b) {
  const double plus = (a.coeffs() - b.coeffs()).cwiseAbs().maxCoeff();
  const double minus = (a.coeffs() + b.coeffs()).cwiseAbs().maxCoeff();
  return std::min(plus, minus);
}

using crowdlab::test::slurp;

void spit(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

// Runs the Khronos validator on `files` (one Node.js process); returns one JSON summary per file, or
// an empty list (after a WARN) when the validator cannot run here.
std::vector<nlohmann::json> khronos_validate(const std::vector<std::filesystem::path>& files) {
  const auto package = test::source_dir() / ".tools" / "node_modules" / "gltf-validator";
  if (std::system("command -v node >/dev/null 2>&1") != 0) {
    WARN("skipping glTF-Validator check: node (Node.js) is not installed");
    return {};
  }
  if (!std::filesystem::exists(package / "package.json")) {
    WARN("skipping glTF-Validator check: run scripts/install-deps.sh --test to install it into .tools/");
    return {};
  }
  const auto out = files.front().string() + ".validator.json";
  std::string cmd =
      "node " + test::shell_quote((test::source_dir() / "tests" / "support" / "validate_gltf.mjs").string()) +
      " " + test::shell_quote(package.string());
  for (const auto& f : files) cmd += " " + test::shell_quote(f.string());
  cmd += " > " + test::shell_quote(out);
  REQUIRE(std::system(cmd.c_str()) == 0);
  const nlohmann::json all = nlohmann::json::parse(slurp(out));
  REQUIRE(all.size() == files.size());
  return {all.begin(), all.end()};
}

// A closed lat-long sphere around the pelvis, skinned to two joints with vertex-dependent weights
// (the same topology and weights for every shape; positions scale with the body height).
std::shared_ptr<const SkinnedMesh> sphere_surface(const BodyShape& shape) {
  auto m = std::make_shared<SkinnedMesh>();
  m->rest_joints_m = joint_positions(shape, Pose::rest(shape));
  const int rings = 6, segments = 8;
  const Vec3 centre = m->rest_joints_m[kPelvis];
  const double r = 0.1 * shape.params.height_m;
  auto add = [&](const Vec3& dir) {
    m->rest_vertices_m.push_back(centre + r * dir);
    m->rest_normals.push_back(dir);
    const double w = 0.5 + 0.4 * dir.y();
    m->joints.push_back({kPelvis, kSpine1, 0, 0});
    m->weights.push_back({w, 1.0 - w, 0.0, 0.0});
    m->region.push_back(w >= 0.5 ? kPelvis : kSpine1);
  };
  add(-Vec3::UnitY());
  for (int i = 1; i < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      const double th = M_PI * i / rings - M_PI / 2, ph = 2 * M_PI * k / segments;
      add(Vec3(std::cos(th) * std::sin(ph), std::sin(th), std::cos(th) * std::cos(ph)));
    }
  add(Vec3::UnitY());
  const int top = static_cast<int>(m->rest_vertices_m.size()) - 1;
  auto ring = [&](int i, int k) { return 1 + (i - 1) * segments + (k % segments); };
  for (int k = 0; k < segments; ++k) {
    m->triangles.emplace_back(0, ring(1, k + 1), ring(1, k));
    for (int i = 1; i + 1 < rings; ++i) {
      m->triangles.emplace_back(ring(i, k), ring(i, k + 1), ring(i + 1, k + 1));
      m->triangles.emplace_back(ring(i, k), ring(i + 1, k + 1), ring(i + 1, k));
    }
    m->triangles.emplace_back(top, ring(rings - 1, k), ring(rings - 1, k + 1));
  }
  return m;
}

}  // namespace

TEST_CASE("a character's own skinned surface round-trips - characters share its topology accessors") {
  const auto dir = test::scratch_dir("glb-surface");
  CrowdAnimation crowd = random_crowd(21, 3, 4);
  crowd.characters[0].mesh = sphere_surface(crowd.characters[0].shape);
  crowd.characters[2].mesh = sphere_surface(crowd.characters[2].shape);
  const auto file = dir / "surface.glb";
  write_crowd_glb(crowd, file.string());
  const CrowdAnimation back = read_crowd_glb(file.string());
  CHECK(back.characters[1].mesh == nullptr);  // the procedural body stays a capsule preview
  for (size_t c : {size_t{0}, size_t{2}}) {
    REQUIRE(back.characters[c].mesh);
    const SkinnedMesh& a = *crowd.characters[c].mesh;
    const SkinnedMesh& b = *back.characters[c].mesh;
    REQUIRE(b.rest_vertices_m.size() == a.rest_vertices_m.size());
    CHECK(b.triangles == a.triangles);
    CHECK(b.joints == a.joints);
    CHECK(b.region == a.region);
    for (size_t v = 0; v < a.rest_vertices_m.size(); ++v) {
      CHECK((b.rest_vertices_m[v] - a.rest_vertices_m[v]).norm() < 1e-6);
      CHECK((b.rest_normals[v] - a.rest_normals[v]).norm() < 1e-6);
      for (size_t k = 0; k < 4; ++k) CHECK(b.weights[v][k] == Approx(a.weights[v][k]).margin(1e-6));
    }
    for (size_t j = 0; j < kJointCount; ++j) CHECK((b.rest_joints_m[j] - a.rest_joints_m[j]).norm() < 1e-12);
  }
  // Topology (indices, joints, weights) is stored once for both surfaces.
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string()));
  int shared = 0;
  for (const tinygltf::Accessor& acc : model.accessors)
    shared += acc.name.find("_surface_indices") != std::string::npos;
  CHECK(shared == 1);
  // A surface bound to another skeleton is rejected.
  crowd.characters[0].mesh = sphere_surface(crowd.characters[2].shape);
  CHECK_THROWS_AS(write_crowd_glb(crowd, (dir / "bad.glb").string()), InputError);
  auto broken = std::make_shared<SkinnedMesh>(*crowd.characters[2].mesh);
  broken->weights[3] = {0.7, 0.7, 0.0, 0.0};
  crowd.characters[0].mesh = broken;
  CHECK_THROWS_WITH(write_crowd_glb(crowd, (dir / "bad.glb").string()),
                    Catch::Contains("body mesh: vertex 3: weights sum to 1.4"));
  broken->weights[3] = {1.0, 0.0, 0.0, 0.0};
  broken->rest_vertices_m[5].y() = std::nan("");
  CHECK_THROWS_WITH(write_crowd_glb(crowd, (dir / "bad.glb").string()),
                    Catch::Contains("body mesh: vertex 5: position or normal is not finite"));
}

TEST_CASE("a crowd round-trips through .glb: rotations to 1e-6, shapes and metadata exactly") {
  const auto dir = test::scratch_dir("glb-roundtrip");
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const CrowdAnimation in = random_crowd(seed, 2 + static_cast<int>(seed), test::kSanitized ? 12 : 40);
    const auto path = (dir / ("crowd" + std::to_string(seed) + ".glb")).string();
    write_crowd_glb(in, path);
    const CrowdAnimation out = read_crowd_glb(path);
    if (seed == 1)
      for (const nlohmann::json& report : khronos_validate({path}))
        CHECK(report.at("errors").get<int>() == 0);
    CHECK(out.meta.fps == in.meta.fps);
    CHECK(out.meta.seed == in.meta.seed);
    CHECK(out.meta.condition_id == in.meta.condition_id);
    CHECK(out.meta.scenario == in.meta.scenario);
    REQUIRE(out.characters.size() == in.characters.size());
    double worst_rotation = 0.0, worst_root = 0.0;
    for (size_t c = 0; c < in.characters.size(); ++c) {
      const CharacterAnimation& a = in.characters[c];
      const CharacterAnimation& b = out.characters[c];
      CHECK(b.name == a.name);
      CHECK(b.palette == a.palette);
      CHECK(b.shape.params.sex == a.shape.params.sex);
      CHECK(b.shape.params.height_m == a.shape.params.height_m);
      CHECK(b.shape.params.girth == a.shape.params.girth);
      CHECK(b.shape.rest_contact_pairs == a.shape.rest_contact_pairs);
      for (int j = 0; j < kJointCount; ++j) {
        const auto k = static_cast<size_t>(j);
        CHECK(b.shape.joint_offsets_m[k] == a.shape.joint_offsets_m[k]);
        CHECK(b.shape.capsules[k].a == a.shape.capsules[k].a);
        CHECK(b.shape.capsules[k].b == a.shape.capsules[k].b);
        CHECK(b.shape.capsules[k].radius_m == a.shape.capsules[k].radius_m);
      }
      REQUIRE(b.frames.size() == a.frames.size());
      for (size_t f = 0; f < a.frames.size(); ++f) {
        worst_root = std::max(worst_root, (b.frames[f].root_position_m - a.frames[f].root_position_m).norm());
        for (size_t j = 0; j < kJointCount; ++j)
          worst_rotation = std::max(
              worst_rotation, quat_distance(a.frames[f].local_rotations[j], b.frames[f].local_rotations[j]));
      }
    }
    INFO("worst rotation error " << worst_rotation << ", worst root error " << worst_root << " m");
    CHECK(worst_rotation <= 1e-6);
    CHECK(worst_root <= 20.0 * 1e-6);  // float storage: ~6e-8 relative at 20 m
    CHECK(out.environment.ground_plane);
    REQUIRE(out.environment.boxes.size() == 1);
    CHECK((out.environment.boxes[0].center_m - in.environment.boxes[0].center_m).norm() < 1e-12);
    CHECK((out.environment.boxes[0].half_extents_m - in.environment.boxes[0].half_extents_m).norm() < 1e-12);
    CHECK(quat_distance(out.environment.boxes[0].rotation, in.environment.boxes[0].rotation) < 1e-12);
    REQUIRE(out.environment.meshes.size() == 1);
    CHECK(out.environment.meshes[0].name == "ramp");
    CHECK(out.environment.meshes[0].triangles == in.environment.meshes[0].triangles);
    for (size_t v = 0; v < 4; ++v)
      CHECK((out.environment.meshes[0].vertices_m[v] - in.environment.meshes[0].vertices_m[v]).norm() < 1e-7);
  }
}

TEST_CASE("written .glb files pass the Khronos glTF-Validator with zero errors") {
  const auto dir = test::scratch_dir("glb-validator");
  CrowdAnimation with_env = random_crowd(11, 3, 10);
  with_env.characters[1].mesh = sphere_surface(with_env.characters[1].shape);
  with_env.characters[2].mesh = sphere_surface(with_env.characters[2].shape);
  CrowdAnimation bare = random_crowd(12, 1, 2);
  bare.environment = Environment{};
  bare.environment.ground_plane = false;
  write_crowd_glb(with_env, (dir / "env.glb").string());
  write_crowd_glb(bare, (dir / "bare.glb").string());
  for (const nlohmann::json& report : khronos_validate({dir / "env.glb", dir / "bare.glb"})) {
    INFO(report.dump(1));
    CHECK(report.at("errors").get<int>() == 0);
    CHECK(report.at("warnings").get<int>() == 0);
  }
}

TEST_CASE("the glTF-Validator check can fail: a wrong accessor bound is reported") {
  const auto dir = test::scratch_dir("glb-validator-negative");
  const auto good = dir / "good.glb";
  write_crowd_glb(random_crowd(13, 1, 2), good.string());
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  std::string err, warn;
  REQUIRE(gltf.LoadBinaryFromFile(&model, &err, &warn, good.string()));
  model.accessors[0].maxValues = {999.0};  // key_times: the declared maximum no longer matches the data
  const auto bad = dir / "bad.glb";
  REQUIRE(gltf.WriteGltfSceneToFile(&model, bad.string(), false, true, false, true));
  for (const nlohmann::json& report : khronos_validate({bad})) {
    CHECK(report.at("errors").get<int>() >= 1);
    CHECK(report.at("issues").dump().find("ACCESSOR_MAX_MISMATCH") != std::string::npos);
  }
}

TEST_CASE("writing rejects NaN poses and bad environments, naming what is wrong") {
  const auto path = (test::scratch_dir("glb-nan") / "nan.glb").string();
  CrowdAnimation crowd = random_crowd(5, 2, 3);
  crowd.characters[1].frames[2].local_rotations[kLeftKnee].x() = std::nan("");
  CHECK_THROWS_WITH(write_crowd_glb(crowd, path), Catch::Contains("c101") && Catch::Contains("left_knee"));
  crowd = random_crowd(5, 2, 3);
  crowd.characters[0].frames[1].root_position_m.y() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(write_crowd_glb(crowd, path), InputError);
  crowd = random_crowd(5, 2, 3);
  crowd.environment.boxes[0].half_extents_m.x() = 0.0;
  CHECK_THROWS_WITH(write_crowd_glb(crowd, path), Catch::Contains("box 0"));
  crowd = random_crowd(5, 2, 3);
  crowd.environment.meshes[0].triangles[0][1] = 9;
  CHECK_THROWS_WITH(write_crowd_glb(crowd, path), Catch::Contains("mesh 'ramp'"));
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_THROWS_AS(
      write_crowd_glb(random_crowd(5, 1, 2), (test::scratch_dir("glb-nan") / "no" / "dir.glb").string()),
      RuntimeError);
}

TEST_CASE("truncated and garbage .glb files give InputError naming the file") {
  const auto dir = test::scratch_dir("glb-truncated");
  const auto good = dir / "good.glb";
  write_crowd_glb(random_crowd(7, 2, 5), good.string());
  const std::string bytes = slurp(good);
  const auto cut = dir / "cut.glb";
  // Every 4 bytes through the GLB and JSON chunk headers, then ~80 cuts spread over the rest.
  std::vector<size_t> cuts;
  for (size_t n = 0; n < 64; n += 4) cuts.push_back(n);
  const size_t step = bytes.size() / (test::kSanitized ? 20 : 80) + 1;
  for (size_t n = 64; n < bytes.size(); n += step) cuts.push_back(n);
  cuts.push_back(bytes.size() - 1);
  for (size_t n : cuts) {
    spit(cut, bytes.substr(0, n));
    INFO("truncated to " << n << " of " << bytes.size() << " bytes");
    CHECK_THROWS_WITH(read_crowd_glb(cut.string()), Catch::Contains(cut.string()));
  }
  spit(cut, std::string(4096, 'x'));
  CHECK_THROWS_WITH(read_crowd_glb(cut.string()), Catch::Contains("cannot read glTF"));
  CHECK_THROWS_WITH(read_crowd_glb((dir / "absent.glb").string()),
                    Catch::Contains("absent.glb: no such file"));
}

TEST_CASE("corrupt content is caught and named: NaN data, renamed joints, missing channels") {
  const auto dir = test::scratch_dir("glb-corrupt");
  const auto good = dir / "good.glb";
  write_crowd_glb(random_crowd(8, 2, 6), good.string());
  auto edit = [&](const std::string& name, auto&& change) {
    tinygltf::Model model;
    tinygltf::TinyGLTF gltf;
    std::string err, warn;
    REQUIRE(gltf.LoadBinaryFromFile(&model, &err, &warn, good.string()));
    change(model);
    const auto path = dir / name;
    REQUIRE(gltf.WriteGltfSceneToFile(&model, path.string(), false, true, false, true));
    return path.string();
  };
  auto accessor_named = [](const tinygltf::Model& m, const std::string& name) {
    for (size_t i = 0; i < m.accessors.size(); ++i)
      if (m.accessors[i].name == name) return i;
    FAIL("no accessor " << name);
    return size_t{0};
  };
  const std::string nan_file = edit("nan.glb", [&](tinygltf::Model& m) {
    const tinygltf::Accessor& a = m.accessors[accessor_named(m, "c101/right_elbow/rotation")];
    const tinygltf::BufferView& v = m.bufferViews[static_cast<size_t>(a.bufferView)];
    const float nan = std::nanf("");
    std::memcpy(&m.buffers[0].data[v.byteOffset + a.byteOffset + 4 * sizeof(float) * 3 + 4], &nan,
                sizeof nan);
  });
  CHECK_THROWS_WITH(read_crowd_glb(nan_file), Catch::Contains("c101/right_elbow/rotation") &&
                                                  Catch::Contains("element 3 is not a finite number"));

  const std::string renamed = edit("renamed.glb", [&](tinygltf::Model& m) {
    for (auto& n : m.nodes)
      if (n.name == "left_knee") n.name = "knee";
  });
  CHECK_THROWS_WITH(read_crowd_glb(renamed),
                    Catch::Contains("'knee'") && Catch::Contains("must be named 'left_knee'"));

  const std::string no_channel =
      edit("nochannel.glb", [&](tinygltf::Model& m) { m.animations[0].channels.pop_back(); });
  CHECK_THROWS_WITH(read_crowd_glb(no_channel),
                    Catch::Contains("c101") && Catch::Contains("no root translation"));

  const std::string short_data = edit("short.glb", [&](tinygltf::Model& m) {
    m.accessors[accessor_named(m, "c100/head/rotation")].count = 1000000;
  });
  CHECK_THROWS_WITH(read_crowd_glb(short_data),
                    Catch::Contains("c100/head/rotation") && Catch::Contains("do not fit"));

  const std::string bad_times = edit("times.glb", [&](tinygltf::Model& m) {
    const tinygltf::Accessor& a = m.accessors[accessor_named(m, "key_times")];
    const tinygltf::BufferView& v = m.bufferViews[static_cast<size_t>(a.bufferView)];
    const float t = 99.0f;
    std::memcpy(&m.buffers[0].data[v.byteOffset + 2 * sizeof(float)], &t, sizeof t);
  });
  CHECK_THROWS_WITH(read_crowd_glb(bad_times), Catch::Contains("key 2 is at 99"));

  const std::string no_meta =
      edit("nometa.glb", [&](tinygltf::Model& m) { m.scenes[0].extras = tinygltf::Value(); });
  CHECK_THROWS_WITH(read_crowd_glb(no_meta), Catch::Contains("not a crowdlab crowd file"));

  const std::string bad_shape = edit("shape.glb", [&](tinygltf::Model& m) {
    for (auto& n : m.nodes)
      if (n.name == "c100") {
        auto obj = n.extras.Get<tinygltf::Value::Object>();
        auto character = obj["crowdlab_character"].Get<tinygltf::Value::Object>();
        character["sex"] = tinygltf::Value(std::string("robot"));
        obj["crowdlab_character"] = tinygltf::Value(character);
        n.extras = tinygltf::Value(obj);
      }
  });
  CHECK_THROWS_WITH(read_crowd_glb(bad_shape),
                    Catch::Contains("'c100'") && Catch::Contains("'sex' must be female or male"));
}

TEST_CASE("crowdlab export-csv writes one row per character per frame") {
  const auto dir = test::scratch_dir("glb-csv");
  CrowdAnimation crowd = random_crowd(9, 2, 4);
  // Known headings: character c turns by c * 0.5 rad about +Y at frame f, plus f * 0.1 rad.
  for (size_t c = 0; c < 2; ++c)
    for (size_t f = 0; f < 4; ++f)
      crowd.characters[c].frames[f].local_rotations[0] =
          Quat(Eigen::AngleAxisd(0.5 * static_cast<double>(c) + 0.1 * static_cast<double>(f), Vec3::UnitY()));
  const auto glb = dir / "crowd.glb";
  write_crowd_glb(crowd, glb.string());
  const auto csv = dir / "roots.csv";
  const auto r = test::run_cli({"export-csv", glb.string(), "--out", csv.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::istringstream in(slurp(csv));
  std::string line;
  std::getline(in, line);
  CHECK(line == "character,frame,time_s,x,z,heading_rad");
  int rows = 0;
  while (std::getline(in, line)) {
    const size_t c = static_cast<size_t>(rows / 4), f = static_cast<size_t>(rows % 4);
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    REQUIRE(cells.size() == 6);
    CHECK(cells[0] == crowd.characters[c].name);
    CHECK(std::stoul(cells[1]) == f);
    CHECK(std::stod(cells[2]) == Approx(static_cast<double>(f) / crowd.meta.fps));
    CHECK(std::stod(cells[3]) == Approx(crowd.characters[c].frames[f].root_position_m.x()).margin(1e-5));
    CHECK(std::stod(cells[4]) == Approx(crowd.characters[c].frames[f].root_position_m.z()).margin(1e-5));
    CHECK(std::stod(cells[5]) ==
          Approx(0.5 * static_cast<double>(c) + 0.1 * static_cast<double>(f)).margin(1e-6));
    ++rows;
  }
  CHECK(rows == 8);
  const auto bad = test::run_cli({"export-csv", (dir / "absent.glb").string(), "--out", csv.string()});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Contains("absent.glb: no such file"));
  CHECK(test::run_cli({"export-csv", "--help"}).out.find("heading_rad") != std::string::npos);
}

TEST_CASE("a dressed surface's labels (SurfaceKind per vertex) round-trip through _SURFACE") {
  const auto dir = test::scratch_dir("glb-surface-labels");
  CrowdAnimation crowd = random_crowd(22, 2, 3);
  auto labelled = std::make_shared<SkinnedMesh>(*sphere_surface(crowd.characters[0].shape));
  for (size_t v = 0; v < labelled->rest_vertices_m.size(); ++v)
    labelled->surface.push_back(static_cast<std::uint8_t>(v % static_cast<size_t>(SurfaceKind::kCount)));
  crowd.characters[0].mesh = labelled;
  crowd.characters[1].mesh = sphere_surface(crowd.characters[1].shape);  // no labels: none written
  const auto file = dir / "labels.glb";
  write_crowd_glb(crowd, file.string());
  const CrowdAnimation back = read_crowd_glb(file.string());
  REQUIRE(back.characters[0].mesh);
  CHECK(back.characters[0].mesh->surface == labelled->surface);
  CHECK(back.characters[1].mesh->surface.empty());
  // An unknown label is refused by the validator (and so by the writer).
  auto bad = std::make_shared<SkinnedMesh>(*labelled);
  bad->surface[3] = 200;
  CHECK_THROWS_AS(validate_skinned_mesh(*bad, "test"), InputError);
}

TEST_CASE("an animation channel with no keys says so, not 'has 0 keys, expected 0'") {
  // Issue 33: acc_count_zero.glb.
  const auto dir = test::scratch_dir("glb-zero-keys");
  const auto good = dir / "good.glb";
  write_crowd_glb(random_crowd(9, 1, 4), good.string());
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  std::string err, warn;
  REQUIRE(gltf.LoadBinaryFromFile(&model, &err, &warn, good.string()));
  REQUIRE_FALSE(model.animations.empty());
  const auto& anim = model.animations[0];
  const int input = anim.samplers[static_cast<size_t>(anim.channels[0].sampler)].input;
  for (auto& sampler : model.animations[0].samplers)  // every channel shares the key times: empty them all
    if (sampler.input == input) model.accessors[static_cast<size_t>(input)].count = 0;
  const auto path = dir / "acc_count_zero.glb";
  REQUIRE(gltf.WriteGltfSceneToFile(&model, path.string(), false, true, false, true));
  try {
    read_crowd_glb(path.string());
    FAIL("expected InputError");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Catch::Contains("acc_count_zero.glb") && Catch::Contains("animation channel 0") &&
                      Catch::Contains("no keys"));
    CHECK_THAT(m, !Catch::Contains("expected 0"));
  }
}

}  // namespace test_crowd_glb
