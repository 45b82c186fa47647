#include "framework/io/write_crowd_glb.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "crowdlab_version.hpp"
#include "framework/core/appearance.hpp"
#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/write_file.hpp"
#include "framework/io/capsule_mesh.hpp"
#include "framework/io/crowd_glb_format.hpp"
#include "framework/io/gltf_builder.hpp"
#include "framework/io/validate_environment.hpp"

namespace crowdlab {
namespace {

// Capsule tessellation: 8 segments x 3 rings per hemisphere = 50 vertices per bone, enough to read
// as a body in a viewer while keeping a 60-character file small.
constexpr int kCapsuleSegments = 8;
constexpr int kCapsuleRings = 3;
// Ground quad margin around the area the roots cover, metres.
constexpr double kGroundMargin_m = 2.0;

// Muted clothing colours (linear RGB) indexed by CharacterAnimation::palette.
constexpr std::array<std::array<double, 3>, 8> kPalette = {{{0.55, 0.20, 0.18},
                                                            {0.18, 0.32, 0.55},
                                                            {0.22, 0.45, 0.25},
                                                            {0.60, 0.50, 0.20},
                                                            {0.40, 0.25, 0.50},
                                                            {0.20, 0.45, 0.50},
                                                            {0.50, 0.50, 0.50},
                                                            {0.30, 0.22, 0.15}}};

nlohmann::json vec3_json(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json character_extras(const CharacterAnimation& ch) {
  const BodyShape& s = ch.shape;
  nlohmann::json offsets = nlohmann::json::array();
  nlohmann::json capsules = nlohmann::json::array();
  for (int j = 0; j < kJointCount; ++j) {
    offsets.push_back(vec3_json(s.joint_offsets_m[static_cast<size_t>(j)]));
    const Capsule& c = s.capsules[static_cast<size_t>(j)];
    capsules.push_back({{"a", vec3_json(c.a)}, {"b", vec3_json(c.b)}, {"radius_m", c.radius_m}});
  }
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& [i, j] : s.rest_contact_pairs) pairs.push_back({i, j});
  nlohmann::json e = {{"name", ch.name},
                      {"palette", ch.palette},
                      {"sex", std::string(to_string(s.params.sex))},
                      {"height_m", s.params.height_m},
                      {"girth", s.params.girth},
                      {"joint_offsets_m", offsets},
                      {"capsules", capsules},
                      {"rest_contact_pairs", pairs}};
  if (ch.mesh) e["body_mesh"] = true;  // the skin mesh is the character's own surface (read back)
  return e;
}

std::vector<double> quat_xyzw(const Quat& q) {
  return {q.x(), q.y(), q.z(), q.w()};
}

int add_node(tinygltf::Model& model, tinygltf::Node node) {
  model.nodes.push_back(std::move(node));
  return static_cast<int>(model.nodes.size()) - 1;
}

int palette_material(tinygltf::Model& model, std::vector<int>& cache, int palette) {
  const size_t k = static_cast<size_t>(palette) % kPalette.size();
  if (cache[k] >= 0) return cache[k];
  tinygltf::Material m;
  m.name = "palette_" + std::to_string(k);
  m.pbrMetallicRoughness.baseColorFactor = {kPalette[k][0], kPalette[k][1], kPalette[k][2], 1.0};
  m.pbrMetallicRoughness.metallicFactor = 0.0;
  m.pbrMetallicRoughness.roughnessFactor = 0.8;
  model.materials.push_back(m);
  cache[k] = static_cast<int>(model.materials.size()) - 1;
  return cache[k];
}

// A triangle primitive with a character's POSITION and NORMAL accessors (flat float xyz lists).
tinygltf::Primitive positions_normals_primitive(GltfBuilder& builder, const std::vector<float>& pos,
                                                const std::vector<float>& nrm, const std::string& name) {
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] =
      builder.add_floats(pos, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true, name + "_positions");
  prim.attributes["NORMAL"] =
      builder.add_floats(nrm, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false, name + "_normals");
  return prim;
}

// Accessors of a skinned surface's topology (indices, joints, weights), shared by every character
// whose mesh has the same topology (all MPFB2 bodies of one asset folder do): only positions and
// normals are stored per character.
struct SharedTopology {
  const SkinnedMesh* mesh = nullptr;
  int indices = -1, joints = -1, weights = -1;
};

bool same_topology(const SkinnedMesh& a, const SkinnedMesh& b) {
  return a.triangles == b.triangles && a.joints == b.joints && a.weights == b.weights;
}

// The primitive of a character's own skinned surface (CharacterAnimation::mesh).
tinygltf::Primitive skinned_surface_primitive(GltfBuilder& builder, const CharacterAnimation& ch,
                                              std::vector<SharedTopology>& shared) {
  const SkinnedMesh& m = *ch.mesh;
  std::vector<float> pos, nrm;
  pos.reserve(3 * m.rest_vertices_m.size());
  nrm.reserve(3 * m.rest_vertices_m.size());
  for (size_t v = 0; v < m.rest_vertices_m.size(); ++v) {
    // glTF requires unit normals; a vertex without area (none on the MPFB2 body) gets +Y.
    const Vec3 n = m.rest_normals[v].norm() > 0.5 ? Vec3(m.rest_normals[v].normalized()) : Vec3::UnitY();
    for (int c = 0; c < 3; ++c) {
      pos.push_back(static_cast<float>(m.rest_vertices_m[v][c]));
      nrm.push_back(static_cast<float>(n[c]));
    }
  }
  auto it = std::find_if(shared.begin(), shared.end(),
                         [&](const SharedTopology& t) { return same_topology(*t.mesh, m); });
  if (it == shared.end()) {
    SharedTopology t;
    t.mesh = &m;
    std::vector<std::uint32_t> idx;
    for (const Eigen::Vector3i& tri : m.triangles)
      for (int k = 0; k < 3; ++k) idx.push_back(static_cast<std::uint32_t>(tri[k]));
    std::vector<std::uint8_t> joints;
    std::vector<float> weights;
    for (size_t v = 0; v < m.joints.size(); ++v) {
      // glTF wants each vertex's weights to sum to 1 in the stored precision; the largest (first)
      // absorbs the float rounding of the others.
      float rest_sum = 0.0f;
      for (size_t k = 1; k < 4; ++k) rest_sum += static_cast<float>(m.weights[v][k]);
      for (size_t k = 0; k < 4; ++k) {
        joints.push_back(static_cast<std::uint8_t>(m.weights[v][k] > 0.0 ? m.joints[v][k] : 0));
        weights.push_back(k == 0 ? 1.0f - rest_sum : static_cast<float>(m.weights[v][k]));
      }
    }
    const std::string name = ch.name + "_surface";
    t.indices = builder.add_indices_u32(idx, name + "_indices");
    t.joints = builder.add_joints_u8(joints, name + "_joints");
    t.weights = builder.add_floats(weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false,
                                   name + "_weights");
    shared.push_back(t);
    it = shared.end() - 1;
  }
  tinygltf::Primitive prim = positions_normals_primitive(builder, pos, nrm, ch.name);
  prim.attributes["JOINTS_0"] = it->joints;
  prim.attributes["WEIGHTS_0"] = it->weights;
  prim.indices = it->indices;
  if (!m.surface.empty()) {
    // What each vertex is (SurfaceKind), per character (lips follow each face's shape). A float scalar: glTF
    // wants vertex attributes 4-byte aligned per vertex, so a byte would take as much room.
    const std::vector<float> kinds(m.surface.begin(), m.surface.end());
    prim.attributes["_SURFACE"] = builder.add_floats(
        kinds, TINYGLTF_TYPE_SCALAR, 1, TINYGLTF_TARGET_ARRAY_BUFFER, false, ch.name + "_surface_kind");
  }
  return prim;
}

// The capsule preview of a procedural body: one low-poly capsule per bone, rigidly skinned.
tinygltf::Primitive capsule_body_primitive(GltfBuilder& builder, const CharacterAnimation& ch,
                                           const std::array<Vec3, kJointCount>& rest) {
  TriangleSoup soup;
  std::vector<std::uint8_t> joints;
  for (int j = 0; j < kJointCount; ++j) {
    const size_t before = soup.positions.size();
    append_capsule_mesh(ch.shape.capsules[static_cast<size_t>(j)], kCapsuleSegments, kCapsuleRings, soup);
    for (size_t v = before; v < soup.positions.size(); ++v) {
      soup.positions[v] += rest[static_cast<size_t>(j)];
      joints.insert(joints.end(), {static_cast<std::uint8_t>(j), 0, 0, 0});
    }
  }
  std::vector<float> pos, nrm, weights;
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    const Vec3 n = soup.normals[v].normalized();
    for (int c = 0; c < 3; ++c) {
      pos.push_back(static_cast<float>(soup.positions[v][c]));
      nrm.push_back(static_cast<float>(n[c]));
    }
    weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
  }
  std::vector<std::uint16_t> indices(soup.indices.begin(), soup.indices.end());
  tinygltf::Primitive prim = positions_normals_primitive(builder, pos, nrm, ch.name);
  prim.attributes["JOINTS_0"] = builder.add_joints_u8(joints, ch.name + "_joints");
  prim.attributes["WEIGHTS_0"] = builder.add_floats(
      weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false, ch.name + "_weights");
  prim.indices = builder.add_indices_u16(indices, ch.name + "_indices");
  return prim;
}

// The body mesh + skin of one character (its own surface, or the capsule preview); returns the
// skinned mesh node.
int add_character_body(tinygltf::Model& model, GltfBuilder& builder, const CharacterAnimation& ch,
                       const std::vector<int>& joint_nodes, int material,
                       std::vector<SharedTopology>& shared) {
  const auto rest = joint_positions(ch.shape, Pose::rest(ch.shape));
  tinygltf::Primitive prim =
      ch.mesh ? skinned_surface_primitive(builder, ch, shared) : capsule_body_primitive(builder, ch, rest);
  prim.material = material;
  tinygltf::Mesh mesh;
  mesh.name = ch.name + "_body";
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);

  // Inverse bind matrices: translation by minus the rest position (column-major 4x4).
  std::vector<float> ibm;
  for (int j = 0; j < kJointCount; ++j) {
    const Vec3& p = rest[static_cast<size_t>(j)];
    const float m[16] = {1,
                         0,
                         0,
                         0,
                         0,
                         1,
                         0,
                         0,
                         0,
                         0,
                         1,
                         0,
                         static_cast<float>(-p.x()),
                         static_cast<float>(-p.y()),
                         static_cast<float>(-p.z()),
                         1};
    ibm.insert(ibm.end(), m, m + 16);
  }
  tinygltf::Skin skin;
  skin.name = ch.name;
  skin.joints = joint_nodes;
  skin.skeleton = joint_nodes[0];
  skin.inverseBindMatrices =
      builder.add_floats(ibm, TINYGLTF_TYPE_MAT4, 16, 0, false, ch.name + "_inverse_bind");
  model.skins.push_back(skin);

  tinygltf::Node body;
  body.name = ch.name + "_body";
  body.mesh = static_cast<int>(model.meshes.size()) - 1;
  body.skin = static_cast<int>(model.skins.size()) - 1;
  return add_node(model, body);
}

// Character group node + 24 joint nodes; returns the joint node indices (SMPL order).
std::vector<int> add_character_skeleton(tinygltf::Model& model, const CharacterAnimation& ch, int& group) {
  tinygltf::Node g;
  g.name = ch.name;
  g.extras = to_gltf_value({{kCharacterExtrasKey, character_extras(ch)}});
  group = add_node(model, g);
  std::vector<int> joint_nodes(kJointCount);
  for (int j = 0; j < kJointCount; ++j) {
    tinygltf::Node n;
    n.name = std::string(joint_name(j));
    const Vec3& t = ch.shape.joint_offsets_m[static_cast<size_t>(j)];
    n.translation = {t.x(), t.y(), t.z()};
    joint_nodes[static_cast<size_t>(j)] = add_node(model, n);
    const int parent = kJointParent[static_cast<size_t>(j)];
    const int parent_node = parent < 0 ? group : joint_nodes[static_cast<size_t>(parent)];
    model.nodes[static_cast<size_t>(parent_node)].children.push_back(joint_nodes[static_cast<size_t>(j)]);
  }
  return joint_nodes;
}

void add_character_animation(GltfBuilder& builder, tinygltf::Animation& anim, const CharacterAnimation& ch,
                             const std::vector<int>& joint_nodes, int times) {
  const size_t frames = ch.frames.size();
  auto add_channel = [&](int node, const char* path, int output) {
    tinygltf::AnimationSampler s;
    s.input = times;
    s.output = output;
    s.interpolation = "LINEAR";
    anim.samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = static_cast<int>(anim.samplers.size()) - 1;
    c.target_node = node;
    c.target_path = path;
    anim.channels.push_back(c);
  };
  for (int j = 0; j < kJointCount; ++j) {
    std::vector<float> q;
    q.reserve(frames * 4);
    Quat previous = Quat::Identity();
    for (size_t f = 0; f < frames; ++f) {
      Quat r = ch.frames[f].local_rotations[static_cast<size_t>(j)].normalized();
      if (f > 0 && r.coeffs().dot(previous.coeffs()) < 0.0) r.coeffs() *= -1.0;
      previous = r;
      for (double c : quat_xyzw(r)) q.push_back(static_cast<float>(c));
    }
    const int out = builder.add_floats(q, TINYGLTF_TYPE_VEC4, 4, 0, false,
                                       ch.name + "/" + std::string(joint_name(j)) + "/rotation");
    add_channel(joint_nodes[static_cast<size_t>(j)], "rotation", out);
  }
  std::vector<float> t;
  t.reserve(frames * 3);
  for (const Pose& p : ch.frames)
    for (int c = 0; c < 3; ++c) t.push_back(static_cast<float>(p.root_position_m[c]));
  const int out = builder.add_floats(t, TINYGLTF_TYPE_VEC3, 3, 0, false, ch.name + "/pelvis/translation");
  add_channel(joint_nodes[0], "translation", out);
}

int add_ground(tinygltf::Model& model, GltfBuilder& builder, const CrowdAnimation& crowd) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const CharacterAnimation& ch : crowd.characters)
    for (const Pose& p : ch.frames) {
      const Vec2 xz(p.root_position_m.x(), p.root_position_m.z());
      lo = lo.cwiseMin(xz);
      hi = hi.cwiseMax(xz);
    }
  lo.array() -= kGroundMargin_m;
  hi.array() += kGroundMargin_m;
  const std::vector<float> pos = {static_cast<float>(lo.x()), 0, static_cast<float>(lo.y()),
                                  static_cast<float>(lo.x()), 0, static_cast<float>(hi.y()),
                                  static_cast<float>(hi.x()), 0, static_cast<float>(hi.y()),
                                  static_cast<float>(hi.x()), 0, static_cast<float>(lo.y())};
  const std::vector<float> nrm = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  tinygltf::Material m;
  m.name = "ground";
  m.pbrMetallicRoughness.baseColorFactor = {0.6, 0.6, 0.58, 1.0};
  m.pbrMetallicRoughness.metallicFactor = 0.0;
  m.pbrMetallicRoughness.roughnessFactor = 1.0;
  model.materials.push_back(m);
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = static_cast<int>(model.materials.size()) - 1;
  prim.attributes["POSITION"] =
      builder.add_floats(pos, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true, "ground_positions");
  prim.attributes["NORMAL"] =
      builder.add_floats(nrm, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false, "ground_normals");
  prim.indices = builder.add_indices_u16({0, 1, 2, 0, 2, 3}, "ground_indices");  // CCW seen from +Y
  tinygltf::Mesh mesh;
  mesh.name = "ground";
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node n;
  n.name = "ground";
  n.mesh = static_cast<int>(model.meshes.size()) - 1;
  n.extras = to_gltf_value({{kEnvironmentExtrasKey, "ground"}});
  return add_node(model, n);
}

// The unit cube [-1, 1]^3 with flat normals (24 vertices, 12 triangles), shared by every box.
int add_unit_cube_mesh(tinygltf::Model& model, GltfBuilder& builder) {
  std::vector<float> pos, nrm;
  std::vector<std::uint16_t> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      Vec3 n = Vec3::Zero();
      n[axis] = sign;
      const Vec3 u = Vec3::Unit((axis + 1) % 3), v = Vec3::Unit((axis + 2) % 3);
      const auto base = static_cast<std::uint16_t>(pos.size() / 3);
      const Vec3 corners[4] = {n - u - v, n + u - v, n + u + v, n - u + v};
      for (const Vec3& c : corners)
        for (int k = 0; k < 3; ++k) {
          pos.push_back(static_cast<float>(c[k]));
          nrm.push_back(static_cast<float>(n[k]));
        }
      // u x v = n for sign +1, so corners wind CCW seen from outside; flip for the negative face.
      if (sign > 0)
        idx.insert(idx.end(),
                   {base, static_cast<std::uint16_t>(base + 1), static_cast<std::uint16_t>(base + 2), base,
                    static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 3)});
      else
        idx.insert(idx.end(),
                   {base, static_cast<std::uint16_t>(base + 2), static_cast<std::uint16_t>(base + 1), base,
                    static_cast<std::uint16_t>(base + 3), static_cast<std::uint16_t>(base + 2)});
    }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] =
      builder.add_floats(pos, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true, "box_positions");
  prim.attributes["NORMAL"] =
      builder.add_floats(nrm, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false, "box_normals");
  prim.indices = builder.add_indices_u16(idx, "box_indices");
  tinygltf::Mesh mesh;
  mesh.name = "unit_box";
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  return static_cast<int>(model.meshes.size()) - 1;
}

int add_triangle_mesh(tinygltf::Model& model, GltfBuilder& builder, const TriangleMesh& m) {
  std::vector<float> pos;
  for (const Vec3& v : m.vertices_m)
    for (int k = 0; k < 3; ++k) pos.push_back(static_cast<float>(v[k]));
  std::vector<std::uint32_t> idx;
  for (const Eigen::Vector3i& t : m.triangles)
    for (int k = 0; k < 3; ++k) idx.push_back(static_cast<std::uint32_t>(t[k]));
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = builder.add_floats(pos, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER,
                                                   true, m.name + "_positions");
  prim.indices = builder.add_indices_u32(idx, m.name + "_indices");
  tinygltf::Mesh mesh;
  mesh.name = m.name;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node n;
  n.name = m.name;
  n.mesh = static_cast<int>(model.meshes.size()) - 1;
  n.extras = to_gltf_value({{kEnvironmentExtrasKey, "mesh"}});
  return add_node(model, n);
}

}  // namespace

void write_crowd_glb(const CrowdAnimation& crowd, const std::string& path) {
  validate_crowd(crowd, path);
  validate_environment(crowd.environment, path);
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "crowdlab " CROWDLAB_VERSION;
  GltfBuilder builder(model);
  tinygltf::Scene scene;
  scene.name = crowd.meta.condition_id.empty() ? "crowd" : crowd.meta.condition_id;
  scene.extras = to_gltf_value({{kSceneExtrasKey,
                                 {{"format", kCrowdGlbFormat},
                                  {"fps", crowd.meta.fps},
                                  {"seed", std::to_string(crowd.meta.seed)},
                                  {"condition_id", crowd.meta.condition_id},
                                  {"scenario", crowd.meta.scenario}}}});

  const int frames = crowd.frame_count();
  std::vector<float> key_times(static_cast<size_t>(frames));
  for (int f = 0; f < frames; ++f) key_times[static_cast<size_t>(f)] = static_cast<float>(f / crowd.meta.fps);
  const int times = builder.add_floats(key_times, TINYGLTF_TYPE_SCALAR, 1, 0, true, "key_times");

  tinygltf::Animation anim;
  anim.name = "crowd";
  std::vector<int> material_cache(kPalette.size(), -1);
  std::vector<SharedTopology> shared_topology;
  for (const CharacterAnimation& ch : crowd.characters) {
    int group = -1;
    const std::vector<int> joint_nodes = add_character_skeleton(model, ch, group);
    const int material = palette_material(model, material_cache, clothing_of(ch.palette));
    const int body = add_character_body(model, builder, ch, joint_nodes, material, shared_topology);
    scene.nodes.push_back(group);
    scene.nodes.push_back(body);
    add_character_animation(builder, anim, ch, joint_nodes, times);
  }
  model.animations.push_back(std::move(anim));

  const Environment& env = crowd.environment;
  if (env.ground_plane) scene.nodes.push_back(add_ground(model, builder, crowd));
  if (!env.boxes.empty()) {
    const int cube = add_unit_cube_mesh(model, builder);
    for (size_t k = 0; k < env.boxes.size(); ++k) {
      const Box& b = env.boxes[k];
      tinygltf::Node n;
      n.name = "box_" + std::to_string(k);
      n.mesh = cube;
      n.translation = {b.center_m.x(), b.center_m.y(), b.center_m.z()};
      n.rotation = quat_xyzw(b.rotation.normalized());
      n.scale = {b.half_extents_m.x(), b.half_extents_m.y(), b.half_extents_m.z()};
      n.extras = to_gltf_value({{kEnvironmentExtrasKey, "box"}});
      scene.nodes.push_back(add_node(model, n));
    }
  }
  for (const TriangleMesh& m : env.meshes) scene.nodes.push_back(add_triangle_mesh(model, builder, m));

  model.scenes.push_back(scene);
  model.defaultScene = 0;
  model.buffers[0].name = "crowd";
  // Streamed to a temporary with write(2), its failures checked (tinygltf's own file writer ignores a
  // failed write, so a full disk published a truncated crowd file, issue 21), and renamed into place by
  // the framework's one atomic writer, so that an interrupted run never leaves a truncated file under
  // the final name and a killed run's temporary is removed by the next (remove_stale_temporaries). Not
  // fsync'd: a crowd file can be remade, and the run pipeline's own write of it (stage_runner.hpp) is
  // durable. Streamed rather than built in memory first: a 1 s clip of 60 MPFB2 bodies is ~94 MB.
  write_output_via_temporary(
      path,
      [&](const std::filesystem::path& tmp) {
        write_streamed_file(tmp, [&](std::ostream& glb) {
          tinygltf::TinyGLTF writer;
          if (!writer.WriteGltfSceneToStream(&model, glb, /*prettyPrint=*/false, /*writeBinary=*/true))
            throw RuntimeError(path + ": cannot encode the glTF file");
        });
      },
      /*durable=*/false);
}

}  // namespace crowdlab
