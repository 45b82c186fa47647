#include "framework/io/load_gltf_model.hpp"

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "framework/core/error.hpp"
#include "framework/io/glb_container.hpp"
#include "framework/io/json_nesting_depth.hpp"

namespace crowdlab {
namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
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
  if (!std::filesystem::is_regular_file(path)) throw InputError(file + ": no such file");
  const bool binary = path.extension() == ".glb";
  const std::string bytes = read_bytes(path);
  if (bytes.size() > std::numeric_limits<std::uint32_t>::max())
    throw InputError(file + ": cannot read glTF: the file is " + std::to_string(bytes.size()) +
                     " bytes; glTF files are limited to 4 GiB by the format");
  const std::string_view json = binary ? glb_json_chunk(bytes, file) : std::string_view(bytes);
  const std::size_t json_offset = binary ? kGlbJsonOffset : 0;
  if (json_nesting_depth(json, kMaxGltfJsonDepth) > kMaxGltfJsonDepth)
    throw InputError(file + ": cannot read glTF: its JSON nests arrays/objects more than " +
                     std::to_string(kMaxGltfJsonDepth) + " levels deep (a valid glTF needs fewer than 10)");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
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
  return model;
}

}  // namespace crowdlab
