#pragma once
// Where a parametric line p + t d meets a box or a triangle (used by core/triangle_tree.hpp's ray query
// and surface/triangle_bvh.hpp's segment query, which share them).
//   segment_meets_box       whether p + t d meets the box [lo, hi] (faces included) for some t in
//                           [t0, t1]: the slab method (Kay & Kajiya 1986); a line parallel to a slab meets
//                           it when p lies within the slab.
//   segment_triangle_t      the t at which p + t d meets triangle (a, b, c), either face (Moller &
//                           Trumbore 1997); negative when it misses or runs parallel to the triangle.
// d need not be unit: t is in units of d. Units: those of the points (metres here).
#include "framework/core/math_types.hpp"

namespace crowdlab {

bool segment_meets_box(const Vec3& p, const Vec3& d, const Vec3& lo, const Vec3& hi, double t0, double t1);

double segment_triangle_t(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace crowdlab
