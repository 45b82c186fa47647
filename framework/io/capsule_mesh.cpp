#include "framework/io/capsule_mesh.hpp"

#include <cmath>
#include <numbers>

namespace crowdlab {

void append_capsule_mesh(const Capsule& capsule, int segments, int rings, TriangleSoup& out) {
  const double length = capsule.length_m();
  const bool sphere = length < 1e-9;
  const Vec3 u = sphere ? Vec3::UnitY() : Vec3((capsule.b - capsule.a) / length);
  const Vec3 v = any_perpendicular(u);
  const Vec3 w = u.cross(v);
  const double r = capsule.radius_m;
  const auto base = static_cast<std::uint32_t>(out.positions.size());

  auto add_vertex = [&](const Vec3& centre, const Vec3& normal) {
    out.positions.push_back(centre + r * normal);
    out.normals.push_back(normal);
  };
  // Polar angle theta from +u: 0 at the top pole (end b), pi at the bottom pole (end a).
  auto add_ring = [&](double theta, const Vec3& centre) {
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / segments;
      add_vertex(centre, std::cos(theta) * u + std::sin(theta) * (std::cos(phi) * v + std::sin(phi) * w));
    }
  };
  add_vertex(capsule.b, u);  // top pole
  const double step = 0.5 * std::numbers::pi / rings;
  for (int k = 1; k <= rings; ++k) add_ring(k * step, capsule.b);
  for (int k = sphere ? rings + 1 : rings; k < 2 * rings; ++k) add_ring(k * step, capsule.a);
  add_vertex(capsule.a, -u);  // bottom pole
  const int ring_count = sphere ? 2 * rings - 1 : 2 * rings;

  // Emits a triangle, flipped if needed so that it winds counter-clockwise seen from outside.
  auto add_triangle = [&](std::uint32_t i0, std::uint32_t i1, std::uint32_t i2) {
    const Vec3& p0 = out.positions[i0];
    const Vec3 face = (out.positions[i1] - p0).cross(out.positions[i2] - p0);
    const Vec3 outward = out.normals[i0] + out.normals[i1] + out.normals[i2];
    if (face.dot(outward) < 0.0) std::swap(i1, i2);
    out.indices.insert(out.indices.end(), {i0, i1, i2});
  };
  const auto seg = static_cast<std::uint32_t>(segments);
  auto ring_vertex = [&](int ring, int s) {
    return base + 1 + static_cast<std::uint32_t>(ring) * seg + static_cast<std::uint32_t>(s % segments);
  };
  const std::uint32_t bottom = base + 1 + static_cast<std::uint32_t>(ring_count) * seg;
  for (int s = 0; s < segments; ++s) {
    add_triangle(base, ring_vertex(0, s), ring_vertex(0, s + 1));
    for (int k = 0; k + 1 < ring_count; ++k) {
      add_triangle(ring_vertex(k, s), ring_vertex(k + 1, s), ring_vertex(k + 1, s + 1));
      add_triangle(ring_vertex(k, s), ring_vertex(k + 1, s + 1), ring_vertex(k, s + 1));
    }
    add_triangle(bottom, ring_vertex(ring_count - 1, s + 1), ring_vertex(ring_count - 1, s));
  }
}

}  // namespace crowdlab
