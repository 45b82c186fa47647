#pragma once
// A reproduction runs a paper's shipped spec at a chosen size (fewer frames, repetitions, no video):
// the spec's YAML is edited as a tree and written next to the results, so that every later stage
// (run, simulate-study, analyze report) and the provenance hashes see one real file.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <functional>
#include <string>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::cli {

/// Parses `yaml_text` (e.g. an embedded paper spec), applies `edit` to the root mapping, writes the
/// result to `out_path` (atomically) and loads it with load_experiment_spec (so it is validated).
ExperimentSpec write_spec_variant(const std::string& yaml_text, const std::filesystem::path& out_path,
                                  const std::function<void(YAML::Node& root)>& edit);

}  // namespace crowdlab::cli
