#pragma once
// Procedural scenes for crowds on surfaces (seed 002 Figs. 1, 4, 5). All generated in code: nothing is
// downloaded. Metres, Y up. Each returns a manifold SurfaceMesh (boundary allowed).
#include <string>
#include <vector>

#include "framework/surface/surface_mesh.hpp"

namespace crowdlab {

/// A two-storey car-park style building: a 12 m x 8 m floor strip that winds twice around a central
/// atrium, flat for most of each lap and ramping up `storey_height_m` at one side, so the second storey
/// lies directly above the first (the floor-ceiling situation of seed 002 Fig. 5).
SurfaceMesh make_two_storey_building(double storey_height_m = 2.6, double resolution_m = 0.5);

/// A thin closed slab (width x thickness x depth): agents on its top walk upright, agents on its bottom
/// walk upside down `thickness_m` below them. Seed 002 Fig. 5's floor and ceiling.
SurfaceMesh make_floor_ceiling_slab(double size_m = 10.0, double thickness_m = 0.2,
                                    double resolution_m = 0.5);

/// A floor (y = 0) and a wall (x = 0) meeting at a right-angle edge: agents on perpendicular surfaces
/// (seed 002 Fig. 4, right).
SurfaceMesh make_floor_and_wall(double size_m = 10.0, double resolution_m = 0.5);

/// A Möbius strip: centre radius R, half-width w (non-orientable; seed 002 Fig. 4, centre).
SurfaceMesh make_mobius_strip(double radius_m = 6.0, double half_width_m = 1.5, int segments = 240,
                              int across = 8);

/// A torus: major radius R, minor radius r.
SurfaceMesh make_torus(double major_radius_m = 6.0, double minor_radius_m = 2.0, int major_segments = 160,
                       int minor_segments = 48);

/// A tree: a trunk and thin branches as closed capped tubes (separate components: agents, e.g. ants,
/// stay on the tube they start on). Seed 002 Fig. 4, left.
SurfaceMesh make_tree(double trunk_radius_m = 0.3, double branch_radius_m = 0.08, int ring_segments = 24);

/// A blobby closed surface with at least `min_triangles` triangles: a cube-sphere of radius ~radius_m
/// displaced by smooth low-frequency noise (stands in for the Stanford bunny of seed 002 Fig. 1).
SurfaceMesh make_blobby_surface(int min_triangles = 100000, double radius_m = 8.0);

/// A scene by name: building, floor_ceiling, floor_wall, mobius, torus, tree, blobby;
/// a path ending in .obj, .gltf or .glb is loaded (load_obj_surface / load_gltf_surface).
/// Throws InputError for an unknown name or a missing/bad file.
SurfaceMesh make_surface_scene(const std::string& name_or_path);

/// The names make_surface_scene accepts.
std::vector<std::string> surface_scene_names();

}  // namespace crowdlab
