#include "framework/surface/surface_mesh.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

struct VecHash {
  size_t operator()(const Vec3& v) const {
    const auto h = [](double x) { return std::hash<double>()(x); };
    return h(v.x()) ^ (h(v.y()) * 31) ^ (h(v.z()) * 131);
  }
};
struct VecEq {
  bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
};

}  // namespace

SurfaceMesh make_surface_mesh(std::vector<Vec3> vertices, std::vector<Eigen::Vector3i> triangles,
                              const std::string& source) {
  if (vertices.empty() || triangles.empty()) throw InputError(source + ": mesh has no triangles");
  for (size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite())
      throw InputError(source + ": vertex " + std::to_string(i) + " is not finite");

  // Weld exact duplicates so that separately stored copies of a seam vertex become one.
  std::unordered_map<Vec3, int, VecHash, VecEq> unique;
  std::vector<int> remap(vertices.size());
  SurfaceMesh m;
  m.name = source;
  for (size_t i = 0; i < vertices.size(); ++i) {
    auto [it, inserted] = unique.emplace(vertices[i], static_cast<int>(m.vertices_m.size()));
    if (inserted) m.vertices_m.push_back(vertices[i]);
    remap[i] = it->second;
  }
  for (size_t f = 0; f < triangles.size(); ++f) {
    Eigen::Vector3i t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || static_cast<size_t>(t[k]) >= vertices.size())
        throw InputError(source + ": face " + std::to_string(f) + " has vertex index " +
                         std::to_string(t[k]) + " out of range");
      t[k] = remap[static_cast<size_t>(t[k])];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    const Vec3 a = m.vertices_m[static_cast<size_t>(t[0])], b = m.vertices_m[static_cast<size_t>(t[1])],
               c = m.vertices_m[static_cast<size_t>(t[2])];
    const Vec3 n = (b - a).cross(c - a);
    if (0.5 * n.norm() < 1e-12) continue;
    m.triangles.push_back(t);
    m.face_normals.push_back(n.normalized());
    m.total_area_m2 += 0.5 * n.norm();
  }
  if (m.triangles.empty()) throw InputError(source + ": every triangle is degenerate");

  const size_t F = m.triangles.size();
  m.neighbors.assign(F, {-1, -1, -1});
  m.neighbor_edge.assign(F, {-1, -1, -1});
  m.flips_orientation.assign(F, {false, false, false});
  // Undirected edge -> the (face, edge) half-edges that use it.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edges;
  for (size_t f = 0; f < F; ++f)
    for (int e = 0; e < 3; ++e) {
      const int u = m.triangles[f][e], v = m.triangles[f][(e + 1) % 3];
      edges[{std::min(u, v), std::max(u, v)}].emplace_back(static_cast<int>(f), e);
    }
  for (const auto& [key, uses] : edges) {
    if (uses.size() > 2)
      throw InputError(source + ": non-manifold edge between vertices " + std::to_string(key.first) +
                       " and " + std::to_string(key.second) + " is shared by " + std::to_string(uses.size()) +
                       " triangles");
    if (uses.size() != 2) continue;
    const auto [f0, e0] = uses[0];
    const auto [f1, e1] = uses[1];
    const bool same_direction =
        m.triangles[static_cast<size_t>(f0)][e0] == m.triangles[static_cast<size_t>(f1)][e1];
    m.neighbors[static_cast<size_t>(f0)][static_cast<size_t>(e0)] = f1;
    m.neighbors[static_cast<size_t>(f1)][static_cast<size_t>(e1)] = f0;
    m.neighbor_edge[static_cast<size_t>(f0)][static_cast<size_t>(e0)] = e1;
    m.neighbor_edge[static_cast<size_t>(f1)][static_cast<size_t>(e1)] = e0;
    m.flips_orientation[static_cast<size_t>(f0)][static_cast<size_t>(e0)] = same_direction;
    m.flips_orientation[static_cast<size_t>(f1)][static_cast<size_t>(e1)] = same_direction;
  }
  m.vertex_normals.assign(m.vertices_m.size(), Vec3::Zero());
  for (size_t f = 0; f < F; ++f) {
    const Vec3 a = m.corner(static_cast<int>(f), 0), b = m.corner(static_cast<int>(f), 1),
               c = m.corner(static_cast<int>(f), 2);
    const Vec3 area_normal = 0.5 * (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) m.vertex_normals[static_cast<size_t>(m.triangles[f][k])] += area_normal;
  }
  for (Vec3& n : m.vertex_normals) n = n.norm() > 0 ? n.normalized() : Vec3::UnitY();
  return m;
}

SurfaceMesh load_obj_surface(const std::string& path, double scale) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open mesh file");
  std::vector<Vec3> verts;
  std::vector<Eigen::Vector3i> tris;
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& msg) { throw InputError(SourceLocation{path, line_no, 0, ""}, msg); };
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      double x, y, z;
      if (!(ss >> x >> y >> z)) fail("vertex needs three numbers");
      verts.emplace_back(x * scale, y * scale, z * scale);
    } else if (tag == "f") {
      std::vector<int> idx;
      std::string tok;
      while (ss >> tok) {
        int i = 0;
        const auto slash = tok.find('/');
        const std::string_view head = std::string_view(tok).substr(0, slash);
        auto [p, ec] = std::from_chars(head.data(), head.data() + head.size(), i);
        if (ec != std::errc() || p != head.data() + head.size() || i == 0)
          fail("bad face index '" + tok + "'");
        i = i > 0 ? i - 1 : static_cast<int>(verts.size()) + i;
        if (i < 0 || static_cast<size_t>(i) >= verts.size()) fail("face index '" + tok + "' out of range");
        idx.push_back(i);
      }
      if (idx.size() < 3) fail("face needs at least three vertices");
      for (size_t k = 1; k + 1 < idx.size(); ++k) tris.emplace_back(idx[0], idx[k], idx[k + 1]);
    }
  }
  return make_surface_mesh(std::move(verts), std::move(tris), path);
}

}  // namespace crowdlab
