#pragma once
// A MakeHuman proxy asset (clothes, shoes, hair, eyebrows; CC0, makehumancommunity.org): an OBJ mesh
// plus a `.mhclo` fitting file that ties every asset vertex to the base mesh, so the asset follows any
// shaped body (MakeHuman's "proxy" fitting; file format as MakeHuman 1.x writes it):
//   obj_file NAME                 the mesh, next to the .mhclo (Y-up decimetres, the base mesh's frame)
//   x_scale A B D (y_, z_)        per axis, scale s = |base[A] - base[B]| (that axis) / D
//   verts 0                       then one line per asset vertex, in OBJ order:
//       "i j k wi wj wk dx dy dz"  p = wi base[i] + wj base[j] + wk base[k] + (s_x dx, s_y dy, s_z dz)
//       "i"                        p = base[i]
//   delete_verts                  then base-mesh vertex indices ("a" or "a - b") the asset covers
// Other keys (name, uuid, material, tags, z_depth...) are ignored. Units: decimetres throughout.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "framework/body/obj_mesh.hpp"

namespace crowdlab {

struct MhcloProxy {
  std::string name;                                    ///< the file's stem (e.g. "short02")
  std::vector<std::array<int, 3>> refs;                ///< (V) base-mesh vertices each asset vertex follows
  std::vector<Vec3> ref_weights;                       ///< (V) their weights
  std::vector<Vec3> offsets_dm;                        ///< (V) unscaled offsets
  std::array<std::array<int, 2>, 3> scale_vertices{};  ///< per axis x, y, z: the two base vertices
  Vec3 scale_denominator = Vec3::Ones();               ///< per axis: their distance in the reference body
  std::vector<std::vector<int>> faces;                 ///< the OBJ's faces (0-based asset vertex indices)
  std::vector<int> deleted_base_vertices;              ///< sorted: base vertices the asset hides
};

/// Reads `path` and the OBJ it names. base_vertex_count bounds every base-mesh index. Throws InputError
/// "file:line: ..." on malformed lines, indices out of range, or a vertex count that differs from the OBJ's.
MhcloProxy read_mhclo(const std::filesystem::path& path, int base_vertex_count);

/// The asset's vertices fitted to a shaped base mesh (decimetres, as shaped_vertices_dm gives them).
std::vector<Vec3> fit_mhclo_proxy(const MhcloProxy& proxy, const std::vector<Vec3>& base_dm);

}  // namespace crowdlab
