#include "framework/body/mpfb2_model.hpp"

#include <tbb/parallel_for.h>

// GCC 12 at -O3 reports a false -Wnull-dereference inside nlohmann::json's inlined get<std::string>()
// (the json value is a reference, never null); silenced for this translation unit only.
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <zlib.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/nearest_site.hpp"

namespace crowdlab {
namespace {

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open (is this an MPFB2 asset folder?)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string() + ": invalid JSON: " + e.what());
  }
}

JointPlacement parse_placement(const nlohmann::json& j, const ObjMesh& base, const std::string& where) {
  JointPlacement p;
  try {
    const auto& d = j.at("default_position");
    p.default_position_blender = Vec3(d.at(0).get<double>(), d.at(1).get<double>(), d.at(2).get<double>());
    const std::string strategy = j.at("strategy").get<std::string>();
    if (strategy == "MEAN") {
      p.strategy = JointPlacement::Strategy::kMean;
      p.vertices = j.at("vertex_indices").get<std::vector<int>>();
    } else if (strategy == "CUBE") {
      p.strategy = JointPlacement::Strategy::kCube;
      const std::string cube = j.at("cube_name").get<std::string>();
      const int g = base.group_index(cube);
      if (g < 0) throw InputError(where + ": joint cube group '" + cube + "' not in the base mesh");
      p.vertices = base.group_vertices(g);
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": " + e.what());
  }
  for (int v : p.vertices)
    if (v < 0 || v >= static_cast<int>(base.vertices.size()))
      throw InputError(where + ": vertex index " + std::to_string(v) + " out of range");
  if (p.strategy != JointPlacement::Strategy::kDefault && p.vertices.empty())
    throw InputError(where + ": placement lists no vertices");
  return p;
}

double round_to_sixteenth(double x) {
  return std::round(x * 16.0) / 16.0;
}

}  // namespace

ShapeTarget read_target_gz(const std::filesystem::path& path, int vertex_count) {
  require_regular_input(path, "target file");  // a FIFO would block gzopen for ever
  gzFile f = gzopen(path.string().c_str(), "rb");
  if (!f) throw InputError(path.string() + ": cannot open target file");
  // A target moves each vertex at most once, in lines of a few dozen bytes: the decompressed size and
  // the entries are bounded by the vertex count, so a gzip bomb (2.2 MB inflating to gigabytes took
  // 4.4 GB and 71 s, issue 32) is refused as soon as it passes the bound, before it is held.
  const long long max_bytes = static_cast<long long>(vertex_count) * kMaxTargetLineBytes + (1 << 20);
  ShapeTarget t;
  char buf[512];
  int line_no = 0;
  while (gzgets(f, buf, sizeof buf)) {
    ++line_no;
    if (gztell(f) > max_bytes || t.indices.size() >= static_cast<size_t>(vertex_count) + 1) {
      gzclose(f);
      throw InputError(
          SourceLocation{path.string(), line_no, 0, ""},
          "the target inflates past " + std::to_string(max_bytes) + " bytes or " +
              std::to_string(vertex_count) + " entries, the limit for a mesh of " +
              std::to_string(vertex_count) + " vertices (" + std::to_string(kMaxTargetLineBytes) +
              " bytes and one entry per vertex, plus 1 MiB); not an MPFB2 target (a gzip bomb?)");
    }
    if (buf[0] == '#' || buf[0] == '\n' || buf[0] == '\r' || buf[0] == '\0') continue;
    // strtol/strtod: several times faster than istringstream on the ~10^4-line targets.
    char* end = nullptr;
    const long idx = std::strtol(buf, &end, 10);
    bool ok = end != buf;
    std::array<double, 3> d{};
    for (double& x : d) {
      char* start = end;
      x = std::strtod(start, &end);
      ok = ok && end != start && std::isfinite(x);
    }
    if (!ok || idx < 0 || idx >= vertex_count) {
      gzclose(f);
      throw InputError(SourceLocation{path.string(), line_no, 0, ""},
                       "expected 'index dx dy dz' with a valid index");
    }
    const double x = d[0], y = d[1], z = d[2];
    t.indices.push_back(static_cast<int>(idx));
    t.offsets_dm.emplace_back(x, y, z);
  }
  int err = 0;
  const char* msg = gzerror(f, &err);
  const bool bad = err != Z_OK && err != Z_STREAM_END;
  const std::string err_text = bad ? std::string(msg) : "";
  gzclose(f);
  if (bad) throw InputError(path.string() + ": corrupt gzip data: " + err_text);
  return t;
}

namespace {

/// For every vertex, the nearest of `body` (itself when it is one; ties to the body vertex listed first).
std::vector<int> nearest_body_vertices(const std::vector<Vec3>& vertices, const std::vector<int>& body) {
  std::vector<int> anchor(vertices.size(), -1);
  for (int b : body) anchor[static_cast<size_t>(b)] = b;
  const NearestSiteGrid grid(vertices, body);
  tbb::parallel_for(size_t{0}, vertices.size(), [&](size_t v) {
    if (anchor[v] < 0) anchor[v] = grid.nearest(vertices[v]);
  });
  return anchor;
}

}  // namespace

std::shared_ptr<const Mpfb2Model> Mpfb2Model::load(const std::filesystem::path& dir) {
  if (dir.empty() || !std::filesystem::is_directory(dir))
    throw InputError("MPFB2 assets: '" + dir.string() + "' is not a directory");
  auto m = std::shared_ptr<Mpfb2Model>(new Mpfb2Model());
  m->dir_ = dir;
  m->base_ = read_obj(dir / "3dobjs" / "base.obj");
  const int body = m->base_.group_index("body");
  if (body < 0) throw InputError((dir / "3dobjs" / "base.obj").string() + ": no group 'body'");
  m->body_vertices_ = m->base_.group_vertices(body);
  for (size_t f = 0; f < m->base_.faces.size(); ++f) {
    if (m->base_.face_group[f] != body) continue;
    const auto& face = m->base_.faces[f];
    for (size_t k = 1; k + 1 < face.size(); ++k)
      m->body_triangles_.emplace_back(face[0], face[k], face[k + 1]);
  }
  m->shape_anchor_ = nearest_body_vertices(m->base_.vertices, m->body_vertices_);

  const auto rig_path = dir / "rigs" / "standard" / "rig.mixamo.json";
  const nlohmann::json rig = read_json(rig_path);
  if (!rig.contains("bones") || !rig["bones"].is_object())
    throw InputError(rig_path.string() + ": no 'bones' object");
  for (const auto& [name, bj] : rig["bones"].items()) {
    const std::string where = rig_path.string() + ": bones." + name;
    RigBone b;
    b.name = name;
    // A numeric parent reached the animation stage as a bare json type_error naming the output file
    // (issue 33): the asset file and key are named here.
    if (!bj.is_object()) throw InputError(where + ": must be an object, got a " + bj.type_name());
    if (bj.contains("parent") && !bj["parent"].is_string())
      throw InputError(where + ".parent: must be a string (a bone name, or \"\" for the root), got a " +
                       std::string(bj["parent"].type_name()));
    b.parent = bj.value("parent", std::string());
    if (!bj.contains("head") || !bj.contains("tail")) throw InputError(where + ": needs 'head' and 'tail'");
    b.head = parse_placement(bj["head"], m->base_, where + ".head");
    b.tail = parse_placement(bj["tail"], m->base_, where + ".tail");
    m->bones_[name] = std::move(b);
  }

  const auto weights_path = dir / "rigs" / "standard" / "weights.mixamo.json";
  const nlohmann::json wj = read_json(weights_path);
  if (!wj.contains("weights") || !wj["weights"].is_object())
    throw InputError(weights_path.string() + ": no 'weights' object");
  const int n = static_cast<int>(m->base_.vertices.size());
  for (const auto& [bone, list] : wj["weights"].items()) {
    auto& out = m->weights_[bone];
    for (const auto& pair : list) {
      const bool numbers =
          pair.is_array() && pair.size() == 2 && pair[0].is_number_integer() && pair[1].is_number();
      const long long v = numbers ? pair[0].get<long long>() : -1;
      const double w = numbers ? pair[1].get<double>() : 0.0;
      if (v < 0 || v >= n || !std::isfinite(w))
        throw InputError(weights_path.string() + ": weights." + bone +
                         ": bad entry (expected [vertex index, weight], vertex index below " +
                         std::to_string(n) + ")");
      out.emplace_back(static_cast<int>(v), w);
    }
  }

  const auto macro_path = dir / "targets" / "macrodetails" / "macro.json";
  const nlohmann::json macro = read_json(macro_path);
  try {
    for (const auto& [var, vj] : macro.at("macrotargets").items()) {
      for (const auto& pj : vj.at("parts")) {
        // The file's bounds sit just outside the nominal part ends (-0.01, 0.49998, 1.01, ...) so that
        // exact ends fall in one part; the nominal ends are the nearest sixteenths (0, 3/16, 1/2, 1).
        MacroPart part{round_to_sixteenth(pj.at("lowest").get<double>()),
                       round_to_sixteenth(pj.at("highest").get<double>()), pj.at("low").get<std::string>(),
                       pj.at("high").get<std::string>()};
        m->macro_parts_[var].push_back(part);
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(macro_path.string() + ": " + e.what());
  }
  return m;
}

const ShapeTarget& Mpfb2Model::target(const std::string& name) const {
  std::lock_guard<std::mutex> lock(cache_mutex_);
  auto it = cache_.find(name);
  if (it != cache_.end()) return *it->second;
  const auto path = dir_ / "targets" / "macrodetails" / (name + ".target.gz");
  auto t = std::make_unique<ShapeTarget>(read_target_gz(path, static_cast<int>(base_.vertices.size())));
  return *(cache_[name] = std::move(t));
}

}  // namespace crowdlab
