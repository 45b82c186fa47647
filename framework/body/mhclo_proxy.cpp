#include "framework/body/mhclo_proxy.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

enum class Section { kHeader, kVerts, kDelete };

}  // namespace

MhcloProxy read_mhclo(const std::filesystem::path& path, int base_vertex_count) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open .mhclo file");
  MhcloProxy proxy;
  proxy.name = path.stem().string();
  std::string obj_file, line;
  int line_no = 0;
  Section section = Section::kHeader;
  auto fail = [&](const std::string& msg) {
    throw InputError(SourceLocation{path.string(), line_no, 0, ""}, msg);
  };
  auto base_index = [&](long v) {
    if (v < 0 || v >= base_vertex_count) fail("base-mesh vertex " + std::to_string(v) + " out of range");
    return static_cast<int>(v);
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string key;
    ss >> key;
    if (key.empty()) continue;
    const bool numeric = std::isdigit(static_cast<unsigned char>(key[0])) != 0;
    if (!numeric) {
      // Header keys may follow "verts" (MakeHuman writes `material` there); only the two section keys switch.
      if (key == "verts") section = Section::kVerts;
      if (key == "delete_verts") section = Section::kDelete;
      if (key == "obj_file") ss >> obj_file;
      const int axis = key == "x_scale" ? 0 : key == "y_scale" ? 1 : key == "z_scale" ? 2 : -1;
      if (axis >= 0) {
        long a = 0, b = 0;
        double d = 0.0;
        if (!(ss >> a >> b >> d) || !(d > 0.0) || !std::isfinite(d))
          fail(key + " needs two vertices and a distance > 0");
        proxy.scale_vertices[static_cast<size_t>(axis)] = {base_index(a), base_index(b)};
        proxy.scale_denominator[axis] = d;
      }
      continue;
    }
    std::vector<double> values;
    std::istringstream all(line);
    std::string token;
    while (all >> token) {
      if (token == "-") {
        values.push_back(-1.0);  // a range marker in delete_verts
        continue;
      }
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v)) fail("'" + token + "' is not a number");
      values.push_back(v);
    }
    if (section == Section::kVerts) {
      if (values.size() == 1) {
        const int i = base_index(static_cast<long>(values[0]));
        proxy.refs.push_back({i, i, i});
        proxy.ref_weights.emplace_back(1.0, 0.0, 0.0);
        proxy.offsets_dm.push_back(Vec3::Zero());
      } else if (values.size() == 9) {
        proxy.refs.push_back({base_index(static_cast<long>(values[0])),
                              base_index(static_cast<long>(values[1])),
                              base_index(static_cast<long>(values[2]))});
        proxy.ref_weights.emplace_back(values[3], values[4], values[5]);
        proxy.offsets_dm.emplace_back(values[6], values[7], values[8]);
      } else {
        fail("a vertex line needs 1 or 9 numbers, got " + std::to_string(values.size()));
      }
    } else if (section == Section::kDelete) {
      for (size_t k = 0; k < values.size(); ++k) {
        if (values[k] < 0.0) {  // "a - b": a was pushed already
          if (k == 0 || k + 1 >= values.size()) fail("a delete_verts range needs both ends");
          const int a = base_index(static_cast<long>(values[k - 1])),
                    b = base_index(static_cast<long>(values[k + 1]));
          for (int v = a + 1; v <= b; ++v) proxy.deleted_base_vertices.push_back(v);
          ++k;
          continue;
        }
        proxy.deleted_base_vertices.push_back(base_index(static_cast<long>(values[k])));
      }
    } else {
      fail("a number outside the verts and delete_verts sections");
    }
  }
  if (obj_file.empty()) throw InputError(path.string() + ": no obj_file line");
  if (proxy.refs.empty()) throw InputError(path.string() + ": no fitted vertices (verts section)");
  std::sort(proxy.deleted_base_vertices.begin(), proxy.deleted_base_vertices.end());
  proxy.deleted_base_vertices.erase(
      std::unique(proxy.deleted_base_vertices.begin(), proxy.deleted_base_vertices.end()),
      proxy.deleted_base_vertices.end());
  const ObjMesh obj = read_obj(path.parent_path() / obj_file);
  if (obj.vertices.size() != proxy.refs.size())
    throw InputError(path.string() + ": " + std::to_string(proxy.refs.size()) + " fitted vertices but " +
                     obj_file + " has " + std::to_string(obj.vertices.size()));
  proxy.faces = obj.faces;
  return proxy;
}

std::vector<Vec3> fit_mhclo_proxy(const MhcloProxy& proxy, const std::vector<Vec3>& base_dm) {
  Vec3 scale;
  for (int axis = 0; axis < 3; ++axis) {
    const auto& [a, b] = proxy.scale_vertices[static_cast<size_t>(axis)];
    if (a == b) {  // no scale line for this axis: offsets as written
      scale[axis] = 1.0;
      continue;
    }
    scale[axis] = std::abs(base_dm[static_cast<size_t>(a)][axis] - base_dm[static_cast<size_t>(b)][axis]) /
                  proxy.scale_denominator[axis];
  }
  std::vector<Vec3> out(proxy.refs.size());
  for (size_t v = 0; v < out.size(); ++v) {
    const auto& r = proxy.refs[v];
    const Vec3& w = proxy.ref_weights[v];
    out[v] = w[0] * base_dm[static_cast<size_t>(r[0])] + w[1] * base_dm[static_cast<size_t>(r[1])] +
             w[2] * base_dm[static_cast<size_t>(r[2])] + proxy.offsets_dm[v].cwiseProduct(scale);
  }
  return out;
}

}  // namespace crowdlab
