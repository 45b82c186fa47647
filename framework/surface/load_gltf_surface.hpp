#pragma once
// Loading a walkable SurfaceMesh from glTF 2.0 (.gltf with external or data-URI buffers, or binary .glb),
// through tinygltf.
//
// What is read: every node of the default scene (scene 0 when none is marked; all root nodes when the
// file has no scenes), depth first, with its world transform (matrix, or T * R * S); every primitive of
// each node's mesh with mode TRIANGLES (4), TRIANGLE_STRIP (5) or TRIANGLE_FAN (6) (glTF 2.0 spec
// §3.7.2.1; strips keep their winding by swapping every odd triangle). POSITION must be float VEC3;
// indices may be unsigned byte/short/int, or absent (consecutive vertices). A node transform with a
// negative determinant reverses its triangles' winding so that normals still point outwards.
// All primitives are merged into one mesh: coincident vertices of different primitives are welded by
// make_surface_mesh, which also builds adjacency and area-weighted per-vertex normals (file NORMALs are
// ignored: agents need the normals of the walked triangles) and applies its documented repairs.
//
// Errors (InputError naming the file and the mesh/primitive): unreadable or malformed files, POINTS or
// LINES primitives, missing or non-float POSITION, out-of-range indices, buffers too short, non-finite
// coordinates, no triangles, non-manifold edges (from make_surface_mesh).
#include <string>

#include "framework/surface/surface_mesh.hpp"

namespace crowdlab {

/// `scale` converts file units to metres (glTF files are in metres: default 1).
SurfaceMesh load_gltf_surface(const std::string& path, double scale = 1.0);

}  // namespace crowdlab
