#pragma once
// The built-in surface scenes a manifold spec may name (scenario.mesh), and the mesh file types it may
// give instead. Here, in the spec stage, so that the spec loader (and so `validate`) refuses
// `mesh: bogus_scene` or `mesh: /etc/passwd` at its line and column, as `run` would refuse them later
// (issue 33); framework/surface/surface_scenes.cpp builds the scenes by these names.
#include <array>
#include <string_view>

namespace crowdlab {

inline constexpr std::array<std::string_view, 7> kSurfaceSceneNames = {
    "building", "floor_ceiling", "floor_wall", "mobius", "torus", "tree", "blobby"};

/// Extensions of the mesh files a surface scene may be loaded from (load_obj_surface, load_gltf_surface).
inline constexpr std::array<std::string_view, 3> kSurfaceMeshExtensions = {".obj", ".gltf", ".glb"};

}  // namespace crowdlab
