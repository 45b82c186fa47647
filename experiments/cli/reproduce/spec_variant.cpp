#include "experiments/cli/reproduce/spec_variant.hpp"

#include "framework/pipeline/provenance.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli {

ExperimentSpec write_spec_variant(const std::string& yaml_text, const std::filesystem::path& out_path,
                                  const std::function<void(YAML::Node& root)>& edit) {
  YAML::Node root = YAML::Load(yaml_text);
  edit(root);
  YAML::Emitter emitter;
  emitter << root;
  std::filesystem::create_directories(out_path.parent_path());
  write_file_atomic(out_path, std::string(emitter.c_str()) + "\n");
  return load_experiment_spec(out_path.string());
}

}  // namespace crowdlab::cli
