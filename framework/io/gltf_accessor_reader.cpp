#include "framework/io/gltf_accessor_reader.hpp"

#include <cmath>
#include <cstring>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

struct RawAccessor {
  const unsigned char* data = nullptr;  ///< first element
  size_t count = 0;
  size_t stride = 0;  ///< bytes between elements
};

std::string who(const tinygltf::Model& model, int index, const std::string& context) {
  std::string s = context + ": accessor " + std::to_string(index);
  if (index >= 0 && static_cast<size_t>(index) < model.accessors.size() &&
      !model.accessors[static_cast<size_t>(index)].name.empty())
    s += " ('" + model.accessors[static_cast<size_t>(index)].name + "')";
  return s;
}

RawAccessor locate(const tinygltf::Model& model, int index, int component_type_size, int components,
                   const std::string& context) {
  const std::string w = who(model, index, context);
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    throw InputError(w + ": no such accessor (the file has " + std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
  if (a.sparse.isSparse) throw InputError(w + ": sparse accessors are not supported");
  if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model.bufferViews.size())
    throw InputError(w + ": bufferView " + std::to_string(a.bufferView) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size())
    throw InputError(w + ": buffer " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& buf = model.buffers[static_cast<size_t>(view.buffer)].data;
  const size_t element = static_cast<size_t>(component_type_size) * static_cast<size_t>(components);
  const size_t stride = view.byteStride == 0 ? element : view.byteStride;
  if (stride < element) throw InputError(w + ": byteStride is smaller than one element");
  if (view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset)
    throw InputError(w + ": bufferView " + std::to_string(a.bufferView) +
                     " lies outside its buffer (truncated file?)");
  if (a.count > 0) {
    const size_t span = (a.count - 1) * stride + element;
    if (a.count > view.byteLength / stride + 1 || a.byteOffset > view.byteLength ||
        span > view.byteLength - a.byteOffset)
      throw InputError(w + ": " + std::to_string(a.count) + " elements do not fit in bufferView " +
                       std::to_string(a.bufferView));
  }
  return {buf.data() + view.byteOffset + a.byteOffset, a.count, stride};
}

}  // namespace

std::vector<float> read_float_accessor(const tinygltf::Model& model, int index, int type,
                                       const std::string& context) {
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type));
  if (index >= 0 && static_cast<size_t>(index) < model.accessors.size()) {
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      throw InputError(who(model, index, context) + ": expected FLOAT components, got type code " +
                       std::to_string(a.componentType));
    if (a.type != type)
      throw InputError(who(model, index, context) + ": expected " + std::to_string(components) +
                       " components per element, got element type code " + std::to_string(a.type));
  }
  const RawAccessor raw = locate(model, index, 4, components, context);
  std::vector<float> out(raw.count * static_cast<size_t>(components));
  for (size_t i = 0; i < raw.count; ++i)
    std::memcpy(&out[i * static_cast<size_t>(components)], raw.data + i * raw.stride,
                sizeof(float) * static_cast<size_t>(components));
  for (size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      throw InputError(who(model, index, context) + ": element " +
                       std::to_string(i / static_cast<size_t>(components)) + " is not a finite number");
  return out;
}

std::vector<std::uint32_t> read_index_accessor(const tinygltf::Model& model, int index,
                                               const std::string& context) {
  return read_uint_accessor(model, index, TINYGLTF_TYPE_SCALAR, context);
}

std::vector<std::uint32_t> read_uint_accessor(const tinygltf::Model& model, int index, int type,
                                              const std::string& context) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    throw InputError(who(model, index, context) + ": no such accessor");
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type));
  if (a.type != type)
    throw InputError(who(model, index, context) + ": expected " + std::to_string(components) +
                     " components per element, got element type code " + std::to_string(a.type));
  int size = 0;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      size = 1;
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      size = 2;
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      size = 4;
      break;
    default:
      throw InputError(who(model, index, context) + ": expected unsigned integers, got type code " +
                       std::to_string(a.componentType));
  }
  const auto n = static_cast<size_t>(components);
  const RawAccessor raw = locate(model, index, size, components, context);
  std::vector<std::uint32_t> out(raw.count * n);
  for (size_t i = 0; i < raw.count; ++i)
    for (size_t c = 0; c < n; ++c) {
      const unsigned char* p = raw.data + i * raw.stride + c * static_cast<size_t>(size);
      std::uint32_t& v = out[i * n + c];
      if (size == 1) v = *p;
      if (size == 2) {
        std::uint16_t u;
        std::memcpy(&u, p, 2);
        v = u;
      }
      if (size == 4) std::memcpy(&v, p, 4);
    }
  return out;
}

}  // namespace crowdlab
