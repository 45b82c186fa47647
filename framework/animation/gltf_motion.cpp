#include "framework/animation/gltf_motion.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"
#include "framework/io/gltf_accessor_reader.hpp"
#include "framework/io/gltf_node_parents.hpp"
#include "framework/io/load_gltf_model.hpp"

namespace crowdlab {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& where, const std::string& msg) {
  throw InputError(SourceLocation{path.string(), 0, 0, where}, msg);
}

// Reads a float accessor of `components` (1, 3 or 4) floats per element through the shared bounds-checked
// reader (framework/io/gltf_accessor_reader.hpp); errors name the file, the sampler and the accessor.
std::vector<double> read_floats(const tinygltf::Model& m, int accessor, int components,
                                const std::filesystem::path& path, const std::string& where) {
  const int type = components == 1   ? TINYGLTF_TYPE_SCALAR
                   : components == 3 ? TINYGLTF_TYPE_VEC3
                                     : TINYGLTF_TYPE_VEC4;
  const std::vector<float> values = read_float_accessor(m, accessor, type, path.string() + ": " + where);
  return {values.begin(), values.end()};
}

struct Trs {
  Vec3 t = Vec3::Zero();
  Quat r = Quat::Identity();
  double s = 1.0;  // uniform part of the scale
};

Trs node_trs(const tinygltf::Node& n) {
  Trs x;
  if (n.matrix.size() == 16) {
    Eigen::Matrix4d mat;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) mat(r, c) = n.matrix[static_cast<size_t>(c * 4 + r)];
    Mat3 lin = mat.block<3, 3>(0, 0);
    x.s = std::cbrt(std::abs(lin.determinant()));
    if (x.s > 0) lin /= x.s;
    x.r = Quat(lin).normalized();
    x.t = mat.block<3, 1>(0, 3);
    return x;
  }
  if (n.translation.size() == 3) x.t = Vec3(n.translation[0], n.translation[1], n.translation[2]);
  if (n.rotation.size() == 4)
    x.r = Quat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]).normalized();
  if (n.scale.size() == 3) x.s = std::cbrt(std::abs(n.scale[0] * n.scale[1] * n.scale[2]));
  return x;
}

struct Track {
  std::vector<double> times;
  std::vector<double> values;  // 3 or 4 per key (the value part for CUBICSPLINE)
  int width = 3;
  bool step = false;
};

Vec3 sample_vec3(const Track& k, double t) {
  auto at = [&](size_t i) { return Vec3(k.values[3 * i], k.values[3 * i + 1], k.values[3 * i + 2]); };
  if (t <= k.times.front()) return at(0);
  if (t >= k.times.back()) return at(k.times.size() - 1);
  const size_t i =
      static_cast<size_t>(std::upper_bound(k.times.begin(), k.times.end(), t) - k.times.begin()) - 1;
  if (k.step) return at(i);
  const double u = (t - k.times[i]) / std::max(1e-12, k.times[i + 1] - k.times[i]);
  return at(i) * (1 - u) + at(i + 1) * u;
}

Quat sample_quat(const Track& k, double t) {
  auto at = [&](size_t i) {
    return Quat(k.values[4 * i + 3], k.values[4 * i], k.values[4 * i + 1], k.values[4 * i + 2]).normalized();
  };
  if (t <= k.times.front()) return at(0);
  if (t >= k.times.back()) return at(k.times.size() - 1);
  const size_t i =
      static_cast<size_t>(std::upper_bound(k.times.begin(), k.times.end(), t) - k.times.begin()) - 1;
  if (k.step) return at(i);
  const double u = (t - k.times[i]) / std::max(1e-12, k.times[i + 1] - k.times[i]);
  return at(i).slerp(u, at(i + 1)).normalized();
}

}  // namespace

BvhMotion import_gltf_animation(const std::filesystem::path& path, int animation_index, int skin_index,
                                double fps) {
  if (!(fps > 0)) fail(path, "", "fps must be > 0");
  const tinygltf::Model m = load_gltf_model(path);
  if (animation_index < 0 || animation_index >= static_cast<int>(m.animations.size()))
    fail(path, "animations[" + std::to_string(animation_index) + "]",
         "no such animation (file has " + std::to_string(m.animations.size()) + ")");
  const tinygltf::Animation& anim = m.animations[static_cast<size_t>(animation_index)];
  const std::string anim_where = "animations[" + std::to_string(animation_index) + "]";

  // Parents of all nodes, checked to form trees (the walks below go up and down them).
  const std::vector<int> parent = gltf_node_parents(m, path.string());

  // Joint set.
  std::set<int> joint_set;
  if (!m.skins.empty()) {
    if (skin_index < 0 || skin_index >= static_cast<int>(m.skins.size()))
      fail(path, "skins[" + std::to_string(skin_index) + "]", "no such skin");
    for (int j : m.skins[static_cast<size_t>(skin_index)].joints) {
      if (j < 0 || j >= static_cast<int>(m.nodes.size()))
        fail(path, "skins[" + std::to_string(skin_index) + "]", "joint index out of range");
      joint_set.insert(j);
    }
  } else {
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const int target = anim.channels[c].target_node;
      if (target < 0 || target >= static_cast<int>(m.nodes.size()))
        fail(path, anim_where + ".channels[" + std::to_string(c) + "]",
             "target node " + std::to_string(target) + " does not exist (" + std::to_string(m.nodes.size()) +
                 " nodes)");
      for (int n = target; n >= 0; n = parent[static_cast<size_t>(n)]) joint_set.insert(n);
    }
  }
  if (joint_set.empty()) fail(path, anim_where, "no skeleton joints");

  // Parents-first order (depth-first from the skeleton roots, children in file order), with an explicit
  // stack: a parent->child chain of any length must not recurse on the call stack.
  BvhMotion out;
  out.source = path.string();
  std::map<int, int> index_of;
  std::vector<int> node_of;
  const auto visit = [&](int root) {
    std::vector<std::pair<int, int>> pending{{root, -1}};  // (node, its parent's joint index)
    while (!pending.empty()) {
      const auto [node, parent_joint] = pending.back();
      pending.pop_back();
      const int idx = static_cast<int>(out.joints.size());
      index_of[node] = idx;
      node_of.push_back(node);
      BvhJoint j;
      j.name = m.nodes[static_cast<size_t>(node)].name.empty() ? "node" + std::to_string(node)
                                                               : m.nodes[static_cast<size_t>(node)].name;
      j.parent = parent_joint;
      out.joints.push_back(j);
      const std::vector<int>& children = m.nodes[static_cast<size_t>(node)].children;
      for (auto c = children.rbegin(); c != children.rend(); ++c)
        if (joint_set.count(*c)) pending.emplace_back(*c, idx);
    }
  };
  for (int n : joint_set)
    if (parent[static_cast<size_t>(n)] < 0 || !joint_set.count(parent[static_cast<size_t>(n)])) visit(n);

  // Bake non-joint ancestors into the roots: world transform of the root's parent chain.
  std::vector<Trs> base(out.joints.size());  // rest local TRS per joint (roots include ancestors)
  std::vector<double> scale_above(out.joints.size(), 1.0);
  for (size_t i = 0; i < out.joints.size(); ++i) {
    base[i] = node_trs(m.nodes[static_cast<size_t>(node_of[i])]);
    if (out.joints[i].parent >= 0) {
      scale_above[i] =
          scale_above[static_cast<size_t>(out.joints[i].parent)] *
          node_trs(m.nodes[static_cast<size_t>(node_of[static_cast<size_t>(out.joints[i].parent)])]).s;
      continue;
    }
    Trs chain;  // ancestors, outermost first
    std::vector<int> ancestors;
    for (int a = parent[static_cast<size_t>(node_of[i])]; a >= 0; a = parent[static_cast<size_t>(a)])
      ancestors.push_back(a);
    for (auto it = ancestors.rbegin(); it != ancestors.rend(); ++it) {
      const Trs t = node_trs(m.nodes[static_cast<size_t>(*it)]);
      chain.t = chain.t + chain.r * (t.t * chain.s);
      chain.r = (chain.r * t.r).normalized();
      chain.s *= t.s;
    }
    scale_above[i] = chain.s;
    base[i].t = chain.t + chain.r * (base[i].t * chain.s);
    base[i].r = (chain.r * base[i].r).normalized();
  }
  for (size_t i = 0; i < out.joints.size(); ++i) {
    out.joints[i].offset = out.joints[i].parent < 0 ? base[i].t : Vec3(base[i].t * scale_above[i]);
    out.joints[i].channels = {BvhChannel::kXposition, BvhChannel::kYposition, BvhChannel::kZposition,
                              BvhChannel::kZrotation, BvhChannel::kXrotation, BvhChannel::kYrotation};
    out.joints[i].first_channel = 6 * static_cast<int>(i);
  }
  out.channel_count = 6 * static_cast<int>(out.joints.size());

  // Tracks.
  std::map<int, Track> translation, rotation;
  double t0 = 1e300, t1 = -1e300;
  for (size_t c = 0; c < anim.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = anim.channels[c];
    const std::string where = anim_where + ".channels[" + std::to_string(c) + "]";
    if (!index_of.count(ch.target_node)) continue;
    if (ch.target_path != "translation" && ch.target_path != "rotation") continue;
    if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size()))
      fail(path, where, "sampler index out of range");
    const tinygltf::AnimationSampler& s = anim.samplers[static_cast<size_t>(ch.sampler)];
    Track k;
    k.width = ch.target_path == "rotation" ? 4 : 3;
    k.step = s.interpolation == "STEP";
    k.times = read_floats(m, s.input, 1, path, where + ".input");
    std::vector<double> values = read_floats(m, s.output, k.width, path, where + ".output");
    if (s.interpolation == "CUBICSPLINE") {  // [in-tangent, value, out-tangent] per key
      if (values.size() != 3 * k.times.size() * static_cast<size_t>(k.width))
        fail(path, where, "CUBICSPLINE output must hold 3 values per key");
      std::vector<double> v;
      for (size_t i = 0; i < k.times.size(); ++i)
        for (int d = 0; d < k.width; ++d)
          v.push_back(values[(3 * i + 1) * static_cast<size_t>(k.width) + static_cast<size_t>(d)]);
      values = v;
    }
    if (k.times.empty() || values.size() != k.times.size() * static_cast<size_t>(k.width))
      fail(path, where, "sampler input and output counts differ");
    for (size_t i = 1; i < k.times.size(); ++i)
      if (k.times[i] < k.times[i - 1]) fail(path, where, "key times must increase");
    k.values = values;
    t0 = std::min(t0, k.times.front());
    t1 = std::max(t1, k.times.back());
    (ch.target_path == "rotation" ? rotation : translation)[index_of[ch.target_node]] = std::move(k);
  }
  if (t0 > t1) fail(path, anim_where, "animation has no translation or rotation channel on the skeleton");

  out.frame_time_s = 1.0 / fps;
  const double frames = std::floor((t1 - t0) * fps + 1e-9) + 1;
  if (frames * out.channel_count > kMaxGltfClipValues)
    fail(path, anim_where,
         "sampling its " + std::to_string(t1 - t0) + " s at " + std::to_string(fps) + " fps gives " +
             std::to_string(frames) + " frames x " + std::to_string(out.channel_count) +
             " channels, more than the limit of " + std::to_string(kMaxGltfClipValues) +
             " values (kMaxGltfClipValues; key times not in seconds?)");
  out.frame_count = static_cast<int>(frames);
  out.values.resize(static_cast<size_t>(out.frame_count) * static_cast<size_t>(out.channel_count));
  for (int f = 0; f < out.frame_count; ++f) {
    const double t = t0 + f / fps;
    for (size_t i = 0; i < out.joints.size(); ++i) {
      const int idx = static_cast<int>(i);
      Vec3 tr = out.joints[i].offset;
      Quat rot = base[i].r;
      if (translation.count(idx)) {
        const Vec3 raw = sample_vec3(translation[idx], t);
        if (out.joints[i].parent < 0) {  // re-apply the baked ancestors
          const Trs rest = node_trs(m.nodes[static_cast<size_t>(node_of[i])]);
          tr = base[i].t + (base[i].r * rest.r.conjugate()) * ((raw - rest.t) * scale_above[i]);
        } else {
          tr = raw * scale_above[i];
        }
      }
      if (rotation.count(idx)) {
        const Quat q = sample_quat(rotation[idx], t);
        rot = out.joints[i].parent < 0
                  ? Quat(base[i].r * node_trs(m.nodes[static_cast<size_t>(node_of[i])]).r.conjugate() * q)
                  : q;
      }
      const Vec3 e = rot.normalized().toRotationMatrix().eulerAngles(2, 0, 1) * (180.0 / anim::kPi);
      double* v = out.values.data() + static_cast<size_t>(f) * static_cast<size_t>(out.channel_count) + 6 * i;
      v[0] = tr.x(), v[1] = tr.y(), v[2] = tr.z(), v[3] = e.x(), v[4] = e.y(), v[5] = e.z();
    }
  }
  return out;
}

}  // namespace crowdlab
