#include "framework/surface/surface_scenes.hpp"

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>

#include "framework/core/error.hpp"
#include "framework/spec/surface_scene_names.hpp"
#include "framework/surface/load_gltf_surface.hpp"

namespace crowdlab {
namespace {

using Grid = std::function<Vec3(double u, double v)>;

/// Triangulates a (nu x nv)-cell parametric patch over [0,1]^2. Vertices on shared boundaries are
/// welded later by make_surface_mesh, so periodic patches close up when the map repeats exactly.
void add_patch(std::vector<Vec3>& verts, std::vector<Eigen::Vector3i>& tris, const Grid& map, int nu, int nv,
               bool flip = false) {
  const int base = static_cast<int>(verts.size());
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j)
      verts.push_back(map(static_cast<double>(i) / nu, static_cast<double>(j) / nv));
  auto id = [&](int i, int j) { return base + i * (nv + 1) + j; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      Eigen::Vector3i t0(id(i, j), id(i, j + 1), id(i + 1, j)),
          t1(id(i + 1, j), id(i, j + 1), id(i + 1, j + 1));
      if (flip) {
        std::swap(t0[1], t0[2]);
        std::swap(t1[1], t1[2]);
      }
      tris.push_back(t0);
      tris.push_back(t1);
    }
}

int cells(double length, double resolution) {
  return std::max(1, static_cast<int>(std::ceil(length / resolution)));
}

/// Rounds coordinates to 1e-9 m so that analytically equal seam points weld exactly.
Vec3 snap(const Vec3& p) {
  return Vec3(std::round(p.x() * 1e9) / 1e9, std::round(p.y() * 1e9) / 1e9, std::round(p.z() * 1e9) / 1e9);
}

/// Adds the six faces of an axis-aligned box (outward normals) as grids of cells.
void add_box(std::vector<Vec3>& v, std::vector<Eigen::Vector3i>& t, const Vec3& lo, const Vec3& hi,
             double res) {
  const Vec3 s = hi - lo;
  const int nx = cells(s.x(), res), ny = cells(s.y(), res), nz = cells(s.z(), res);
  auto P = [&](double x, double y, double z) { return snap(lo + Vec3(x * s.x(), y * s.y(), z * s.z())); };
  // add_patch's unflipped normal is d(second param) x d(first param); flips make every normal outward.
  add_patch(
      v, t, [&](double a, double b) { return P(a, 1, b); }, nx, nz, false);  // top (+y)
  add_patch(
      v, t, [&](double a, double b) { return P(a, 0, b); }, nx, nz, true);  // bottom (-y)
  add_patch(
      v, t, [&](double a, double b) { return P(1, a, b); }, ny, nz, true);  // +x
  add_patch(
      v, t, [&](double a, double b) { return P(0, a, b); }, ny, nz, false);  // -x
  add_patch(
      v, t, [&](double a, double b) { return P(a, b, 1); }, nx, ny, true);  // +z
  add_patch(
      v, t, [&](double a, double b) { return P(a, b, 0); }, nx, ny, false);  // -z
}

}  // namespace

SurfaceMesh make_two_storey_building(double storey_height_m, double resolution_m) {
  // Centre line: a rectangle loop around a 6 m x 2 m atrium, walked twice; the strip is 3 m wide.
  // Each lap is flat except a ramp in the middle of the third side (not at corners, so the slope is the
  // same across the strip's width): 2.6 m over 6 m, about 23 degrees.
  const double ax = 4.5, az = 2.5, half_width = 1.5;
  const double side_len[4] = {2 * ax, 2 * az, 2 * ax, 2 * az};
  const double perimeter = 4 * (ax + az);
  const double ramp_start = side_len[0] + side_len[1] + half_width;
  const double ramp_end = side_len[0] + side_len[1] + side_len[2] - half_width;
  auto height = [&](double s) {
    const double lap = std::floor(s / perimeter + 1e-12), local = s - lap * perimeter;
    return storey_height_m * (lap + std::clamp((local - ramp_start) / (ramp_end - ramp_start), 0.0, 1.0));
  };
  const Vec2 corners[4] = {Vec2(-ax, -az), Vec2(ax, -az), Vec2(ax, az), Vec2(-ax, az)};
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  for (int lap = 0; lap < 2; ++lap) {
    double s0 = lap * perimeter;
    for (int side = 0; side < 4; ++side) {
      const double len = side_len[side];
      const Vec2 dir = (corners[(side + 1) % 4] - corners[side]) / len;
      const Vec2 outward(dir.y(), -dir.x());
      // Columns: the end columns are mitred onto the corner diagonals (along-offset -w and len + w);
      // the interior ones are evenly spaced between half_width and len - half_width, so interior cells
      // are rectangles and corner cells never fold over.
      const int interior = cells(len - 2 * half_width, resolution_m);
      const int columns = interior + 2;
      add_patch(
          v, t,
          [&, s0, len, dir, outward, side, interior, columns](double a, double b) {
            const int k = static_cast<int>(std::lround(a * columns));
            const double w = (b * 2 - 1) * half_width;
            const double along = k == 0         ? -w
                                 : k == columns ? len + w
                                                : half_width + (k - 1) * (len - 2 * half_width) / interior;
            const Vec2 p = corners[side] + dir * along + outward * w;
            return snap(Vec3(p.x(), height(s0 + std::clamp(along, 0.0, len)), p.y()));
          },
          columns, cells(2 * half_width, resolution_m), true);
      s0 += len;
    }
  }
  return make_surface_mesh(std::move(v), std::move(t), "building");
}

SurfaceMesh make_floor_ceiling_slab(double size_m, double thickness_m, double resolution_m) {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_box(v, t, Vec3(-size_m / 2, 2.5, -size_m / 2), Vec3(size_m / 2, 2.5 + thickness_m, size_m / 2),
          resolution_m);
  return make_surface_mesh(std::move(v), std::move(t), "floor_ceiling");
}

SurfaceMesh make_floor_and_wall(double size_m, double resolution_m) {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  const int n = cells(size_m, resolution_m);
  // Floor normal +y, wall normal +x: both face the same (inner) side, so the orientation is consistent.
  add_patch(
      v, t, [&](double a, double b) { return snap(Vec3(a * size_m, 0, b * size_m)); }, n, n, false);
  add_patch(
      v, t, [&](double a, double b) { return snap(Vec3(0, a * size_m, b * size_m)); }, n, n, true);
  return make_surface_mesh(std::move(v), std::move(t), "floor_wall");
}

SurfaceMesh make_mobius_strip(double R, double w, int segments, int across) {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_patch(
      v, t,
      [&](double a, double b) {
        const double u = a * 2 * std::numbers::pi, s = (b * 2 - 1) * w;
        return snap(Vec3((R + s * std::cos(u / 2)) * std::cos(u), s * std::sin(u / 2),
                         (R + s * std::cos(u / 2)) * std::sin(u)));
      },
      segments, across);
  return make_surface_mesh(std::move(v), std::move(t), "mobius");
}

SurfaceMesh make_torus(double R, double r, int nu, int nv) {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_patch(
      v, t,
      [&](double a, double b) {
        const double u = a * 2 * std::numbers::pi, phi = b * 2 * std::numbers::pi;
        return snap(Vec3((R + r * std::cos(phi)) * std::cos(u), r * std::sin(phi),
                         (R + r * std::cos(phi)) * std::sin(u)));
      },
      nu, nv, false);
  return make_surface_mesh(std::move(v), std::move(t), "torus");
}

SurfaceMesh make_tree(double trunk_r, double branch_r, int ring) {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  // A capped tube from a to b: side patch + two fan caps.
  auto tube = [&](const Vec3& a, const Vec3& b, double r) {
    const Vec3 axis = (b - a).normalized();
    const Vec3 e1 =
        (std::abs(axis.y()) < 0.9 ? axis.cross(Vec3::UnitY()) : axis.cross(Vec3::UnitX())).normalized();
    const Vec3 e2 = axis.cross(e1);
    const int nl = std::max(2, static_cast<int>((b - a).norm() / (2 * std::numbers::pi * r / ring)));
    auto ringpt = [&](const Vec3& c, double ang) {
      return snap(c + r * (std::cos(ang) * e1 + std::sin(ang) * e2));
    };
    add_patch(
        v, t, [&](double s, double q) { return ringpt(a + s * (b - a), q * 2 * std::numbers::pi); }, nl,
        ring);
    for (int end = 0; end < 2; ++end) {
      const Vec3 c = end ? b : a;
      const int centre = static_cast<int>(v.size());
      v.push_back(snap(c));
      for (int k = 0; k < ring; ++k) {
        const int i0 = static_cast<int>(v.size());
        v.push_back(ringpt(c, k * 2 * std::numbers::pi / ring));
        v.push_back(ringpt(c, (k + 1) * 2 * std::numbers::pi / ring));
        if (end)
          t.emplace_back(centre, i0, i0 + 1);
        else
          t.emplace_back(centre, i0 + 1, i0);
      }
    }
  };
  tube(Vec3(0, 0, 0), Vec3(0, 6, 0), trunk_r);
  const int branches = 6;
  for (int k = 0; k < branches; ++k) {
    const double ang = k * 2.3998, y = 2.0 + 0.7 * k;  // golden-angle spiral of branches
    const Vec3 dir(std::cos(ang), 0.6, std::sin(ang));
    const Vec3 start = Vec3(0, y, 0) + dir.normalized() * (trunk_r + 0.05);
    tube(start, start + dir.normalized() * (2.5 - 0.2 * k), branch_r);
  }
  return make_surface_mesh(std::move(v), std::move(t), "tree");
}

SurfaceMesh make_blobby_surface(int min_triangles, double radius_m) {
  // Cube-sphere: 6 faces x n x n cells x 2 triangles.
  const int n = static_cast<int>(std::ceil(std::sqrt(min_triangles / 12.0)));
  auto displace = [&](const Vec3& dir) {
    const double bump = 0.18 * std::sin(3 * dir.x() + 1.0) * std::cos(2 * dir.y()) +
                        0.12 * std::sin(5 * dir.z() + 2 * dir.x()) +
                        0.08 * std::cos(7 * dir.y() + 3 * dir.z());
    return snap(dir * radius_m * (1.0 + bump));
  };
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  for (int axis = 0; axis < 3; ++axis)
    for (int sgn : {-1, 1}) {
      add_patch(
          v, t,
          [&](double a, double b) {
            Vec3 p;
            p[axis] = sgn;
            p[(axis + 1) % 3] = 2 * a - 1;
            p[(axis + 2) % 3] = 2 * b - 1;
            // Equal-angle mapping keeps cells even; exact at shared cube edges so seams weld.
            for (int k = 1; k <= 2; ++k)
              p[(axis + k) % 3] = std::tan(p[(axis + k) % 3] * std::numbers::pi / 4);
            return displace(p.normalized());
          },
          n, n, sgn > 0);
    }
  return make_surface_mesh(std::move(v), std::move(t), "blobby");
}

std::vector<std::string> surface_scene_names() {
  return {kSurfaceSceneNames.begin(), kSurfaceSceneNames.end()};
}

SurfaceMesh make_surface_scene(const std::string& name) {
  if (name == "building") return make_two_storey_building();
  if (name == "floor_ceiling") return make_floor_ceiling_slab();
  if (name == "floor_wall") return make_floor_and_wall();
  if (name == "mobius") return make_mobius_strip();
  if (name == "torus") return make_torus();
  if (name == "tree") return make_tree();
  if (name == "blobby") return make_blobby_surface();
  if (name.ends_with(".obj")) return load_obj_surface(name);
  if (name.ends_with(".gltf") || name.ends_with(".glb")) return load_gltf_surface(name);
  throw InputError("unknown surface scene '" + name +
                   "' (expected one of building, floor_ceiling, floor_wall, "
                   "mobius, torus, tree, blobby, or an .obj, .gltf or .glb file)");
}

}  // namespace crowdlab
