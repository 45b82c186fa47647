#pragma once
// Mesh-level overlap (issue 27): how much of what is rendered lies inside another character's rendered
// surface, on the skinned meshes (posed_meshes.hpp: the MPFB2 skin with its garments, hair, eyes and
// shoes), not on the capsules the correction and the volume metrics use.
//
// On a sampled frame f (posed_meshes.hpp, mesh_sample_frames), vertex v of character a is inside
// character b when its signed distance to b's mesh is negative (core/triangle_tree.hpp: closest point,
// sign from the interpolated vertex normals; exact for a closed mesh, and the skin with the garments
// that cover its holes is closed as a whole; a closest point on the rim of an open sheet, such as a hair
// strand's tip, counts as outside). depth(v) = max over b != a of -s_b(v).
//   fraction(f)       inside vertices / rendered vertices of all characters with a mesh
//   fraction_mean/max over the sampled frames
//   depth_p99_m/max_m nearest-rank p99 / max of depth over the inside vertex-frames
// A vertex more than max_depth_m (0.2 m) behind b's surface counts as outside: no point is that deep in
// a human body (a torso's inscribed radius is about 0.15 m), so the sign test failed there (on 3 s clips
// about 0.01-0.02 % of the vertices, at 0.25-0.45 m, in crowds whose real overlap was ~0; the rim rule
// above removed most of the rest). Within that bound, an inside sign counts only when the ray from the
// vertex away from its closest point meets b again (surfaces_inside.hpp: the sign fails on the folds of
// thin shells, such as a shoe's collar; session 25).
// Only vertices inside b's bounding box are tested (nothing outside it can be inside b).
// Sampled frames are measured in parallel (TBB) and reduced in frame order: thread-count independent.
#include <vector>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

struct MeshOverlap {
  int frames = 0;              ///< sampled frames measured (0: no character has a mesh)
  double fraction_mean = 0.0;  ///< mean over sampled frames of the inside share of vertices
  double fraction_max = 0.0;   ///< its largest value
  double depth_p99_m = 0.0;    ///< over inside vertex-frames (0 when there are none)
  double depth_max_m = 0.0;
  long inside_samples = 0;                                       ///< inside vertex-frames
  int worst_character = -1, worst_other = -1, worst_frame = -1;  ///< where depth_max_m is (-1: none)
  std::vector<int> sampled_frames;
  std::vector<double> per_frame_fraction;  ///< (sampled_frames.size())
};

/// Frames from first_frame on, one every interval_s seconds.
inline constexpr double kMaxBodyDepth_m = 0.2;

MeshOverlap measure_mesh_overlap(const CrowdAnimation& crowd, int first_frame = 0, double interval_s = 0.5,
                                 double max_depth_m = kMaxBodyDepth_m);

}  // namespace crowdlab
