#include "framework/surface/load_gltf_surface.hpp"

#include <tiny_gltf.h>

#include <cmath>
#include <utility>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/io/gltf_accessor_reader.hpp"
#include "framework/io/gltf_node_matrix.hpp"
#include "framework/io/load_gltf_model.hpp"

namespace crowdlab {
namespace {

/// Reads a primitive's accessors through framework/io's bounds-checked accessor reader (the one the
/// crowd-file reader uses), adding the surface's own checks.
struct Reader {
  const tinygltf::Model& model;
  std::string path;

  [[noreturn]] void fail(const std::string& where, const std::string& msg) const {
    throw InputError(SourceLocation{path, 0, 0, where}, msg);
  }

  std::string context(const std::string& where, const std::string& what) const {
    return path + ": " + where + " " + what;
  }

  std::vector<Vec3> positions(int accessor, const std::string& where) const {
    const std::vector<float> xyz =
        read_float_accessor(model, accessor, TINYGLTF_TYPE_VEC3, context(where, "POSITION"));
    std::vector<Vec3> out(xyz.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    return out;
  }

  std::vector<int> indices(int accessor, size_t vertex_count, const std::string& where) const {
    std::vector<int> out;
    if (accessor < 0) {  // non-indexed: consecutive vertices
      for (size_t i = 0; i < vertex_count; ++i) out.push_back(static_cast<int>(i));
      return out;
    }
    for (const std::uint32_t v : read_index_accessor(model, accessor, context(where, "indices"))) {
      if (v >= vertex_count)
        fail(where,
             "index " + std::to_string(v) + " out of range (" + std::to_string(vertex_count) + " vertices)");
      out.push_back(static_cast<int>(v));
    }
    return out;
  }
};

}  // namespace

SurfaceMesh load_gltf_surface(const std::string& path, double scale) {
  const tinygltf::Model model = load_gltf_model(path);
  const Reader reader{model, path};

  std::vector<Vec3> vertices;
  std::vector<Eigen::Vector3i> triangles;
  const auto add_mesh = [&](int mesh_index, const Eigen::Matrix4d& world) {
    if (mesh_index < 0 || mesh_index >= static_cast<int>(model.meshes.size()))
      reader.fail("nodes", "mesh index " + std::to_string(mesh_index) + " out of range");
    const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(mesh_index)];
    const bool mirrored = world.block<3, 3>(0, 0).determinant() < 0;
    for (size_t k = 0; k < mesh.primitives.size(); ++k) {
      const tinygltf::Primitive& prim = mesh.primitives[k];
      const std::string where =
          "meshes[" + std::to_string(mesh_index) + "] '" + mesh.name + "' primitive " + std::to_string(k);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1)
        reader.fail(where, "mode " + std::to_string(prim.mode) +
                               " is not a triangle mode (points/lines cannot be walked on)");
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) reader.fail(where, "primitive has no POSITION");
      const std::vector<Vec3> local = reader.positions(pos->second, where);
      const std::vector<int> idx = reader.indices(prim.indices, local.size(), where);
      const int base = static_cast<int>(vertices.size());
      for (const Vec3& v : local) vertices.push_back(scale * (world * v.homogeneous()).head<3>());
      const auto emit = [&](int a, int b, int c) {
        if (mirrored) std::swap(b, c);
        triangles.emplace_back(base + a, base + b, base + c);
      };
      if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t t = 0; t + 2 < idx.size(); ++t)
          t % 2 == 0 ? emit(idx[t], idx[t + 1], idx[t + 2]) : emit(idx[t + 1], idx[t], idx[t + 2]);
      } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t t = 1; t + 1 < idx.size(); ++t) emit(idx[0], idx[t], idx[t + 1]);
      } else {
        if (idx.size() % 3 != 0)
          reader.fail(where,
                      "triangle index count " + std::to_string(idx.size()) + " is not a multiple of 3");
        for (size_t t = 0; t + 2 < idx.size(); t += 3) emit(idx[t], idx[t + 1], idx[t + 2]);
      }
    }
  };
  // Depth-first, children in file order, with an explicit stack: a parent->child chain of any length
  // (100,000 nodes in a fuzzed file) must not recurse on the call stack.
  std::vector<int> visits(model.nodes.size(), 0);
  const auto visit = [&](int root, const Eigen::Matrix4d& root_parent) {
    std::vector<std::pair<int, Eigen::Matrix4d>> pending{{root, root_parent}};
    while (!pending.empty()) {
      const auto [node, parent] = pending.back();
      pending.pop_back();
      if (node < 0 || node >= static_cast<int>(model.nodes.size()))
        reader.fail("nodes", "node index " + std::to_string(node) + " out of range");
      if (visits[static_cast<size_t>(node)]++)
        reader.fail("nodes", "node " + std::to_string(node) + " is visited twice (cycle or shared child)");
      const tinygltf::Node& n = model.nodes[static_cast<size_t>(node)];
      const Eigen::Matrix4d world = parent * gltf_node_matrix(n);
      if (n.mesh >= 0) add_mesh(n.mesh, world);
      for (auto child = n.children.rbegin(); child != n.children.rend(); ++child)
        pending.emplace_back(*child, world);
    }
  };
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 && model.defaultScene < static_cast<int>(model.scenes.size())
                          ? model.defaultScene
                          : 0;
    for (int root : model.scenes[static_cast<size_t>(scene)].nodes) visit(root, Eigen::Matrix4d::Identity());
  } else if (!model.nodes.empty()) {
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && c < static_cast<int>(is_child.size())) is_child[static_cast<size_t>(c)] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) visit(static_cast<int>(i), Eigen::Matrix4d::Identity());
  } else {
    for (size_t m = 0; m < model.meshes.size(); ++m)
      add_mesh(static_cast<int>(m), Eigen::Matrix4d::Identity());
  }
  if (triangles.empty()) throw InputError(path + ": glTF file has no triangle primitives");
  return make_surface_mesh(std::move(vertices), std::move(triangles), path);
}

}  // namespace crowdlab
