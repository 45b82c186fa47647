#include "tests/determinism/output_digests.hpp"

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <vector>

#include "framework/core/csv.hpp"
#include "framework/core/sha256.hpp"
#include "tests/support/test_paths.hpp"

namespace crowdlab::test {
namespace fs = std::filesystem;
namespace {

/// Values appended as their exact bytes (doubles bit for bit), strings and lists with their lengths,
/// so that no two different sequences of values give the same bytes.
class CanonicalBytes {
 public:
  void add(double v) { append(&v, sizeof v); }
  void add(std::int64_t v) { append(&v, sizeof v); }
  void add(std::uint64_t v) { append(&v, sizeof v); }
  void add(int v) { add(static_cast<std::int64_t>(v)); }
  void add(bool v) { add(static_cast<std::int64_t>(v)); }
  void add(const std::string& s) {
    add(s.size());
    bytes_ += s;
  }
  void add(const Vec3& v) {
    for (int i = 0; i < 3; ++i) add(v[i]);
  }
  void add(const Quat& q) {
    add(q.w());
    add(q.x());
    add(q.y());
    add(q.z());
  }
  void add(const Eigen::Vector3i& t) {
    for (int i = 0; i < 3; ++i) add(t[i]);
  }
  template <typename T, size_t N>
  void add(const std::array<T, N>& values) {
    for (const T& v : values) add(v);
  }
  template <typename T>
  void add(const std::vector<T>& values) {
    add(values.size());
    for (const T& v : values) add(v);
  }
  std::string digest() const { return sha256_hex(bytes_); }

 private:
  void append(const void* p, size_t n) { bytes_.append(static_cast<const char*>(p), n); }
  std::string bytes_;
};

void add_shape(CanonicalBytes& b, const BodyShape& shape) {
  b.add(static_cast<int>(shape.params.sex));
  b.add(shape.params.height_m);
  b.add(shape.params.girth);
  b.add(shape.joint_offsets_m);
  for (const Capsule& c : shape.capsules) {
    b.add(c.a);
    b.add(c.b);
    b.add(c.radius_m);
  }
  b.add(shape.rest_contact_pairs.size());
  for (const auto& [i, j] : shape.rest_contact_pairs) {
    b.add(i);
    b.add(j);
  }
}

void add_mesh(CanonicalBytes& b, const SkinnedMesh* mesh) {
  b.add(mesh != nullptr);
  if (!mesh) return;
  b.add(mesh->rest_vertices_m);
  b.add(mesh->rest_normals);
  b.add(mesh->triangles);
  b.add(mesh->joints);
  b.add(mesh->weights);
  b.add(mesh->region);
  b.add(mesh->rest_joints_m);
}

void add_environment(CanonicalBytes& b, const Environment& env) {
  b.add(env.ground_plane);
  b.add(env.boxes.size());
  for (const Box& box : env.boxes) {
    b.add(box.center_m);
    b.add(box.half_extents_m);
    b.add(box.rotation);
  }
  b.add(env.meshes.size());
  for (const TriangleMesh& m : env.meshes) {
    b.add(m.name);
    b.add(m.vertices_m);
    b.add(m.triangles);
  }
}

}  // namespace

std::string crowd_animation_digest(const CrowdAnimation& crowd) {
  CanonicalBytes b;
  b.add(crowd.meta.fps);
  b.add(crowd.meta.seed);
  b.add(crowd.meta.condition_id);
  b.add(crowd.meta.scenario);
  b.add(crowd.characters.size());
  for (const CharacterAnimation& ch : crowd.characters) {
    b.add(ch.name);
    b.add(ch.palette);
    add_shape(b, ch.shape);
    add_mesh(b, ch.mesh.get());
    b.add(ch.frames.size());
    for (const Pose& pose : ch.frames) {
      b.add(pose.root_position_m);
      b.add(pose.local_rotations);
    }
  }
  add_environment(b, crowd.environment);
  return b.digest();
}

std::string png_frames_digest(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".png") files.push_back(entry.path());
  if (files.empty()) throw std::runtime_error(folder.string() + ": no PNG frames");
  std::sort(files.begin(), files.end());
  CanonicalBytes b;
  b.add(files.size());
  for (const fs::path& file : files) {
    const cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
    if (image.empty()) throw std::runtime_error(file.string() + ": cannot decode");
    b.add(file.filename().string());
    b.add(image.rows);
    b.add(image.cols);
    b.add(image.channels());
    b.add(static_cast<int>(image.elemSize1()));
    for (int row = 0; row < image.rows; ++row)
      b.add(std::string(reinterpret_cast<const char*>(image.ptr(row)), image.cols * image.elemSize()));
  }
  return b.digest();
}

std::string csv_digest_without_column(const fs::path& file, const std::string& column) {
  const CsvTable table = read_csv(file.string());
  const auto keep = [&](size_t col) { return table.header[col] != column; };
  std::string text;
  std::vector<std::string> fields;
  const auto add_line = [&](const std::vector<std::string>& cells) {
    fields.clear();
    for (size_t col = 0; col < cells.size(); ++col)
      if (keep(col)) fields.push_back(cells[col]);
    text += csv_line(fields);
  };
  add_line(table.header);
  for (const auto& row : table.rows) add_line(row);
  return sha256_hex(text);
}

std::string json_digest(const fs::path& file) {
  return sha256_hex(nlohmann::json::parse(slurp(file)).dump());
}

std::string text_digest(const fs::path& file,
                        const std::vector<std::pair<std::string, std::string>>& placeholders) {
  std::string text = slurp(file);
  for (const auto& [from, to] : placeholders)
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  return sha256_hex(text);
}

}  // namespace crowdlab::test
