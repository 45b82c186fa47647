#pragma once
// One stage of the run pipeline, described as data (issue 22): what it is called, what it reads (the
// input hashes of the stages upstream), the parameters that change its output, the files it makes and
// how, and how to read its result back when those files are up to date. StageRunner (stage_runner.hpp)
// runs every stage the same way; provenance.hpp defines the input hash and the sidecars.
//
// A stage's result usually lives in memory too (a CrowdAnimation, a metrics JSON): `compute` makes it
// when some output is stale, each output's `write` writes it to a file, and `load` reads it back from the
// files: instead of computing when every output is up to date, and after writing when it computed. So
// the stages downstream always consume exactly what is on disk (a float32 crowd file, say), whether the
// run computed the result or resumed from it: an interrupted run reproduces an uninterrupted one
// (issue 21). Stages that only write files leave compute/load empty.
//
// What a stage reads is part of its input hash twice over: `upstream` names the recipes of the stages
// upstream (their input hashes), and `inputs` names the files it reads, whose SHA-256 is hashed in when
// the stage runs. So an upstream output that was deleted and recomputed with different bytes (new
// body-model assets, another library version) redoes everything downstream of it (issue 21).
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
  std::vector<std::string> upstream;          ///< input hashes of the stages whose results this one reads
  std::vector<std::filesystem::path> inputs;  ///< files this stage reads: they must exist when it runs
  std::vector<StageOutput> outputs;           ///< at least one; the first is the main one (see StageRunner)
  std::function<void()> compute;              ///< optional: makes the result before any output is written
  std::function<void()> load;  ///< optional: reads the result from the outputs (skipped or just written)

  /// stage_input_hash(name, params, upstream + the SHA-256 of every input file): what the outputs'
  /// sidecars must record to be up to date. Throws RuntimeError when an input file is missing.
  std::string input_hash() const;
};

}  // namespace crowdlab
