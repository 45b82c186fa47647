// glTF skinned-animation import: skeleton from the skin, baked armature scale, LINEAR/STEP sampling,
// retargeting through the same path as BVH, and errors naming file and element.
#include <tiny_gltf.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "framework/animation/gltf_motion.hpp"
#include "framework/animation/retarget.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_gltf_motion {

using namespace crowdlab;

namespace {
int add_accessor(tinygltf::Model& m, const std::vector<float>& data, int type) {
  tinygltf::Buffer& b = m.buffers.front();
  const size_t offset = b.data.size();
  b.data.resize(offset + data.size() * sizeof(float));
  std::memcpy(b.data.data() + offset, data.data(), data.size() * sizeof(float));
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = offset;
  v.byteLength = data.size() * sizeof(float);
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = type;
  a.count = data.size() / static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

// Our skeleton as glTF nodes (SMPL names, centimetres) under an "Armature" node scaled 0.01, with a
// skin, and one animation: the left knee flexes 0 -> 90 deg about +X (LINEAR) and the pelvis moves
// 150 cm forward over 1 s; the right elbow steps to 60 deg at 0.5 s (STEP).
std::filesystem::path write_test_gltf(const BodyShape& s, const std::filesystem::path& dir) {
  tinygltf::Model m;
  m.buffers.resize(1);
  tinygltf::Node armature;
  armature.name = "Armature";
  armature.scale = {0.01, 0.01, 0.01};
  m.nodes.push_back(armature);
  tinygltf::Skin skin;
  for (int j = 0; j < kJointCount; ++j) {
    tinygltf::Node n;
    n.name = std::string(joint_name(j));
    const Vec3 o = s.joint_offsets_m[static_cast<size_t>(j)] * 100.0;
    n.translation = {o.x(), o.y(), o.z()};
    m.nodes.push_back(n);
    skin.joints.push_back(j + 1);
    const int parent = kJointParent[static_cast<size_t>(j)];
    m.nodes[static_cast<size_t>(parent < 0 ? 0 : parent + 1)].children.push_back(j + 1);
  }
  m.skins.push_back(skin);
  tinygltf::Animation anim;
  const int times = add_accessor(m, {0.0f, 1.0f}, TINYGLTF_TYPE_SCALAR);
  const float h = static_cast<float>(std::sqrt(0.5));
  const int knee = add_accessor(m, {0, 0, 0, 1, h, 0, 0, h}, TINYGLTF_TYPE_VEC4);
  const Vec3 p0 = s.joint_offsets_m[kPelvis] * 100.0;
  const int root = add_accessor(
      m, {float(p0.x()), float(p0.y()), float(p0.z()), float(p0.x()), float(p0.y()), float(p0.z() + 150)},
      TINYGLTF_TYPE_VEC3);
  const int step_times = add_accessor(m, {0.0f, 0.5f}, TINYGLTF_TYPE_SCALAR);
  const float c = static_cast<float>(std::cos(0.5236)), sn = static_cast<float>(std::sin(0.5236));
  const int elbow = add_accessor(m, {0, 0, 0, 1, 0, sn, 0, c}, TINYGLTF_TYPE_VEC4);
  auto channel = [&](int input, int output, int node, const char* what, const char* interp) {
    tinygltf::AnimationSampler smp;
    smp.input = input;
    smp.output = output;
    smp.interpolation = interp;
    anim.samplers.push_back(smp);
    tinygltf::AnimationChannel ch;
    ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
    ch.target_node = node + 1;
    ch.target_path = what;
    anim.channels.push_back(ch);
  };
  channel(times, knee, kLeftKnee, "rotation", "LINEAR");
  channel(times, root, kPelvis, "translation", "LINEAR");
  channel(step_times, elbow, kRightElbow, "rotation", "STEP");
  m.animations.push_back(anim);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  m.asset.version = "2.0";
  const auto file = dir / "skeleton.gltf";
  tinygltf::TinyGLTF writer;
  REQUIRE(writer.WriteGltfSceneToFile(&m, file.string(), true, true, true, false));
  return file;
}
}  // namespace

TEST_CASE("glTF animation import: sampling, baked armature scale, retargeting round trip") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.7, 1.0});
  const auto file = write_test_gltf(s, test::scratch_dir("gltf_motion"));
  const BvhMotion m = import_gltf_animation(file, 0, 0, 30.0);
  REQUIRE(m.joints.size() == static_cast<size_t>(kJointCount));
  CHECK(m.frame_count == 31);
  const int knee = m.find_joint("left_knee");
  const int elbow = m.find_joint("right_elbow");
  REQUIRE(knee >= 0);
  CHECK(Eigen::AngleAxisd(m.local_transform(knee, 15).rotation).angle() ==
        Approx(3.14159265 / 4).margin(1e-4));
  CHECK(Eigen::AngleAxisd(m.local_transform(elbow, 14).rotation).angle() ==
        Approx(0).margin(1e-6));  // t < 0.5: STEP holds
  CHECK(Eigen::AngleAxisd(m.local_transform(elbow, 16).rotation).angle() ==
        Approx(1.0472).margin(1e-3));  // after the step
  // Armature scale 0.01 is baked: metres.
  const auto w = m.world_transforms(30);
  CHECK((w[0].translation - (s.joint_offsets_m[kPelvis] + Vec3(0, 0, 1.5))).norm() < 1e-5);
  // Retargeting onto the same body reproduces the pose (knee at 45 deg in frame 15).
  const RetargetedClip c = retarget_bvh(m, s, RetargetOptions{false});
  CHECK(c.scale == Approx(1.0).epsilon(1e-6));
  Pose expect;
  expect.local_rotations[kLeftKnee] = Quat(Eigen::AngleAxisd(3.14159265358979 / 4, Vec3::UnitX()));
  expect.local_rotations[kRightElbow] =
      Quat(Eigen::AngleAxisd(2 * 0.5236, Vec3::UnitY()));  // STEP key at t = 0.5
  const auto a = joint_positions(s, expect), b = joint_positions(s, c.frames[15]);
  for (int j = 0; j < kJointCount; ++j)
    CHECK(((a[static_cast<size_t>(j)] - a[0]) - (b[static_cast<size_t>(j)] - b[0])).norm() < 1e-4);
}

TEST_CASE("glTF animation import: errors name the file and the element") {
  const auto dir = test::scratch_dir("gltf_motion_errors");
  const auto bad = dir / "bad.gltf";
  std::ofstream(bad) << "{ this is not json";
  CHECK_THROWS_WITH(import_gltf_animation(bad), Catch::Contains("bad.gltf"));
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.6, 1.0});
  const auto good = write_test_gltf(s, dir);
  CHECK_THROWS_WITH(import_gltf_animation(good, 3),
                    Catch::Contains("skeleton.gltf") && Catch::Contains("animations[3]"));
  CHECK_THROWS_AS(import_gltf_animation(dir / "missing.glb"), InputError);
}

namespace {
// A .gltf whose only animation turns node `target` (LINEAR, key times `t0`, `t1` seconds), with `nodes`
// given as JSON text; its buffer lies beside it.
std::filesystem::path write_node_clip(const std::filesystem::path& dir, const std::string& name,
                                      const std::string& nodes, int target, float t1 = 1.0f) {
  const float data[10] = {0.0f, t1, 0, 0, 0, 1, 0.6f, 0, 0, 0.8f};
  std::ofstream(dir / (name + ".bin"), std::ios::binary)
      .write(reinterpret_cast<const char*>(data), sizeof data);
  const std::string json =
      R"({"asset":{"version":"2.0"},"buffers":[{"uri":")" + name +
      R"(.bin","byteLength":40}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":8},{"buffer":0,"byteOffset":8,"byteLength":32}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":2,"type":"SCALAR"},)"
      R"({"bufferView":1,"componentType":5126,"count":2,"type":"VEC4"}],)"
      R"("animations":[{"samplers":[{"input":0,"output":1}],"channels":[{"sampler":0,"target":{"node":)" +
      std::to_string(target) + R"(,"path":"rotation"}}]}],"nodes":)" + nodes + "}";
  const auto file = dir / (name + ".gltf");
  std::ofstream(file) << json;
  return file;
}
}  // namespace

TEST_CASE("glTF animation import: a 100,000-node chain imports without recursing, and cycles are refused") {
  // Issue 21: the recursive skeleton walk overflowed the stack (SIGSEGV) on a fuzzed parent->child chain,
  // and the walk up to the roots never ended on a cycle.
  const auto dir = test::scratch_dir("gltf_motion_chain");
  constexpr int kNodes = 100000;
  std::string chain = "[";
  for (int i = 0; i + 1 < kNodes; ++i) chain += R"({"children":[)" + std::to_string(i + 1) + "]},";
  chain += R"({"name":"tip"}])";
  const BvhMotion m = import_gltf_animation(write_node_clip(dir, "chain", chain, kNodes - 1), 0, 0, 1.0);
  REQUIRE(m.joints.size() == static_cast<size_t>(kNodes));
  CHECK(m.joints.back().name == "tip");
  CHECK(m.joints.back().parent == kNodes - 2);
  CHECK(m.frame_count == 2);
  CHECK(Eigen::AngleAxisd(m.local_transform(kNodes - 1, 1).rotation).angle() ==
        Approx(2 * std::atan2(0.6, 0.8)).margin(1e-5));

  const auto cycle =
      write_node_clip(dir, "cycle", R"([{"children":[1]},{"children":[2]},{"children":[0]}])", 2);
  CHECK_THROWS_WITH(import_gltf_animation(cycle), Catch::Contains("cycle.gltf") &&
                                                      Catch::Contains("own ancestor") &&
                                                      Catch::Contains("cycle"));
  const auto two_parents =
      write_node_clip(dir, "two_parents", R"([{"children":[2]},{"children":[2]},{}])", 2);
  CHECK_THROWS_WITH(import_gltf_animation(two_parents),
                    Catch::Contains("nodes[2] is a child of both nodes[0] and nodes[1]"));
  const auto no_target = write_node_clip(dir, "no_target", "[{}]", 7);
  CHECK_THROWS_WITH(import_gltf_animation(no_target), Catch::Contains("no_target.gltf") &&
                                                          Catch::Contains("animations[0].channels[0]") &&
                                                          Catch::Contains("target node 7 does not exist"));
  // A key time of 1e7 s would be sampled into 300 million frames.
  const auto long_clip = write_node_clip(dir, "long", "[{}]", 0, 1e7f);
  CHECK_THROWS_WITH(import_gltf_animation(long_clip), Catch::Contains("long.gltf") &&
                                                          Catch::Contains("animations[0]") &&
                                                          Catch::Contains("kMaxGltfClipValues"));
}

}  // namespace test_gltf_motion
