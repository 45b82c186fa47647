#include "framework/io/load_gltf_model.hpp"

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/io/glb_container.hpp"
#include "framework/io/untrusted_json.hpp"

namespace crowdlab {
namespace {

constexpr std::uintmax_t kMaxGltfBytes = std::numeric_limits<std::uint32_t>::max();  // the format's limit

/// tinygltf's reader of external buffers and images (uri), which sized its buffer from seekg/tellg: a
/// `uri: "."` (a folder) or "/dev/zero" asked for exabytes (issue 32). Only regular files within the
/// format's size limit are read.
bool read_regular_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                             void*) {
  try {
    const std::string bytes = read_regular_file(path, "the glTF buffer", kMaxGltfBytes, "");
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputError& e) {
    if (err) *err += e.what();
    return false;
  }
}

/// Refuses accessors that together view more bytes than the buffers hold many times over: each reads
/// count x element size bytes into memory, so a 40 MB file whose accessors all view one buffer asked
/// for 7.2 GB (issue 32). Accessors that do not fit their bufferView are left to the accessor reader,
/// which names the accessor. A valid file views each byte about once (indices and attributes do not
/// overlap); the limit allows kMaxAccessorOverlap times, plus 1 MiB for tiny files.
constexpr double kMaxAccessorOverlap = 4.0;
void check_accessor_amplification(const tinygltf::Model& model, const std::string& file) {
  double buffer_bytes = 0.0, accessor_bytes = 0.0;
  for (const tinygltf::Buffer& b : model.buffers) buffer_bytes += static_cast<double>(b.data.size());
  for (const tinygltf::Accessor& a : model.accessors) {
    const int component = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (component <= 0 || components <= 0 || a.bufferView < 0 ||
        a.bufferView >= static_cast<int>(model.bufferViews.size()))
      continue;  // refused with its own message by gltf_accessor_reader when read
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
    const double element = static_cast<double>(component) * components;
    const double stride = view.byteStride > 0 ? static_cast<double>(view.byteStride) : element;
    const double needed =
        a.count == 0 ? 0.0 : static_cast<double>(a.byteOffset) + (a.count - 1.0) * stride + element;
    if (needed > static_cast<double>(view.byteLength)) continue;  // likewise: does not fit its view
    accessor_bytes += static_cast<double>(a.count) * element;
  }
  const double limit = kMaxAccessorOverlap * buffer_bytes + 1048576.0;
  if (accessor_bytes > limit)
    throw InputError(file + ": cannot read glTF: its " + std::to_string(model.accessors.size()) +
                     " accessors view " + std::to_string(static_cast<long long>(accessor_bytes)) +
                     " bytes of buffers holding " + std::to_string(static_cast<long long>(buffer_bytes)) +
                     " bytes, more than the limit of " + std::to_string(static_cast<long long>(limit)) +
                     " (" + std::to_string(static_cast<int>(kMaxAccessorOverlap)) +
                     " x the buffers + 1 MiB; a valid glTF views each byte about once)");
}

/// Where the JSON text is not JSON, from nlohmann's parser (tinygltf's own message carries no position,
/// or one within the JSON chunk only): "the JSON is not valid at byte N of the file (line L, column C
/// of the JSON): <what>", or "" when it parses. `offset` is where the JSON starts in the file.
std::string json_syntax_error(std::string_view json, std::size_t offset) {
  try {
    const nlohmann::json parsed = nlohmann::json::parse(json.begin(), json.end());
    (void)parsed;
  } catch (const nlohmann::json::parse_error& e) {
    // what(): "[json.exception.parse_error.101] parse error at line 1, column 5: syntax error ..."
    const std::string what = e.what();
    const std::size_t at = what.find(" at line "), colon = what.find(": ", at == std::string::npos ? 0 : at);
    const std::string line_column = at == std::string::npos || colon == std::string::npos
                                        ? ""
                                        : " (" + what.substr(at + 4, colon - at - 4) + " of the JSON)";
    return "the JSON is not valid at byte " + std::to_string(offset + e.byte - (e.byte > 0 ? 1 : 0)) +
           " of the file" + line_column + ": " + (colon == std::string::npos ? what : what.substr(colon + 2));
  }
  return "";
}

}  // namespace

tinygltf::Model load_gltf_model(const std::filesystem::path& path) {
  const std::string file = path.string();
  const bool binary = path.extension() == ".glb";
  // A FIFO or device is refused before it is opened, a file over 4 GiB before it is read.
  const std::string bytes = read_regular_file(path, "glTF", kMaxGltfBytes,
                                              "nothing (glTF files are limited to 4 GiB by the format)");
  const std::string_view json = binary ? glb_json_chunk(bytes, file) : std::string_view(bytes);
  const std::size_t json_offset = binary ? kGlbJsonOffset : 0;
  JsonLimits limits;
  limits.max_depth = kMaxGltfJsonDepth;
  limits.max_bytes = bytes.size();  // the container's own limit (4 GiB) is checked above
  check_untrusted_json(json, file, limits, json_offset);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks fs_callbacks{&tinygltf::FileExists, &tinygltf::ExpandFilePath,
                                     &read_regular_whole_file, &tinygltf::WriteWholeFile, nullptr};
  loader.SetFsCallbacks(fs_callbacks);
  std::string err, warn;
  const std::string base_dir = path.parent_path().string();
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                       reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       static_cast<unsigned int>(bytes.size()), base_dir)
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                                      static_cast<unsigned int>(bytes.size()), base_dir);
  if (!ok) {
    std::string why = json_syntax_error(json, json_offset);
    if (why.empty()) why = err;
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
    // tinygltf quotes the offending value whole: a fuzzed `type` of 30,000 brackets filled the terminal.
    constexpr std::size_t kMaxReason = 400;
    if (why.size() > kMaxReason)
      why =
          why.substr(0, kMaxReason) + "... (" + std::to_string(why.size() - kMaxReason) + " more characters)";
    throw InputError(
        file + ": cannot read glTF: " +
        (why.empty() ? std::string("the file is not valid glTF 2.0 (the parser gave no reason)") : why));
  }
  check_accessor_amplification(model, file);
  return model;
}

}  // namespace crowdlab
