#pragma once
// A smoothly varying "up" for bodies standing on a SurfaceMesh: the face's vertex normals
// (area-weighted, SurfaceMesh::vertex_normals) blended with the point's barycentric coordinates
// (Phong-style normal interpolation, Phong 1975). Across a crease the body then tilts over the width
// of the triangles next to it instead of snapping between face normals in one frame.
// Each vertex normal is first flipped to the side of the point's own up (face normal * up_sign), so
// the blend is well defined where windings disagree (the Möbius strip's seam) and on thin sheets.
// Falls back to the face up when the blend degenerates (|n| < 1e-6) or leans more than 80 degrees
// away from the face up (a knife-edge, where a blended normal would lay the body into the surface).
#include "framework/surface/surface_walk.hpp"

namespace crowdlab {

/// Unit vector; world frame.
Vec3 smooth_surface_up(const SurfaceMesh& mesh, const SurfacePoint& point);

}  // namespace crowdlab
