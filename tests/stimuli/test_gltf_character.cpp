// Characters from files: a skinned glTF character (written here from a procedural mannequin, with
// Mixamo joint names) is loaded, fitted to other bodies, rendered, and bad files fail clearly.
#include <tiny_gltf.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "framework/core/capsule.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/io/gltf_builder.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "stimuli/gltf_character.hpp"
#include "stimuli/palette.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/synthetic_crowd.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_gltf_character {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

// Mixamo names of the 24 SMPL joints (the convention of Mixamo's exported rigs).
const char* const kMixamoNames[kJointCount] = {
    "Hips",        "LeftUpLeg",    "RightUpLeg",    "Spine",     "LeftLeg",         "RightLeg",
    "Spine1",      "LeftFoot",     "RightFoot",     "Spine2",    "LeftToeBase",     "RightToeBase",
    "Neck",        "LeftShoulder", "RightShoulder", "Head",      "LeftArm",         "RightArm",
    "LeftForeArm", "RightForeArm", "LeftHand",      "RightHand", "LeftHandMiddle1", "RightHandMiddle1"};

/// Appends the inverse bind matrix of a joint at `p` with the world axes (a translation by -p),
/// column-major as glTF stores it.
void append_translation_ibm(const Vec3& p, std::vector<float>& ibm) {
  ibm.insert(ibm.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0});
  ibm.insert(ibm.end(),
             {static_cast<float>(-p.x()), static_cast<float>(-p.y()), static_cast<float>(-p.z()), 1});
}

struct WriteOptions {
  bool bad_joint_index = false;   ///< one vertex uses a joint the skin does not have
  bool unmappable_names = false;  ///< joints named bone0, bone1, ...
  bool centimetres = false;       ///< mesh and joints in cm under an "Armature" node scaled by 0.01
};

/// Writes a .glb: the mannequin of `shape` (5 cm grid) bound to a Mixamo-named skeleton under an
/// "Armature" node, with an extra unweighted finger joint, COLOR_0 from palette 3 (linear RGB) and a
/// material. Returns the number of vertices.
size_t write_test_character(const std::filesystem::path& path, const BodyShape& shape, WriteOptions w = {}) {
  MannequinOptions mo;
  mo.voxel_m = 0.05;
  const MannequinMesh mesh = build_mannequin_mesh(shape, mo);
  const BoneTransforms rest = forward_kinematics(shape, Pose::rest(shape));
  tinygltf::Model model;
  GltfBuilder builder(model);
  tinygltf::Node armature;
  armature.name = "Armature";
  const double unit = w.centimetres ? 100.0 : 1.0;
  if (w.centimetres) armature.scale = {0.01, 0.01, 0.01};
  model.nodes.push_back(armature);
  const int first_joint = 1;
  std::vector<float> ibm;
  for (int j = 0; j < kJointCount; ++j) {
    tinygltf::Node n;
    n.name = w.unmappable_names ? "bone" + std::to_string(j) : std::string("mixamorig:") + kMixamoNames[j];
    const int parent = kJointParent[static_cast<size_t>(j)];
    const Vec3 t = unit * (rest[static_cast<size_t>(j)].translation -
                           (parent >= 0 ? rest[static_cast<size_t>(parent)].translation : Vec3::Zero()));
    n.translation = {t.x(), t.y(), t.z()};
    model.nodes.push_back(n);
    append_translation_ibm(unit * rest[static_cast<size_t>(j)].translation, ibm);
  }
  model.nodes[0].children.push_back(first_joint);
  for (int j = 1; j < kJointCount; ++j)
    model.nodes[static_cast<size_t>(first_joint + kJointParent[static_cast<size_t>(j)])].children.push_back(
        first_joint + j);
  tinygltf::Node finger;  // unmapped: follows its nearest mapped ancestor, the SMPL left wrist
  finger.name = "mixamorig:LeftHandIndex1";
  finger.translation = {0.05 * unit, 0.0, 0.02 * unit};
  const int finger_node = static_cast<int>(model.nodes.size());
  model.nodes.push_back(finger);
  model.nodes[static_cast<size_t>(first_joint + kLeftWrist)].children.push_back(finger_node);
  append_translation_ibm(unit * (rest[kLeftWrist].translation + Vec3(0.05, 0.0, 0.02)), ibm);

  std::vector<float> pos, nrm, weights, colour;
  std::vector<std::uint8_t> joints;
  const Palette& pal = palette(3);
  for (const MannequinVertex& v : mesh.vertices) {
    for (float x : v.position) pos.push_back(static_cast<float>(unit) * x);
    nrm.insert(nrm.end(), v.normal.begin(), v.normal.end());
    for (int k = 0; k < 4; ++k) {
      joints.push_back(v.bones[static_cast<size_t>(k)]);
      weights.push_back(static_cast<float>(v.weights[static_cast<size_t>(k)]) / 255.0f);
    }
    const Rgb c = pal.colour(static_cast<SkinRegion>(v.region));
    for (float x : c) colour.push_back(x * x);  // glTF colours are linear
  }
  if (w.bad_joint_index) joints[0] = 40;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] =
      builder.add_floats(pos, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true, "pos");
  prim.attributes["NORMAL"] =
      builder.add_floats(nrm, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false, "nrm");
  prim.attributes["COLOR_0"] =
      builder.add_floats(colour, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false, "col");
  prim.attributes["WEIGHTS_0"] =
      builder.add_floats(weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false, "weights");
  prim.attributes["JOINTS_0"] = builder.add_joints_u8(joints, "joints");
  prim.indices = builder.add_indices_u32(mesh.indices, "indices");
  tinygltf::Material mat;
  mat.name = "cloth";
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  model.materials.push_back(mat);
  prim.material = 0;
  tinygltf::Mesh gm;
  gm.primitives.push_back(prim);
  model.meshes.push_back(gm);
  tinygltf::Skin skin;
  for (int j = 0; j < kJointCount; ++j) skin.joints.push_back(first_joint + j);
  skin.joints.push_back(finger_node);
  skin.inverseBindMatrices = builder.add_floats(ibm, TINYGLTF_TYPE_MAT4, 16, 0, false, "ibm");
  model.skins.push_back(skin);
  tinygltf::Node body;
  body.name = "Body";
  body.mesh = 0;
  body.skin = 0;
  model.nodes.push_back(body);
  tinygltf::Scene scene;
  scene.nodes = {0, static_cast<int>(model.nodes.size()) - 1};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  REQUIRE(writer.WriteGltfSceneToFile(&model, path.string(), false, true, false, true));
  return mesh.vertices.size();
}

double distance_to_body(const Vec3& p, const WorldCapsules& caps) {
  double d = 1e9;
  for (const Capsule& c : caps)
    d = std::min(d, segment_closest_points(p, p, c.a, c.b).distance_m - c.radius_m);
  return d;
}

}  // namespace

TEST_CASE("a skinned glTF character loads, maps onto the SMPL joints and fits other bodies", "[stimuli]") {
  const auto dir = test::scratch_dir("gltf_character");
  const BodyShape source = make_procedural_body({Sex::kFemale, 1.62, 1.0});
  const bool centimetres = GENERATE(false, true);  // a centimetre rig under a 0.01-scaled armature too
  INFO("centimetres " << centimetres);
  const auto path = dir / (centimetres ? "woman_cm.glb" : "woman.glb");
  const size_t vertices = write_test_character(path, source, {false, false, centimetres});
  const GltfCharacter c = load_gltf_character(path);
  CHECK(c.positions.size() == vertices);
  CHECK(c.joint_names.size() == kJointCount + 1);
  for (int j = 0; j < kJointCount; ++j) CHECK(c.smpl_source[static_cast<size_t>(j)] == j);
  CHECK(c.smpl_of_joint[kJointCount] == kLeftWrist);  // the unmapped finger follows its hand
  CHECK(c.colours[0][3] == 255);

  for (const BodyParams& params : {BodyParams{Sex::kFemale, 1.62, 1.0}, BodyParams{Sex::kMale, 1.92, 1.2},
                                   BodyParams{Sex::kFemale, 1.50, 0.85}}) {
    INFO("height " << params.height_m << " girth " << params.girth);
    const BodyShape target = make_procedural_body(params);
    const MannequinMesh fitted = fit_gltf_character(c, target);
    REQUIRE(fitted.vertices.size() == vertices);
    REQUIRE(fitted.indices == c.indices);
    // The mesh stands on the floor, as tall as the body, and hugs the body's capsules.
    const WorldCapsules caps = world_capsules(target, Pose::rest(target));
    double y_lo = 1e9, y_hi = -1e9;
    int near = 0;
    for (const MannequinVertex& v : fitted.vertices) {
      const Vec3 p(v.position[0], v.position[1], v.position[2]);
      y_lo = std::min(y_lo, p.y());
      y_hi = std::max(y_hi, p.y());
      near += std::abs(distance_to_body(p, caps)) < 0.05;
      int sum = 0;
      for (int k = 0; k < 4; ++k) sum += v.weights[static_cast<size_t>(k)];
      REQUIRE(sum == 255);
      REQUIRE(v.colour[3] == 255);
    }
    CHECK(y_hi - y_lo == Approx(params.height_m).epsilon(0.05));
    CHECK(std::abs(y_lo) < 0.05);
    CHECK(near > 0.9 * static_cast<double>(vertices));
  }
}

TEST_CASE("glTF characters render in place of the mannequin, deterministically", "[stimuli]") {
  const auto dir = test::scratch_dir("gltf_character_render");
  const auto path = dir / "man.glb";
  write_test_character(path, make_procedural_body({Sex::kMale, 1.8, 1.0}));
  SyntheticCrowdOptions co;
  co.characters = 3;
  co.spacing_m = 0.9;
  co.frames = 2;
  co.stage = false;
  CrowdAnimation crowd = make_synthetic_crowd(co);
  crowd.environment.ground_plane = false;
  RenderOptions options;
  options.width = 320;
  options.height = 180;
  Renderer renderer;
  const Camera cam = Viewpoint(ViewpointId::V1, crowd, options.width, options.height).at(1);
  const BgrImage mannequin = render_frame(renderer, crowd, options, cam, 1);
  options.character_files = {path.string()};
  const BgrImage file = render_frame(renderer, crowd, options, cam, 1);
  const BgrImage again = render_frame(renderer, crowd, options, cam, 1);
  CHECK(file.bgr == again.bgr);
  // Characters are drawn where the camera model puts their heads and chests (not background) ...
  const Rgb bg = options.scene.background;
  int hit = 0, checked = 0;
  for (const CharacterAnimation& ch : crowd.characters) {
    const BoneTransforms bones = forward_kinematics(ch.shape, ch.frames[1]);
    for (int joint : {static_cast<int>(kSpine3), static_cast<int>(kHead)}) {
      const auto px = cam.project(bones[static_cast<size_t>(joint)].translation + Vec3(0, 0.05, 0));
      REQUIRE(px);
      const size_t at = 3 * (static_cast<size_t>(px->y()) * 320 + static_cast<size_t>(px->x()));
      ++checked;
      hit += std::abs(file.bgr[at + 2] - std::lround(bg[0] * 255)) > 6 ||
             std::abs(file.bgr[at + 1] - std::lround(bg[1] * 255)) > 6 ||
             std::abs(file.bgr[at] - std::lround(bg[2] * 255)) > 6;
    }
  }
  CHECK(hit == checked);
  // ... in the file's colours (palette 3 everywhere), not the three mannequins' own palettes.
  size_t differing = 0;
  for (size_t i = 0; i < file.bgr.size(); ++i) differing += file.bgr[i] != mannequin.bgr[i];
  CHECK(differing > 300);
  // A fresh renderer (files read again) gives the same pixels.
  Renderer fresh;
  CHECK(render_frame(fresh, crowd, options, cam, 1).bgr == file.bgr);
}

TEST_CASE("bad glTF characters fail with the file and the element named", "[stimuli]") {
  const auto dir = test::scratch_dir("gltf_character_bad");
  const BodyShape shape = make_procedural_body({Sex::kFemale, 1.65, 1.0});
  auto message = [](const std::filesystem::path& p) -> std::string {
    try {
      load_gltf_character(p);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  write_test_character(dir / "bad_joint.glb", shape, {true, false});
  std::string m = message(dir / "bad_joint.glb");
  CHECK(m.find("bad_joint.glb") != std::string::npos);
  CHECK(m.find("meshes[0].primitives[0].attributes.JOINTS_0") != std::string::npos);
  write_test_character(dir / "names.glb", shape, {false, true});
  m = message(dir / "names.glb");
  CHECK(m.find("names.glb") != std::string::npos);
  CHECK(m.find("pelvis") != std::string::npos);
  m = message(dir / "missing.glb");
  CHECK(m.find("missing.glb") != std::string::npos);
  std::ofstream(dir / "garbage.glb") << "glTF but not really";
  m = message(dir / "garbage.glb");
  CHECK(m.find("garbage.glb") != std::string::npos);
  // A file with a mesh but no skin.
  tinygltf::Model model;
  tinygltf::Node n;
  n.name = "static";
  model.nodes.push_back(n);
  tinygltf::TinyGLTF writer;
  REQUIRE(writer.WriteGltfSceneToFile(&model, (dir / "noskin.gltf").string(), false, true, false, false));
  m = message(dir / "noskin.gltf");
  CHECK(m.find("no skinned mesh") != std::string::npos);
}

TEST_CASE("render.characters in a spec and --character on the command line", "[stimuli][cli]") {
  const auto dir = test::scratch_dir("gltf_character_cli");
  const auto path = dir / "person.glb";
  write_test_character(path, make_procedural_body({Sex::kMale, 1.75, 1.0}));
  const std::string mp4 = (dir / "clip.mp4").string();
  const auto ok = test::run_cli({"-q", "render", "--synthetic", "2", "--character", path.string(), "--out",
                                 mp4, "--width", "160", "--height", "96", "--max-frames", "2"});
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(std::filesystem::file_size(mp4) > 100);
  const std::string spec_head =
      "crowdlab: 1\nname: t\nseed: 1\nscenario: {type: stationary, area: {width_m: 2.5, depth_m: 2.5}}\n"
      "factors:\n  density: [3.33]\nrender:\n  characters: [";
  const ExperimentSpec spec = load_experiment_spec_text(spec_head + "person.glb]\n", "t.yaml", dir.string());
  REQUIRE(spec.render.characters.size() == 1);
  CHECK(std::filesystem::path(spec.render.characters[0]).filename() == "person.glb");
  try {
    load_experiment_spec_text(spec_head + "nobody.glb]\n", "t.yaml", dir.string());
    FAIL("expected a spec error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("render.characters[0]") != std::string::npos);
  }
}

}  // namespace test_gltf_character
