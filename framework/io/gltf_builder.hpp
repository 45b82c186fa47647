#pragma once
// GltfBuilder: appends typed arrays to the single binary buffer of a .glb and creates the matching
// bufferView + accessor (internal to framework/io).
//
// Every accessor gets its own tightly packed bufferView, aligned to 4 bytes (glTF 2.0 §3.6.2.4 requires
// accessor offsets aligned to the component size; vertex attribute strides to 4). Float accessors record
// exact min/max of the stored float values, which glTF requires for POSITION and animation inputs
// (glTF 2.0 §3.6.2.5, §3.11) and which the Khronos validator compares bit for bit.
#include <tiny_gltf.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace crowdlab {

class GltfBuilder {
 public:
  explicit GltfBuilder(tinygltf::Model& model);

  /// `values` holds count x components floats (row-major). `type` is TINYGLTF_TYPE_*; `target` is
  /// TINYGLTF_TARGET_* or 0. Returns the accessor index.
  int add_floats(const std::vector<float>& values, int type, int components, int target, bool min_max,
                 const std::string& name);
  /// Unsigned 16-bit indices (ELEMENT_ARRAY_BUFFER, SCALAR).
  int add_indices_u16(const std::vector<std::uint16_t>& values, const std::string& name);
  /// Unsigned 32-bit indices (ELEMENT_ARRAY_BUFFER, SCALAR).
  int add_indices_u32(const std::vector<std::uint32_t>& values, const std::string& name);
  /// Unsigned 8-bit VEC4 vertex attribute (JOINTS_0).
  int add_joints_u8(const std::vector<std::uint8_t>& values, const std::string& name);

 private:
  int add_view(const void* data, size_t bytes, int target);
  int add_accessor(int view, int component_type, size_t count, int type, const std::string& name);

  tinygltf::Model* model_;
};

/// nlohmann::json <-> tinygltf::Value, for `extras`. Integers that fit in int stay integers; other
/// numbers are stored as doubles (17 significant digits in the file, so they round-trip exactly).
tinygltf::Value to_gltf_value(const nlohmann::json& j);
nlohmann::json from_gltf_value(const tinygltf::Value& v);

}  // namespace crowdlab
