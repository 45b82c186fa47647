#pragma once
// One stage of the run pipeline, described as data (issue 22): what it is called, what it reads (the
// input hashes of the stages upstream), the parameters that change its output, the files it makes and
// how, and how to read its result back when those files are up to date. StageRunner (stage_runner.hpp)
// runs every stage the same way; provenance.hpp defines the input hash and the sidecars.
//
// A stage's result usually lives in memory too (a CrowdAnimation, a metrics JSON): `compute` makes it
// when some output is stale, each output's `write` writes it to a file, and `load` reads it back instead
// when every output is up to date. Stages that only write files leave compute/load empty.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace crowdlab {

struct StageOutput {
  std::filesystem::path path;  ///< the final file (written via a temporary in its folder)
  /// Writes the complete file at `tmp` (same folder and extension as `path`).
  std::function<void(const std::filesystem::path& tmp)> write;
};

struct Stage {
  std::string name;                                  ///< "crowd", "animation", ...: recorded in the sidecars
  nlohmann::json params = nlohmann::json::object();  ///< everything besides upstream that changes the output
  std::vector<std::string> upstream;  ///< input hashes of the stages whose outputs this one reads
  std::vector<StageOutput> outputs;   ///< at least one; the first is the main one (see StageRunner)
  std::function<void()> compute;      ///< optional: makes the result before any output is written
  std::function<void()> load;         ///< optional: reads the result back when every output is up to date

  /// stage_input_hash(name, params, upstream): what the outputs' sidecars must record to be up to date.
  std::string input_hash() const;
};

}  // namespace crowdlab
