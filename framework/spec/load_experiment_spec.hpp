#pragma once
// Loading and validating experiment specs (YAML), and enumerating their conditions.
#include <stdexcept>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// Every problem found in one spec, each formatted "file:line:column: key.path: message".
/// what() joins them with newlines. Derives from InputError, so the CLI exits with code 2.
class SpecError : public InputError {
 public:
  explicit SpecError(std::vector<std::string> messages);
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  std::vector<std::string> messages_;
};

/// Parses and validates the YAML file at `path`: every key known, every type and range checked,
/// referenced files (clips, meshes, body model) resolved relative to the spec's folder and checked to
/// exist, and work within the limits of docs/spec-reference.md. Throws SpecError listing all problems.
ExperimentSpec load_experiment_spec(const std::string& path);

/// The same from YAML text; `source_name` is used in messages, `base_dir` resolves relative files.
ExperimentSpec load_experiment_spec_text(const std::string& yaml_text, const std::string& source_name,
                                         const std::string& base_dir);

/// The full crossing of factor levels x repetitions, in spec order (first factor varies slowest,
/// repetition fastest). Ids are built from factor names and level texts, never indices, so adding a
/// level leaves every other condition's id and seed unchanged. seed = derive_seed(spec.seed, id).
std::vector<Condition> enumerate_conditions(const ExperimentSpec& spec);

/// Practice conditions (protocol.practice), ids prefixed "practice_", practice = true.
std::vector<Condition> enumerate_practice_conditions(const ExperimentSpec& spec);

}  // namespace crowdlab
