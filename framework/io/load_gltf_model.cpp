#include "framework/io/load_gltf_model.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "framework/core/error.hpp"
#include "framework/io/json_nesting_depth.hpp"

namespace crowdlab {
namespace {

/// The JSON text of a glTF file: the whole file for .gltf, the first (JSON) chunk for .glb (glTF 2.0
/// §4.4: a 12-byte header, then chunk length, chunk type 'JSON', data). Empty when the GLB header is
/// not one (tinygltf then reports what is wrong).
std::string gltf_json_text(const std::filesystem::path& path, bool binary) {
  std::ifstream in(path, std::ios::binary);
  if (!binary) {
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  unsigned char header[20] = {};
  if (!in.read(reinterpret_cast<char*>(header), sizeof header)) return "";
  if (std::memcmp(header, "glTF", 4) != 0 || std::memcmp(header + 16, "JSON", 4) != 0) return "";
  const std::uint32_t length =
      static_cast<std::uint32_t>(header[12]) | static_cast<std::uint32_t>(header[13]) << 8 |
      static_cast<std::uint32_t>(header[14]) << 16 | static_cast<std::uint32_t>(header[15]) << 24;
  const auto file_size = std::filesystem::file_size(path);
  if (length > file_size) return "";  // a lying header: tinygltf rejects it
  std::string json(length, '\0');
  in.read(json.data(), static_cast<std::streamsize>(length));
  json.resize(static_cast<size_t>(in.gcount()));
  return json;
}

}  // namespace

tinygltf::Model load_gltf_model(const std::filesystem::path& path) {
  const std::string file = path.string();
  if (!std::filesystem::is_regular_file(path)) throw InputError(file + ": no such file");
  const bool binary = path.extension() == ".glb";
  if (json_nesting_depth(gltf_json_text(path, binary), kMaxGltfJsonDepth) > kMaxGltfJsonDepth)
    throw InputError(file + ": cannot read glTF: its JSON nests arrays/objects more than " +
                     std::to_string(kMaxGltfJsonDepth) + " levels deep (a valid glTF needs fewer than 10)");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!ok)
    throw InputError(
        file + ": cannot read glTF: " +
        (err.empty() ? std::string("the file is not valid glTF 2.0 (the parser gave no reason)") : err));
  return model;
}

}  // namespace crowdlab
