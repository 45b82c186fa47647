#include "framework/body/obj_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "framework/core/error.hpp"

namespace crowdlab {

int ObjMesh::group_index(const std::string& name) const {
  const auto it = std::find(groups.begin(), groups.end(), name);
  return it == groups.end() ? -1 : static_cast<int>(it - groups.begin());
}

std::vector<int> ObjMesh::group_vertices(int group) const {
  std::vector<int> out;
  for (size_t f = 0; f < faces.size(); ++f)
    if (face_group[f] == group) out.insert(out.end(), faces[f].begin(), faces[f].end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

ObjMesh read_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open OBJ file");
  ObjMesh mesh;
  int current_group = -1;
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& msg) {
    throw InputError(SourceLocation{path.string(), line_no, 0, ""}, msg);
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (line.size() < 2) continue;
    if (line[0] == 'v' && line[1] == ' ') {
      std::istringstream ss(line.substr(2));
      double x = 0, y = 0, z = 0;
      if (!(ss >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        fail("vertex needs 3 finite coordinates");
      mesh.vertices.emplace_back(x, y, z);
    } else if (line[0] == 'g' && line[1] == ' ') {
      const std::string name = line.substr(2);
      current_group = mesh.group_index(name);
      if (current_group < 0) {
        mesh.groups.push_back(name);
        current_group = static_cast<int>(mesh.groups.size()) - 1;
      }
    } else if (line[0] == 'f' && line[1] == ' ') {
      std::istringstream ss(line.substr(2));
      std::vector<int> face;
      std::string token;
      while (ss >> token) {
        const int idx = std::atoi(token.substr(0, token.find('/')).c_str());
        const int n = static_cast<int>(mesh.vertices.size());
        const int zero_based = idx > 0 ? idx - 1 : n + idx;  // negative indices count from the end
        if (idx == 0 || zero_based < 0 || zero_based >= n) fail("face index '" + token + "' out of range");
        face.push_back(zero_based);
      }
      if (face.size() < 3) fail("face needs at least 3 vertices");
      if (current_group < 0) {
        mesh.groups.push_back("default");
        current_group = static_cast<int>(mesh.groups.size()) - 1;
      }
      mesh.faces.push_back(std::move(face));
      mesh.face_group.push_back(current_group);
    }
  }
  if (mesh.vertices.empty() || mesh.faces.empty())
    throw InputError(path.string() + ": OBJ has no vertices or faces");
  return mesh;
}

}  // namespace crowdlab
