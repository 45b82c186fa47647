#include "stimuli/gltf_character.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "framework/animation/bvh.hpp"
#include "framework/animation/retarget.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/io/gltf_accessor_reader.hpp"
#include "framework/io/gltf_node_matrix.hpp"
#include "framework/io/load_gltf_model.hpp"

namespace crowdlab::stimuli {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& message) {
  throw InputError(SourceLocation{file, 0, 0, where}, message);
}

std::uint8_t encode_gamma2(double linear) {  // the renderer's colour convention (shaders.cpp)
  return static_cast<std::uint8_t>(std::lround(255.0 * std::sqrt(std::clamp(linear, 0.0, 1.0))));
}

/// The next SMPL joint down the chain that defines joint j's bone direction (trunk first).
int primary_child(int j) {
  if (j == kPelvis) return kSpine1;
  if (j == kSpine3) return kNeck;
  for (int c = 0; c < kJointCount; ++c)
    if (kJointParent[static_cast<size_t>(c)] == j) return c;
  return -1;
}

void append_primitive(const tinygltf::Model& m, const tinygltf::Primitive& prim, const std::string& file,
                      const std::string& where, int joint_count, GltfCharacter& c) {
  const auto attribute = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const std::string ctx = file + ": " + where;
  if (attribute("POSITION") < 0) fail(file, where + ".attributes", "no POSITION attribute");
  if (attribute("JOINTS_0") < 0 || attribute("WEIGHTS_0") < 0)
    fail(file, where + ".attributes", "a skinned primitive needs JOINTS_0 and WEIGHTS_0");
  const std::vector<float> pos = read_float_accessor(m, attribute("POSITION"), TINYGLTF_TYPE_VEC3, ctx);
  const size_t count = pos.size() / 3;
  // JOINTS_0 (glTF 2.0 §3.7.3.1: VEC4 of unsigned byte or short), bounds-checked by the shared reader.
  const std::vector<std::uint32_t> joint_ids =
      read_uint_accessor(m, attribute("JOINTS_0"), TINYGLTF_TYPE_VEC4, ctx + ".attributes.JOINTS_0");
  std::vector<std::array<int, 4>> joints(joint_ids.size() / 4);
  for (size_t v = 0; v < joints.size(); ++v)
    for (size_t k = 0; k < 4; ++k) joints[v][k] = static_cast<int>(joint_ids[4 * v + k]);
  const std::vector<float> weights = read_float_accessor(m, attribute("WEIGHTS_0"), TINYGLTF_TYPE_VEC4, ctx);
  std::vector<float> normals;
  if (attribute("NORMAL") >= 0)
    normals = read_float_accessor(m, attribute("NORMAL"), TINYGLTF_TYPE_VEC3, ctx);
  std::vector<float> colours;
  int colour_width = 0;
  if (const int ci = attribute("COLOR_0"); ci >= 0) {
    if (ci >= static_cast<int>(m.accessors.size()))
      fail(file, where + ".attributes.COLOR_0", "no such accessor");
    const int type = m.accessors[static_cast<size_t>(ci)].type;
    colour_width = type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    colours = read_float_accessor(m, ci, colour_width == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, ctx);
  }
  if (joints.size() != count || weights.size() != 4 * count ||
      (!normals.empty() && normals.size() != 3 * count) ||
      (colour_width > 0 && colours.size() != static_cast<size_t>(colour_width) * count))
    fail(file, where + ".attributes", "attributes have different vertex counts");
  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    idx = read_index_accessor(m, prim.indices, ctx);
  } else {
    idx.resize(count);
    for (size_t i = 0; i < count; ++i) idx[i] = static_cast<std::uint32_t>(i);
  }
  if (idx.size() % 3 != 0) fail(file, where + ".indices", "index count is not a multiple of 3");
  for (std::uint32_t i : idx)
    if (i >= count) fail(file, where + ".indices", "index " + std::to_string(i) + " >= vertex count");
  // Material colour (linear baseColorFactor; glTF 2.0 §3.9.2), default white.
  std::array<double, 3> base = {1.0, 1.0, 1.0};
  if (prim.material >= 0 && prim.material < static_cast<int>(m.materials.size())) {
    const auto& f = m.materials[static_cast<size_t>(prim.material)].pbrMetallicRoughness.baseColorFactor;
    if (f.size() >= 3) base = {f[0], f[1], f[2]};
  }
  const auto first = static_cast<std::uint32_t>(c.positions.size());
  for (size_t v = 0; v < count; ++v) {
    c.positions.emplace_back(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    c.normals.push_back(normals.empty() ? Vec3::Zero()
                                        : Vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]));
    std::array<double, 4> w{};
    double sum = 0.0;
    for (size_t k = 0; k < 4; ++k) {
      w[k] = static_cast<double>(weights[4 * v + k]);
      if (w[k] < 0.0)
        fail(file, where + ".attributes.WEIGHTS_0", "negative weight at vertex " + std::to_string(v));
      if (w[k] > 0.0 && joints[v][k] >= joint_count)
        fail(file, where + ".attributes.JOINTS_0",
             "vertex " + std::to_string(v) + " uses joint " + std::to_string(joints[v][k]) +
                 " but the skin has " + std::to_string(joint_count));
      sum += w[k];
    }
    if (!(sum > 1e-6))
      fail(file, where + ".attributes.WEIGHTS_0", "vertex " + std::to_string(v) + " has no weight");
    for (double& x : w) x /= sum;
    c.weights.push_back(w);
    std::array<int, 4> j = joints[v];
    for (size_t k = 0; k < 4; ++k)
      if (w[k] == 0.0) j[k] = 0;  // unused slots may hold any index
    c.joints.push_back(j);
    std::array<double, 3> rgb = base;
    if (colour_width > 0)
      for (size_t k = 0; k < 3; ++k)
        rgb[k] *= static_cast<double>(colours[static_cast<size_t>(colour_width) * v + k]);
    c.colours.push_back({encode_gamma2(rgb[0]), encode_gamma2(rgb[1]), encode_gamma2(rgb[2]), 255});
  }
  for (std::uint32_t i : idx) c.indices.push_back(first + i);
  if (normals.empty()) {  // area-weighted vertex normals of this primitive
    for (size_t t = 0; t < idx.size(); t += 3) {
      const Vec3 &a = c.positions[first + idx[t]], &b = c.positions[first + idx[t + 1]],
                 &d = c.positions[first + idx[t + 2]];
      const Vec3 n = (b - a).cross(d - a);
      for (size_t k = 0; k < 3; ++k) c.normals[first + idx[t + k]] += n;
    }
  }
}

}  // namespace

GltfCharacter load_gltf_character(const std::filesystem::path& path) {
  const std::string file = path.string();
  const tinygltf::Model m = load_gltf_model(path);
  int node = -1;
  for (size_t i = 0; i < m.nodes.size() && node < 0; ++i)
    if (m.nodes[i].mesh >= 0 && m.nodes[i].skin >= 0) node = static_cast<int>(i);
  if (node < 0) fail(file, "nodes", "no skinned mesh (a node with both a mesh and a skin)");
  const tinygltf::Node& holder = m.nodes[static_cast<size_t>(node)];
  const std::string node_where = "nodes[" + std::to_string(node) + "]";
  if (holder.skin >= static_cast<int>(m.skins.size())) fail(file, node_where, "skin index out of range");
  if (holder.mesh >= static_cast<int>(m.meshes.size())) fail(file, node_where, "mesh index out of range");
  const tinygltf::Skin& skin = m.skins[static_cast<size_t>(holder.skin)];
  const std::string skin_where = "skins[" + std::to_string(holder.skin) + "]";
  if (skin.joints.empty()) fail(file, skin_where, "the skin has no joints");

  GltfCharacter c;
  c.source = file;
  // Skin joints: names, parents among the skin joints, bind positions.
  std::vector<int> parent_node(m.nodes.size(), -1);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    for (int ch : m.nodes[i].children) {
      if (ch < 0 || ch >= static_cast<int>(m.nodes.size()))
        fail(file, "nodes[" + std::to_string(i) + "]", "child index out of range");
      parent_node[static_cast<size_t>(ch)] = static_cast<int>(i);
    }
  std::map<int, int> joint_of_node;
  for (size_t k = 0; k < skin.joints.size(); ++k) {
    const int jn = skin.joints[k];
    if (jn < 0 || jn >= static_cast<int>(m.nodes.size()))
      fail(file, skin_where + ".joints[" + std::to_string(k) + "]", "node index out of range");
    joint_of_node[jn] = static_cast<int>(k);
  }
  const size_t nj = skin.joints.size();
  c.joint_names.resize(nj);
  c.joint_parent.assign(nj, -1);
  c.joint_bind_position.resize(nj);
  std::vector<Eigen::Matrix4d> skin_matrix(nj);
  std::vector<float> ibm;
  if (skin.inverseBindMatrices >= 0) {
    ibm = read_float_accessor(m, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, file + ": " + skin_where);
    if (ibm.size() != 16 * nj) fail(file, skin_where + ".inverseBindMatrices", "needs one matrix per joint");
  }
  for (size_t k = 0; k < nj; ++k) {
    const int jn = skin.joints[k];
    const tinygltf::Node& jnode = m.nodes[static_cast<size_t>(jn)];
    c.joint_names[k] = jnode.name.empty() ? "node" + std::to_string(jn) : jnode.name;
    int depth = 0;
    for (int a = parent_node[static_cast<size_t>(jn)]; a >= 0; a = parent_node[static_cast<size_t>(a)]) {
      if (++depth > static_cast<int>(m.nodes.size()))
        fail(file, "nodes[" + std::to_string(jn) + "]", "the node hierarchy has a cycle");
      if (joint_of_node.count(a)) {
        c.joint_parent[k] = joint_of_node[a];
        break;
      }
    }
    // The joint's world transform in the file's rest node pose (armature rotations and scales included).
    Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
    for (int a = jn; a >= 0; a = parent_node[static_cast<size_t>(a)]) {
      if (++depth > 2 * static_cast<int>(m.nodes.size()))
        fail(file, "nodes[" + std::to_string(jn) + "]", "the node hierarchy has a cycle");
      world = gltf_node_matrix(m.nodes[static_cast<size_t>(a)]) * world;
    }
    Eigen::Matrix4d inverse_bind = Eigen::Matrix4d::Identity();  // glTF's default
    if (!ibm.empty()) {
      for (int col = 0; col < 4; ++col)
        for (int r = 0; r < 4; ++r) inverse_bind(r, col) = ibm[16 * k + static_cast<size_t>(col * 4 + r)];
      if (std::abs(inverse_bind.determinant()) < 1e-12)
        fail(file, skin_where + ".inverseBindMatrices[" + std::to_string(k) + "]", "singular matrix");
    }
    skin_matrix[k] = world * inverse_bind;  // mesh space -> world, the joint matrix of glTF 2.0 §3.7.3
    c.joint_bind_position[k] = world.block<3, 1>(0, 3);
  }
  // Geometry.
  const tinygltf::Mesh& mesh = m.meshes[static_cast<size_t>(holder.mesh)];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string where =
        "meshes[" + std::to_string(holder.mesh) + "].primitives[" + std::to_string(p) + "]";
    if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points and lines are not skin
    append_primitive(m, prim, file, where, static_cast<int>(nj), c);
  }
  if (c.indices.empty())
    fail(file, "meshes[" + std::to_string(holder.mesh) + "]", "the skinned mesh has no triangles");
  // Pose the mesh by its skin in the rest node pose: world-space vertices and normals (Y-up, metres
  // when the file's nodes say so), whatever the mesh space of the file (e.g. Z-up centimetres).
  for (size_t v = 0; v < c.positions.size(); ++v) {
    Eigen::Matrix4d blend = Eigen::Matrix4d::Zero();
    for (size_t k = 0; k < 4; ++k)
      if (c.weights[v][k] > 0.0) blend += c.weights[v][k] * skin_matrix[static_cast<size_t>(c.joints[v][k])];
    c.positions[v] = (blend * c.positions[v].homogeneous()).head<3>();
    const Mat3 linear = blend.block<3, 3>(0, 0);
    if (std::abs(linear.determinant()) > 1e-18) c.normals[v] = linear.inverse().transpose() * c.normals[v];
  }
  for (Vec3& n : c.normals) n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitY();
  // Joint names -> SMPL joints (the animation layer's name maps); a skeleton-only BvhMotion carries them.
  BvhMotion skeleton;
  skeleton.source = file;
  for (size_t k = 0; k < nj; ++k) {
    BvhJoint j;
    j.name = c.joint_names[k];
    j.parent = c.joint_parent[k];
    skeleton.joints.push_back(j);
  }
  const JointMap map = map_joint_names(skeleton);
  c.smpl_source = map.source;
  std::vector<int> smpl_of(nj, -1);
  for (int j = 0; j < kJointCount; ++j)
    if (map.source[static_cast<size_t>(j)] >= 0)
      smpl_of[static_cast<size_t>(map.source[static_cast<size_t>(j)])] = j;
  c.smpl_of_joint.assign(nj, kPelvis);  // joints above the hips (an armature root) follow the pelvis
  for (size_t k = 0; k < nj; ++k)
    for (int a = static_cast<int>(k); a >= 0; a = c.joint_parent[static_cast<size_t>(a)])
      if (smpl_of[static_cast<size_t>(a)] >= 0) {
        c.smpl_of_joint[k] = smpl_of[static_cast<size_t>(a)];
        break;
      }
  return c;
}

MannequinMesh fit_gltf_character(const GltfCharacter& c, const BodyShape& shape) {
  validate_body_shape(shape, "glTF character " + c.source);
  double y_lo = 1e300, y_hi = -1e300;
  for (const Vec3& p : c.positions) {
    y_lo = std::min(y_lo, p.y());
    y_hi = std::max(y_hi, p.y());
  }
  if (!(y_hi - y_lo > 1e-9))
    throw InputError(SourceLocation{c.source, 0, 0, "meshes"}, "the mesh has no height");
  const double s = shape.params.height_m / (y_hi - y_lo);
  const BoneTransforms rest = forward_kinematics(shape, Pose::rest(shape));
  // Per SMPL joint: rotation R_j and the file joint it sits on.
  std::array<Quat, kJointCount> rotation;
  std::array<Vec3, kJointCount> file_joint;
  for (int j = 0; j < kJointCount; ++j) {  // parents precede children in the SMPL order
    const int parent = kJointParent[static_cast<size_t>(j)];
    rotation[static_cast<size_t>(j)] = parent >= 0 ? rotation[static_cast<size_t>(parent)] : Quat::Identity();
    const int src = c.smpl_source[static_cast<size_t>(j)];
    // An unmapped SMPL joint is never the driver of a vertex (smpl_of_joint names mapped joints only).
    file_joint[static_cast<size_t>(j)] =
        src >= 0 ? c.joint_bind_position[static_cast<size_t>(src)] : Vec3::Zero();
    if (src < 0) continue;
    const int child = primary_child(j);
    if (child < 0 || c.smpl_source[static_cast<size_t>(child)] < 0) continue;
    const Vec3 d_file =
        c.joint_bind_position[static_cast<size_t>(c.smpl_source[static_cast<size_t>(child)])] -
        c.joint_bind_position[static_cast<size_t>(src)];
    const Vec3 d_body =
        rest[static_cast<size_t>(child)].translation - rest[static_cast<size_t>(j)].translation;
    if (d_file.norm() > 1e-9 && d_body.norm() > 1e-9)
      rotation[static_cast<size_t>(j)] = Quat::FromTwoVectors(d_file, d_body).normalized();
  }
  MannequinMesh out;
  out.indices = c.indices;
  out.vertices.resize(c.positions.size());
  for (size_t v = 0; v < c.positions.size(); ++v) {
    Vec3 p = Vec3::Zero(), n = Vec3::Zero();
    std::array<double, kJointCount> influence{};
    for (size_t k = 0; k < 4; ++k) {
      const double w = c.weights[v][k];
      if (w == 0.0) continue;
      const auto j = static_cast<size_t>(c.smpl_of_joint[static_cast<size_t>(c.joints[v][k])]);
      p += w * (rest[j].translation + rotation[j] * (s * (c.positions[v] - file_joint[j])));
      n += w * (rotation[j] * c.normals[v]);
      influence[j] += w;
    }
    MannequinVertex& mv = out.vertices[v];
    n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitY();
    for (int a = 0; a < 3; ++a) {
      mv.position[static_cast<size_t>(a)] = static_cast<float>(p[a]);
      mv.normal[static_cast<size_t>(a)] = static_cast<float>(n[a]);
    }
    // The four largest SMPL influences (ties: lower joint first), as bytes summing to 255.
    std::array<int, kJointCount> order;
    for (int j = 0; j < kJointCount; ++j) order[static_cast<size_t>(j)] = j;
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return influence[static_cast<size_t>(a)] > influence[static_cast<size_t>(b)];
    });
    double total = 0.0;
    for (size_t k = 0; k < 4; ++k) total += influence[static_cast<size_t>(order[k])];
    int assigned = 0;
    for (size_t k = 0; k < 4; ++k) {
      const double w = influence[static_cast<size_t>(order[k])];
      mv.bones[k] = static_cast<std::uint8_t>(w > 0.0 ? order[k] : order[0]);
      const int q = k > 0 && w > 0.0 ? static_cast<int>(std::lround(255.0 * w / total)) : 0;
      mv.weights[k] = static_cast<std::uint8_t>(q);
      assigned += q;
    }
    mv.weights[0] = static_cast<std::uint8_t>(255 - assigned);
    mv.region = static_cast<std::uint8_t>(SkinRegion::kSkin);
    mv.colour = c.colours[v];
  }
  return out;
}

}  // namespace crowdlab::stimuli
