#pragma once
// Simple 2D polygons (x, y in metres; either winding) for placement areas: area, containment,
// distance to the boundary, and the closest boundary point.
#include <string>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

using Polygon2 = std::vector<Vec2>;

/// Axis-aligned rectangle [cx - w/2, cx + w/2] x [cy - d/2, cy + d/2], counter-clockwise.
Polygon2 rectangle_polygon(double width_m, double depth_m, const Vec2& center = Vec2::Zero());
/// Unsigned area (shoelace formula), m^2.
double polygon_area(const Polygon2& polygon);
/// Perimeter, m.
double polygon_perimeter(const Polygon2& polygon);
/// Point in polygon by the crossing-number rule (boundary points may go either way).
bool polygon_contains(const Polygon2& polygon, const Vec2& q);
/// Closest point on the boundary to q.
Vec2 polygon_closest_boundary_point(const Polygon2& polygon, const Vec2& q);
/// Throws InputError (prefixed by `what`) unless the polygon has >= 3 finite vertices and area > 0.
void validate_polygon(const Polygon2& polygon, const std::string& what);

}  // namespace crowdlab
