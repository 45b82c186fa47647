#include "framework/io/load_gltf_model.hpp"

#include <string>

#include "framework/core/error.hpp"

namespace crowdlab {

tinygltf::Model load_gltf_model(const std::filesystem::path& path) {
  const std::string file = path.string();
  if (!std::filesystem::is_regular_file(path)) throw InputError(file + ": no such file");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = path.extension() == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                                             : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!ok)
    throw InputError(file + ": cannot read glTF: " + (err.empty() ? std::string("unknown error") : err));
  return model;
}

}  // namespace crowdlab
