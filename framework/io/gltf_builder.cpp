#include "framework/io/gltf_builder.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace crowdlab {

GltfBuilder::GltfBuilder(tinygltf::Model& model) : model_(&model) {
  if (model_->buffers.empty()) model_->buffers.emplace_back();
}

int GltfBuilder::add_view(const void* data, size_t bytes, int target) {
  std::vector<unsigned char>& buf = model_->buffers[0].data;
  while (buf.size() % 4 != 0) buf.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = bytes;
  view.target = target;
  buf.resize(buf.size() + bytes);
  if (bytes > 0) std::memcpy(buf.data() + view.byteOffset, data, bytes);
  model_->bufferViews.push_back(view);
  return static_cast<int>(model_->bufferViews.size()) - 1;
}

int GltfBuilder::add_accessor(int view, int component_type, size_t count, int type, const std::string& name) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.byteOffset = 0;
  a.componentType = component_type;
  a.count = count;
  a.type = type;
  a.name = name;
  model_->accessors.push_back(a);
  return static_cast<int>(model_->accessors.size()) - 1;
}

int GltfBuilder::add_floats(const std::vector<float>& values, int type, int components, int target,
                            bool min_max, const std::string& name) {
  const size_t count = values.size() / static_cast<size_t>(components);
  const int view = add_view(values.data(), values.size() * sizeof(float), target);
  const int index = add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, count, type, name);
  if (min_max && count > 0) {
    tinygltf::Accessor& a = model_->accessors[static_cast<size_t>(index)];
    a.minValues.assign(static_cast<size_t>(components), std::numeric_limits<double>::infinity());
    a.maxValues.assign(static_cast<size_t>(components), -std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < count; ++i)
      for (size_t c = 0; c < static_cast<size_t>(components); ++c) {
        const double v = values[i * static_cast<size_t>(components) + c];
        a.minValues[c] = std::min(a.minValues[c], v);
        a.maxValues[c] = std::max(a.maxValues[c], v);
      }
  }
  return index;
}

int GltfBuilder::add_indices_u16(const std::vector<std::uint16_t>& values, const std::string& name) {
  const int view =
      add_view(values.data(), values.size() * sizeof(std::uint16_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  return add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, values.size(), TINYGLTF_TYPE_SCALAR,
                      name);
}

int GltfBuilder::add_indices_u32(const std::vector<std::uint32_t>& values, const std::string& name) {
  const int view =
      add_view(values.data(), values.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  return add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, values.size(), TINYGLTF_TYPE_SCALAR, name);
}

int GltfBuilder::add_joints_u8(const std::vector<std::uint8_t>& values, const std::string& name) {
  const int view = add_view(values.data(), values.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
  return add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, values.size() / 4, TINYGLTF_TYPE_VEC4,
                      name);
}

tinygltf::Value to_gltf_value(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return tinygltf::Value();
    case nlohmann::json::value_t::boolean:
      return tinygltf::Value(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: {
      const auto v = j.get<long long>();
      if (v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max())
        return tinygltf::Value(static_cast<int>(v));
      return tinygltf::Value(static_cast<double>(v));
    }
    case nlohmann::json::value_t::number_float:
      return tinygltf::Value(j.get<double>());
    case nlohmann::json::value_t::string:
      return tinygltf::Value(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      tinygltf::Value::Array a;
      for (const auto& e : j) a.push_back(to_gltf_value(e));
      return tinygltf::Value(std::move(a));
    }
    case nlohmann::json::value_t::object: {
      tinygltf::Value::Object o;
      for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = to_gltf_value(it.value());
      return tinygltf::Value(std::move(o));
    }
    default:
      return tinygltf::Value();
  }
}

nlohmann::json from_gltf_value(const tinygltf::Value& v) {
  if (v.IsBool()) return v.Get<bool>();
  if (v.IsInt()) return v.Get<int>();
  if (v.IsReal()) return v.Get<double>();
  if (v.IsString()) return v.Get<std::string>();
  if (v.IsArray()) {
    nlohmann::json a = nlohmann::json::array();
    for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(from_gltf_value(v.Get(static_cast<int>(i))));
    return a;
  }
  if (v.IsObject()) {
    nlohmann::json o = nlohmann::json::object();
    for (const std::string& k : v.Keys()) o[k] = from_gltf_value(v.Get(k));
    return o;
  }
  return nullptr;
}

}  // namespace crowdlab
