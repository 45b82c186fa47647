#include "framework/io/read_crowd_glb.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/library_error.hpp"
#include "framework/io/crowd_glb_format.hpp"
#include "framework/io/gltf_accessor_reader.hpp"
#include "framework/io/gltf_builder.hpp"
#include "framework/io/load_gltf_model.hpp"
#include "framework/io/validate_environment.hpp"

namespace crowdlab {
namespace {

using nlohmann::json;

// Key times may differ from f / fps by float rounding; anything beyond 1 % of a frame is a different
// timing and is rejected.
constexpr double kKeyTimeTolerance_frames = 0.01;

std::string node_label(const tinygltf::Model& model, int node) {
  std::string s = "node " + std::to_string(node);
  if (node >= 0 && static_cast<size_t>(node) < model.nodes.size() &&
      !model.nodes[static_cast<size_t>(node)].name.empty())
    s += " ('" + model.nodes[static_cast<size_t>(node)].name + "')";
  return s;
}

const json* find_key(const json& j, const char* key) {
  if (!j.is_object()) return nullptr;
  auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

Vec3 vec3_from(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw InputError(what + ": expected 3 numbers");
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!j[static_cast<size_t>(k)].is_number()) throw InputError(what + ": expected 3 numbers");
    v[k] = j[static_cast<size_t>(k)].get<double>();
  }
  return v;
}

double number_from(const json& obj, const char* key, const std::string& what) {
  const json* v = find_key(obj, key);
  if (!v || !v->is_number()) throw InputError(what + ": '" + key + "' must be a number");
  return v->get<double>();
}

std::string string_from(const json& obj, const char* key, const std::string& what) {
  const json* v = find_key(obj, key);
  if (!v || !v->is_string()) throw InputError(what + ": '" + key + "' must be text");
  return v->get<std::string>();
}

// The character's name, palette and BodyShape from its group node's extras.
CharacterAnimation character_from_extras(const json& e, const std::string& what) {
  CharacterAnimation ch;
  ch.name = string_from(e, "name", what);
  const double palette = number_from(e, "palette", what);
  // Checked before the cast: converting a fuzzed 1e300 to int is undefined behaviour.
  if (!(palette >= 0.0 && palette <= 2147483647.0) || palette != std::floor(palette))
    throw InputError(what + ": 'palette' must be a whole number in [0, 2147483647]");
  ch.palette = static_cast<int>(palette);
  const std::string sex = string_from(e, "sex", what);
  if (sex != "female" && sex != "male")
    throw InputError(what + ": 'sex' must be female or male, got '" + sex + "'");
  BodyShape& s = ch.shape;
  s.params.sex = sex == "female" ? Sex::kFemale : Sex::kMale;
  s.params.height_m = number_from(e, "height_m", what);
  s.params.girth = number_from(e, "girth", what);
  const json* offsets = find_key(e, "joint_offsets_m");
  const json* capsules = find_key(e, "capsules");
  if (!offsets || !offsets->is_array() || offsets->size() != kJointCount)
    throw InputError(what + ": 'joint_offsets_m' must list 24 offsets");
  if (!capsules || !capsules->is_array() || capsules->size() != kJointCount)
    throw InputError(what + ": 'capsules' must list 24 capsules");
  for (size_t j = 0; j < kJointCount; ++j) {
    const std::string joint = what + ": joint '" + std::string(joint_name(static_cast<int>(j))) + "'";
    s.joint_offsets_m[j] = vec3_from((*offsets)[j], joint + " offset");
    const json& c = (*capsules)[j];
    const json* a = find_key(c, "a");
    const json* b = find_key(c, "b");
    if (!a || !b) throw InputError(joint + " capsule: needs 'a' and 'b'");
    s.capsules[j] = Capsule{vec3_from(*a, joint + " capsule a"), vec3_from(*b, joint + " capsule b"),
                            number_from(c, "radius_m", joint + " capsule")};
  }
  const json* pairs = find_key(e, "rest_contact_pairs");
  if (!pairs || !pairs->is_array()) throw InputError(what + ": 'rest_contact_pairs' must be a list");
  for (const json& p : *pairs) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number_integer() || !p[1].is_number_integer())
      throw InputError(what + ": 'rest_contact_pairs' entries must be [i, j] joint indices");
    const int i = p[0].get<int>(), j = p[1].get<int>();
    if (i < 0 || j < 0 || i >= kJointCount || j >= kJointCount || i >= j)
      throw InputError(what + ": rest contact pair [" + std::to_string(i) + ", " + std::to_string(j) +
                       "] is not 0 <= i < j < 24");
    s.rest_contact_pairs.emplace_back(i, j);
  }
  return ch;
}

// The 24 joint node indices of the character whose group node is `group`, in SMPL order, checked
// against the skin and the node hierarchy.
std::vector<int> joint_nodes_of(const tinygltf::Model& model, int group, const std::string& context) {
  const tinygltf::Node& g = model.nodes[static_cast<size_t>(group)];
  const std::string where = context + ": " + node_label(model, group);
  if (g.children.size() != 1)
    throw InputError(where + ": a character node must have exactly one child (the pelvis)");
  const int pelvis = g.children[0];
  const tinygltf::Skin* skin = nullptr;
  for (const tinygltf::Skin& s : model.skins)
    if (!s.joints.empty() && s.joints[0] == pelvis) skin = &s;
  if (!skin) throw InputError(where + ": no skin has this character's pelvis as its first joint");
  if (skin->joints.size() != kJointCount)
    throw InputError(where + ": its skin has " + std::to_string(skin->joints.size()) +
                     " joints, expected 24");
  for (int j = 0; j < kJointCount; ++j) {
    const int n = skin->joints[static_cast<size_t>(j)];
    if (n < 0 || static_cast<size_t>(n) >= model.nodes.size())
      throw InputError(where + ": skin joint " + std::to_string(j) + " names a missing node");
    if (model.nodes[static_cast<size_t>(n)].name != joint_name(j))
      throw InputError(context + ": " + node_label(model, n) + ": skin joint " + std::to_string(j) +
                       " must be named '" + std::string(joint_name(j)) + "'");
    const int parent = kJointParent[static_cast<size_t>(j)];
    const int parent_node = parent < 0 ? group : skin->joints[static_cast<size_t>(parent)];
    const auto& kids = model.nodes[static_cast<size_t>(parent_node)].children;
    if (std::find(kids.begin(), kids.end(), n) == kids.end())
      throw InputError(context + ": " + node_label(model, n) + ": is not a child of " +
                       node_label(model, parent_node));
  }
  return skin->joints;
}

// The character's own skinned surface (extras body_mesh: true): the mesh of the scene node that uses
// the character's skin. Vertex data are in the rest pose, character frame (crowd_glb_format.hpp).
std::shared_ptr<const SkinnedMesh> read_body_mesh(const tinygltf::Model& model, const tinygltf::Scene& scene,
                                                  int pelvis_node, const CharacterAnimation& ch,
                                                  const std::string& context) {
  const std::string who = context + ": character '" + ch.name + "' body mesh";
  int skin = -1;
  for (size_t s = 0; s < model.skins.size(); ++s)
    if (!model.skins[s].joints.empty() && model.skins[s].joints[0] == pelvis_node) skin = static_cast<int>(s);
  const tinygltf::Node* body = nullptr;
  for (int n : scene.nodes)
    if (n >= 0 && static_cast<size_t>(n) < model.nodes.size() &&
        model.nodes[static_cast<size_t>(n)].skin == skin && model.nodes[static_cast<size_t>(n)].mesh >= 0)
      body = &model.nodes[static_cast<size_t>(n)];
  if (skin < 0 || !body || static_cast<size_t>(body->mesh) >= model.meshes.size() ||
      model.meshes[static_cast<size_t>(body->mesh)].primitives.size() != 1)
    throw InputError(who + ": no scene node with one mesh primitive uses the character's skin");
  const tinygltf::Primitive& p = model.meshes[static_cast<size_t>(body->mesh)].primitives[0];
  auto attribute = [&](const char* name) {
    auto it = p.attributes.find(name);
    if (it == p.attributes.end()) throw InputError(who + ": attribute " + name + " is missing");
    return it->second;
  };
  const std::vector<float> pos =
      read_float_accessor(model, attribute("POSITION"), TINYGLTF_TYPE_VEC3, context);
  const std::vector<float> nrm = read_float_accessor(model, attribute("NORMAL"), TINYGLTF_TYPE_VEC3, context);
  const std::vector<float> w =
      read_float_accessor(model, attribute("WEIGHTS_0"), TINYGLTF_TYPE_VEC4, context);
  const std::vector<std::uint32_t> j =
      read_uint_accessor(model, attribute("JOINTS_0"), TINYGLTF_TYPE_VEC4, context);
  if (p.indices < 0) throw InputError(who + ": no indices");
  const std::vector<std::uint32_t> idx = read_index_accessor(model, p.indices, context);
  const size_t n = pos.size() / 3;
  if (nrm.size() != 3 * n || w.size() != 4 * n || j.size() != 4 * n || idx.size() % 3 != 0)
    throw InputError(who + ": POSITION, NORMAL, JOINTS_0, WEIGHTS_0 and indices disagree in size");
  auto mesh = std::make_shared<SkinnedMesh>();
  mesh->rest_vertices_m.resize(n);
  mesh->rest_normals.resize(n);
  mesh->joints.resize(n);
  mesh->weights.resize(n);
  mesh->region.resize(n);
  for (size_t v = 0; v < n; ++v) {
    mesh->rest_vertices_m[v] = Vec3(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    mesh->rest_normals[v] = Vec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
    double total = 0.0;
    for (size_t k = 0; k < 4; ++k) total += static_cast<double>(w[4 * v + k]);
    if (!(total > 0.5))
      throw InputError(who + ": vertex " + std::to_string(v) + " weights sum to " + std::to_string(total));
    for (size_t k = 0; k < 4; ++k) {
      if (j[4 * v + k] >= static_cast<std::uint32_t>(kJointCount))
        throw InputError(who + ": vertex " + std::to_string(v) + " names joint " +
                         std::to_string(j[4 * v + k]));
      mesh->joints[v][k] = static_cast<int>(j[4 * v + k]);
      mesh->weights[v][k] =
          static_cast<double>(w[4 * v + k]) / total;  // renormalise after the float round trip
    }
    // The region is the dominant joint (the writer stores weights in descending order).
    mesh->region[v] = mesh->joints[v][static_cast<size_t>(
        std::max_element(mesh->weights[v].begin(), mesh->weights[v].end()) - mesh->weights[v].begin())];
  }
  if (const auto s = p.attributes.find("_SURFACE"); s != p.attributes.end()) {
    const std::vector<float> kinds = read_float_accessor(model, s->second, TINYGLTF_TYPE_SCALAR, context);
    if (kinds.size() != n)
      throw InputError(who + ": _SURFACE has " + std::to_string(kinds.size()) + " entries");
    for (const float k : kinds) {
      if (!(k >= 0.0f && k < static_cast<float>(SurfaceKind::kCount)) || k != std::floor(k))
        throw InputError(who + ": _SURFACE holds the unknown label " + std::to_string(k));
      mesh->surface.push_back(static_cast<std::uint8_t>(k));
    }
  }
  for (size_t t = 0; t < idx.size(); t += 3)
    mesh->triangles.emplace_back(static_cast<int>(idx[t]), static_cast<int>(idx[t + 1]),
                                 static_cast<int>(idx[t + 2]));
  mesh->rest_joints_m = joint_positions(ch.shape, Pose::rest(ch.shape));
  validate_skinned_mesh(*mesh, context + ": character '" + ch.name + "'");
  return mesh;
}

struct JointRef {
  size_t character;
  int joint;
};

void read_animation(const tinygltf::Model& model, const std::map<int, JointRef>& joints,
                    CrowdAnimation& crowd, const std::string& context) {
  if (model.animations.empty()) throw InputError(context + ": the file has no animation");
  const tinygltf::Animation& anim = model.animations[0];
  const size_t n_chars = crowd.characters.size();
  std::vector<std::array<bool, kJointCount>> have_rotation(n_chars);
  std::vector<bool> have_root(n_chars, false);
  for (auto& h : have_rotation) h.fill(false);
  long frames = -1;
  const double fps = crowd.meta.fps;
  for (size_t c = 0; c < anim.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = anim.channels[c];
    const std::string where = context + ": animation channel " + std::to_string(c);
    auto it = joints.find(ch.target_node);
    if (it == joints.end())
      throw InputError(where + ": targets " + node_label(model, ch.target_node) + ", not a joint");
    const auto [ci, j] = it->second;
    const bool rotation = ch.target_path == "rotation";
    const bool translation = ch.target_path == "translation";
    if (!rotation && !(translation && j == kPelvis))
      throw InputError(where + ": unexpected '" + ch.target_path + "' channel on " +
                       node_label(model, ch.target_node));
    if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= anim.samplers.size())
      throw InputError(where + ": sampler " + std::to_string(ch.sampler) + " does not exist");
    const tinygltf::AnimationSampler& s = anim.samplers[static_cast<size_t>(ch.sampler)];
    if (s.interpolation != "LINEAR" && s.interpolation != "STEP")
      throw InputError(where + ": " + s.interpolation + " interpolation is not supported (LINEAR or STEP)");
    const std::vector<float> times = read_float_accessor(model, s.input, TINYGLTF_TYPE_SCALAR, context);
    if (times.empty())  // was "has 0 keys, expected 0" when the first channel was the empty one (issue 33)
      throw InputError(where + ": its sampler's input (accessor " + std::to_string(s.input) +
                       ") has no keys; an animation needs at least one frame");
    if (frames < 0) frames = static_cast<long>(times.size());
    if (times.size() != static_cast<size_t>(frames))
      throw InputError(where + ": has " + std::to_string(times.size()) + " keys, expected " +
                       std::to_string(frames) + " (as the first channel)");
    for (size_t f = 0; f < times.size(); ++f)
      if (std::abs(static_cast<double>(times[f]) - static_cast<double>(f) / fps) >
          kKeyTimeTolerance_frames / fps)
        throw InputError(where + ": key " + std::to_string(f) + " is at " + std::to_string(times[f]) +
                         " s, expected f / fps = " + std::to_string(static_cast<double>(f) / fps) + " s");
    CharacterAnimation& character = crowd.characters[ci];
    if (character.frames.empty()) character.frames.resize(static_cast<size_t>(frames));
    const std::string target =
        "character '" + character.name + "' joint '" + std::string(joint_name(j)) + "'";
    if (rotation) {
      if (have_rotation[ci][static_cast<size_t>(j)])
        throw InputError(where + ": second rotation channel for " + target);
      have_rotation[ci][static_cast<size_t>(j)] = true;
      const std::vector<float> q = read_float_accessor(model, s.output, TINYGLTF_TYPE_VEC4, context);
      if (q.size() != 4 * static_cast<size_t>(frames))
        throw InputError(where + ": " + target + ": rotation output has " + std::to_string(q.size() / 4) +
                         " keys, expected " + std::to_string(frames));
      for (size_t f = 0; f < static_cast<size_t>(frames); ++f) {
        Quat r(q[4 * f + 3], q[4 * f], q[4 * f + 1], q[4 * f + 2]);  // glTF stores x, y, z, w
        if (r.norm() < 0.5)
          throw InputError(where + ": " + target + ": frame " + std::to_string(f) +
                           " rotation is not a unit quaternion");
        character.frames[f].local_rotations[static_cast<size_t>(j)] = r.normalized();
      }
    } else {
      if (have_root[ci])
        throw InputError(where + ": second root translation channel for character '" + character.name + "'");
      have_root[ci] = true;
      const std::vector<float> t = read_float_accessor(model, s.output, TINYGLTF_TYPE_VEC3, context);
      if (t.size() != 3 * static_cast<size_t>(frames))
        throw InputError(where + ": root translation of '" + character.name + "' has " +
                         std::to_string(t.size() / 3) + " keys, expected " + std::to_string(frames));
      for (size_t f = 0; f < static_cast<size_t>(frames); ++f)
        character.frames[f].root_position_m = Vec3(t[3 * f], t[3 * f + 1], t[3 * f + 2]);
    }
  }
  for (size_t ci = 0; ci < n_chars; ++ci) {
    for (int j = 0; j < kJointCount; ++j)
      if (!have_rotation[ci][static_cast<size_t>(j)])
        throw InputError(context + ": character '" + crowd.characters[ci].name + "': joint '" +
                         std::string(joint_name(j)) + "' has no rotation channel");
    if (!have_root[ci])
      throw InputError(context + ": character '" + crowd.characters[ci].name +
                       "': no root translation channel");
  }
}

Vec3 node_vec3(const std::vector<double>& v, const Vec3& fallback) {
  return v.size() == 3 ? Vec3(v[0], v[1], v[2]) : fallback;
}

void read_environment_node(const tinygltf::Model& model, int node, const std::string& kind, Environment& env,
                           const std::string& context) {
  const tinygltf::Node& n = model.nodes[static_cast<size_t>(node)];
  const std::string where = context + ": " + node_label(model, node);
  if (kind == "ground") {
    env.ground_plane = true;
  } else if (kind == "box") {
    Box b;
    b.center_m = node_vec3(n.translation, Vec3::Zero());
    b.half_extents_m = node_vec3(n.scale, Vec3::Ones());
    if (n.rotation.size() == 4) b.rotation = Quat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    env.boxes.push_back(b);
  } else if (kind == "mesh") {
    if (n.mesh < 0 || static_cast<size_t>(n.mesh) >= model.meshes.size() ||
        model.meshes[static_cast<size_t>(n.mesh)].primitives.empty())
      throw InputError(where + ": environment mesh node without a mesh");
    const tinygltf::Primitive& p = model.meshes[static_cast<size_t>(n.mesh)].primitives[0];
    auto pos_it = p.attributes.find("POSITION");
    if (pos_it == p.attributes.end() || p.indices < 0)
      throw InputError(where + ": mesh needs POSITION and indices");
    TriangleMesh m;
    m.name = n.name;
    const std::vector<float> pos = read_float_accessor(model, pos_it->second, TINYGLTF_TYPE_VEC3, context);
    for (size_t i = 0; i + 2 < pos.size(); i += 3) m.vertices_m.emplace_back(pos[i], pos[i + 1], pos[i + 2]);
    const std::vector<std::uint32_t> idx = read_index_accessor(model, p.indices, context);
    if (idx.size() % 3 != 0) throw InputError(where + ": index count is not a multiple of 3");
    for (size_t i = 0; i < idx.size(); i += 3) {
      for (size_t k = 0; k < 3; ++k)
        if (idx[i + k] >= m.vertices_m.size())
          throw InputError(where + ": index " + std::to_string(idx[i + k]) + " out of range");
      m.triangles.emplace_back(static_cast<int>(idx[i]), static_cast<int>(idx[i + 1]),
                               static_cast<int>(idx[i + 2]));
    }
    env.meshes.push_back(std::move(m));
  } else {
    throw InputError(where + ": unknown environment kind '" + kind + "'");
  }
}

void read_metadata(const tinygltf::Scene& scene, CrowdMetadata& meta, const std::string& context) {
  const json extras = from_gltf_value(scene.extras);
  const json* m = find_key(extras, kSceneExtrasKey);
  const std::string where = context + ": scene extras";
  if (!m || !m->is_object())
    throw InputError(context + ": not a crowdlab crowd file (scene extras 'crowdlab' missing)");
  const double format = number_from(*m, "format", where);
  if (format != kCrowdGlbFormat)
    throw InputError(where + ": crowd file format " + std::to_string(format) +
                     " is not supported (expected " + std::to_string(kCrowdGlbFormat) + ")");
  meta.fps = number_from(*m, "fps", where);
  if (!(meta.fps > 0.0) || !std::isfinite(meta.fps))
    throw InputError(where + ": fps must be a positive number");
  const std::string seed = string_from(*m, "seed", where);
  try {
    size_t used = 0;
    meta.seed = std::stoull(seed, &used);
    if (used != seed.size() || seed.empty() || seed[0] == '-') throw std::invalid_argument(seed);
  } catch (const std::exception&) {
    throw InputError(where + ": seed '" + seed + "' is not a whole number");
  }
  meta.condition_id = string_from(*m, "condition_id", where);
  meta.scenario = string_from(*m, "scenario", where);
}

}  // namespace

namespace {

CrowdAnimation read_crowd_glb_unwrapped(const std::string& path) {
  const tinygltf::Model model = load_gltf_model(path);
  if (model.scenes.empty()) throw InputError(path + ": the file has no scene");
  const size_t scene_index = model.defaultScene >= 0 ? static_cast<size_t>(model.defaultScene) : 0;
  if (scene_index >= model.scenes.size()) throw InputError(path + ": the default scene does not exist");
  const tinygltf::Scene& scene = model.scenes[scene_index];

  CrowdAnimation crowd;
  crowd.environment.ground_plane = false;
  read_metadata(scene, crowd.meta, path);
  std::map<int, JointRef> joints;
  try {
    for (int node : scene.nodes) {
      if (node < 0 || static_cast<size_t>(node) >= model.nodes.size())
        throw InputError(path + ": the scene lists a missing node " + std::to_string(node));
      const json extras = from_gltf_value(model.nodes[static_cast<size_t>(node)].extras);
      if (const json* c = find_key(extras, kCharacterExtrasKey)) {
        crowd.characters.push_back(character_from_extras(*c, path + ": " + node_label(model, node)));
        const std::vector<int> nodes = joint_nodes_of(model, node, path);
        if (const json* m = find_key(*c, "body_mesh"); m && m->is_boolean() && m->get<bool>())
          crowd.characters.back().mesh =
              read_body_mesh(model, scene, nodes[0], crowd.characters.back(), path);
        for (int j = 0; j < kJointCount; ++j) {
          const bool inserted =
              joints.emplace(nodes[static_cast<size_t>(j)], JointRef{crowd.characters.size() - 1, j}).second;
          if (!inserted)
            throw InputError(path + ": " + node_label(model, nodes[static_cast<size_t>(j)]) +
                             ": shared by two characters");
        }
      } else if (const json* e = find_key(extras, kEnvironmentExtrasKey)) {
        if (!e->is_string())
          throw InputError(path + ": " + node_label(model, node) + ": environment kind must be text");
        read_environment_node(model, node, e->get<std::string>(), crowd.environment, path);
      }
    }
  } catch (const json::exception& e) {
    throw InputError(path + ": malformed crowdlab extras: " + e.what());
  }
  read_animation(model, joints, crowd, path);
  validate_crowd(crowd, path);
  validate_environment(crowd.environment, path);
  return crowd;
}

}  // namespace

CrowdAnimation read_crowd_glb(const std::string& path) {
  // A library's exception the checks above miss (an allocation, a JSON type) names this file (issue 33).
  return at_input_boundary(path, [&] { return read_crowd_glb_unwrapped(path); });
}

}  // namespace crowdlab
